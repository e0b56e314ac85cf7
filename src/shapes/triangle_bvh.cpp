// Top-down binned-SAH construction of a triangle mesh's AABB tree.
#include "shapes/triangle_bvh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace collide::detail {

namespace {

using Node = TriangleMesh::BvhNode;

constexpr int kBinCount = 16;

// Levels a median split needs to bring `count` triangles down to leaves: the smallest L with
// kTriangleBvhMaxLeafSize * 2^L >= count. Each median split lowers it by exactly one.
int medianLevels(std::uint32_t count) {
  int levels = 0;
  std::uint64_t capacity = kTriangleBvhMaxLeafSize;
  while (capacity < count) {
    capacity *= 2;
    ++levels;
  }
  return levels;
}

class Builder {
 public:
  Builder(std::span<const Vec3> vertices, std::span<const MeshTriangle> triangles, int maxDepth,
          TriangleBvh& out)
      : maxDepth_(maxDepth), out_(out) {
    boxes_.reserve(triangles.size());
    centers_.reserve(triangles.size());
    for (const MeshTriangle& t : triangles) {
      Aabb box;
      for (std::uint32_t index : t.v) box.grow(vertices[index]);
      boxes_.push_back(box);
      centers_.push_back(box.center());
    }
    out_.triangleOrder.resize(triangles.size());
    for (std::uint32_t i = 0; i < triangles.size(); ++i) out_.triangleOrder[i] = i;
    out_.nodes.reserve(2 * (triangles.size() / kTriangleBvhMaxLeafSize) + 1);
  }

  // Builds the subtree over triangleOrder[begin, end) and returns its node index.
  std::uint32_t build(std::uint32_t begin, std::uint32_t end, int depth) {
    const auto index = static_cast<std::uint32_t>(out_.nodes.size());
    out_.nodes.push_back({});
    Aabb bounds;
    Aabb centerBounds;
    for (std::uint32_t i = begin; i < end; ++i) {
      bounds.grow(boxes_[out_.triangleOrder[i]]);
      centerBounds.grow(centers_[out_.triangleOrder[i]]);
    }
    const std::uint32_t count = end - begin;
    if (count <= kTriangleBvhMaxLeafSize) {
      out_.nodes[index] = {bounds, begin, count};
      return index;
    }
    std::uint32_t middle = sahSplit(begin, end, centerBounds);
    // Invariant depth + medianLevels(count) <= maxDepth holds at the root (maxDepth is at least
    // medianLevels of all triangles) and is kept by every split we accept; a median split keeps it
    // by construction, so the final depth is bounded whatever the geometry.
    const std::uint32_t larger = std::max(middle - begin, end - middle);
    if (middle == begin || middle == end || depth + 1 + medianLevels(larger) > maxDepth_) {
      middle = medianSplit(begin, end, centerBounds);
    }
    build(begin, middle, depth + 1);
    const std::uint32_t second = build(middle, end, depth + 1);
    out_.nodes[index] = {bounds, second, 0};
    return index;
  }

 private:
  // Returns the partition point of the cheapest binned split, or `begin` when there is none (all
  // centres in one bin). Cost of a split: area(left) * count(left) + area(right) * count(right),
  // the expected number of triangle tests for a random ray hitting the parent.
  std::uint32_t sahSplit(std::uint32_t begin, std::uint32_t end, const Aabb& centerBounds) {
    struct Bin {
      Aabb box;
      std::uint32_t count = 0;
    };
    float bestCost = std::numeric_limits<float>::infinity();
    int bestAxis = -1;
    int bestSplit = 0;  // bins [0, bestSplit) go left
    const Vec3 extent = centerBounds.max - centerBounds.min;
    for (int axis = 0; axis < 3; ++axis) {
      // A zero (or denormal) spread cannot be binned: every centre would land in one bin.
      const float scale = kBinCount / extent[axis];
      if (!(extent[axis] > 0.0f) || !std::isfinite(scale)) continue;
      std::array<Bin, kBinCount> bins{};
      for (std::uint32_t i = begin; i < end; ++i) {
        const std::uint32_t t = out_.triangleOrder[i];
        const int b = binOf(centers_[t][axis], centerBounds.min[axis], scale);
        bins[b].box.grow(boxes_[t]);
        ++bins[b].count;
      }
      // Sweep from the right to get the suffix areas and counts, then from the left.
      std::array<float, kBinCount> rightArea{};
      std::array<std::uint32_t, kBinCount> rightCount{};
      Aabb box;
      std::uint32_t n = 0;
      for (int b = kBinCount - 1; b > 0; --b) {
        box.grow(bins[b].box);
        n += bins[b].count;
        rightArea[b] = box.surfaceArea();
        rightCount[b] = n;
      }
      box = Aabb::empty();
      n = 0;
      for (int split = 1; split < kBinCount; ++split) {
        box.grow(bins[split - 1].box);
        n += bins[split - 1].count;
        if (n == 0 || rightCount[split] == 0) continue;
        const float cost = box.surfaceArea() * static_cast<float>(n) +
                           rightArea[split] * static_cast<float>(rightCount[split]);
        if (cost < bestCost) {
          bestCost = cost;
          bestAxis = axis;
          bestSplit = split;
        }
      }
    }
    if (bestAxis < 0) return begin;
    const float scale = kBinCount / extent[bestAxis];
    const float origin = centerBounds.min[bestAxis];
    auto first = out_.triangleOrder.begin();
    auto middle = std::partition(first + begin, first + end, [&](std::uint32_t t) {
      return binOf(centers_[t][bestAxis], origin, scale) < bestSplit;
    });
    return static_cast<std::uint32_t>(middle - first);
  }

  // Halves the range by count along the axis where the centres spread most (any order when they
  // coincide): the fallback that always makes progress.
  std::uint32_t medianSplit(std::uint32_t begin, std::uint32_t end, const Aabb& centerBounds) {
    const Vec3 extent = centerBounds.max - centerBounds.min;
    int axis = 0;
    if (extent.y > extent[axis]) axis = 1;
    if (extent.z > extent[axis]) axis = 2;
    const std::uint32_t middle = begin + (end - begin) / 2;
    auto first = out_.triangleOrder.begin();
    std::nth_element(first + begin, first + middle, first + end,
                     [&](std::uint32_t a, std::uint32_t b) { return centers_[a][axis] < centers_[b][axis]; });
    return middle;
  }

  static int binOf(float value, float origin, float scale) {
    const int b = static_cast<int>((value - origin) * scale);
    return std::clamp(b, 0, kBinCount - 1);
  }

  int maxDepth_;
  TriangleBvh& out_;
  Array<Aabb> boxes_;
  Array<Vec3> centers_;
};

}  // namespace

TriangleBvh buildTriangleBvh(std::span<const Vec3> vertices, std::span<const MeshTriangle> triangles,
                             int maxDepth) {
  TriangleBvh bvh;
  if (triangles.empty()) return bvh;
  const auto count = static_cast<std::uint32_t>(triangles.size());
  Builder builder(vertices, triangles, std::max(maxDepth, medianLevels(count)), bvh);
  builder.build(0, count, 0);
  return bvh;
}

int triangleBvhDepth(std::span<const TriangleMesh::BvhNode> nodes) {
  if (nodes.empty()) return 0;
  int deepest = 0;
  struct Entry {
    std::uint32_t node;
    int depth;
  };
  Array<Entry> stack{{0, 0}};
  while (!stack.empty()) {
    const Entry e = stack.back();
    stack.pop_back();
    deepest = std::max(deepest, e.depth);
    const Node& node = nodes[e.node];
    if (node.count == 0) {
      stack.push_back({e.node + 1, e.depth + 1});
      stack.push_back({node.firstTriangleOrSecondChild, e.depth + 1});
    }
  }
  return deepest;
}

}  // namespace collide::detail
