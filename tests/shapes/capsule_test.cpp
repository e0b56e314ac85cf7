// Capsule proxy: mass properties from the second-moment integrals (an independent derivation of the
// hemisphere terms), rays through the side and the end caps, closest points and support.
#include <collide/shapes.h>
#include <gtest/gtest.h>

#include <cmath>
#include "support/test_assertions.h"

namespace collide {
namespace {

using test::kEps;

using test::expectVecNear;

// Second moments ∫x², ∫y², ∫z² of a capsule (radius r, half height h, axis y), in double, summed
// part by part: the cylinder, and the two hemispheres written as a ball split at its equator and
// shifted by ±h. For the upper hemisphere H (volume 2πr³/3, first moment ∫y' = πr⁴/4):
// ∫(h + y')² = h² V_H + 2h ∫y' + ½ ∫_ball y'², and ∫_ball y'² = 4πr⁵/15.
struct CapsuleMoments {
  double volume, xx, yy, zz;
};
CapsuleMoments capsuleMoments(double r, double h) {
  const double pi = 3.14159265358979323846;
  const double ballSecond = 4.0 * pi * std::pow(r, 5) / 15.0;
  const double hemisphereVolume = 2.0 * pi * r * r * r / 3.0;
  const double hemisphereFirst = pi * std::pow(r, 4) / 4.0;
  CapsuleMoments m;
  m.volume = pi * r * r * 2.0 * h + 2.0 * hemisphereVolume;
  const double cylinderRadial = 2.0 * h * pi * std::pow(r, 4) / 4.0;  // ∫x² over the cylinder
  const double cylinderAxial = pi * r * r * std::pow(2.0 * h, 3) / 12.0;
  m.xx = cylinderRadial + ballSecond;  // both hemispheres together are one ball in x and z
  m.zz = m.xx;
  m.yy = cylinderAxial + 2.0 * (h * h * hemisphereVolume + 2.0 * h * hemisphereFirst + 0.5 * ballSecond);
  return m;
}

TEST(Capsule, MassPropertiesMatchTheSecondMomentIntegrals) {
  for (const auto& [r, h] : {std::pair{0.5f, 1.0f}, std::pair{1.0f, 0.1f}, std::pair{0.2f, 3.0f}}) {
    const float density = 2.0f;
    const MassProperties m = massProperties(Capsule{r, h}, density);
    const CapsuleMoments moments = capsuleMoments(r, h);
    const double scale = density * moments.volume * (r + h) * (r + h);  // a typical inertia
    EXPECT_NEAR(m.volume, moments.volume, 1e-5 * moments.volume) << r << " " << h;
    EXPECT_NEAR(m.mass, density * moments.volume, 1e-5 * density * moments.volume);
    expectVecNear(Vec3(0.0f), m.centerOfMass);
    // I_xx = ∫(y² + z²), I_yy = ∫(x² + z²).
    EXPECT_NEAR(m.inertia[0][0], density * (moments.yy + moments.zz), 1e-5 * scale) << r << " " << h;
    EXPECT_NEAR(m.inertia[1][1], density * (moments.xx + moments.zz), 1e-5 * scale) << r << " " << h;
    EXPECT_NEAR(m.inertia[2][2], density * (moments.xx + moments.yy), 1e-5 * scale) << r << " " << h;
    EXPECT_EQ(m.inertia[0][1], 0.0f);
    EXPECT_EQ(m.inertia[1][2], 0.0f);
    EXPECT_EQ(m.inertia[0][2], 0.0f);
  }
}

TEST(Capsule, ShortCapsuleHasTheBallsMassProperties) {
  const MassProperties m = massProperties(Capsule{1.0f, 1e-6f}, 1.0f);
  const float ballMass = 4.0f / 3.0f * kPi;
  EXPECT_NEAR(m.mass, ballMass, 1e-4f);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(m.inertia[i][i], 0.4f * ballMass, 1e-4f);
}

const Capsule kCapsule{0.5f, 1.0f};

TEST(Capsule, RayHitsTheSide) {
  const auto hit = rayCast(kCapsule, Transform{}, Ray{Vec3(-3.0f, 0.3f, 0.0f), Vec3(1.0f, 0.0f, 0.0f)});
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->distance, 2.5f, kEps);
  expectVecNear(Vec3(-1.0f, 0.0f, 0.0f), hit->normal);
}

TEST(Capsule, DiagonalRayHitsTheSide) {
  // x = -2 + s, y = -1 + s with s = t / sqrt(2): the side x = -0.5 at s = 1.5, y = 0.5.
  const auto hit =
      rayCast(kCapsule, Transform{}, Ray{Vec3(-2.0f, -1.0f, 0.0f), glm::normalize(Vec3(1.0f, 1.0f, 0.0f))});
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->distance, 1.5f * std::sqrt(2.0f), kEps);
  expectVecNear(Vec3(-0.5f, 0.5f, 0.0f), hit->point);
  expectVecNear(Vec3(-1.0f, 0.0f, 0.0f), hit->normal);
}

TEST(Capsule, RayHitsTheEndCapPoleAndAnOffCentreCapPoint) {
  const auto pole = rayCast(kCapsule, Transform{}, Ray{Vec3(0.0f, 5.0f, 0.0f), Vec3(0.0f, -1.0f, 0.0f)});
  ASSERT_TRUE(pole);
  EXPECT_NEAR(pole->distance, 3.5f, kEps);
  expectVecNear(Vec3(0.0f, 1.0f, 0.0f), pole->normal);
  // At y = 1.3 the upper end sphere (centre y = 1) has half-width sqrt(0.25 - 0.09) = 0.4.
  const auto cap = rayCast(kCapsule, Transform{}, Ray{Vec3(-3.0f, 1.3f, 0.0f), Vec3(1.0f, 0.0f, 0.0f)});
  ASSERT_TRUE(cap);
  EXPECT_NEAR(cap->distance, 2.6f, kEps);
  expectVecNear(Vec3(-0.8f, 0.6f, 0.0f), cap->normal);
  // The lower cap, from below and to the side.
  const auto lower = rayCast(kCapsule, Transform{}, Ray{Vec3(0.3f, -5.0f, 0.0f), Vec3(0.0f, 1.0f, 0.0f)});
  ASSERT_TRUE(lower);
  EXPECT_NEAR(lower->distance, 4.0f - 0.4f, kEps);
  expectVecNear(Vec3(0.6f, -0.8f, 0.0f), lower->normal);
}

TEST(Capsule, TangentRayTouchesTheSideAndAWiderOneMisses) {
  const auto touch = rayCast(kCapsule, Transform{}, Ray{Vec3(-3.0f, 0.0f, 0.5f), Vec3(1.0f, 0.0f, 0.0f)});
  ASSERT_TRUE(touch);
  EXPECT_NEAR(touch->distance, 3.0f, 1e-3f);
  expectVecNear(Vec3(0.0f, 0.0f, 1.0f), touch->normal, 1e-3f);
  EXPECT_FALSE(rayCast(kCapsule, Transform{}, Ray{Vec3(-3.0f, 0.0f, 0.51f), Vec3(1.0f, 0.0f, 0.0f)}));
  EXPECT_FALSE(rayCast(kCapsule, Transform{}, Ray{Vec3(-3.0f, 1.51f, 0.0f), Vec3(1.0f, 0.0f, 0.0f)}));
}

TEST(Capsule, RayFromInsideHitsAtZeroAndBeyondMaxDistanceMisses) {
  const auto inside = rayCast(kCapsule, Transform{}, Ray{Vec3(0.0f, 1.2f, 0.1f), Vec3(0.0f, 0.0f, 1.0f)});
  ASSERT_TRUE(inside);
  EXPECT_EQ(inside->distance, 0.0f);
  expectVecNear(Vec3(0.0f, 0.0f, -1.0f), inside->normal);
  EXPECT_FALSE(rayCast(kCapsule, Transform{}, Ray{Vec3(-3.0f, 0.0f, 0.0f), Vec3(1.0f, 0.0f, 0.0f), 2.4f}));
  EXPECT_FALSE(rayCast(kCapsule, Transform{}, Ray{Vec3(-3.0f, 0.0f, 0.0f), Vec3(-1.0f, 0.0f, 0.0f)}));
}

TEST(Capsule, RayUnderRotationLaysTheCapsuleAlongX) {
  // Rotating +y onto +x: the capsule spans x in [-3, 3] at scale 2 (half height 2 + radius 1).
  const Transform t{Vec3(0.0f), glm::angleAxis(-kPi / 2.0f, Vec3(0.0f, 0.0f, 1.0f)), 2.0f};
  const auto hit = rayCast(kCapsule, t, Ray{Vec3(-10.0f, 0.0f, 0.0f), Vec3(1.0f, 0.0f, 0.0f)});
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->distance, 7.0f, 1e-4f);
  expectVecNear(Vec3(-1.0f, 0.0f, 0.0f), hit->normal, 1e-4f);
}

TEST(Capsule, ClosestPointOnSideCapAndInside) {
  const Shape s(kCapsule);
  const SurfacePoint side = closestPoint(s, Transform{}, Vec3(2.0f, 0.5f, 0.0f));
  expectVecNear(Vec3(0.5f, 0.5f, 0.0f), side.point);
  expectVecNear(Vec3(1.0f, 0.0f, 0.0f), side.normal);
  EXPECT_NEAR(side.signedDistance, 1.5f, kEps);
  const SurfacePoint pole = closestPoint(s, Transform{}, Vec3(0.0f, 3.0f, 0.0f));
  expectVecNear(Vec3(0.0f, 1.5f, 0.0f), pole.point);
  EXPECT_NEAR(pole.signedDistance, 1.5f, kEps);
  // Off the axis above the segment's end: the nearest point is on the end sphere.
  const SurfacePoint cap = closestPoint(s, Transform{}, Vec3(1.0f, 2.0f, 0.0f));
  const Vec3 n = glm::normalize(Vec3(1.0f, 1.0f, 0.0f));
  expectVecNear(Vec3(0.0f, 1.0f, 0.0f) + 0.5f * n, cap.point);
  expectVecNear(n, cap.normal);
  EXPECT_NEAR(cap.signedDistance, std::sqrt(2.0f) - 0.5f, kEps);
  const SurfacePoint inside = closestPoint(s, Transform{}, Vec3(0.2f, -0.5f, 0.0f));
  EXPECT_NEAR(inside.signedDistance, -0.3f, kEps);
  expectVecNear(Vec3(1.0f, 0.0f, 0.0f), inside.normal);
  const SurfacePoint axis = closestPoint(s, Transform{}, Vec3(0.0f, 0.3f, 0.0f));
  EXPECT_NEAR(axis.signedDistance, -0.5f, kEps);
  EXPECT_NEAR(glm::length(axis.point - Vec3(0.0f, 0.3f, 0.0f)), 0.5f, kEps);
}

TEST(Capsule, SupportIsTheEndSphereAlongTheDirection) {
  const Vec3 n = glm::normalize(Vec3(1.0f, 1.0f, 0.0f));
  expectVecNear(Vec3(0.0f, 1.0f, 0.0f) + 0.5f * n, support(kCapsule, Vec3(1.0f, 1.0f, 0.0f)));
  expectVecNear(Vec3(0.0f, -1.5f, 0.0f), support(kCapsule, Vec3(0.0f, -2.0f, 0.0f)));
  const Vec3 side = support(kCapsule, Vec3(0.0f, 0.0f, 1.0f));
  EXPECT_NEAR(side.z, 0.5f, kEps);
  EXPECT_NEAR(side.x, 0.0f, kEps);
}

TEST(Capsule, WorldBoundsOfATiltedCapsuleAreExact) {
  // Axis rotated 90° about z lies along -x: the box is [-h-r, h+r] x [-r, r] x [-r, r], shifted.
  const Transform t{Vec3(1.0f, 2.0f, 3.0f), glm::angleAxis(kPi / 2.0f, Vec3(0.0f, 0.0f, 1.0f)), 1.0f};
  const Aabb box = worldBounds(kCapsule, t);
  expectVecNear(Vec3(1.0f - 1.5f, 1.5f, 2.5f), box.min);
  expectVecNear(Vec3(1.0f + 1.5f, 2.5f, 3.5f), box.max);
}

}  // namespace
}  // namespace collide
