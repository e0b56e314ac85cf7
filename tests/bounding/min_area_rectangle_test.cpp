// 2D convex hull and the minimum-area rectangle against brute force: every edge direction of the
// hull tried with a full scan (Freeman & Shapira's theorem says the optimum is one of them), and a
// dense sweep of angles that the optimum can never beat.
#include <gtest/gtest.h>

#include "bounding/min_area_rectangle.h"
#include "support/point_clouds.h"

#include <cmath>

using namespace collide;
using namespace collide::bounding;

namespace {

double rectangleAreaAlong(const glm::dvec2& axis, const Array<glm::dvec2>& points) {
  const glm::dvec2 perpendicular(-axis.y, axis.x);
  glm::dvec2 low(INFINITY), high(-INFINITY);
  for (const glm::dvec2& p : points) {
    const glm::dvec2 q(glm::dot(axis, p), glm::dot(perpendicular, p));
    low = glm::min(low, q);
    high = glm::max(high, q);
  }
  return (high.x - low.x) * (high.y - low.y);
}

}  // namespace

TEST(ConvexHull2d, SquareWithInteriorAndEdgePointsKeepsOnlyTheCornersCounterClockwise) {
  const Array<glm::dvec2> points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.5, 0.5}, {0.5, 0}, {1, 0.3}, {0, 0}};
  const Array<glm::dvec2> hull = convexHull2d(points);
  ASSERT_EQ(hull.size(), 4u);
  double signedArea = 0.0;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const glm::dvec2 a = hull[i], b = hull[(i + 1) % hull.size()];
    signedArea += a.x * b.y - a.y * b.x;
  }
  EXPECT_DOUBLE_EQ(0.5 * signedArea, 1.0);  // positive: counter-clockwise
}

TEST(MinimumAreaRectangle, RotatedRectangleIsRecoveredExactly) {
  test::Random random(5);
  for (int trial = 0; trial < 50; ++trial) {
    const double angle = random.uniform(0.0f, kPi), w = random.uniform(0.1f, 3.0f),
                 h = random.uniform(0.1f, 3.0f);
    const glm::dvec2 u(std::cos(angle), std::sin(angle)), v(-u.y, u.x);
    Array<glm::dvec2> points;
    for (int i = 0; i < 4; ++i) points.push_back(((i & 1) ? w : -w) * u + ((i & 2) ? h : -h) * v);
    for (int i = 0; i < 20; ++i)
      points.push_back(random.uniform(-1, 1) * w * u + random.uniform(-1, 1) * h * v);
    const Rectangle2d r = minimumAreaRectangle(convexHull2d(points));
    EXPECT_NEAR(r.area(), 4.0 * w * h, 1e-9 * w * h);
    EXPECT_NEAR(std::abs(glm::dot(r.axis, u) * glm::dot(r.axis, v)), 0.0, 1e-9);  // aligned with a side
  }
}

TEST(MinimumAreaRectangle, EqualsTheBestEdgeDirectionAndBeatsEveryOtherAngle) {
  test::Random random(6);
  for (int trial = 0; trial < 100; ++trial) {
    Array<glm::dvec2> points;
    const int n = random.integer(3, 40);
    const double stretch = random.uniform(0.1f, 1.0f);
    for (int i = 0; i < n; ++i) points.emplace_back(random.uniform(-1, 1), stretch * random.uniform(-1, 1));
    const Array<glm::dvec2> hull = convexHull2d(points);
    if (hull.size() < 3) continue;
    const Rectangle2d r = minimumAreaRectangle(hull);
    // The calipers' extents are those of a full scan along the same axis.
    EXPECT_NEAR(r.area(), rectangleAreaAlong(r.axis, points), 1e-12);
    double bestEdge = INFINITY;
    for (std::size_t i = 0; i < hull.size(); ++i) {
      const glm::dvec2 edge = glm::normalize(hull[(i + 1) % hull.size()] - hull[i]);
      bestEdge = std::min(bestEdge, rectangleAreaAlong(edge, points));
    }
    EXPECT_NEAR(r.area(), bestEdge, 1e-12) << "trial " << trial;
    for (int step = 0; step < 720; ++step) {
      const double angle = step * kPi / 720.0;
      EXPECT_LE(r.area(), rectangleAreaAlong({std::cos(angle), std::sin(angle)}, points) + 1e-12);
    }
  }
}
