// Hull building: the half-edge structure Qhull's facets turn into, on inputs with known answers.
#include "shapes/hull_builder.h"
#include "support/collide_error.h"

#include "support/hull_invariants.h"
#include "support/simple_geometry.h"
#include "support/test_random.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <random>
#include <vector>

using namespace collide;
using collide::testing_support::isValidHalfEdgeHull;
using ::testing::HasSubstr;

namespace {

using test::boxCorners;

// `count` points on the sphere of `radius`, from the generator seeded `seed`.
std::vector<Vec3> pointsOnSphere(int count, float radius, unsigned seed) {
  std::mt19937 rng(seed);
  return test::randomPointsOnSphere(count, radius, rng);
}

}  // namespace

TEST(HullBuilder, CubeWithInteriorAndDuplicatePointsHasSixQuadFaces) {
  std::vector<Vec3> points = boxCorners(Vec3(1.0f));
  points.push_back(Vec3(0.0f));
  points.push_back(Vec3(0.5f, -0.25f, 0.1f));
  points.push_back(points[3]);  // exact duplicates of corners
  points.push_back(points[5]);
  points.push_back(Vec3(1.0f, 0.0f, 0.0f));  // on a face: not a vertex
  const ConvexHull hull = HullBuilder::build(points);
  EXPECT_EQ(hull.vertices().size(), 8u);
  EXPECT_EQ(hull.edgeCount(), 12u);
  ASSERT_EQ(hull.faces().size(), 6u);
  for (const ConvexHull::Face& face : hull.faces()) {
    EXPECT_EQ(face.edgeCount, 4u);
    // Each face plane is one of the six axis planes at distance 1.
    EXPECT_NEAR(glm::length(face.plane.normal), 1.0f, 1e-6f);
    EXPECT_NEAR(std::abs(face.plane.normal.x) + std::abs(face.plane.normal.y) + std::abs(face.plane.normal.z),
                1.0f, 1e-6f);
    EXPECT_NEAR(face.plane.distance, 1.0f, 1e-6f);
  }
  EXPECT_TRUE(isValidHalfEdgeHull(hull, 1e-5f));
}

TEST(HullBuilder, KeepsOnlyHullVerticesOfARandomCloud) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
  std::vector<Vec3> points;
  for (int i = 0; i < 500; ++i) points.emplace_back(uniform(rng), uniform(rng), uniform(rng));
  const ConvexHull hull = HullBuilder::build(points);
  EXPECT_LT(hull.vertices().size(), points.size());
  EXPECT_TRUE(isValidHalfEdgeHull(hull, 1e-5f));
  // Every hull vertex is an input point.
  for (const Vec3& v : hull.vertices()) {
    EXPECT_TRUE(std::find(points.begin(), points.end(), v) != points.end());
  }
}

TEST(HullBuilder, SphereCloudIsAValidTriangulatedPolyhedron) {
  const std::vector<Vec3> points = pointsOnSphere(200, 1.5f, 11);
  const ConvexHull hull = HullBuilder::build(points);
  // Points in general position on a sphere: all are vertices, every face a triangle, so
  // F = 2V - 4 and E = 3V - 6.
  EXPECT_EQ(hull.vertices().size(), 200u);
  EXPECT_EQ(hull.faces().size(), 2 * 200u - 4);
  EXPECT_EQ(hull.edgeCount(), 3 * 200u - 6);
  EXPECT_TRUE(isValidHalfEdgeHull(hull, 1e-5f));
}

TEST(HullBuilder, FarFromTheOriginKeepsVolumeAndCentroid) {
  const Vec3 center(1000.0f, -2000.0f, 500.0f);
  const ConvexHull hull = HullBuilder::build(boxCorners(Vec3(1.0f, 2.0f, 0.5f), center));
  EXPECT_NEAR(hull.volume(), 8.0f, 8.0f * 1e-4f);
  EXPECT_NEAR(glm::length(hull.centroid() - center), 0.0f, 1e-3f);
  // Box inertia per unit mass about x: (hy^2 + hz^2) / 3.
  EXPECT_NEAR(hull.unitInertia()[0][0], 8.0f * (4.0f + 0.25f) / 3.0f, 1e-2f);
  EXPECT_TRUE(isValidHalfEdgeHull(hull, 1e-3f));
}

TEST(HullBuilder, ThinButSolidSlabBuilds) {
  // 1e-3 thick over a unit square: flat to the eye, but 1000 times the flatness tolerance.
  std::vector<Vec3> points = boxCorners(Vec3(0.5f, 0.5f, 0.0005f));
  const ConvexHull hull = HullBuilder::build(points);
  EXPECT_EQ(hull.faces().size(), 6u);
  EXPECT_NEAR(hull.volume(), 1e-3f, 1e-7f);
  EXPECT_TRUE(isValidHalfEdgeHull(hull, 1e-6f));
}

TEST(HullBuilder, QhullPrintsNothing) {
  // Nearly degenerate input makes Qhull merge facets and talk about precision when allowed to.
  std::vector<Vec3> points = pointsOnSphere(300, 1.0f, 3);
  for (int i = 0; i < 100; ++i) points.push_back(points[i] * (1.0f + 1e-7f));
  ::testing::internal::CaptureStdout();
  ::testing::internal::CaptureStderr();
  const ConvexHull hull = HullBuilder::build(points);
  EXPECT_COLLIDE_ERROR(
      HullBuilder::build(std::vector<Vec3>{Vec3(0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0)}));
  const std::string out = ::testing::internal::GetCapturedStdout();
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(out, "");
  EXPECT_EQ(err, "");
  EXPECT_TRUE(isValidHalfEdgeHull(hull, 1e-5f));
}

TEST(HullBuilder, SolidPointSetCheckNamesTheCaller) {
  const std::vector<Vec3> three = {Vec3(0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  EXPECT_THAT([&] { requireSolidPointSet("kdop", three); },
              ::collide::test::ReportsError(HasSubstr("kdop: need at least 4 points")));
}
