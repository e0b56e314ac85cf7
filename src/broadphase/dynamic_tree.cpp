// The dynamic AABB tree: node pool, SAH insertion, removal and AVL-style rebalancing.
#include "broadphase/dynamic_tree.h"
#include "base/assert.h"
#include "base/fail.h"

#include <collide/error.h>

#include <algorithm>
#include <string>

namespace collide {

namespace {

// Rotations are made only when one side is more than this many levels taller than the other. A
// strict AVL bound (1) keeps the tree shortest but fights the SAH: rotating for height regroups boxes
// that are far apart, and on a 100,000-box random walk it made pair queries test 6x more nodes. With a
// slack of 3 the height stays within ~2.2 log2(n) (the minimum size of a tree of height h then grows
// as N(h) = N(h-1) + N(h-4), x^4 = x^3 + 1, x = 1.38) while the SAH decides the grouping.
constexpr int kBalanceSlack = 3;

// Half the surface area: the SAH only compares areas, so the factor 2 is dropped.
inline float halfArea(const Aabb& b) {
  const Vec3 d = b.max - b.min;
  return d.x * d.y + d.y * d.z + d.z * d.x;
}

}  // namespace

std::int32_t DynamicTree::allocateNode() {
  if (freeList_ == kNull) {
    nodes_.emplace_back();
    return static_cast<std::int32_t>(nodes_.size() - 1);
  }
  const std::int32_t index = freeList_;
  freeList_ = nodes_[index].parent;
  nodes_[index] = Node{};
  return index;
}

void DynamicTree::freeNode(std::int32_t index) {
  nodes_[index].parent = freeList_;
  nodes_[index].height = -1;
  nodes_[index].child1 = kNull;
  nodes_[index].child2 = kNull;
  freeList_ = index;
}

std::int32_t DynamicTree::insert(const Aabb& box, std::uint32_t proxy, std::uint32_t layers) {
  const std::int32_t leaf = allocateNode();
  nodes_[leaf].box = box;
  nodes_[leaf].proxy = proxy;
  nodes_[leaf].layers = layers;
  nodes_[leaf].height = 0;
  insertLeaf(leaf);
  ++leafCount_;
  return leaf;
}

void DynamicTree::remove(std::int32_t leaf) {
  COLLIDE_ASSERT(leaf >= 0 && static_cast<std::size_t>(leaf) < nodes_.size() && nodes_[leaf].isLeaf());
  removeLeaf(leaf);
  freeNode(leaf);
  --leafCount_;
}

void DynamicTree::move(std::int32_t leaf, const Aabb& box) {
  COLLIDE_ASSERT(leaf >= 0 && static_cast<std::size_t>(leaf) < nodes_.size() && nodes_[leaf].isLeaf());
  removeLeaf(leaf);
  nodes_[leaf].box = box;
  insertLeaf(leaf);
}

void DynamicTree::setLayers(std::int32_t leaf, std::uint32_t layers) {
  COLLIDE_ASSERT(leaf >= 0 && static_cast<std::size_t>(leaf) < nodes_.size() && nodes_[leaf].isLeaf());
  nodes_[leaf].layers = layers;
  for (std::int32_t index = nodes_[leaf].parent; index != kNull; index = nodes_[index].parent) {
    Node& n = nodes_[index];
    n.layers = nodes_[n.child1].layers | nodes_[n.child2].layers;
  }
}

void DynamicTree::insertLeaf(std::int32_t leaf) {
  if (root_ == kNull) {
    root_ = leaf;
    nodes_[leaf].parent = kNull;
    return;
  }
  // Descend towards the sibling that adds the least area. Placing the leaf beside node n costs the
  // area of the new parent (n ∪ leaf) plus the growth of every ancestor (the "inherited" cost);
  // going further down costs at least the inherited cost plus the child's own growth.
  const Aabb leafBox = nodes_[leaf].box;
  std::int32_t index = root_;
  while (!nodes_[index].isLeaf()) {
    const Node& n = nodes_[index];
    const float area = halfArea(n.box);
    const float combinedArea = halfArea(merge(n.box, leafBox));
    const float here = 2.0f * combinedArea;
    const float inherited = 2.0f * (combinedArea - area);
    auto descendCost = [&](std::int32_t child) {
      const Node& c = nodes_[child];
      const float grown = halfArea(merge(c.box, leafBox));
      return inherited + (c.isLeaf() ? grown : grown - halfArea(c.box));
    };
    const float cost1 = descendCost(n.child1);
    const float cost2 = descendCost(n.child2);
    if (here < cost1 && here < cost2) break;
    index = cost1 < cost2 ? n.child1 : n.child2;
  }

  const std::int32_t sibling = index;
  const std::int32_t oldParent = nodes_[sibling].parent;
  const std::int32_t newParent = allocateNode();
  Node& p = nodes_[newParent];
  p.parent = oldParent;
  p.box = merge(leafBox, nodes_[sibling].box);
  p.layers = nodes_[leaf].layers | nodes_[sibling].layers;
  p.height = nodes_[sibling].height + 1;
  p.child1 = sibling;
  p.child2 = leaf;
  nodes_[sibling].parent = newParent;
  nodes_[leaf].parent = newParent;
  if (oldParent == kNull) {
    root_ = newParent;
  } else if (nodes_[oldParent].child1 == sibling) {
    nodes_[oldParent].child1 = newParent;
  } else {
    nodes_[oldParent].child2 = newParent;
  }
  refitUpwards(oldParent);
}

void DynamicTree::removeLeaf(std::int32_t leaf) {
  if (leaf == root_) {
    root_ = kNull;
    return;
  }
  const std::int32_t parent = nodes_[leaf].parent;
  const std::int32_t grandParent = nodes_[parent].parent;
  const std::int32_t sibling = nodes_[parent].child1 == leaf ? nodes_[parent].child2 : nodes_[parent].child1;
  if (grandParent == kNull) {
    root_ = sibling;
    nodes_[sibling].parent = kNull;
    freeNode(parent);
    return;
  }
  // The sibling takes the parent's place; the ancestors shrink and may need rebalancing.
  if (nodes_[grandParent].child1 == parent) {
    nodes_[grandParent].child1 = sibling;
  } else {
    nodes_[grandParent].child2 = sibling;
  }
  nodes_[sibling].parent = grandParent;
  freeNode(parent);
  refitUpwards(grandParent);
}

void DynamicTree::refitUpwards(std::int32_t index) {
  while (index != kNull) {
    index = rebalance(index);
    Node& n = nodes_[index];
    const Node& c1 = nodes_[n.child1];
    const Node& c2 = nodes_[n.child2];
    n.box = merge(c1.box, c2.box);
    n.layers = c1.layers | c2.layers;
    n.height = 1 + std::max(c1.height, c2.height);
    index = n.parent;
  }
}

// If one child of `a` is more than kBalanceSlack levels taller than the other, lift that child's taller
// grandchild side up: the tall child becomes the subtree root, `a` takes its shorter grandchild.
// This is the single rotation of an AVL tree (Adelson-Velsky and Landis 1962); for a BVH any
// regrouping is valid, so one rotation always suffices to restore the bound. Returns the node now
// at the position of `a`.
std::int32_t DynamicTree::rebalance(std::int32_t a) {
  Node& nodeA = nodes_[a];
  if (nodeA.isLeaf() || nodeA.height < 2) return a;
  const std::int32_t b = nodeA.child1;
  const std::int32_t c = nodeA.child2;
  const int balance = nodes_[c].height - nodes_[b].height;
  if (balance >= -kBalanceSlack && balance <= kBalanceSlack) return a;

  // `up` is the taller child, `stay` the shorter one.
  const bool liftSecond = balance > 1;
  const std::int32_t up = liftSecond ? c : b;
  const std::int32_t stay = liftSecond ? b : c;
  Node& nodeUp = nodes_[up];
  const std::int32_t f = nodeUp.child1;
  const std::int32_t g = nodeUp.child2;

  // `up` replaces `a` under a's parent.
  nodeUp.parent = nodeA.parent;
  if (nodeUp.parent == kNull) {
    root_ = up;
  } else if (nodes_[nodeUp.parent].child1 == a) {
    nodes_[nodeUp.parent].child1 = up;
  } else {
    nodes_[nodeUp.parent].child2 = up;
  }
  nodeA.parent = up;

  // `up` keeps its taller child and adopts `a`; `a` keeps `stay` and takes the shorter grandchild.
  const bool fTaller = nodes_[f].height > nodes_[g].height;
  const std::int32_t keep = fTaller ? f : g;
  const std::int32_t give = fTaller ? g : f;
  nodeUp.child1 = a;
  nodeUp.child2 = keep;
  nodeA.child1 = stay;
  nodeA.child2 = give;
  nodes_[give].parent = a;
  nodes_[stay].parent = a;

  nodeA.box = merge(nodes_[stay].box, nodes_[give].box);
  nodeA.layers = nodes_[stay].layers | nodes_[give].layers;
  nodeA.height = 1 + std::max(nodes_[stay].height, nodes_[give].height);
  nodeUp.box = merge(nodeA.box, nodes_[keep].box);
  nodeUp.layers = nodeA.layers | nodes_[keep].layers;
  nodeUp.height = 1 + std::max(nodeA.height, nodes_[keep].height);
  return up;
}

void DynamicTree::validate() const {
  auto fail = [](const std::string& what, std::int32_t index) {
    detail::raiseError("dynamic tree: " + what + " at node " + std::to_string(index));
  };
  if (root_ == kNull) {
    if (leafCount_ != 0) return fail("empty tree with a non-zero leaf count", kNull);
    return;
  }
  if (nodes_[root_].parent != kNull) return fail("root has a parent", root_);
  std::size_t leaves = 0;
  Array<std::int32_t> stack{root_};
  while (!stack.empty()) {
    const std::int32_t index = stack.back();
    stack.pop_back();
    const Node& n = nodes_[index];
    if (n.height < 0) return fail("free node reachable", index);
    if (n.isLeaf()) {
      if (n.height != 0) return fail("leaf with non-zero height", index);
      ++leaves;
      continue;
    }
    if (n.child2 == kNull) return fail("inner node with one child", index);
    const Node& c1 = nodes_[n.child1];
    const Node& c2 = nodes_[n.child2];
    if (c1.parent != index || c2.parent != index) return fail("child whose parent link is wrong", index);
    if (n.height != 1 + std::max(c1.height, c2.height)) return fail("wrong height", index);
    if (!n.box.contains(c1.box) || !n.box.contains(c2.box))
      return fail("box not containing a child's box", index);
    if (n.layers != (c1.layers | c2.layers)) return fail("layers not the union of the children's", index);
    stack.push_back(n.child1);
    stack.push_back(n.child2);
  }
  if (leaves != leafCount_) {
    COLLIDE_FAIL("dynamic tree: " + std::to_string(leaves) + " leaves reachable, " +
                 std::to_string(leafCount_) + " expected");
  }
}

float DynamicTree::areaRatio() const {
  if (root_ == kNull) return 0.0f;
  const float rootArea = halfArea(nodes_[root_].box);
  if (rootArea <= 0.0f) return 0.0f;
  float total = 0.0f;
  for (const Node& n : nodes_) {
    if (n.height > 0) total += halfArea(n.box);
  }
  return total / rootArea;
}

}  // namespace collide
