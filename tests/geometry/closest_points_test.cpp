// Segment–segment closest points against a brute-force search over both parameters.
#include <gtest/gtest.h>

#include <random>

#include "geometry/closest_points.h"

using namespace collide;

TEST(ClosestPoints, SegmentSegmentMatchesBruteForce) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  for (int i = 0; i < 300; ++i) {
    const Vec3 p1(unit(rng), unit(rng), unit(rng)), q1(unit(rng), unit(rng), unit(rng));
    Vec3 p2(unit(rng), unit(rng), unit(rng)), q2(unit(rng), unit(rng), unit(rng));
    if (i % 5 == 0) q2 = p2 + (q1 - p1) * 0.7f;  // parallel
    if (i % 7 == 0) q2 = p2;                     // a point
    const detail::SegmentPair pair = detail::closestPointsSegmentSegment(p1, q1, p2, q2);
    float best = 1e30f;
    for (int a = 0; a <= 200; ++a) {
      for (int b = 0; b <= 200; ++b) {
        const Vec3 d = p1 + (a / 200.0f) * (q1 - p1) - p2 - (b / 200.0f) * (q2 - p2);
        best = std::min(best, glm::dot(d, d));
      }
    }
    EXPECT_LE(pair.distanceSquared, best + 1e-6f);
    EXPECT_GE(pair.distanceSquared, best - 2e-2f * std::sqrt(best) - 1e-4f);  // the grid is 1/200 coarse
    EXPECT_GE(pair.s, 0.0f);
    EXPECT_LE(pair.s, 1.0f);
    EXPECT_GE(pair.t, 0.0f);
    EXPECT_LE(pair.t, 1.0f);
  }
}

TEST(ClosestPoints, CrossingAndParallelSegments) {
  const detail::SegmentPair crossing =
      detail::closestPointsSegmentSegment(Vec3(-1, 0, 0), Vec3(1, 0, 0), Vec3(0, -1, 1), Vec3(0, 1, 1));
  EXPECT_NEAR(crossing.distanceSquared, 1.0f, 1e-6f);
  EXPECT_NEAR(crossing.s, 0.5f, 1e-6f);
  EXPECT_NEAR(crossing.t, 0.5f, 1e-6f);
  const detail::SegmentPair parallel =
      detail::closestPointsSegmentSegment(Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(1, 1, 0), Vec3(3, 1, 0));
  EXPECT_NEAR(parallel.distanceSquared, 1.0f, 1e-6f);
  EXPECT_NEAR(detail::closestParameterOnSegment(Vec3(5, 1, 0), Vec3(0, 0, 0), Vec3(2, 0, 0)), 1.0f, 1e-6f);
}
