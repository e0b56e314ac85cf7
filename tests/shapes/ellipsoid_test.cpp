// Ellipsoid proxy: mass properties, rays, support, and closest points checked against a dense
// brute-force sampling of the surface, including the degenerate "waist" of an oblate ellipsoid
// where a point near the centre has its nearest points off the plane it lies in.
#include <collide/shapes.h>
#include <gtest/gtest.h>

#include <cmath>
#include "support/test_assertions.h"

namespace collide {
namespace {

using test::kEps;

using test::expectVecNear;

// The distance from p to the surface, by sampling it on a (theta, phi) grid (in double) and then
// refining around the best sample: an independent reference for closestPoint.
double bruteForceSurfaceDistance(const Vec3& radii, const Vec3& p) {
  const double pi = 3.14159265358979323846;
  auto at = [&](double theta, double phi) {
    return glm::dvec3(radii.x * std::sin(theta) * std::cos(phi), radii.y * std::cos(theta),
                      radii.z * std::sin(theta) * std::sin(phi));
  };
  const glm::dvec3 q(p);
  double bestTheta = 0.0, bestPhi = 0.0, best = 1e300;
  constexpr int kSteps = 360;
  for (int i = 0; i <= kSteps; ++i) {
    for (int j = 0; j < 2 * kSteps; ++j) {
      const double theta = pi * i / kSteps, phi = pi * j / kSteps;
      const double d = glm::length(at(theta, phi) - q);
      if (d < best) best = d, bestTheta = theta, bestPhi = phi;
    }
  }
  // Pattern search around the best grid point.
  for (double step = pi / kSteps; step > 1e-12; step *= 0.5) {
    for (bool improved = true; improved;) {
      improved = false;
      for (const auto& [dt, dp] : {std::pair{1, 0}, std::pair{-1, 0}, std::pair{0, 1}, std::pair{0, -1}}) {
        const double d = glm::length(at(bestTheta + dt * step, bestPhi + dp * step) - q);
        if (d < best) best = d, bestTheta += dt * step, bestPhi += dp * step, improved = true;
      }
    }
  }
  return best;
}

void expectClosestPointMatchesBruteForce(const Vec3& radii, const Vec3& p) {
  const SurfacePoint cp = closestPoint(Ellipsoid{radii}, Transform{}, p);
  const Vec3 onSurface = cp.point / radii;
  EXPECT_NEAR(glm::dot(onSurface, onSurface), 1.0f, 1e-5f)
      << "point off the surface for " << p.x << " " << p.y << " " << p.z;
  const double reference = bruteForceSurfaceDistance(radii, p);
  EXPECT_NEAR(std::abs(cp.signedDistance), reference, 2e-5) << "query " << p.x << " " << p.y << " " << p.z;
  EXPECT_NEAR(glm::length(p - cp.point), std::abs(cp.signedDistance), 2e-5f);
  const bool inside = glm::dot(p / radii, p / radii) <= 1.0f;
  EXPECT_EQ(cp.signedDistance < 0.0f, inside);
  // The normal is the surface gradient's direction at the point.
  expectVecNear(glm::normalize(cp.point / (radii * radii)), cp.normal, 1e-5f);
}

TEST(Ellipsoid, MassPropertiesAreTheSolidEllipsoidFormulas) {
  // V = 4/3 pi abc, I_x = m (b² + c²) / 5.
  const MassProperties m = massProperties(Ellipsoid{Vec3(3.0f, 2.0f, 1.0f)}, 2.0f);
  const float volume = 8.0f * kPi;
  EXPECT_NEAR(m.volume, volume, 1e-4f);
  EXPECT_NEAR(m.mass, 2.0f * volume, 1e-4f);
  EXPECT_NEAR(m.inertia[0][0], m.mass * 5.0f / 5.0f, 1e-3f);
  EXPECT_NEAR(m.inertia[1][1], m.mass * 10.0f / 5.0f, 1e-3f);
  EXPECT_NEAR(m.inertia[2][2], m.mass * 13.0f / 5.0f, 1e-3f);
  EXPECT_EQ(m.inertia[0][1], 0.0f);
}

const Ellipsoid kEllipsoid{Vec3(3.0f, 2.0f, 1.0f)};

TEST(Ellipsoid, RaysAlongTheAxesHitTheVertices) {
  const auto x = rayCast(kEllipsoid, Transform{}, Ray{Vec3(-10.0f, 0.0f, 0.0f), Vec3(1.0f, 0.0f, 0.0f)});
  ASSERT_TRUE(x);
  EXPECT_NEAR(x->distance, 7.0f, kEps);
  expectVecNear(Vec3(-1.0f, 0.0f, 0.0f), x->normal);
  const auto z = rayCast(kEllipsoid, Transform{}, Ray{Vec3(0.0f, 0.0f, 10.0f), Vec3(0.0f, 0.0f, -1.0f)});
  ASSERT_TRUE(z);
  EXPECT_NEAR(z->distance, 9.0f, kEps);
  expectVecNear(Vec3(0.0f, 0.0f, 1.0f), z->normal);
}

TEST(Ellipsoid, ObliqueRayHasTheGradientNormal) {
  // y = 1 meets x²/9 + y²/4 = 1 at x = -3 sqrt(3)/2; the normal is along (x/9, y/4, 0).
  const auto hit = rayCast(kEllipsoid, Transform{}, Ray{Vec3(-10.0f, 1.0f, 0.0f), Vec3(1.0f, 0.0f, 0.0f)});
  ASSERT_TRUE(hit);
  const float x = -1.5f * std::sqrt(3.0f);
  EXPECT_NEAR(hit->distance, 10.0f + x, kEps);
  expectVecNear(glm::normalize(Vec3(x / 9.0f, 0.25f, 0.0f)), hit->normal);
}

TEST(Ellipsoid, TangentRayTouchesAndWiderMissesAndInsideHitsAtZero) {
  const auto touch = rayCast(kEllipsoid, Transform{}, Ray{Vec3(-10.0f, 2.0f, 0.0f), Vec3(1.0f, 0.0f, 0.0f)});
  ASSERT_TRUE(touch);
  EXPECT_NEAR(touch->distance, 10.0f, 1e-3f);
  expectVecNear(Vec3(0.0f, 1.0f, 0.0f), touch->normal, 1e-3f);
  EXPECT_FALSE(rayCast(kEllipsoid, Transform{}, Ray{Vec3(-10.0f, 2.01f, 0.0f), Vec3(1.0f, 0.0f, 0.0f)}));
  EXPECT_FALSE(rayCast(kEllipsoid, Transform{}, Ray{Vec3(-10.0f, 0.0f, 0.0f), Vec3(1.0f, 0.0f, 0.0f), 6.9f}));
  const auto inside = rayCast(kEllipsoid, Transform{}, Ray{Vec3(2.0f, 0.0f, 0.0f), Vec3(0.0f, 1.0f, 0.0f)});
  ASSERT_TRUE(inside);
  EXPECT_EQ(inside->distance, 0.0f);
}

TEST(Ellipsoid, ClosestPointOnTheAxes) {
  const SurfacePoint x = closestPoint(kEllipsoid, Transform{}, Vec3(5.0f, 0.0f, 0.0f));
  expectVecNear(Vec3(3.0f, 0.0f, 0.0f), x.point);
  EXPECT_NEAR(x.signedDistance, 2.0f, kEps);
  const SurfacePoint z = closestPoint(kEllipsoid, Transform{}, Vec3(0.0f, 0.0f, -3.0f));
  expectVecNear(Vec3(0.0f, 0.0f, -1.0f), z.point);
  expectVecNear(Vec3(0.0f, 0.0f, -1.0f), z.normal);
  EXPECT_NEAR(z.signedDistance, 2.0f, kEps);
  // Inside on the long axis near its vertex: the vertex is nearest (the evolute's cusp on x is at
  // x = (a² - c²) / a = 8/3).
  const SurfacePoint nearVertex = closestPoint(kEllipsoid, Transform{}, Vec3(2.9f, 0.0f, 0.0f));
  expectVecNear(Vec3(3.0f, 0.0f, 0.0f), nearVertex.point);
  EXPECT_NEAR(nearVertex.signedDistance, -0.1f, kEps);
}

TEST(Ellipsoid, ClosestPointAtTheCentreIsTheShortestSemiAxis) {
  const SurfacePoint c = closestPoint(kEllipsoid, Transform{}, Vec3(0.0f));
  EXPECT_NEAR(c.signedDistance, -1.0f, kEps);
  EXPECT_NEAR(std::abs(c.point.z), 1.0f, kEps);
}

TEST(Ellipsoid, ClosestPointMatchesBruteForceOnAndOffTheAxes) {
  const Vec3 points[] = {Vec3(4.0f, 3.0f, 2.0f), Vec3(-1.0f, 0.5f, 0.2f), Vec3(0.5f, -2.5f, 0.0f),
                         Vec3(2.0f, 0.0f, 0.0f), Vec3(0.0f, 1.5f, 0.0f),  Vec3(1.0f, 1.0f, 0.5f),
                         Vec3(0.0f, 0.0f, 0.5f), Vec3(-6.0f, 0.1f, -0.1f)};
  for (const Vec3& p : points) expectClosestPointMatchesBruteForce(kEllipsoid.radii, p);
}

// The oblate case: radii (2, 0.5, 2). A point inside on the equatorial plane (y = 0) near the
// centre is nearest to two points on the "waist" above and below it, not to any point in its plane.
const Vec3 kOblate(2.0f, 0.5f, 2.0f);

TEST(Ellipsoid, OblateWaistNearTheCentre) {
  // x = a² p / (a² - b²) = 4 * 0.3 / 3.75 = 0.32, y = b sqrt(1 - (x / a)²).
  const SurfacePoint w = closestPoint(Ellipsoid{kOblate}, Transform{}, Vec3(0.3f, 0.0f, 0.0f));
  const float x = 0.32f, y = 0.5f * std::sqrt(1.0f - 0.16f * 0.16f);
  expectVecNear(Vec3(x, y, 0.0f), Vec3(w.point.x, std::abs(w.point.y), w.point.z));
  EXPECT_NEAR(w.signedDistance, -std::sqrt(0.02f * 0.02f + y * y), kEps);
  for (const Vec3& p : {Vec3(0.3f, 0.0f, 0.0f), Vec3(0.0f, 0.0f, 0.0f), Vec3(0.2f, 0.0f, -1.0f),
                        Vec3(1.4f, 0.0f, 0.3f), Vec3(1.8f, 0.0f, 0.0f), Vec3(2.5f, 0.0f, 0.0f)}) {
    expectClosestPointMatchesBruteForce(kOblate, p);
  }
}

TEST(Ellipsoid, OblateWaistIsContinuousJustOffThePlane) {
  // Points a tiny height above the equatorial plane take the iterative path rather than the waist
  // formula; the answer must not jump between them.
  const SurfacePoint onPlane = closestPoint(Ellipsoid{kOblate}, Transform{}, Vec3(0.3f, 0.0f, 0.2f));
  for (float height : {1e-2f, 1e-4f, 1e-6f, 1e-8f, 1e-12f, 1e-20f}) {
    const Vec3 p(0.3f, height, 0.2f);
    const SurfacePoint above = closestPoint(Ellipsoid{kOblate}, Transform{}, p);
    EXPECT_GT(above.point.y, 0.0f) << height;
    EXPECT_NEAR(above.signedDistance, onPlane.signedDistance, 2.0f * height + 1e-5f) << height;
    expectClosestPointMatchesBruteForce(kOblate, p);
    const SurfacePoint below = closestPoint(Ellipsoid{kOblate}, Transform{}, Vec3(0.3f, -height, 0.2f));
    EXPECT_LT(below.point.y, 0.0f) << height;
  }
}

TEST(Ellipsoid, ProlateWithTwoEqualShortAxes) {
  // Radii (0.5, 2, 0.5): a point inside on the long axis has a circle of nearest points.
  const Vec3 prolate(0.5f, 2.0f, 0.5f);
  for (const Vec3& p :
       {Vec3(0.0f, 1.0f, 0.0f), Vec3(0.0f, 1.9f, 0.0f), Vec3(0.1f, 0.0f, 0.0f), Vec3(0.0f, 0.0f, 0.0f)}) {
    expectClosestPointMatchesBruteForce(prolate, p);
  }
}

TEST(Ellipsoid, SupportIsTheGradientPoint) {
  // The support along d is the surface point whose normal is d: x = R² d / |R d|.
  const Vec3 d = glm::normalize(Vec3(1.0f, 1.0f, 1.0f));
  const Vec3 r = kEllipsoid.radii;
  expectVecNear(r * r * d / glm::length(r * d), support(kEllipsoid, d));
  expectVecNear(Vec3(0.0f, -2.0f, 0.0f), support(kEllipsoid, Vec3(0.0f, -1.0f, 0.0f)));
}

TEST(Ellipsoid, WorldBoundsOfARotatedEllipsoidAreExact) {
  // 90° about z swaps the x and y radii; 45° gives sqrt((9 + 4) / 2) in x and y.
  const Aabb swapped =
      worldBounds(kEllipsoid, Transform{Vec3(0.0f), glm::angleAxis(kPi / 2.0f, Vec3(0, 0, 1)), 1.0f});
  expectVecNear(Vec3(2.0f, 3.0f, 1.0f), swapped.max, 1e-5f);
  const Aabb diagonal =
      worldBounds(kEllipsoid, Transform{Vec3(1.0f), glm::angleAxis(kPi / 4.0f, Vec3(0, 0, 1)), 2.0f});
  const float xy = 2.0f * std::sqrt(6.5f);
  expectVecNear(Vec3(1.0f + xy, 1.0f + xy, 3.0f), diagonal.max, 1e-4f);
}

}  // namespace
}  // namespace collide
