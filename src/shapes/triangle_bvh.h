// The bounding volume hierarchy of a triangle mesh: an AABB tree over its triangles, built once
// when the mesh is created (lecture: "bounding volume hierarchies").
#pragma once

#include <collide/shapes.h>

#include <span>
#include <vector>

namespace collide::detail {

// Leaves hold at most this many triangles: few enough that a leaf test is cheap, enough that the
// tree has a quarter as many leaves as triangles.
inline constexpr std::uint32_t kTriangleBvhMaxLeafSize = 4;
// Deepest level (root = 0) the builder produces. The traversals keep one pending node per level on
// a 64-entry stack (TriangleMesh::forEachTriangleOverlapping), so this must stay below 60.
inline constexpr int kTriangleBvhMaxDepth = 56;

struct TriangleBvh {
  // Depth-first: an inner node's first child is at index + 1, its second at
  // firstTriangleOrSecondChild; a leaf covers triangleOrder[first, first + count).
  Array<TriangleMesh::BvhNode> nodes;
  Array<std::uint32_t> triangleOrder;
};

// Binned SAH build (Wald, "On fast construction of SAH-based bounding volume hierarchies", 2007),
// falling back to a median split by count where the SAH finds no split or would make the tree
// deeper than maxDepth (raised to the depth a pure median split needs, if it is lower). Indices
// must be valid (the mesh factory checks them).
TriangleBvh buildTriangleBvh(std::span<const Vec3> vertices, std::span<const MeshTriangle> triangles,
                             int maxDepth = kTriangleBvhMaxDepth);

// The depth of the deepest leaf (root = 0).
int triangleBvhDepth(std::span<const TriangleMesh::BvhNode> nodes);

}  // namespace collide::detail
