// Half-space proxy: the surface y = 2 (normal +y, distance 2) with the solid below.
#include <collide/shapes.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include "support/collide_error.h"
#include "support/test_assertions.h"

namespace collide {
namespace {

using ::testing::HasSubstr;

using test::kEps;

using test::expectVecNear;

const Plane kGround{Vec3(0.0f, 1.0f, 0.0f), 2.0f};

TEST(Plane, RayFromAboveHitsTheSurface) {
  const auto straight = rayCast(kGround, Transform{}, Ray{Vec3(1.0f, 5.0f, 1.0f), Vec3(0.0f, -1.0f, 0.0f)});
  ASSERT_TRUE(straight);
  EXPECT_NEAR(straight->distance, 3.0f, kEps);
  expectVecNear(Vec3(0.0f, 1.0f, 0.0f), straight->normal);
  const auto oblique =
      rayCast(kGround, Transform{}, Ray{Vec3(0.0f, 5.0f, 0.0f), glm::normalize(Vec3(1.0f, -1.0f, 0.0f))});
  ASSERT_TRUE(oblique);
  EXPECT_NEAR(oblique->distance, 3.0f * std::sqrt(2.0f), kEps);
  expectVecNear(Vec3(3.0f, 2.0f, 0.0f), oblique->point);
}

TEST(Plane, ParallelAwayAndTooShortRaysMiss) {
  EXPECT_FALSE(rayCast(kGround, Transform{}, Ray{Vec3(0.0f, 5.0f, 0.0f), Vec3(1.0f, 0.0f, 0.0f)}));
  EXPECT_FALSE(rayCast(kGround, Transform{}, Ray{Vec3(0.0f, 5.0f, 0.0f), Vec3(0.0f, 1.0f, 0.0f)}));
  EXPECT_FALSE(rayCast(kGround, Transform{}, Ray{Vec3(0.0f, 5.0f, 0.0f), Vec3(0.0f, -1.0f, 0.0f), 2.9f}));
}

TEST(Plane, RayFromTheSolidSideHitsAtZero) {
  const auto hit = rayCast(kGround, Transform{}, Ray{Vec3(0.0f, 1.0f, 0.0f), Vec3(0.0f, 1.0f, 0.0f)});
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->distance, 0.0f);
  expectVecNear(Vec3(0.0f, -1.0f, 0.0f), hit->normal);
}

TEST(Plane, ClosestPointAndContainment) {
  const SurfacePoint above = closestPoint(kGround, Transform{}, Vec3(1.0f, 5.0f, -1.0f));
  expectVecNear(Vec3(1.0f, 2.0f, -1.0f), above.point);
  EXPECT_NEAR(above.signedDistance, 3.0f, kEps);
  const SurfacePoint below = closestPoint(kGround, Transform{}, Vec3(1.0f, -1.0f, -1.0f));
  EXPECT_NEAR(below.signedDistance, -3.0f, kEps);
  expectVecNear(Vec3(0.0f, 1.0f, 0.0f), below.normal);
  EXPECT_TRUE(containsPoint(kGround, Transform{}, Vec3(100.0f, 1.9f, -50.0f)));
  EXPECT_FALSE(containsPoint(kGround, Transform{}, Vec3(100.0f, 2.1f, -50.0f)));
}

TEST(Plane, TransformMovesAndTurnsTheSurface) {
  // Rotating +y onto -x and moving by (1, 0, 0), at scale 2: the solid is -x * 2 <= ... i.e. the
  // surface x = 1 - 2 * 2 = -3 with the solid at x >= -3.
  const Transform t{Vec3(1.0f, 0.0f, 0.0f), glm::angleAxis(kPi / 2.0f, Vec3(0.0f, 0.0f, 1.0f)), 2.0f};
  const SurfacePoint p = closestPoint(kGround, t, Vec3(-5.0f, 7.0f, 3.0f));
  EXPECT_NEAR(p.signedDistance, 2.0f, 1e-4f);
  expectVecNear(Vec3(-1.0f, 0.0f, 0.0f), p.normal, 1e-5f);
  EXPECT_TRUE(containsPoint(kGround, t, Vec3(-2.9f, 0.0f, 0.0f)));
  EXPECT_FALSE(containsPoint(kGround, t, Vec3(-3.1f, 0.0f, 0.0f)));
}

TEST(Plane, BoundsAreInfiniteExceptBeyondAnAxisAlignedSurface) {
  const Aabb local = localBounds(kGround);
  EXPECT_EQ(local.max.y, 2.0f);
  EXPECT_LE(local.min.y, -1e29f);
  EXPECT_LE(local.min.x, -1e29f);
  EXPECT_GE(local.max.x, 1e29f);
  // Moved up by 1: nothing above y = 3.
  const Aabb moved = worldBounds(kGround, Transform{Vec3(4.0f, 1.0f, 0.0f), Quat(1, 0, 0, 0), 1.0f});
  EXPECT_NEAR(moved.max.y, 3.0f, kEps);
  // Flipped upside down (normal -y, surface y = -2): nothing below y = -2.
  const Aabb flipped = worldBounds(kGround, Transform{Vec3(0.0f), Quat(0, 1, 0, 0), 1.0f});
  EXPECT_NEAR(flipped.min.y, -2.0f, kEps);
  EXPECT_GE(flipped.max.y, 1e29f);
}

TEST(Plane, BoundsOfASlightlyTiltedPlaneContainItsSolid) {
  // Bug: a normal within 1e-6 of an axis (here tilted by 1 mrad) was treated as axis-aligned and
  // the box cut at y = distance, but the solid y <= -0.001 x rises above it for negative x.
  const Plane tilted{glm::normalize(Vec3(0.001f, 1.0f, 0.0f)), 0.0f};
  const Vec3 solidPoint(-1000.0f, 0.5f, 0.0f);
  ASSERT_TRUE(containsPoint(tilted, Transform{}, solidPoint));
  EXPECT_TRUE(localBounds(tilted).contains(solidPoint));
  EXPECT_TRUE(worldBounds(tilted, Transform{}).contains(solidPoint));
}

TEST(Plane, AlmostUnitNormalKeepsThePlaneEquation) {
  // The half-space normal·x <= distance is a 4-vector (lecture, slide 58); normalising it divides
  // both parts, so the surface of (0, 1.0005, 0)·x = 2 stays at y = 2 / 1.0005.
  const Shape plane(Plane{Vec3(0.0f, 1.0005f, 0.0f), 2.0f});
  EXPECT_NEAR(plane.plane().distance, 2.0f / 1.0005f, 1e-6f);
  EXPECT_NEAR(glm::length(plane.plane().normal), 1.0f, 1e-6f);
}

TEST(Plane, HasNoMassAndNoSupport) {
  EXPECT_THAT([] { massProperties(kGround, 1.0f); }, ::collide::test::ReportsError(HasSubstr("plane")));
  EXPECT_THAT([] { support(kGround, Vec3(0.0f, 1.0f, 0.0f)); },
              ::collide::test::ReportsError(HasSubstr("plane")));
  EXPECT_FALSE(Shape(kGround).isConvex());
}

}  // namespace
}  // namespace collide
