// Cylinder proxy, radius 1 and half height 2 along y: mass properties, rays through the side, the
// caps and near the rim, closest points on the side, caps and rim, and support.
#include <collide/shapes.h>
#include <gtest/gtest.h>

#include <cmath>
#include "support/test_assertions.h"

namespace collide {
namespace {

using test::kEps;

using test::expectVecNear;

const Cylinder kCylinder{1.0f, 2.0f};

TEST(Cylinder, MassPropertiesAreTheSolidCylinderFormulas) {
  // V = pi r² L with L = 4; I_axis = m r² / 2, I_transverse = m (3 r² + L²) / 12.
  const MassProperties m = massProperties(kCylinder, 1.5f);
  EXPECT_NEAR(m.volume, 4.0f * kPi, 1e-4f);
  EXPECT_NEAR(m.mass, 6.0f * kPi, 1e-4f);
  EXPECT_NEAR(m.inertia[1][1], m.mass / 2.0f, 1e-4f);
  EXPECT_NEAR(m.inertia[0][0], m.mass * (3.0f + 16.0f) / 12.0f, 1e-4f);
  EXPECT_NEAR(m.inertia[2][2], m.mass * (3.0f + 16.0f) / 12.0f, 1e-4f);
  EXPECT_EQ(m.inertia[0][2], 0.0f);
}

TEST(Cylinder, RaysHitTheSideAndTheCaps) {
  const auto side = rayCast(kCylinder, Transform{}, Ray{Vec3(-5.0f, 1.0f, 0.0f), Vec3(1.0f, 0.0f, 0.0f)});
  ASSERT_TRUE(side);
  EXPECT_NEAR(side->distance, 4.0f, kEps);
  expectVecNear(Vec3(-1.0f, 0.0f, 0.0f), side->normal);
  const auto cap = rayCast(kCylinder, Transform{}, Ray{Vec3(0.5f, 5.0f, 0.0f), Vec3(0.0f, -1.0f, 0.0f)});
  ASSERT_TRUE(cap);
  EXPECT_NEAR(cap->distance, 3.0f, kEps);
  expectVecNear(Vec3(0.0f, 1.0f, 0.0f), cap->normal);
  const auto bottom = rayCast(kCylinder, Transform{}, Ray{Vec3(0.0f, -5.0f, 0.5f), Vec3(0.0f, 1.0f, 0.0f)});
  ASSERT_TRUE(bottom);
  EXPECT_NEAR(bottom->distance, 3.0f, kEps);
  expectVecNear(Vec3(0.0f, -1.0f, 0.0f), bottom->normal);
}

TEST(Cylinder, ObliqueRaysHitTheFaceTheyCrossFirst) {
  // From (-5, 0, 0) rising 1 in 4: reaches x = -1 at y = 1, inside the side.
  const auto side =
      rayCast(kCylinder, Transform{}, Ray{Vec3(-5.0f, 0.0f, 0.0f), glm::normalize(Vec3(1.0f, 0.25f, 0.0f))});
  ASSERT_TRUE(side);
  expectVecNear(Vec3(-1.0f, 1.0f, 0.0f), side->point);
  expectVecNear(Vec3(-1.0f, 0.0f, 0.0f), side->normal);
  // From above and outside the radius: the side crossing would be at y = 3, above the cap, so the
  // ray enters through the cap at x = 0.
  const auto cap =
      rayCast(kCylinder, Transform{}, Ray{Vec3(-3.0f, 5.0f, 0.0f), glm::normalize(Vec3(1.0f, -1.0f, 0.0f))});
  ASSERT_TRUE(cap);
  EXPECT_NEAR(cap->distance, 3.0f * std::sqrt(2.0f), kEps);
  expectVecNear(Vec3(0.0f, 2.0f, 0.0f), cap->point);
  expectVecNear(Vec3(0.0f, 1.0f, 0.0f), cap->normal);
}

TEST(Cylinder, RaysThatPassAboveTheCapOrBesideTheSideMiss) {
  EXPECT_FALSE(rayCast(kCylinder, Transform{}, Ray{Vec3(-5.0f, 2.01f, 0.0f), Vec3(1.0f, 0.0f, 0.0f)}));
  EXPECT_FALSE(rayCast(kCylinder, Transform{}, Ray{Vec3(-5.0f, 0.0f, 1.01f), Vec3(1.0f, 0.0f, 0.0f)}));
  EXPECT_FALSE(rayCast(kCylinder, Transform{}, Ray{Vec3(1.01f, 5.0f, 0.0f), Vec3(0.0f, -1.0f, 0.0f)}));
  // Passes the rim diagonally: crosses the cap's plane at x = -1.2 and the side's at y = 2.2.
  EXPECT_FALSE(
      rayCast(kCylinder, Transform{}, Ray{Vec3(-3.0f, 0.2f, 0.0f), glm::normalize(Vec3(1.0f, 1.0f, 0.0f))}));
  EXPECT_FALSE(rayCast(kCylinder, Transform{}, Ray{Vec3(-5.0f, 0.0f, 0.0f), Vec3(1.0f, 0.0f, 0.0f), 3.9f}));
}

TEST(Cylinder, TangentRayTouchesTheSide) {
  const auto touch = rayCast(kCylinder, Transform{}, Ray{Vec3(-5.0f, 0.0f, 1.0f), Vec3(1.0f, 0.0f, 0.0f)});
  ASSERT_TRUE(touch);
  EXPECT_NEAR(touch->distance, 5.0f, 1e-3f);
  expectVecNear(Vec3(0.0f, 0.0f, 1.0f), touch->normal, 1e-3f);
}

TEST(Cylinder, RayFromInsideHitsAtZero) {
  const auto hit = rayCast(kCylinder, Transform{}, Ray{Vec3(0.5f, 1.9f, 0.0f), Vec3(0.0f, 1.0f, 0.0f)});
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->distance, 0.0f);
  expectVecNear(Vec3(0.0f, -1.0f, 0.0f), hit->normal);
}

TEST(Cylinder, ClosestPointOnSideCapAndRim) {
  const Shape c(kCylinder);
  const SurfacePoint side = closestPoint(c, Transform{}, Vec3(0.0f, 1.0f, 3.0f));
  expectVecNear(Vec3(0.0f, 1.0f, 1.0f), side.point);
  expectVecNear(Vec3(0.0f, 0.0f, 1.0f), side.normal);
  EXPECT_NEAR(side.signedDistance, 2.0f, kEps);
  const SurfacePoint cap = closestPoint(c, Transform{}, Vec3(0.5f, -4.0f, 0.0f));
  expectVecNear(Vec3(0.5f, -2.0f, 0.0f), cap.point);
  expectVecNear(Vec3(0.0f, -1.0f, 0.0f), cap.normal);
  EXPECT_NEAR(cap.signedDistance, 2.0f, kEps);
  // Beyond the rim: offset (3, 4) in the (radial, axial) plane from the rim point (1, 2).
  const SurfacePoint rim = closestPoint(c, Transform{}, Vec3(4.0f, 6.0f, 0.0f));
  expectVecNear(Vec3(1.0f, 2.0f, 0.0f), rim.point);
  expectVecNear(Vec3(0.6f, 0.8f, 0.0f), rim.normal);
  EXPECT_NEAR(rim.signedDistance, 5.0f, kEps);
}

TEST(Cylinder, ClosestPointFromInsideLeavesThroughTheNearerOfSideAndCap) {
  const Shape c(kCylinder);
  const SurfacePoint nearSide = closestPoint(c, Transform{}, Vec3(0.9f, 0.0f, 0.0f));
  expectVecNear(Vec3(1.0f, 0.0f, 0.0f), nearSide.point);
  EXPECT_NEAR(nearSide.signedDistance, -0.1f, kEps);
  const SurfacePoint nearCap = closestPoint(c, Transform{}, Vec3(0.0f, 1.95f, 0.3f));
  expectVecNear(Vec3(0.0f, 2.0f, 0.3f), nearCap.point);
  expectVecNear(Vec3(0.0f, 1.0f, 0.0f), nearCap.normal);
  EXPECT_NEAR(nearCap.signedDistance, -0.05f, kEps);
  const SurfacePoint centre = closestPoint(c, Transform{}, Vec3(0.0f));
  EXPECT_NEAR(centre.signedDistance, -1.0f, kEps);
}

TEST(Cylinder, PointJustOutsideTheSideGetsTheRadialNormal) {
  // Bug: the normal was (p - point) / |p - point| with p a few ulps outside, so both vectors were
  // equal up to rounding and the "normal" was rounding noise in any direction.
  for (float angle = 0.1f; angle < 6.2f; angle += 0.37f) {
    const Vec3 radial(std::cos(angle), 0.0f, std::sin(angle));
    Vec3 p = radial * std::nextafter(1.0f, 2.0f) + Vec3(0.0f, 0.3f, 0.0f);
    p.x = std::nextafter(p.x, 2.0f * p.x);
    p.z = std::nextafter(p.z, 2.0f * p.z);
    const SurfacePoint cp = closestPoint(kCylinder, Transform{}, p);
    ASSERT_GT(p.x * p.x + p.z * p.z, 1.0f);
    expectVecNear(radial, cp.normal, 1e-4f);
    EXPECT_NEAR(cp.signedDistance, 0.0f, 1e-5f);
  }
}

TEST(Cylinder, SupportIsOnTheRimOrTheCapCentre) {
  expectVecNear(Vec3(1.0f, 2.0f, 0.0f), support(kCylinder, Vec3(1.0f, 1.0f, 0.0f)));
  expectVecNear(Vec3(std::sqrt(0.5f), 2.0f, std::sqrt(0.5f)), support(kCylinder, Vec3(1.0f, 0.0f, 1.0f)));
  expectVecNear(Vec3(0.0f, -2.0f, 0.0f), support(kCylinder, Vec3(0.0f, -3.0f, 0.0f)));
}

TEST(Cylinder, WorldBoundsOfATiltedCylinderAreExact) {
  // Axis along (sin 30°, cos 30°, 0): x extent h sin 30° + r cos 30°, y extent h cos 30° + r sin 30°,
  // z extent r.
  const Transform t{Vec3(0.0f), glm::angleAxis(-kPi / 6.0f, Vec3(0.0f, 0.0f, 1.0f)), 1.0f};
  const Aabb box = worldBounds(kCylinder, t);
  const float s = 0.5f, c = std::sqrt(3.0f) / 2.0f;
  expectVecNear(Vec3(2.0f * s + c, 2.0f * c + s, 1.0f), box.max, 1e-5f);
}

}  // namespace
}  // namespace collide
