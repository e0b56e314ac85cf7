// Convex hull proxy: mass properties against closed forms, and every query against the Box proxy
// (the hull of a box's corners is that box) or against brute force over the input points.
#include <collide/shapes.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "support/collide_error.h"
#include "support/test_random.h"

#include "support/hull_invariants.h"
#include "support/simple_geometry.h"

#include <cmath>
#include <limits>
#include <random>
#include <vector>

using namespace collide;
using collide::testing_support::isValidHalfEdgeHull;
using ::testing::AllOf;
using ::testing::HasSubstr;

namespace {

using test::boxCorners;

using test::randomPointsOnSphere;

void expectMatrixNear(const Mat3& actual, const Mat3& expected, float tolerance) {
  for (int c = 0; c < 3; ++c) {
    for (int r = 0; r < 3; ++r)
      EXPECT_NEAR(actual[c][r], expected[c][r], tolerance) << "element " << c << "," << r;
  }
}

const Vec3 kBoxHalfExtents(0.5f, 0.3f, 0.2f);

}  // namespace

TEST(ConvexHull, BoxCornersGiveTheBoxTopologyAndMassProperties) {
  std::vector<Vec3> points = boxCorners(kBoxHalfExtents);
  points.push_back(Vec3(0.1f, -0.1f, 0.05f));  // interior
  points.push_back(points[2]);                 // duplicate
  const ConvexHull hull = ConvexHull::fromPoints(points);
  EXPECT_EQ(hull.vertices().size(), 8u);
  EXPECT_EQ(hull.edgeCount(), 12u);
  EXPECT_EQ(hull.faces().size(), 6u);
  for (const ConvexHull::Face& face : hull.faces()) EXPECT_EQ(face.edgeCount, 4u);
  EXPECT_TRUE(isValidHalfEdgeHull(hull, 1e-6f));

  const MassProperties expected = massProperties(Box{kBoxHalfExtents}, 2.5f);
  const MassProperties actual = massProperties(Shape(hull), 2.5f);
  EXPECT_NEAR(actual.volume, expected.volume, 1e-6f);
  EXPECT_NEAR(actual.mass, expected.mass, 1e-5f);
  EXPECT_NEAR(glm::length(actual.centerOfMass), 0.0f, 1e-6f);
  expectMatrixNear(actual.inertia, expected.inertia, 1e-6f);
  EXPECT_EQ(hull.bounds().min, -kBoxHalfExtents);
  EXPECT_EQ(hull.bounds().max, kBoxHalfExtents);
}

TEST(ConvexHull, RegularTetrahedronVolumeAndInertia) {
  // Alternate cube corners: edge a = 2 sqrt 2, volume a^3 / (6 sqrt 2) = 8/3, and the inertia is
  // isotropic, m a^2 / 20 about the centroid.
  const Vec3 offset(0.3f, -0.2f, 1.0f);
  const std::vector<Vec3> points = {Vec3(1, 1, 1) + offset, Vec3(1, -1, -1) + offset,
                                    Vec3(-1, 1, -1) + offset, Vec3(-1, -1, 1) + offset};
  const ConvexHull hull = ConvexHull::fromPoints(points);
  EXPECT_EQ(hull.faces().size(), 4u);
  EXPECT_EQ(hull.edgeCount(), 6u);
  EXPECT_TRUE(isValidHalfEdgeHull(hull, 1e-6f));
  const float volume = 8.0f / 3.0f;
  EXPECT_NEAR(hull.volume(), volume, 1e-5f);
  EXPECT_NEAR(glm::length(hull.centroid() - offset), 0.0f, 1e-6f);
  expectMatrixNear(hull.unitInertia(), Mat3(volume * 8.0f / 20.0f), 1e-5f);
}

TEST(ConvexHull, OctahedronVolumeAndInertia) {
  // |x| + |y| + |z| <= r: volume 4 r^3 / 3, inertia m r^2 / 5 about every axis.
  const float r = 1.5f;
  const std::vector<Vec3> points = {Vec3(r, 0, 0),  Vec3(-r, 0, 0), Vec3(0, r, 0),
                                    Vec3(0, -r, 0), Vec3(0, 0, r),  Vec3(0, 0, -r)};
  const ConvexHull hull = ConvexHull::fromPoints(points);
  EXPECT_EQ(hull.vertices().size(), 6u);
  EXPECT_EQ(hull.faces().size(), 8u);
  EXPECT_EQ(hull.edgeCount(), 12u);
  EXPECT_TRUE(isValidHalfEdgeHull(hull, 1e-6f));
  const float volume = 4.0f / 3.0f * r * r * r;
  EXPECT_NEAR(hull.volume(), volume, 1e-5f);
  expectMatrixNear(hull.unitInertia(), Mat3(volume * r * r / 5.0f), 1e-5f);
  // Each face is at distance r / sqrt 3 from the centre.
  for (const ConvexHull::Face& face : hull.faces())
    EXPECT_NEAR(face.plane.distance, r / std::sqrt(3.0f), 1e-6f);
}

TEST(ConvexHull, SphereCloudHullIsInsideTheSphereAndHoldsEveryPoint) {
  std::mt19937 rng(2024);
  const float radius = 2.0f;
  const std::vector<Vec3> points = randomPointsOnSphere(200, radius, rng);
  const ConvexHull hull = ConvexHull::fromPoints(points);
  const Shape shape(hull);
  EXPECT_TRUE(isValidHalfEdgeHull(hull, 1e-5f));

  // The hull is inscribed in the sphere and contains the ball of its inradius around the centre.
  float inradius = std::numeric_limits<float>::max();
  for (const ConvexHull::Face& face : hull.faces()) inradius = std::min(inradius, face.plane.distance);
  const float sphereVolume = 4.0f / 3.0f * kPi * radius * radius * radius;
  EXPECT_LT(hull.volume(), sphereVolume);
  EXPECT_GT(hull.volume(), sphereVolume * std::pow(inradius / radius, 3.0f));
  EXPECT_GT(inradius, 0.5f * radius);  // 200 points cover the sphere far better than that

  // Monte Carlo volume through the point test: 40000 samples in the bounding cube, 4 sigma.
  std::uniform_real_distribution<float> cube(-radius, radius);
  const int samples = 40000;
  int inside = 0;
  for (int i = 0; i < samples; ++i) {
    inside += containsPoint(shape, Transform{}, Vec3(cube(rng), cube(rng), cube(rng))) ? 1 : 0;
  }
  const float cubeVolume = 8.0f * radius * radius * radius;
  const float fraction = float(inside) / samples;
  const float sigma = cubeVolume * std::sqrt(fraction * (1.0f - fraction) / samples);
  EXPECT_NEAR(fraction * cubeVolume, hull.volume(), 4.0f * sigma);

  for (const Vec3& p : points) EXPECT_TRUE(containsPoint(shape, Transform{}, p));

  // The support point reaches as far as the farthest input point, in every direction.
  for (int i = 0; i < 1000; ++i) {
    const Vec3 d = test::randomUnitVector(rng) * 3.0f;
    float best = -std::numeric_limits<float>::max();
    for (const Vec3& p : points) best = std::max(best, glm::dot(p, d));
    EXPECT_NEAR(glm::dot(support(shape, d), d), best, 1e-5f);
  }
}

TEST(ConvexHull, RayCastsAgreeWithTheBox) {
  std::mt19937 rng(5);
  const Shape box(Box{kBoxHalfExtents});
  const Shape hull(ConvexHull::fromPoints(boxCorners(kBoxHalfExtents)));
  std::uniform_real_distribution<float> spread(-1.5f, 1.5f);
  int hits = 0;
  for (int i = 0; i < 1000; ++i) {
    const Transform t = test::randomTransform(rng);
    // From a random point towards a random point in or near the box: most hit; some start inside,
    // some stop short.
    const Vec3 from = t.applyToPoint(Vec3(spread(rng), spread(rng), spread(rng)));
    const Vec3 to = t.applyToPoint(kBoxHalfExtents * Vec3(spread(rng), spread(rng), spread(rng)));
    if (glm::length(to - from) < 1e-3f) continue;
    const Ray ray{from, glm::normalize(to - from), i % 4 == 0 ? 0.5f * glm::length(to - from) : 100.0f};
    const auto expected = rayCast(box, t, ray);
    const auto actual = rayCast(hull, t, ray);
    ASSERT_EQ(actual.has_value(), expected.has_value()) << "ray " << i;
    if (!expected) continue;
    ++hits;
    EXPECT_NEAR(actual->distance, expected->distance, 1e-4f) << "ray " << i;
    EXPECT_NEAR(glm::length(actual->point - expected->point), 0.0f, 1e-4f) << "ray " << i;
    EXPECT_NEAR(glm::length(actual->normal - expected->normal), 0.0f, 1e-4f) << "ray " << i;
  }
  EXPECT_GT(hits, 400);
  EXPECT_LT(hits, 950);
}

TEST(ConvexHull, ClosestPointsAndContainmentAgreeWithTheBox) {
  std::mt19937 rng(6);
  const Shape box(Box{kBoxHalfExtents});
  const Shape hull(ConvexHull::fromPoints(boxCorners(kBoxHalfExtents)));
  std::uniform_real_distribution<float> spread(-1.0f, 1.0f);
  int inside = 0;
  for (int i = 0; i < 1000; ++i) {
    const Transform t = test::randomTransform(rng);
    const Vec3 p = t.applyToPoint(Vec3(spread(rng), spread(rng), spread(rng)));
    const bool boxContains = containsPoint(box, t, p);
    EXPECT_EQ(containsPoint(hull, t, p), boxContains) << "point " << i;
    inside += boxContains ? 1 : 0;
    const SurfacePoint expected = closestPoint(box, t, p);
    const SurfacePoint actual = closestPoint(hull, t, p);
    EXPECT_NEAR(actual.signedDistance, expected.signedDistance, 1e-4f) << "point " << i;
    EXPECT_NEAR(glm::length(actual.point - expected.point), 0.0f, 1e-4f) << "point " << i;
    EXPECT_NEAR(glm::length(actual.normal - expected.normal), 0.0f, 1e-3f) << "point " << i;
  }
  EXPECT_GT(inside, 10);
}

TEST(ConvexHull, WorldBoundsAreExact) {
  std::mt19937 rng(8);
  const Shape box(Box{kBoxHalfExtents});
  const Shape hull(ConvexHull::fromPoints(boxCorners(kBoxHalfExtents)));
  EXPECT_EQ(localBounds(hull).max, kBoxHalfExtents);
  for (int i = 0; i < 100; ++i) {
    const Transform t = test::randomTransform(rng);
    const Aabb expected = worldBounds(box, t);
    const Aabb actual = worldBounds(hull, t);
    EXPECT_NEAR(glm::length(actual.min - expected.min), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::length(actual.max - expected.max), 0.0f, 1e-5f);
  }
}

TEST(ConvexHull, FaceVerticesWalkTheFaceCounterClockwise) {
  const ConvexHull hull = ConvexHull::fromPoints(boxCorners(Vec3(1.0f)));
  for (std::uint32_t f = 0; f < hull.faces().size(); ++f) {
    const std::vector<Vec3> loop = hull.faceVertices(f);
    ASSERT_EQ(loop.size(), 4u);
    const Vec3 n = hull.faces()[f].plane.normal;
    for (int i = 0; i < 4; ++i) {
      const Vec3 turn = glm::cross(loop[(i + 1) % 4] - loop[i], loop[(i + 2) % 4] - loop[(i + 1) % 4]);
      EXPECT_NEAR(glm::dot(turn, n), 4.0f, 1e-5f);  // unit-square... side 2: |turn| = 4, along n
    }
  }
  EXPECT_THAT([&] { (void)hull.faceVertices(6); },
              ::collide::test::ReportsError(HasSubstr("face index 6 out of range")));
}

TEST(ConvexHull, RejectsBadPointSets) {
  const std::vector<Vec3> three = {Vec3(0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  EXPECT_THAT([&] { ConvexHull::fromPoints(three); },
              ::collide::test::ReportsError(
                  AllOf(HasSubstr("convex_hull: need at least 4 points"), HasSubstr("got 3"))));
  EXPECT_THAT([] { ConvexHull::fromPoints({}); },
              ::collide::test::ReportsError(AllOf(HasSubstr("at least 4 points"), HasSubstr("got 0"))));

  std::vector<Vec3> points = boxCorners(Vec3(1.0f));
  points[5].y = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THAT([&] { ConvexHull::fromPoints(points); },
              ::collide::test::ReportsError(HasSubstr("point 5 is not finite")));
  points[5].y = std::numeric_limits<float>::infinity();
  EXPECT_THAT([&] { ConvexHull::fromPoints(points); },
              ::collide::test::ReportsError(HasSubstr("point 5 is not finite")));

  // Coplanar, even when far from the origin and tilted; and within float noise of a plane.
  std::vector<Vec3> coplanar;
  const Vec3 u = glm::normalize(Vec3(1, 2, 3)), v = glm::normalize(glm::cross(u, Vec3(0, 0, 1)));
  for (int i = 0; i < 10; ++i) coplanar.push_back(Vec3(100, 50, -20) + float(i % 3) * u + float(i / 3) * v);
  EXPECT_THAT([&] { ConvexHull::fromPoints(coplanar); },
              ::collide::test::ReportsError(HasSubstr("convex_hull: points are coplanar")));
  const std::vector<Vec3> square = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 1e-8f)};
  EXPECT_THAT([&] { ConvexHull::fromPoints(square); }, ::collide::test::ReportsError(HasSubstr("coplanar")));

  std::vector<Vec3> collinear;
  for (int i = 0; i < 6; ++i) collinear.push_back(Vec3(1, 2, 3) * float(i));
  EXPECT_THAT([&] { ConvexHull::fromPoints(collinear); },
              ::collide::test::ReportsError(HasSubstr("collinear")));

  const std::vector<Vec3> identical(5, Vec3(3, 4, 5));
  EXPECT_THAT([&] { ConvexHull::fromPoints(identical); },
              ::collide::test::ReportsError(HasSubstr("identical")));
}

// The edge list the separating-axis test walks: every edge exactly once, as its smaller half-edge,
// with that half-edge's end points and the faces on either side; Euler's V - E + F = 2 holds.
TEST(ConvexHull, EdgeListNamesEveryEdgeOnceWithItsEndsAndFaces) {
  std::mt19937 rng(7);
  for (const ConvexHull& hull : {ConvexHull::fromPoints(boxCorners(kBoxHalfExtents)),
                                 ConvexHull::fromPoints(randomPointsOnSphere(12, 0.5f, rng)),
                                 ConvexHull::fromPoints(randomPointsOnSphere(100, 1.0f, rng))}) {
    const auto halfEdges = hull.halfEdges();
    ASSERT_EQ(hull.edges().size(), hull.edgeCount());
    EXPECT_EQ(hull.vertices().size() + hull.faces().size(), hull.edges().size() + 2);
    std::vector<int> seen(halfEdges.size(), 0);
    std::uint32_t previous = 0;
    for (std::size_t i = 0; i < hull.edges().size(); ++i) {
      const ConvexHull::Edge& edge = hull.edges()[i];
      const ConvexHull::HalfEdge& half = halfEdges[edge.halfEdge];
      EXPECT_LT(edge.halfEdge, half.twin);
      if (i > 0) {
        EXPECT_GT(edge.halfEdge, previous);  // in half-edge order
      }
      previous = edge.halfEdge;
      EXPECT_EQ(edge.origin, half.origin);
      EXPECT_EQ(edge.end, halfEdges[half.next].origin);
      EXPECT_EQ(edge.face1, half.face);
      EXPECT_EQ(edge.face2, halfEdges[half.twin].face);
      ++seen[edge.halfEdge];
      ++seen[half.twin];
    }
    for (const int count : seen) EXPECT_EQ(count, 1);
  }
}
