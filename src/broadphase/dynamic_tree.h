// A dynamic AABB tree: a binary bounding-volume hierarchy over boxes that supports incremental
// insert, remove and move. Insertion picks the sibling by the surface-area heuristic (the cost of a
// tree is the summed area of its inner nodes: Goldsmith and Salmon 1987; the branch-and-descend
// variant of Catto's b2DynamicTree, GDC 2019 "Dynamic BVH"), and every node on the way back up is
// rebalanced by an AVL-style rotation when its subtrees' heights differ by more than a small slack,
// so the height stays logarithmic under any insertion order (see kBalanceSlack for why not strict).
// Nodes live in one array addressed by index (no pointers), with a free list. Each node carries the
// union of its leaves' layer bits (Box2D v3's category bits), so that a traversal with a mask skips
// the subtrees of layers the mask leaves out without testing their boxes.
#pragma once

#include <collide/math.h>

#include <cstdint>
#include <vector>

namespace collide {

class DynamicTree {
 public:
  static constexpr std::int32_t kNull = -1;

  struct Node {
    Aabb box;
    std::int32_t parent = kNull;  // the next free node while on the free list
    std::int32_t child1 = kNull;
    std::int32_t child2 = kNull;
    std::int32_t height = 0;   // 0 for a leaf, -1 for a free node
    std::uint32_t proxy = 0;   // leaves only
    std::uint32_t layers = 0;  // a leaf's layer; an inner node's, the union of its children's

    bool isLeaf() const { return child1 == kNull; }
  };

  // Returns the leaf's node index, stable until the leaf is removed.
  std::int32_t insert(const Aabb& box, std::uint32_t proxy, std::uint32_t layers = ~0u);
  void remove(std::int32_t leaf);
  // Re-inserts the leaf with a new box (keeps its node index).
  void move(std::int32_t leaf, const Aabb& box);
  // Gives the leaf new layer bits (and its ancestors their new unions).
  void setLayers(std::int32_t leaf, std::uint32_t layers);

  const Aabb& box(std::int32_t leaf) const { return nodes_[leaf].box; }
  std::uint32_t proxy(std::int32_t leaf) const { return nodes_[leaf].proxy; }
  std::int32_t root() const { return root_; }
  const Node& node(std::int32_t index) const { return nodes_[index]; }
  int height() const { return root_ == kNull ? 0 : nodes_[root_].height; }
  std::size_t leafCount() const { return leafCount_; }
  std::size_t memoryBytes() const { return nodes_.capacity() * sizeof(Node); }

  // Visits every leaf of a layer in `mask` (every leaf for ~0u) whose box passes `test`, pruning
  // subtrees with no such layer or whose box fails it. `test` must be monotone (a box that contains a passing
  // box passes), so no leaf is wrongly pruned. `visit(node)` returns false to stop. Returns false when
  // stopped. Counts box tests.
  template <typename Test, typename Visit>
  bool traverse(Test&& test, Visit&& visit, std::uint64_t& ioTests, std::uint32_t mask = ~0u) const;

  // Checks parent links, heights, containment of children, layer unions and the leaf count; throws
  // collide::Error.
  void validate() const;
  // Sum of inner-node surface areas divided by the root's: the SAH quality measure of the tree.
  float areaRatio() const;

 private:
  std::int32_t allocateNode();
  void freeNode(std::int32_t index);
  void insertLeaf(std::int32_t leaf);
  void removeLeaf(std::int32_t leaf);
  std::int32_t rebalance(std::int32_t index);
  void refitUpwards(std::int32_t index);

  Array<Node> nodes_;
  std::int32_t root_ = kNull;
  std::int32_t freeList_ = kNull;
  std::size_t leafCount_ = 0;
};

// A traversal stack that lives on the call stack for any balanced tree and spills to the heap for
// a pathological one.
class NodeStack {
 public:
  void push(std::int32_t index) {
    if (size_ < kInline) {
      inline_[size_++] = index;
    } else {
      spill_.push_back(index);
      ++size_;
    }
  }
  std::int32_t pop() {
    --size_;
    if (size_ < kInline) return inline_[size_];
    const std::int32_t index = spill_.back();
    spill_.pop_back();
    return index;
  }
  bool empty() const { return size_ == 0; }

 private:
  static constexpr std::size_t kInline = 128;
  std::int32_t inline_[kInline];
  std::size_t size_ = 0;
  Array<std::int32_t> spill_;
};

template <typename Test, typename Visit>
bool DynamicTree::traverse(Test&& test, Visit&& visit, std::uint64_t& ioTests, std::uint32_t mask) const {
  if (root_ == kNull) return true;
  NodeStack stack;
  stack.push(root_);
  while (!stack.empty()) {
    const Node& n = nodes_[stack.pop()];
    if (mask != ~0u && (n.layers & mask) == 0) continue;  // all layers: layer 0 too (a pair's rule)
    ++ioTests;
    if (!test(n.box)) continue;
    if (n.isLeaf()) {
      if (!visit(n)) return false;
    } else {
      stack.push(n.child1);
      stack.push(n.child2);
    }
  }
  return true;
}

}  // namespace collide
