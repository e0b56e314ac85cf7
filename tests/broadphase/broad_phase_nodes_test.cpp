// BroadPhase::visitNodes: the Tree's nodes form two binary trees over the proxies' (fattened) boxes,
// the Grid's cells are the ones its proxies occupy, and the other algorithms have no boxes to show.
#include <collide/broadphase.h>
#include <gtest/gtest.h>

#include "support/test_random.h"

#include <algorithm>
#include <random>
#include <tuple>
#include <vector>

using namespace collide;

namespace {

std::vector<BroadPhaseNode> nodesOf(const BroadPhase& broadPhase) {
  std::vector<BroadPhaseNode> nodes;
  broadPhase.visitNodes([&](const BroadPhaseNode& node) { nodes.push_back(node); });
  return nodes;
}

bool sameBox(const Aabb& a, const Aabb& b) { return a.min == b.min && a.max == b.max; }

}  // namespace

TEST(BroadPhaseNodes, TreeNodesAreTwoBinaryTreesOverTheProxyBoxes) {
  BroadPhaseSettings settings;
  settings.type = BroadPhaseType::Tree;
  settings.treeMargin = 0.1f;
  auto tree = createBroadPhase(settings);
  EXPECT_TRUE(nodesOf(*tree).empty());

  std::mt19937 rng(11);
  std::vector<Aabb> movable, fixed;
  for (int i = 0; i < 60; ++i) {
    const Vec3 center = test::randomPoint(rng, -20.0f, 20.0f);
    const Aabb box = Aabb::fromCenterHalfExtents(center, Vec3(0.5f + 0.01f * static_cast<float>(i)));
    const MotionType motion = i % 4 == 0 ? MotionType::Static : MotionType::Movable;
    tree->add({box, motion});
    (motion == MotionType::Static ? fixed : movable).push_back(box);
  }
  const std::vector<BroadPhaseNode> nodes = nodesOf(*tree);

  for (const MotionType motion : {MotionType::Static, MotionType::Movable}) {
    const std::vector<Aabb>& proxies = motion == MotionType::Static ? fixed : movable;
    std::vector<BroadPhaseNode> inTree;
    std::copy_if(nodes.begin(), nodes.end(), std::back_inserter(inTree),
                 [&](const BroadPhaseNode& n) { return n.tree == motion; });
    // A binary tree with n leaves has n - 1 inner nodes and one root.
    const auto leaves =
        std::count_if(inTree.begin(), inTree.end(), [](const BroadPhaseNode& n) { return n.isLeaf; });
    EXPECT_EQ(static_cast<std::size_t>(leaves), proxies.size());
    EXPECT_EQ(inTree.size(), 2 * proxies.size() - 1);
    EXPECT_EQ(
        std::count_if(inTree.begin(), inTree.end(), [](const BroadPhaseNode& n) { return n.depth == 0; }), 1);
    // The leaves are the proxies' boxes, fattened by the margin when movable.
    for (const Aabb& proxy : proxies) {
      const Aabb expected = motion == MotionType::Movable ? proxy.expanded(settings.treeMargin) : proxy;
      EXPECT_TRUE(std::any_of(inTree.begin(), inTree.end(),
                              [&](const BroadPhaseNode& n) { return n.isLeaf && sameBox(n.box, expected); }));
    }
    // Every node below a root lies in a node one level up (its parent), and no level is empty
    // above the deepest one.
    int deepest = 0;
    for (const BroadPhaseNode& n : inTree) deepest = std::max(deepest, n.depth);
    for (const BroadPhaseNode& n : inTree) {
      if (n.depth == 0) continue;
      EXPECT_TRUE(std::any_of(inTree.begin(), inTree.end(),
                              [&](const BroadPhaseNode& parent) {
                                return !parent.isLeaf && parent.depth == n.depth - 1 &&
                                       parent.box.contains(n.box);
                              }))
          << "node at depth " << n.depth;
    }
    EXPECT_LT(deepest, static_cast<int>(proxies.size()));  // balanced trees are far shallower
  }
}

TEST(BroadPhaseNodes, GridCellsAreTheOccupiedCells) {
  BroadPhaseSettings settings;
  settings.type = BroadPhaseType::Grid;
  settings.gridCellSize = 1.0f;
  auto grid = createBroadPhase(settings);
  // Away from cell boundaries: one cell, one cell, and two cells along x.
  grid->add({Aabb{Vec3(0.2f), Vec3(0.8f)}});
  grid->add({Aabb{Vec3(1.2f, 0.2f, 0.2f), Vec3(1.8f, 0.8f, 0.8f)}});
  const ProxyId spanning = grid->add({Aabb{Vec3(2.5f, 0.2f, 0.2f), Vec3(3.5f, 0.8f, 0.8f)}});
  // Wider than gridMaxCellsPerAxis cells: kept apart, in no cell.
  grid->add({Aabb{Vec3(-50.0f, -1.0f, -50.0f), Vec3(50.0f, 0.0f, 50.0f)}, MotionType::Static});

  const auto cellsAlongX = [&] {
    std::vector<std::tuple<float, float, float>> corners;
    for (const BroadPhaseNode& n : nodesOf(*grid)) {
      EXPECT_TRUE(n.isLeaf);
      EXPECT_EQ(n.depth, 0);
      EXPECT_EQ(n.box.max - n.box.min, Vec3(1.0f));
      corners.emplace_back(n.box.min.x, n.box.min.y, n.box.min.z);
    }
    std::sort(corners.begin(), corners.end());
    return corners;
  };
  using Corner = std::tuple<float, float, float>;
  EXPECT_EQ(
      cellsAlongX(),
      (std::vector<Corner>{{0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, {2.0f, 0.0f, 0.0f}, {3.0f, 0.0f, 0.0f}}));
  grid->remove(spanning);
  EXPECT_EQ(cellsAlongX(), (std::vector<Corner>{{0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}}));
}

TEST(BroadPhaseNodes, SweepAndPruneAndBruteForceHaveNone) {
  for (const BroadPhaseType type : {BroadPhaseType::SweepAndPrune, BroadPhaseType::BruteForce}) {
    BroadPhaseSettings settings;
    settings.type = type;
    auto broadPhase = createBroadPhase(settings);
    broadPhase->add({Aabb{Vec3(0.0f), Vec3(1.0f)}});
    broadPhase->add({Aabb{Vec3(0.5f), Vec3(1.5f)}});
    EXPECT_TRUE(nodesOf(*broadPhase).empty()) << toString(type);
  }
}
