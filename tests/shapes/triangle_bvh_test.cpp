#include "shapes/triangle_bvh.h"
#include "support/test_meshes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

using namespace collide;
using namespace collide::detail;

namespace {

// Checks the layout promised in triangle_bvh.h and returns the depth.
void expectValidBvh(const TriangleBvh& bvh, std::span<const Vec3> vertices,
                    std::span<const MeshTriangle> triangles) {
  ASSERT_FALSE(bvh.nodes.empty());
  ASSERT_EQ(bvh.triangleOrder.size(), triangles.size());
  std::vector<int> seen(triangles.size(), 0);
  // Walk from the root; every node must be reached exactly once.
  std::vector<int> reached(bvh.nodes.size(), 0);
  std::vector<std::uint32_t> stack{0};
  while (!stack.empty()) {
    const std::uint32_t index = stack.back();
    stack.pop_back();
    ASSERT_LT(index, bvh.nodes.size());
    ++reached[index];
    const TriangleMesh::BvhNode& node = bvh.nodes[index];
    if (node.count > 0) {
      EXPECT_LE(node.count, kTriangleBvhMaxLeafSize);
      ASSERT_LE(node.firstTriangleOrSecondChild + node.count, bvh.triangleOrder.size());
      for (std::uint32_t i = 0; i < node.count; ++i) {
        const std::uint32_t t = bvh.triangleOrder[node.firstTriangleOrSecondChild + i];
        ASSERT_LT(t, triangles.size());
        ++seen[t];
        for (std::uint32_t v : triangles[t].v) EXPECT_TRUE(node.bounds.contains(vertices[v]));
      }
    } else {
      const std::uint32_t first = index + 1, second = node.firstTriangleOrSecondChild;
      ASSERT_GT(second, first);  // depth-first: the first subtree sits between the two
      ASSERT_LT(second, bvh.nodes.size());
      EXPECT_TRUE(node.bounds.contains(bvh.nodes[first].bounds));
      EXPECT_TRUE(node.bounds.contains(bvh.nodes[second].bounds));
      stack.push_back(first);
      stack.push_back(second);
    }
  }
  for (std::size_t t = 0; t < seen.size(); ++t) EXPECT_EQ(seen[t], 1) << "triangle " << t;
  for (std::size_t n = 0; n < reached.size(); ++n) EXPECT_EQ(reached[n], 1) << "node " << n;
  EXPECT_LT(triangleBvhDepth(bvh.nodes), 60);
}

TriangleBvh buildFromMesh(const TriangleMesh& mesh) {
  return buildTriangleBvh(mesh.vertices(), mesh.triangles());
}

}  // namespace

TEST(TriangleBvh, TerrainTreeIsValidAndShallow) {
  const TriangleMesh mesh = test::terrain(64, 1.0f, 5.0f, 3);
  const TriangleBvh bvh = buildFromMesh(mesh);
  expectValidBvh(bvh, mesh.vertices(), mesh.triangles());
  // 8192 triangles in leaves of <= 4: a balanced tree has 11 levels; SAH on a grid stays close.
  EXPECT_LE(triangleBvhDepth(bvh.nodes), 16);
  // The mesh keeps exactly the tree the builder makes.
  ASSERT_EQ(mesh.bvh().size(), bvh.nodes.size());
  EXPECT_TRUE(std::equal(bvh.triangleOrder.begin(), bvh.triangleOrder.end(), mesh.triangleOrder().begin()));
}

TEST(TriangleBvh, RandomTriangleSoupTreeIsValid) {
  std::mt19937 rng(5);
  std::vector<Vec3> vertices;
  std::vector<MeshTriangle> triangles;
  for (std::uint32_t i = 0; i < 3000; ++i) {
    const Vec3 center = test::randomPoint(rng, -50.0f, 50.0f);
    for (int k = 0; k < 3; ++k) vertices.push_back(center + test::randomPoint(rng, -2.0f, 2.0f));
    triangles.push_back({{3 * i, 3 * i + 1, 3 * i + 2}});
  }
  expectValidBvh(buildTriangleBvh(vertices, triangles), vertices, triangles);
}

TEST(TriangleBvh, TenThousandTinyTrianglesInALineStayShallow) {
  std::vector<Vec3> vertices;
  std::vector<MeshTriangle> triangles;
  for (std::uint32_t i = 0; i < 10000; ++i) {
    const Vec3 base(0.01f * static_cast<float>(i), 0.0f, 0.0f);
    vertices.push_back(base);
    vertices.push_back(base + Vec3(0.001f, 0.0f, 0.0f));
    vertices.push_back(base + Vec3(0.0f, 0.001f, 0.0f));
    triangles.push_back({{3 * i, 3 * i + 1, 3 * i + 2}});
  }
  // Through the mesh factory, which must accept them (their area is tiny but not degenerate).
  const TriangleMesh mesh = TriangleMesh::fromTriangles(vertices, triangles);
  expectValidBvh(buildFromMesh(mesh), mesh.vertices(), mesh.triangles());
  EXPECT_LT(triangleBvhDepth(mesh.bvh()), 60);
}

TEST(TriangleBvh, CoincidentCentresFallBackToMedianSplit) {
  // 5000 different triangles with the same box centre: no binned split exists.
  std::mt19937 rng(9);
  std::vector<Vec3> vertices;
  std::vector<MeshTriangle> triangles;
  for (std::uint32_t i = 0; i < 5000; ++i) {
    const Vec3 d = test::randomUnitVector(rng);
    vertices.push_back(d);
    vertices.push_back(-d);
    // |p_i| <= |d_i|, so the box is exactly [-|d|, |d|] and its centre exactly 0.
    vertices.push_back(0.5f * Vec3(d.x, -d.y, d.z));
    triangles.push_back({{3 * i, 3 * i + 1, 3 * i + 2}});
  }
  const TriangleBvh bvh = buildTriangleBvh(vertices, triangles);
  expectValidBvh(bvh, vertices, triangles);
  // Median splits halve the count: ceil(log2(5000 / 4)) = 11 levels.
  EXPECT_LE(triangleBvhDepth(bvh.nodes), 11);
}

TEST(TriangleBvh, DepthLimitOverridesTheSahAndStillBuildsAValidTree) {
  // Clustered, heavy-tailed positions make the SAH tree unbalanced; a depth limit just above the
  // balanced depth (ceil(log2(10000 / 4)) = 12) must be met by switching to median splits.
  std::mt19937 rng(10);
  std::lognormal_distribution<float> spread(0.0f, 2.0f);
  std::vector<Vec3> vertices;
  std::vector<MeshTriangle> triangles;
  for (std::uint32_t i = 0; i < 10000; ++i) {
    const Vec3 center = spread(rng) * test::randomUnitVector(rng);
    for (int k = 0; k < 3; ++k) vertices.push_back(center + test::randomPoint(rng, -0.05f, 0.05f));
    triangles.push_back({{3 * i, 3 * i + 1, 3 * i + 2}});
  }
  const TriangleBvh free = buildTriangleBvh(vertices, triangles);
  expectValidBvh(free, vertices, triangles);
  ASSERT_GT(triangleBvhDepth(free.nodes), 13) << "the limit below would not bind";
  const TriangleBvh limited = buildTriangleBvh(vertices, triangles, 13);
  expectValidBvh(limited, vertices, triangles);
  EXPECT_LE(triangleBvhDepth(limited.nodes), 13);
  // A limit below the balanced depth is raised to it, not violated.
  EXPECT_EQ(triangleBvhDepth(buildTriangleBvh(vertices, triangles, 3).nodes), 12);
}

TEST(TriangleBvh, ForEachTriangleOverlappingMatchesBruteForce) {
  const TriangleMesh mesh = test::terrain(64, 1.0f, 5.0f, 21);
  std::vector<Aabb> triangleBoxes;
  for (std::uint32_t t = 0; t < mesh.triangles().size(); ++t) {
    Aabb box;
    for (const Vec3& v : mesh.triangle(t)) box.grow(v);
    triangleBoxes.push_back(box);
  }
  std::mt19937 rng(4);
  std::uniform_real_distribution<float> size(0.0f, 12.0f);
  std::size_t total = 0;
  for (int query = 0; query < 300; ++query) {
    const Vec3 center = test::randomPoint(rng, -4.0f, 68.0f);
    const Aabb box = Aabb::fromCenterHalfExtents(center, Vec3(size(rng), size(rng), size(rng)));
    std::vector<std::uint32_t> found;
    mesh.forEachTriangleOverlapping(box, [&](std::uint32_t t) { found.push_back(t); });
    std::vector<std::uint32_t> expected;
    for (std::uint32_t t = 0; t < triangleBoxes.size(); ++t) {
      if (triangleBoxes[t].overlaps(box)) expected.push_back(t);
    }
    std::vector<std::uint32_t> filtered = found;
    std::sort(filtered.begin(), filtered.end());
    EXPECT_EQ(std::adjacent_find(filtered.begin(), filtered.end()), filtered.end()) << "reported twice";
    EXPECT_EQ(filtered, expected);
    total += expected.size();
  }
  EXPECT_GT(total, 1000u);
}
