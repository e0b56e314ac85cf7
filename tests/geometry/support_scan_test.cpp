// The blocked support scan against the plain loop it replaces: the same index (the first point
// with the largest dot product) for every count, including ties and padding.
#include <collide/shapes.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "geometry/support_scan.h"

using namespace collide;

namespace {

std::uint32_t scalarScan(const Array<Vec3>& points, const Vec3& direction) {
  std::uint32_t best = 0;
  for (std::uint32_t i = 1; i < points.size(); ++i) {
    if (glm::dot(points[i], direction) > glm::dot(points[best], direction)) best = i;
  }
  return best;
}

}  // namespace

TEST(SupportScan, SameIndexAsThePlainLoopForEveryCount) {
  std::mt19937 rng(17);
  std::normal_distribution<float> normal(0.0f, 1.0f);
  int checks = 0;
  for (std::uint32_t count = 1; count <= 70; ++count) {
    Array<Vec3> points(count);
    for (Vec3& p : points) p = Vec3(normal(rng), normal(rng), normal(rng));
    const Array<float> blocked = detail::blockCoordinates(points);
    ASSERT_EQ(blocked.size(), 3 * std::size_t(detail::blockedLanes(count)));
    for (int trial = 0; trial < 50; ++trial) {
      const Vec3 direction(normal(rng), normal(rng), normal(rng));
      EXPECT_EQ(detail::farthestAlong(blocked.data(), count, direction), scalarScan(points, direction))
          << count << " points, trial " << trial;
      ++checks;
    }
  }
  EXPECT_EQ(checks, 70 * 50);
}

TEST(SupportScan, TiesGoToTheFirstPoint) {
  // A cube's corners listed twice: along an axis four (eight with the copies) corners tie, along a
  // diagonal one corner and its copy. The first of them wins, as in the plain loop; so does vertex 0
  // against the padding that repeats it.
  Array<Vec3> corners;
  for (int pass = 0; pass < 2; ++pass) {
    for (int i = 0; i < 8; ++i)
      corners.emplace_back(i & 1 ? 1.0f : -1.0f, i & 2 ? 1.0f : -1.0f, i & 4 ? 1.0f : -1.0f);
  }
  corners.emplace_back(0.0f, 0.0f, 0.0f);  // 17 points: 3 lanes of padding
  const Array<float> blocked = detail::blockCoordinates(corners);
  const Vec3 directions[] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, 0, -1}, {1, 1, 1}, {-1, 1, -1}, {0, 0, 0}};
  for (const Vec3& d : directions) {
    EXPECT_EQ(detail::farthestAlong(blocked.data(), 17, d), scalarScan(corners, d));
  }
  EXPECT_EQ(detail::farthestAlong(blocked.data(), 17, Vec3(1, 0, 0)), 1u);
  EXPECT_EQ(detail::farthestAlong(blocked.data(), 17, Vec3(0, 0, 0)), 0u);  // all tie
  const Array<Vec3> one{{2.0f, 3.0f, 4.0f}};
  EXPECT_EQ(detail::farthestAlong(detail::blockCoordinates(one).data(), 1, Vec3(-1, 0, 0)), 0u);
  EXPECT_EQ(detail::farthestAlong(nullptr, 0, Vec3(1, 0, 0)), 0u);
}

// Coordinates near the float range overflow: x dx + y dy + z dz is +inf, -inf or NaN (inf - inf).
// A NaN never wins, and the index is always one of the points, never the padding after them (a
// fuzzed world read past its hull's vertices here when the maximum's lanes disagreed).
TEST(SupportScan, OverflowingProductsPickARealPointAndNeverNaN) {
  const Array<Vec3> points{{-1.98444f, 0.0f, -1.99219f},
                           {3e38f, 3e38f, 3e38f},
                           {-1.99762f, -2.0f, 3e38f},
                           {-1.76471f, -3e38f, -2.0f},
                           {3e38f, -2.0f, 2.0f}};
  const Array<float> blocked = detail::blockCoordinates(points);
  // Products: -11.98, +inf, -inf, -inf, NaN.
  EXPECT_EQ(detail::farthestAlong(blocked.data(), 5, Vec3(5.99449f, 3e38f, 0.044826f)), 1u);
  // Along (1, inf, 0): point 0's product is NaN (0 inf), point 1's -inf, point 2's +inf.
  const Array<Vec3> first{{-2.0f, 0.0f, 0.0f}, {1.0f, -1.0f, 0.0f}, {4.0f, 2.0f, 0.0f}};
  EXPECT_EQ(detail::farthestAlong(detail::blockCoordinates(first).data(), 3,
                                  Vec3(1.0f, std::numeric_limits<float>::infinity(), 0.0f)),
            2u);
  std::mt19937 rng(23);
  std::uniform_int_distribution<int> pick(0, 6);
  const float values[] = {0.0f, 1.0f, -2.0f, 3e38f, -3e38f, 1e-30f, 7.0f};
  for (int trial = 0; trial < 2000; ++trial) {
    const std::uint32_t count = 1 + static_cast<std::uint32_t>(trial % 9);
    Array<Vec3> cloud(count);
    for (Vec3& p : cloud) p = Vec3(values[pick(rng)], values[pick(rng)], values[pick(rng)]);
    const Vec3 d(values[pick(rng)], values[pick(rng)], values[pick(rng)]);
    const std::uint32_t index = detail::farthestAlong(detail::blockCoordinates(cloud).data(), count, d);
    ASSERT_LT(index, count) << "trial " << trial;
    // No point's product (NaN as -infinity) is larger than the one picked, and none before it equal.
    const auto product = [&](std::uint32_t i) {
      const float v = (cloud[i].x * d.x + cloud[i].y * d.y) + cloud[i].z * d.z;
      return std::isnan(v) ? -std::numeric_limits<float>::infinity() : v;
    };
    for (std::uint32_t i = 0; i < count; ++i) {
      EXPECT_FALSE(product(i) > product(index)) << "trial " << trial;
      if (i < index) {
        EXPECT_FALSE(product(i) == product(index)) << "trial " << trial;
      }
    }
  }
}

TEST(SupportScan, ConvexHullSupportIsItsFarthestVertex) {
  std::mt19937 rng(5);
  std::normal_distribution<float> normal(0.0f, 1.0f);
  Array<Vec3> cloud(40);
  for (Vec3& p : cloud) p = Vec3(normal(rng), normal(rng), normal(rng));
  const ConvexHull hull = ConvexHull::fromPoints(cloud);
  const Array<Vec3> vertices(hull.vertices().begin(), hull.vertices().end());
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 d(normal(rng), normal(rng), normal(rng));
    EXPECT_EQ(hull.support(d), vertices[scalarScan(vertices, d)]);
  }
}
