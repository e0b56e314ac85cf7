// A flat tessellated floor for mesh tests, on its own so that any test can include it without the
// random helpers of test_meshes.h.
#pragma once

#include <collide/shapes.h>

#include <cstdint>
#include <utility>
#include <vector>

namespace collide::test {

// An n x n grid of unit quads on y = 0 centred on the origin, two triangles each, counter-clockwise
// seen from +y (a flat tessellated floor: every inner edge is shared by coplanar triangles).
inline TriangleMesh flatGrid(int n) {
  std::vector<Vec3> vertices;
  std::vector<MeshTriangle> triangles;
  const float offset = 0.5f * float(n);
  for (int z = 0; z <= n; ++z) {
    for (int x = 0; x <= n; ++x) vertices.emplace_back(float(x) - offset, 0.0f, float(z) - offset);
  }
  auto index = [&](int x, int z) { return static_cast<std::uint32_t>(z * (n + 1) + x); };
  for (int z = 0; z < n; ++z) {
    for (int x = 0; x < n; ++x) {
      triangles.push_back({{index(x, z), index(x, z + 1), index(x + 1, z + 1)}});
      triangles.push_back({{index(x, z), index(x + 1, z + 1), index(x + 1, z)}});
    }
  }
  return TriangleMesh::fromTriangles(std::move(vertices), std::move(triangles));
}

}  // namespace collide::test
