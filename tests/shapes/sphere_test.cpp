// Sphere proxy: textbook mass properties, rays, closest points and support at hand-checked values.
#include <collide/shapes.h>
#include <gtest/gtest.h>

#include <cmath>
#include "support/test_assertions.h"

namespace collide {
namespace {

using test::kEps;

using test::expectVecNear;

TEST(Sphere, MassPropertiesAreTheSolidBallFormulas) {
  // V = 4/3 pi r^3, I = 2/5 m r^2 about every axis, centre of mass at the centre.
  const MassProperties m = massProperties(Sphere{2.0f}, 3.0f);
  const float volume = 4.0f / 3.0f * kPi * 8.0f;
  EXPECT_NEAR(m.volume, volume, 1e-4f);
  EXPECT_NEAR(m.mass, 3.0f * volume, 1e-3f);
  expectVecNear(Vec3(0.0f), m.centerOfMass);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(m.inertia[i][j], i == j ? 0.4f * m.mass * 4.0f : 0.0f, 1e-3f);
  }
}

TEST(Sphere, RayHitsHeadOnAtTheNearSide) {
  const auto hit = rayCast(Sphere{2.0f}, Transform{}, Ray{Vec3(-5.0f, 0.0f, 0.0f), Vec3(1.0f, 0.0f, 0.0f)});
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->distance, 3.0f, kEps);
  expectVecNear(Vec3(-2.0f, 0.0f, 0.0f), hit->point);
  expectVecNear(Vec3(-1.0f, 0.0f, 0.0f), hit->normal);
}

TEST(Sphere, ObliqueRayHitsWhereTheChordStarts) {
  // The line y = 1 meets x^2 + y^2 = 4 at x = -sqrt(3); the normal there is (-sqrt(3), 1) / 2.
  const auto hit = rayCast(Sphere{2.0f}, Transform{}, Ray{Vec3(-5.0f, 1.0f, 0.0f), Vec3(1.0f, 0.0f, 0.0f)});
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->distance, 5.0f - std::sqrt(3.0f), kEps);
  expectVecNear(Vec3(-std::sqrt(3.0f) / 2.0f, 0.5f, 0.0f), hit->normal);
}

TEST(Sphere, RayUnderTransformScalesAndMoves) {
  // Radius 2 scaled by 1.5 is 3, centred at (10, 0, 0): the ray from the origin enters at x = 7.
  const Transform t{Vec3(10.0f, 0.0f, 0.0f), glm::angleAxis(0.7f, glm::normalize(Vec3(1, 2, 3))), 1.5f};
  const auto hit = rayCast(Sphere{2.0f}, t, Ray{Vec3(0.0f), Vec3(1.0f, 0.0f, 0.0f)});
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->distance, 7.0f, 1e-4f);
  expectVecNear(Vec3(-1.0f, 0.0f, 0.0f), hit->normal, 1e-4f);
}

TEST(Sphere, TangentRayTouchesAndSlightlyWiderRayMisses) {
  const auto touch = rayCast(Sphere{2.0f}, Transform{}, Ray{Vec3(-5.0f, 2.0f, 0.0f), Vec3(1.0f, 0.0f, 0.0f)});
  ASSERT_TRUE(touch);
  EXPECT_NEAR(touch->distance, 5.0f, 1e-3f);
  expectVecNear(Vec3(0.0f, 1.0f, 0.0f), touch->normal, 1e-3f);
  EXPECT_FALSE(rayCast(Sphere{2.0f}, Transform{}, Ray{Vec3(-5.0f, 2.01f, 0.0f), Vec3(1.0f, 0.0f, 0.0f)}));
}

TEST(Sphere, RayFromInsideHitsAtZeroFacingBack) {
  const Vec3 direction = glm::normalize(Vec3(1.0f, -2.0f, 0.5f));
  const auto hit = rayCast(Sphere{2.0f}, Transform{}, Ray{Vec3(0.5f, 0.5f, 0.0f), direction});
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->distance, 0.0f);
  expectVecNear(-direction, hit->normal);
}

TEST(Sphere, RayMissesBehindOrBeyondMaxDistance) {
  EXPECT_FALSE(rayCast(Sphere{2.0f}, Transform{}, Ray{Vec3(5.0f, 0.0f, 0.0f), Vec3(1.0f, 0.0f, 0.0f)}));
  EXPECT_FALSE(
      rayCast(Sphere{2.0f}, Transform{}, Ray{Vec3(-5.0f, 0.0f, 0.0f), Vec3(1.0f, 0.0f, 0.0f), 2.9f}));
  EXPECT_TRUE(
      rayCast(Sphere{2.0f}, Transform{}, Ray{Vec3(-5.0f, 0.0f, 0.0f), Vec3(1.0f, 0.0f, 0.0f), 3.01f}));
}

TEST(Sphere, ClosestPointOutsideInsideAndAtTheCentre) {
  const Shape s(Sphere{2.0f});
  const SurfacePoint out = closestPoint(s, Transform{}, Vec3(0.0f, 0.0f, 5.0f));
  expectVecNear(Vec3(0.0f, 0.0f, 2.0f), out.point);
  expectVecNear(Vec3(0.0f, 0.0f, 1.0f), out.normal);
  EXPECT_NEAR(out.signedDistance, 3.0f, kEps);
  const SurfacePoint in = closestPoint(s, Transform{}, Vec3(0.5f, 0.0f, 0.0f));
  expectVecNear(Vec3(2.0f, 0.0f, 0.0f), in.point);
  EXPECT_NEAR(in.signedDistance, -1.5f, kEps);
  const SurfacePoint centre = closestPoint(s, Transform{}, Vec3(0.0f));
  EXPECT_NEAR(centre.signedDistance, -2.0f, kEps);
  EXPECT_NEAR(glm::length(centre.point), 2.0f, kEps);
  EXPECT_NEAR(glm::length(centre.normal), 1.0f, kEps);
}

TEST(Sphere, SignedDistanceScalesWithTheTransform) {
  const Transform t{Vec3(1.0f, 2.0f, 3.0f), Quat(1.0f, 0.0f, 0.0f, 0.0f), 2.0f};
  const SurfacePoint p = closestPoint(Sphere{1.0f}, t, Vec3(1.0f, 2.0f, 8.0f));
  EXPECT_NEAR(p.signedDistance, 3.0f, kEps);
  expectVecNear(Vec3(1.0f, 2.0f, 5.0f), p.point);
}

TEST(Sphere, SupportIsRadiusAlongTheDirection) {
  expectVecNear(Vec3(std::sqrt(2.0f), std::sqrt(2.0f), 0.0f), support(Sphere{2.0f}, Vec3(3.0f, 3.0f, 0.0f)));
}

TEST(Sphere, WorldBoundsAreCentreAndScaledRadius) {
  const Transform t{Vec3(1.0f, -2.0f, 3.0f), glm::angleAxis(1.0f, Vec3(0.0f, 1.0f, 0.0f)), 2.0f};
  const Aabb box = worldBounds(Sphere{0.5f}, t);
  expectVecNear(Vec3(0.0f, -3.0f, 2.0f), box.min);
  expectVecNear(Vec3(2.0f, -1.0f, 4.0f), box.max);
}

TEST(Sphere, ContainsPointOnAndInsideButNotOutside) {
  EXPECT_TRUE(containsPoint(Sphere{2.0f}, Transform{}, Vec3(0.0f, 1.99f, 0.0f)));
  EXPECT_FALSE(containsPoint(Sphere{2.0f}, Transform{}, Vec3(0.0f, 2.01f, 0.0f)));
}

}  // namespace
}  // namespace collide
