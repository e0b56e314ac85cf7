// The dynamic AABB tree's invariants: containment, parent links, heights, and a logarithmic height
// whatever the insertion order (the AVL rotations' job).
#include "broadphase/dynamic_tree.h"
#include "base/task_runner.h"
#include "broadphase/broad_phase_internal.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

using namespace collide;

namespace {

float log2Of(std::size_t n) { return std::log2(static_cast<float>(n)); }

}  // namespace

TEST(DynamicTree, RandomInsertsKeepInvariantsAndLogHeight) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> position(-100.0f, 100.0f), size(0.1f, 2.0f);
  DynamicTree tree;
  std::vector<std::int32_t> leaves;
  for (std::uint32_t i = 0; i < 4096; ++i) {
    const Vec3 c(position(rng), position(rng), position(rng));
    leaves.push_back(tree.insert(Aabb::fromCenterHalfExtents(c, Vec3(size(rng), size(rng), size(rng))), i));
    if ((i & (i + 1)) == 0) tree.validate();  // at every power of two
  }
  tree.validate();
  EXPECT_EQ(tree.leafCount(), 4096u);
  EXPECT_LE(tree.height(), 2.5f * log2Of(4096));
  // Every leaf is found by a query with its own box.
  for (std::uint32_t i = 0; i < leaves.size(); i += 97) {
    bool found = false;
    std::uint64_t tests = 0;
    const Aabb box = tree.box(leaves[i]);
    tree.traverse([&](const Aabb& b) { return b.overlaps(box); },
                  [&](const DynamicTree::Node& leaf) {
                    found = found || leaf.proxy == i;
                    return true;
                  },
                  tests);
    EXPECT_TRUE(found);
    EXPECT_LT(tests, 4096u);  // and the query prunes
  }
  // Remove half, move the rest: still valid and balanced.
  for (std::size_t i = 0; i < leaves.size(); i += 2) tree.remove(leaves[i]);
  for (std::size_t i = 1; i < leaves.size(); i += 2) {
    const Vec3 c(position(rng), position(rng), position(rng));
    tree.move(leaves[i], Aabb::fromCenterHalfExtents(c, Vec3(1.0f)));
  }
  tree.validate();
  EXPECT_EQ(tree.leafCount(), 2048u);
  EXPECT_LE(tree.height(), 2.5f * log2Of(2048));
}

TEST(DynamicTree, SortedInsertionStaysBalanced) {
  // Boxes along a line inserted in order: the worst case for an unbalanced incremental tree, which
  // would degenerate into a list of height n.
  DynamicTree tree;
  for (std::uint32_t i = 0; i < 2000; ++i) {
    tree.insert(Aabb::fromCenterHalfExtents(Vec3(static_cast<float>(i), 0.0f, 0.0f), Vec3(0.4f)), i);
  }
  tree.validate();
  EXPECT_LE(tree.height(), 2.5f * log2Of(2000));
}

TEST(DynamicTree, EmptyAndSingleLeaf) {
  DynamicTree tree;
  tree.validate();
  EXPECT_EQ(tree.height(), 0);
  const std::int32_t leaf = tree.insert(Aabb{Vec3(0.0f), Vec3(1.0f)}, 3);
  EXPECT_EQ(tree.root(), leaf);
  EXPECT_EQ(tree.proxy(leaf), 3u);
  tree.remove(leaf);
  EXPECT_EQ(tree.root(), DynamicTree::kNull);
  tree.validate();
}

TEST(TreeBroadPhase, FatBoxesAbsorbSmallMotionAndTreesStayBalanced) {
  BroadPhaseSettings settings;
  settings.treeMargin = 0.5f;
  auto bp = createBroadPhase(settings);
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> position(-50.0f, 50.0f);
  std::vector<ProxyId> ids;
  for (int i = 0; i < 1000; ++i) {
    const Vec3 c(position(rng), position(rng), position(rng));
    ids.push_back(bp->add(
        {Aabb::fromCenterHalfExtents(c, Vec3(0.5f)), i % 5 == 0 ? MotionType::Static : MotionType::Movable}));
  }
  Array<ProxyPair> pairs;
  bp->findPairs(pairs);
  const DynamicTree* movable = treeOfBroadPhase(*bp, MotionType::Movable);
  const DynamicTree* fixed = treeOfBroadPhase(*bp, MotionType::Static);
  ASSERT_NE(movable, nullptr);
  EXPECT_EQ(movable->leafCount(), 800u);
  EXPECT_EQ(fixed->leafCount(), 200u);
  EXPECT_LE(movable->height(), 2.5f * log2Of(800));
  // Moving every movable box by 0.2 (< margin 0.5) re-inserts nothing: the next findPairs queries no
  // tree and only re-checks the few persistent pairs (two box tests each at most).
  for (std::size_t i = 0; i < ids.size(); ++i) {
    if (i % 5 == 0) continue;
    Aabb box = bp->bounds(ids[i]);
    box = {box.min + Vec3(0.2f), box.max + Vec3(0.2f)};
    bp->update(ids[i], box);
  }
  const BroadPhaseStats& stats = bp->findPairs(pairs);
  // A tree query costs at least one box test, so 800 re-insertions would cost 800 tests or more.
  EXPECT_LT(stats.boxTests, 400u);
  bp->validate();
}

// A proxy that leaves its fat box is put back with the box stretched along its motion, four times
// the last update's displacement ahead of it (and the margin around): one moving steadily at twice
// the margin a step is re-inserted every few steps, not every step, and a box that stopped is not.
TEST(TreeBroadPhase, AMovingBoxIsPutBackStretchedAlongItsMotion) {
  BroadPhaseSettings settings;
  settings.treeMargin = 0.1f;
  auto bp = createBroadPhase(settings);
  const ProxyId id = bp->add({Aabb::fromCenterHalfExtents(Vec3(0.0f), Vec3(0.5f)), MotionType::Movable});
  const DynamicTree* tree = treeOfBroadPhase(*bp, MotionType::Movable);
  ASSERT_NE(tree, nullptr);
  const auto fatBox = [&] { return tree->box(tree->root()); };
  EXPECT_FLOAT_EQ(fatBox().max.x, 0.6f);  // the margin alone at first
  int reinserted = 0;
  Aabb last = fatBox();
  for (int step = 1; step <= 20; ++step) {
    bp->update(id, Aabb::fromCenterHalfExtents(Vec3(0.2f * float(step), 0.0f, 0.0f), Vec3(0.5f)));
    const Aabb now = fatBox();
    if (!(now.min == last.min && now.max == last.max)) {
      ++reinserted;
      // Four displacements of 0.2 ahead, the margin behind and across.
      EXPECT_NEAR(now.max.x, 0.2f * float(step) + 0.5f + 0.1f + 0.8f, 1e-5f) << "step " << step;
      EXPECT_NEAR(now.min.x, 0.2f * float(step) - 0.5f - 0.1f, 1e-5f) << "step " << step;
      EXPECT_NEAR(now.max.y, 0.6f, 1e-6f);
    }
    last = now;
  }
  // The first leave at step 1, then every fifth step (0.9 of room ahead at 0.2 a step).
  EXPECT_EQ(reinserted, 4);
  // A teleport 100 away stretches the box by its own size (1) at most, not by 400.
  bp->update(id, Aabb::fromCenterHalfExtents(Vec3(104.0f, 0.0f, 0.0f), Vec3(0.5f)));
  EXPECT_NEAR(fatBox().max.x, 104.0f + 0.5f + 0.1f + 1.0f, 1e-4f);
  EXPECT_NEAR(fatBox().min.x, 104.0f - 0.5f - 0.1f, 1e-4f);
}

// updateInPlace stores a movable box that stays inside its fat box and leaves everything else to
// update(): a box past its fat box, a static proxy, a stale id, a bad box, and every algorithm but
// the tree. Boxes moved through it, the rest through update(), give the pairs update() alone gives.
TEST(TreeBroadPhase, UpdateInPlaceStoresOnlyWhatTheTreeKeepsWhereItIs) {
  BroadPhaseSettings settings;
  settings.treeMargin = 0.1f;
  auto bp = createBroadPhase(settings);
  const Aabb start = Aabb::fromCenterHalfExtents(Vec3(0.0f), Vec3(0.5f));
  const ProxyId id = bp->add({start, MotionType::Movable});
  const ProxyId wall =
      bp->add({Aabb::fromCenterHalfExtents(Vec3(3.0f, 0.0f, 0.0f), Vec3(0.5f)), MotionType::Static});
  const DynamicTree* tree = treeOfBroadPhase(*bp, MotionType::Movable);
  ASSERT_NE(tree, nullptr);
  const Aabb fat = tree->box(tree->root());

  const Aabb nudged = Aabb::fromCenterHalfExtents(Vec3(0.05f, 0.0f, 0.0f), Vec3(0.5f));
  EXPECT_TRUE(bp->updateInPlace(id, nudged));
  EXPECT_EQ(bp->bounds(id).min, nudged.min);
  EXPECT_EQ(tree->box(tree->root()).max, fat.max);  // the tree as it was

  const Aabb past = Aabb::fromCenterHalfExtents(Vec3(0.3f, 0.0f, 0.0f), Vec3(0.5f));
  EXPECT_FALSE(bp->updateInPlace(id, past));
  EXPECT_EQ(bp->bounds(id).min, nudged.min);  // unchanged: update() takes it
  bp->update(id, past);
  EXPECT_GT(tree->box(tree->root()).max.x, fat.max.x);

  const Aabb wallNudged = Aabb::fromCenterHalfExtents(Vec3(3.01f, 0.0f, 0.0f), Vec3(0.5f));
  EXPECT_FALSE(bp->updateInPlace(wall, wallNudged));
  Aabb bad = past;
  bad.max.x = std::nanf("");
  EXPECT_FALSE(bp->updateInPlace(id, bad));
  Aabb inverted = past;
  std::swap(inverted.min.y, inverted.max.y);
  EXPECT_FALSE(bp->updateInPlace(id, inverted));
  bp->remove(wall);
  EXPECT_FALSE(bp->updateInPlace(wall, wallNudged));  // stale: no throw, nothing stored
  EXPECT_FALSE(bp->updateInPlace(ProxyId{}, wallNudged));

  for (const BroadPhaseType type :
       {BroadPhaseType::SweepAndPrune, BroadPhaseType::Grid, BroadPhaseType::BruteForce}) {
    BroadPhaseSettings other;
    other.type = type;
    auto algorithm = createBroadPhase(other);
    const ProxyId p = algorithm->add({start, MotionType::Movable});
    EXPECT_FALSE(algorithm->updateInPlace(p, nudged));
    EXPECT_EQ(algorithm->bounds(p).min, start.min);
  }

  // Random walks: one tree through update() alone, one through updateInPlace first.
  auto direct = createBroadPhase(settings);
  auto inPlace = createBroadPhase(settings);
  std::mt19937 rng(8);
  std::uniform_real_distribution<float> position(-5.0f, 5.0f), nudge(-0.08f, 0.08f);
  std::vector<ProxyId> ids;
  std::vector<Vec3> centers;
  for (int i = 0; i < 300; ++i) {
    const Vec3 c(position(rng), position(rng), position(rng));
    const MotionType motion = i % 10 == 0 ? MotionType::Static : MotionType::Movable;
    const ProxyId a = direct->add({Aabb::fromCenterHalfExtents(c, Vec3(0.4f)), motion});
    const ProxyId b = inPlace->add({Aabb::fromCenterHalfExtents(c, Vec3(0.4f)), motion});
    ASSERT_EQ(a.index, b.index);
    ids.push_back(a);
    centers.push_back(c);
  }
  int stored = 0, updated = 0;
  for (int round = 0; round < 40; ++round) {
    for (std::size_t i = 0; i < ids.size(); ++i) {
      if (i % 10 == 0) continue;
      centers[i] += Vec3(nudge(rng), nudge(rng), nudge(rng));
      const Aabb box = Aabb::fromCenterHalfExtents(centers[i], Vec3(0.4f));
      direct->update(ids[i], box);
      if (inPlace->updateInPlace(ids[i], box)) {
        ++stored;
      } else {
        inPlace->update(ids[i], box);
        ++updated;
      }
    }
    Array<ProxyPair> expected, got;
    direct->findPairs(expected);
    inPlace->findPairs(got);
    ASSERT_EQ(expected, got) << "round " << round;
  }
  // Both ways were taken, most boxes in place.
  EXPECT_GT(stored, updated);
  EXPECT_GT(updated, 0);
}

// A persistent set of tens of thousands of pairs is merged in chunks (of the longer list, the
// candidates split where they fall), in parallel with workers: the pairs and the box tests are those
// of the brute force, one worker and two alike, as boxes move, leave and come back.
TEST(TreeBroadPhase, ManyPairsMergeInChunksAsBruteForceAtAnyWorkerCount) {
  BroadPhaseSettings brute;
  brute.type = BroadPhaseType::BruteForce;
  auto reference = createBroadPhase(brute);
  auto serial = createBroadPhase(BroadPhaseSettings{});
  auto parallel = createBroadPhase(BroadPhaseSettings{});
  detail::TaskRunner one, two;
  two.configure(2, nullptr, nullptr, nullptr);
  std::mt19937 rng(21);
  std::uniform_real_distribution<float> position(-6.0f, 6.0f);
  std::uniform_real_distribution<float> nudge(-0.4f, 0.4f);
  std::vector<ProxyId> ids;
  const auto addAll = [&](const ProxyDef& def) {
    const ProxyId id = reference->add(def);
    EXPECT_EQ(serial->add(def), id);
    EXPECT_EQ(parallel->add(def), id);
    return id;
  };
  for (int i = 0; i < 3000; ++i) {
    const Vec3 c(position(rng), position(rng), position(rng));
    ids.push_back(addAll({Aabb::fromCenterHalfExtents(c, Vec3(0.6f)),
                          i % 10 == 0 ? MotionType::Static : MotionType::Movable}));
  }
  std::size_t most = 0;
  for (int step = 0; step < 12; ++step) {
    Array<ProxyPair> expected, fromOne, fromTwo;
    reference->findPairs(expected);
    serial->findPairs(fromOne, one);
    const std::uint64_t oneTests = serial->lastStats().boxTests;
    parallel->findPairs(fromTwo, two);
    ASSERT_TRUE(fromOne == expected) << "step " << step;
    ASSERT_TRUE(fromTwo == expected) << "step " << step;
    EXPECT_EQ(parallel->lastStats().boxTests, oneTests);
    most = std::max(most, expected.size());
    // A third of the movable boxes move (some beyond their fat boxes), a few leave and come back.
    for (std::size_t i = 0; i < ids.size(); ++i) {
      if (i % 10 == 0 || i % 3 != static_cast<std::size_t>(step) % 3) continue;
      Aabb box = reference->bounds(ids[i]);
      const Vec3 d(nudge(rng), nudge(rng), nudge(rng));
      box = {box.min + d, box.max + d};
      reference->update(ids[i], box);
      serial->update(ids[i], box);
      parallel->update(ids[i], box);
    }
    for (int k = 0; k < 20; ++k) {
      const std::size_t i = 1 + static_cast<std::size_t>(rng() % (ids.size() - 1));
      if (i % 10 == 0) continue;
      const ProxyDef def{reference->bounds(ids[i]), MotionType::Movable};
      reference->remove(ids[i]);
      serial->remove(ids[i]);
      parallel->remove(ids[i]);
      ids[i] = addAll(def);
    }
  }
  EXPECT_GT(most, 3u * 8192u) << "the scene should need several chunks";
}

// The first findPairs queries every proxy: its candidate lists (one per worker, then the joined
// one) hold each overlap, megabytes in a large scene. Once the burst is over they are not kept.
TEST(TreeBroadPhase, ABurstOfCandidatesIsNotKeptOnceItIsOver) {
  auto bp = createBroadPhase(BroadPhaseSettings{});
  detail::TaskRunner two;
  two.configure(2, nullptr, nullptr, nullptr);
  // 48,000 unit boxes 0.8 apart: each overlaps its 26 neighbours' boxes.
  std::vector<ProxyId> ids;
  for (int x = 0; x < 40; ++x)
    for (int y = 0; y < 30; ++y)
      for (int z = 0; z < 40; ++z)
        ids.push_back(
            bp->add({Aabb::fromCenterHalfExtents(0.8f * Vec3(x, y, z), Vec3(0.5f)), MotionType::Movable}));
  Array<ProxyPair> pairs;
  bp->findPairs(pairs, two);
  const std::size_t afterBurst = bp->memoryBytes();
  const std::size_t pairCount = pairs.size();
  ASSERT_GT(pairCount, 500000u);
  // A step where one box moves: the lists of the burst go back; the persistent set and the output
  // stay. The joined list held every key (8 bytes each) at least once, whichever worker found it;
  // how much the workers' own lists held depends on how the queries were split between them (a
  // worker slow to start leaves most to the other), so only the joined list's share is counted on.
  Aabb box = bp->bounds(ids[0]);
  box = {box.min - Vec3(1.0f), box.max - Vec3(1.0f)};
  bp->update(ids[0], box);
  bp->findPairs(pairs, two);
  const std::size_t afterQuiet = bp->memoryBytes();
  EXPECT_LT(afterQuiet + 8 * pairCount * 3 / 4, afterBurst);
}
