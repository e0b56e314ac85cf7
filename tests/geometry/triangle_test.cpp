#include "geometry/triangle.h"

#include <gtest/gtest.h>

#include <random>

using namespace collide;
using namespace collide::detail;

namespace {

struct Triangle {
  Vec3 a, b, c;
};

Triangle randomTriangle(std::mt19937& rng) {
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (;;) {
    const Triangle t{{u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}};
    if (glm::length(glm::cross(t.b - t.a, t.c - t.a)) > 0.05f) return t;  // skip near-slivers
  }
}

}  // namespace

TEST(ClosestPointOnTriangle, NeverFartherThanDenseSamplesAndCloseToTheBest) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-2.0f, 2.0f);
  constexpr int kSteps = 80;  // samples a + (i/k)(b - a) + (j/k)(c - a), i + j <= k
  for (int trial = 0; trial < 60; ++trial) {
    const Triangle t = randomTriangle(rng);
    // Every point of the triangle is within one grid cell diagonal of a sample.
    const float spacing = (glm::length(t.b - t.a) + glm::length(t.c - t.a)) / kSteps;
    for (int k = 0; k < 4; ++k) {
      const Vec3 p(u(rng), u(rng), u(rng));
      float sampled = 1e30f;
      for (int i = 0; i <= kSteps; ++i) {
        for (int j = 0; i + j <= kSteps; ++j) {
          const Vec3 q = t.a + (float(i) / kSteps) * (t.b - t.a) + (float(j) / kSteps) * (t.c - t.a);
          sampled = std::min(sampled, glm::length(p - q));
        }
      }
      const TriangleClosestPoint result = closestPointOnTriangle(p, t.a, t.b, t.c);
      const float distance = glm::length(p - result.point);
      // The true minimum is below every sample and within one grid step of the best sample.
      EXPECT_LE(distance, sampled + 1e-5f);
      EXPECT_GE(distance, sampled - spacing);
      // The barycentric weights describe the returned point.
      const Vec3 w = result.barycentric;
      EXPECT_GE(std::min({w.x, w.y, w.z}), -1e-6f);
      EXPECT_NEAR(w.x + w.y + w.z, 1.0f, 1e-5f);
      const Vec3 fromWeights = w.x * t.a + w.y * t.b + w.z * t.c;
      EXPECT_LT(glm::length(fromWeights - result.point), 1e-5f);
    }
  }
}

TEST(ClosestPointOnTriangle, RegionsOfARightTriangle) {
  const Vec3 a(0, 0, 0), b(2, 0, 0), c(0, 2, 0);
  // Above the face: the orthogonal projection.
  TriangleClosestPoint r = closestPointOnTriangle({0.5f, 0.5f, 3.0f}, a, b, c);
  EXPECT_EQ(r.point, Vec3(0.5f, 0.5f, 0.0f));
  // Beyond vertex a, b and c.
  EXPECT_EQ(closestPointOnTriangle({-1, -1, 1}, a, b, c).point, a);
  EXPECT_EQ(closestPointOnTriangle({3, -1, 0}, a, b, c).point, b);
  r = closestPointOnTriangle({-1, 3, 0}, a, b, c);
  EXPECT_EQ(r.point, c);
  EXPECT_EQ(r.barycentric, Vec3(0, 0, 1));
  // Beside edge ab, and beside the hypotenuse bc (its midpoint).
  r = closestPointOnTriangle({1, -1, 0}, a, b, c);
  EXPECT_EQ(r.point, Vec3(1, 0, 0));
  EXPECT_FLOAT_EQ(r.barycentric.z, 0.0f);
  r = closestPointOnTriangle({2, 2, 1}, a, b, c);
  EXPECT_NEAR(glm::length(r.point - Vec3(1, 1, 0)), 0.0f, 1e-6f);
  EXPECT_NEAR(r.barycentric.x, 0.0f, 1e-6f);
}

// Reference: intersect the ray with the triangle's plane, then test the barycentric coordinates of
// that point (solved in double from the 2x2 Gram system).
TEST(RayTriangle, MollerTrumboreAgreesWithPlaneIntersectionAndBarycentricTest) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-2.0f, 2.0f);
  int hits = 0, compared = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const Triangle t = randomTriangle(rng);
    Ray ray;
    ray.origin = Vec3(u(rng), u(rng), u(rng));
    // Aim at a point of the triangle's plane around it, so that hits and misses both occur often.
    std::uniform_real_distribution<float> weight(-0.3f, 1.0f);
    const Vec3 target = t.a + weight(rng) * (t.b - t.a) + weight(rng) * (t.c - t.a);
    ray.direction = glm::normalize(target - ray.origin);
    ray.maxDistance = trial % 4 == 0 ? 1.5f : 1e30f;

    const glm::dvec3 a(t.a), b(t.b), c(t.c), o(ray.origin), d(ray.direction);
    const glm::dvec3 n = glm::cross(b - a, c - a);
    const double along = glm::dot(n, d);
    if (std::abs(along) < 1e-3 * glm::length(n)) continue;  // grazing: ill-conditioned reference
    const double tPlane = glm::dot(n, a - o) / along;
    const glm::dvec3 q = o + tPlane * d;
    const glm::dvec3 e1 = b - a, e2 = c - a, r = q - a;
    const double d11 = glm::dot(e1, e1), d12 = glm::dot(e1, e2), d22 = glm::dot(e2, e2);
    const double r1 = glm::dot(r, e1), r2 = glm::dot(r, e2);
    const double det = d11 * d22 - d12 * d12;
    const double bu = (d22 * r1 - d12 * r2) / det;
    const double bv = (d11 * r2 - d12 * r1) / det;
    const double margin = std::min({bu, bv, 1.0 - bu - bv});
    if (std::abs(margin) < 1e-4 || std::abs(tPlane) < 1e-4 || std::abs(tPlane - ray.maxDistance) < 1e-4) {
      continue;  // too close to an edge or an end of the ray to call
    }
    const bool expected = margin > 0.0 && tPlane >= 0.0 && tPlane <= ray.maxDistance;
    const std::optional<RayTriangleHit> hit = intersectRayTriangle(ray, t.a, t.b, t.c);
    ++compared;
    ASSERT_EQ(hit.has_value(), expected) << "trial " << trial;
    if (hit) {
      ++hits;
      EXPECT_NEAR(hit->distance, tPlane, 1e-4 * std::max(1.0, tPlane));
      EXPECT_NEAR(hit->u, bu, 1e-4);
      EXPECT_NEAR(hit->v, bv, 1e-4);
    }
  }
  EXPECT_GT(compared, 15000);
  EXPECT_GT(hits, compared / 5);  // both outcomes well represented
  EXPECT_LT(hits, compared * 4 / 5);
}

TEST(RayTriangle, TwoSidedParallelAndMaxDistance) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  // From the front (+z, where abc is counter-clockwise) and from the back.
  std::optional<RayTriangleHit> hit =
      intersectRayTriangle({{0.25f, 0.25f, 2.0f}, {0, 0, -1}, 10.0f}, a, b, c);
  ASSERT_TRUE(hit);
  EXPECT_FLOAT_EQ(hit->distance, 2.0f);
  hit = intersectRayTriangle({{0.25f, 0.25f, -3.0f}, {0, 0, 1}, 10.0f}, a, b, c);
  ASSERT_TRUE(hit);
  EXPECT_FLOAT_EQ(hit->distance, 3.0f);
  EXPECT_FLOAT_EQ(hit->u, 0.25f);
  EXPECT_FLOAT_EQ(hit->v, 0.25f);
  // Parallel to the plane, pointing away, and too short.
  EXPECT_FALSE(intersectRayTriangle({{0.25f, 0.25f, 1.0f}, {1, 0, 0}, 10.0f}, a, b, c));
  EXPECT_FALSE(intersectRayTriangle({{0.25f, 0.25f, 1.0f}, {0, 0, 1}, 10.0f}, a, b, c));
  EXPECT_FALSE(intersectRayTriangle({{0.25f, 0.25f, 1.0f}, {0, 0, -1}, 0.99f}, a, b, c));
}
