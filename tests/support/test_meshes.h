// Meshes built for the tests, independently of the code under test: a box, an icosphere and a
// random-height terrain grid, plus random transforms.
#pragma once

#include <collide/shapes.h>

#include "support/test_random.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <utility>
#include <vector>

namespace collide::test {

// The 12-triangle surface of the box |x| <= h, counter-clockwise seen from outside, with every
// vertex mapped through `place`.
template <class Place>
TriangleMesh boxMesh(const Vec3& h, Place&& place) {
  std::vector<Vec3> vertices;
  for (int i = 0; i < 8; ++i) {
    vertices.push_back(place(Vec3(i & 1 ? h.x : -h.x, i & 2 ? h.y : -h.y, i & 4 ? h.z : -h.z)));
  }
  std::vector<MeshTriangle> triangles;
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;  // u x v = axis
    for (int side = 0; side < 2; ++side) {
      auto corner = [&](int du, int dv) {
        return static_cast<std::uint32_t>((side << axis) | (du << u) | (dv << v));
      };
      std::uint32_t q[4] = {corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1)};  // CCW about +axis
      if (side == 0) std::swap(q[1], q[3]);
      triangles.push_back({{q[0], q[1], q[2]}});
      triangles.push_back({{q[0], q[2], q[3]}});
    }
  }
  return TriangleMesh::fromTriangles(std::move(vertices), std::move(triangles));
}

inline TriangleMesh boxMesh(const Vec3& h) {
  return boxMesh(h, [](const Vec3& p) { return p; });
}

// A unit icosahedron subdivided `levels` times, vertices pushed onto the unit sphere; triangles
// turned to face away from the origin (the surface is star-shaped about it).
inline TriangleMesh icosphere(int levels) {
  const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
  std::vector<Vec3> vertices = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                                {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  for (Vec3& v : vertices) v = glm::normalize(v);
  std::vector<MeshTriangle> triangles = {
      {{0, 11, 5}},  {{0, 5, 1}},  {{0, 1, 7}},  {{0, 7, 10}}, {{0, 10, 11}}, {{1, 5, 9}}, {{5, 11, 4}},
      {{11, 10, 2}}, {{10, 7, 6}}, {{7, 1, 8}},  {{3, 9, 4}},  {{3, 4, 2}},   {{3, 2, 6}}, {{3, 6, 8}},
      {{3, 8, 9}},   {{4, 9, 5}},  {{2, 4, 11}}, {{6, 2, 10}}, {{8, 6, 7}},   {{9, 8, 1}}};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoints;
    auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      const auto key = std::minmax(a, b);
      auto [it, inserted] = midpoints.try_emplace({key.first, key.second}, 0);
      if (inserted) {
        it->second = static_cast<std::uint32_t>(vertices.size());
        vertices.push_back(glm::normalize(vertices[a] + vertices[b]));
      }
      return it->second;
    };
    std::vector<MeshTriangle> finer;
    for (const MeshTriangle& tri : triangles) {
      const std::uint32_t a = tri.v[0], b = tri.v[1], c = tri.v[2];
      const std::uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      finer.push_back({{a, ab, ca}});
      finer.push_back({{b, bc, ab}});
      finer.push_back({{c, ca, bc}});
      finer.push_back({{ab, bc, ca}});
    }
    triangles = std::move(finer);
  }
  for (MeshTriangle& tri : triangles) {
    const Vec3 a = vertices[tri.v[0]], b = vertices[tri.v[1]], c = vertices[tri.v[2]];
    if (glm::dot(glm::cross(b - a, c - a), a + b + c) < 0.0f) std::swap(tri.v[1], tri.v[2]);
  }
  return TriangleMesh::fromTriangles(std::move(vertices), std::move(triangles));
}

// An n x n grid of cells over [0, n * spacing]^2 in x and z, heights y uniform in [0, maxHeight).
inline TriangleMesh terrain(int n, float spacing, float maxHeight, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> height(0.0f, maxHeight);
  std::vector<Vec3> vertices;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) vertices.push_back({i * spacing, height(rng), j * spacing});
  }
  std::vector<MeshTriangle> triangles;
  auto index = [&](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      triangles.push_back({{index(i, j), index(i, j + 1), index(i + 1, j)}});
      triangles.push_back({{index(i + 1, j), index(i, j + 1), index(i + 1, j + 1)}});
    }
  }
  return TriangleMesh::fromTriangles(std::move(vertices), std::move(triangles));
}

}  // namespace collide::test
