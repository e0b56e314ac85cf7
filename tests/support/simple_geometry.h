// Small point sets and meshes that several tests build: a box's corners, a two-triangle fold.
#pragma once

#include <collide/shapes.h>

#include <utility>
#include <vector>

namespace collide::test {

// The eight corners of the box |x - center| <= halfExtents, corner i taking +halfExtents on axis k
// where bit k of i is set.
inline std::vector<Vec3> boxCorners(const Vec3& halfExtents, const Vec3& center = Vec3(0.0f)) {
  std::vector<Vec3> corners;
  for (int i = 0; i < 8; ++i) {
    corners.push_back(center + Vec3(i & 1 ? halfExtents.x : -halfExtents.x,
                                    i & 2 ? halfExtents.y : -halfExtents.y,
                                    i & 4 ? halfExtents.z : -halfExtents.z));
  }
  return corners;
}

// Two triangles meeting at the edge x = 0 (z from -1 to 1): one on y = 0 for x < 0, the other
// rising (slope > 0: a valley, concave seen from above) or falling (slope < 0: a ridge, convex).
inline Shape fold(float slope) {
  std::vector<Vec3> vertices{{-1.0f, 0.0f, -1.0f}, {-1.0f, 0.0f, 1.0f}, {0.0f, 0.0f, 1.0f},
                             {0.0f, 0.0f, -1.0f},  {1.0f, slope, 1.0f}, {1.0f, slope, -1.0f}};
  // Counter-clockwise seen from above: quads (0,1,2,3) and (3,2,4,5).
  std::vector<MeshTriangle> triangles{{{0, 1, 2}}, {{0, 2, 3}}, {{3, 2, 4}}, {{3, 4, 5}}};
  return Shape(TriangleMesh::fromTriangles(std::move(vertices), std::move(triangles)));
}

}  // namespace collide::test
