// The mesh and compound fallbacks, through their internal entry points (TriangleMesh and Compound
// are built on other branches): triangles as 3-point polytopes, children through the table.
#include <collide/narrowphase.h>
#include <gtest/gtest.h>

#include "narrowphase/pair_functions.h"
#include "support/narrowphase_helpers.h"

using namespace collide;
using namespace collide::test;

TEST(MeshFallback, BoxOnAFlatTwoTriangleFloor) {
  // The square [-2, 2]² at y = 0 as two triangles; a unit cube sunk 0.1 into it.
  const std::vector<std::array<Vec3, 3>> floor = {
      {Vec3(-2, 0, -2), Vec3(-2, 0, 2), Vec3(2, 0, 2)},
      {Vec3(-2, 0, -2), Vec3(2, 0, 2), Vec3(2, 0, -2)},
  };
  Manifold m;
  ASSERT_TRUE(detail::collideTrianglesConvex(floor, Transform::identity(), Box{Vec3(0.5f)},
                                             at({0.3f, 0.4f, 0.2f}), 0.0f, m));
  EXPECT_NEAR(std::abs(m.normal.y), 1.0f, 1e-4f);
  EXPECT_NEAR(m.maxDepth(), 0.1f, 1e-4f);
  // A sphere over the shared diagonal edge touches both triangles; one merged manifold.
  ASSERT_TRUE(detail::collideTrianglesConvex(floor, Transform::identity(), Sphere{0.5f},
                                             at({0.0f, 0.45f, 0.0f}), 0.0f, m));
  EXPECT_NEAR(m.maxDepth(), 0.05f, 1e-4f);
  // Far away: nothing.
  EXPECT_FALSE(detail::collideTrianglesConvex(floor, Transform::identity(), Sphere{0.5f},
                                              at({0.0f, 3.0f, 0.0f}), 0.0f, m));
}

TEST(CompoundFallback, DumbbellOnTheGroundGetsBothEnds) {
  // Two spheres joined (as a compound) lying on the plane y = 0: one contact under each.
  std::vector<Compound::Child> children;
  children.push_back({Shape(Sphere{0.5f}), at({-1.0f, 0.0f, 0.0f})});
  children.push_back({Shape(Sphere{0.5f}), at({1.0f, 0.0f, 0.0f})});
  const Plane ground{{0.0f, 1.0f, 0.0f}, 0.0f};
  Manifold m;
  ASSERT_TRUE(detail::collideChildrenAny(children, at({0.0f, 0.4f, 0.0f}), Shape(ground),
                                         Transform::identity(), 0.0f, m));
  ASSERT_EQ(m.count, 2);
  EXPECT_NEAR(m.normal.y, -1.0f, 1e-6f);  // compound is A, the plane B: from A towards B is down
  for (int i = 0; i < 2; ++i) EXPECT_NEAR(m.points[i].depth, 0.1f, 1e-5f);
  EXPECT_NE(m.points[0].featureId, m.points[1].featureId);
  // Rotated compound: only the lower end touches.
  ASSERT_TRUE(detail::collideChildrenAny(children, at({0.0f, 0.9f, 0.0f}, axisAngle({0, 0, 1}, 30.0f)),
                                         Shape(ground), Transform::identity(), 0.0f, m));
  ASSERT_EQ(m.count, 1);
  EXPECT_NEAR(m.points[0].depth, 0.5f - (0.9f - std::sin(glm::radians(30.0f))), 1e-5f);
}

TEST(ManifoldReduction, KeepsTheDeepestAndTheWidestSpread) {
  // A 5 × 5 grid of contacts with one deep point in the middle: four survive, the deep one among
  // them, and they span the grid's corners' extent.
  std::vector<ContactPoint> candidates;
  for (int x = 0; x < 5; ++x) {
    for (int z = 0; z < 5; ++z) {
      ContactPoint p;
      p.pointOnA = p.pointOnB = Vec3(float(x), 0.0f, float(z));
      p.depth = (x == 2 && z == 2) ? 0.5f : 0.1f;
      candidates.push_back(p);
    }
  }
  Manifold m;
  detail::reduceContacts(candidates, Vec3(0, 1, 0), m);
  ASSERT_EQ(m.count, 4);
  EXPECT_FLOAT_EQ(m.points[0].depth, 0.5f);
  float minX = 1e30f, maxX = -1e30f;
  for (int i = 0; i < 4; ++i) {
    minX = std::min(minX, m.points[i].pointOnA.x);
    maxX = std::max(maxX, m.points[i].pointOnA.x);
  }
  EXPECT_EQ(maxX - minX, 4.0f);
}
