// k-DOP proxy: slabs against the points they bound, the enclosed polytope against closed forms and
// the hull, and the slab ray test against the polytope's ray cast.
#include <collide/shapes.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "support/collide_error.h"
#include "support/test_random.h"

#include "support/hull_invariants.h"

#include <cmath>
#include <limits>
#include <random>
#include <vector>

using namespace collide;
using collide::testing_support::isValidHalfEdgeHull;
using ::testing::AllOf;
using ::testing::HasSubstr;

namespace {

constexpr int kSupportedK[] = {6, 14, 18, 26};

// An irregular cloud: a stretched, shifted blob.
std::vector<Vec3> randomCloud(int count, std::mt19937& rng) {
  std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
  std::vector<Vec3> points;
  for (int i = 0; i < count; ++i) {
    points.push_back(Vec3(0.3f, -0.2f, 0.5f) +
                     Vec3(1.5f, 0.7f, 1.0f) * Vec3(uniform(rng), uniform(rng), uniform(rng)));
  }
  return points;
}

}  // namespace

TEST(Kdop, AxesAreUnitDistinctAndNested) {
  for (int k : kSupportedK) {
    const auto axes = Kdop::axes(k);
    ASSERT_EQ(int(axes.size()), k / 2);
    for (std::size_t i = 0; i < axes.size(); ++i) {
      EXPECT_NEAR(glm::length(axes[i]), 1.0f, 1e-6f);
      for (std::size_t j = 0; j < i; ++j)
        EXPECT_LT(std::abs(glm::dot(axes[i], axes[j])), 0.99f) << k << ": " << i << j;
    }
    // Every k-DOP starts with the three coordinate axes, so it is never looser than the AABB.
    EXPECT_EQ(axes[0], Vec3(1, 0, 0));
    EXPECT_EQ(axes[1], Vec3(0, 1, 0));
    EXPECT_EQ(axes[2], Vec3(0, 0, 1));
  }
  // 14: cube diagonals (all components ±1/sqrt 3); 18: edge diagonals (one zero component).
  for (const Vec3& a : Kdop::axes(14).subspan(3))
    EXPECT_NEAR(std::abs(a.x * a.y * a.z), std::pow(3.0f, -1.5f), 1e-6f);
  for (const Vec3& a : Kdop::axes(18).subspan(3)) {
    EXPECT_NEAR(std::abs(a.x) + std::abs(a.y) + std::abs(a.z), std::sqrt(2.0f), 1e-6f);
  }
}

TEST(Kdop, SixDopOfPointsIsTheirAabb) {
  std::mt19937 rng(1);
  const std::vector<Vec3> points = randomCloud(100, rng);
  Aabb box;
  for (const Vec3& p : points) box.grow(p);
  const Kdop dop = Kdop::fromPoints(6, points);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(dop.slabMin(i), box.min[i]);
    EXPECT_EQ(dop.slabMax(i), box.max[i]);
  }
  const Shape shape(dop);
  EXPECT_EQ(localBounds(shape).min, box.min);
  EXPECT_EQ(localBounds(shape).max, box.max);
  EXPECT_NEAR(massProperties(shape, 1.0f).volume, box.volume(), 1e-5f * box.volume());
  EXPECT_NEAR(glm::length(massProperties(shape, 1.0f).centerOfMass - box.center()), 0.0f, 1e-5f);
  EXPECT_EQ(dop.polytope().faces().size(), 6u);
}

TEST(Kdop, VolumeShrinksWithMoreAxesButNeverBelowTheHull) {
  std::mt19937 rng(2);
  for (int trial = 0; trial < 5; ++trial) {
    const std::vector<Vec3> points = randomCloud(20 + 40 * trial, rng);
    const float hullVolume = ConvexHull::fromPoints(points).volume();
    float volume[27] = {};
    for (int k : kSupportedK) {
      const Kdop dop = Kdop::fromPoints(k, points);
      EXPECT_TRUE(isValidHalfEdgeHull(dop.polytope(), 1e-5f)) << k;
      volume[k] = massProperties(Shape(dop), 1.0f).volume;
      EXPECT_GE(volume[k], hullVolume * (1.0f - 1e-5f)) << k;
      const Shape shape(dop);
      for (const Vec3& p : points) EXPECT_TRUE(containsPoint(shape, Transform{}, p)) << k;
    }
    const float slack = 1.0f + 1e-5f;
    EXPECT_LE(volume[14], volume[6] * slack);
    EXPECT_LE(volume[18], volume[6] * slack);
    EXPECT_LE(volume[26], volume[14] * slack);
    EXPECT_LE(volume[26], volume[18] * slack);
  }
}

TEST(Kdop, FourteenDopOfCubeCutAtEdgeMidpointsIsACuboctahedron) {
  // Cube [-1, 1]^3 with |±x ± y + z| <= 2: the corners are cut at the edge midpoints, leaving a
  // cuboctahedron: 12 vertices, 14 faces, volume 8 - 8 * (1/6) = 20/3.
  const float d = 2.0f / std::sqrt(3.0f);
  const std::vector<float> lo = {-1, -1, -1, -d, -d, -d, -d}, hi = {1, 1, 1, d, d, d, d};
  const Kdop dop = Kdop::fromSlabs(14, lo, hi);
  EXPECT_EQ(dop.polytope().vertices().size(), 12u);
  EXPECT_EQ(dop.polytope().faces().size(), 14u);
  EXPECT_NEAR(dop.polytope().volume(), 20.0f / 3.0f, 1e-4f);
  EXPECT_TRUE(isValidHalfEdgeHull(dop.polytope(), 1e-5f));
  for (const Vec3& v : dop.polytope().vertices()) EXPECT_NEAR(glm::length(v), std::sqrt(2.0f), 1e-5f);
}

TEST(Kdop, TwentySixDopOfASphereCloudHugsTheSphere) {
  std::mt19937 rng(3);
  std::vector<Vec3> points;
  for (int i = 0; i < 2000; ++i) points.push_back(test::randomUnitVector(rng));
  const Kdop dop = Kdop::fromPoints(26, points);
  // Every slab of the tangent 26-DOP is [-1, 1]; 2000 samples come within 1e-2 of every axis pole.
  for (int i = 0; i < 13; ++i) {
    EXPECT_NEAR(dop.slabMin(i), -1.0f, 1e-2f);
    EXPECT_NEAR(dop.slabMax(i), 1.0f, 1e-2f);
  }
  std::vector<float> lo(13, -1.0f), hi(13, 1.0f);
  const Kdop tangent = Kdop::fromSlabs(26, lo, hi);
  const float sphereVolume = 4.0f / 3.0f * kPi;
  // Nested: sample hull ⊂ DOP of the samples ⊂ tangent DOP, and the tangent DOP holds the sphere.
  EXPECT_LE(dop.polytope().volume(), tangent.polytope().volume());
  EXPECT_GE(dop.polytope().volume(), ConvexHull::fromPoints(points).volume());
  EXPECT_GT(tangent.polytope().volume(), sphereVolume);
  // 26 planes tangent to the sphere: every vertex within 1.2 (a 6-DOP's corners are at sqrt 3).
  for (const Vec3& v : tangent.polytope().vertices()) {
    EXPECT_GT(glm::length(v), 1.0f);
    EXPECT_LT(glm::length(v), 1.2f);
  }
  EXPECT_NEAR(dop.polytope().volume(), sphereVolume, 0.15f * sphereVolume);
}

TEST(Kdop, SlabRayCastAgreesWithThePolytope) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<float> spread(-1.0f, 1.0f);
  for (int k : kSupportedK) {
    const std::vector<Vec3> points = randomCloud(30, rng);
    const Kdop dop = Kdop::fromPoints(k, points);
    const Shape slabs(dop);
    const Shape polytope(std::make_shared<const ConvexHull>(dop.polytope()));
    int hits = 0;
    for (int i = 0; i < 1000; ++i) {
      const Transform t = test::randomTransform(rng);
      const Vec3 from =
          t.applyToPoint(Vec3(0.3f, -0.2f, 0.5f) + 3.0f * Vec3(spread(rng), spread(rng), spread(rng)));
      const Vec3 to =
          t.applyToPoint(Vec3(0.3f, -0.2f, 0.5f) + 1.2f * Vec3(spread(rng), spread(rng), spread(rng)));
      if (glm::length(to - from) < 1e-3f) continue;
      const Ray ray{from, glm::normalize(to - from), 100.0f};
      const auto expected = rayCast(polytope, t, ray);
      const auto actual = rayCast(slabs, t, ray);
      ASSERT_EQ(actual.has_value(), expected.has_value()) << k << "-DOP, ray " << i;
      if (!expected) continue;
      ++hits;
      EXPECT_NEAR(actual->distance, expected->distance, 1e-4f * t.scale) << k << "-DOP, ray " << i;
      // The polytope's faces lie on the slab planes, so the normals are the same.
      EXPECT_NEAR(glm::length(actual->normal - expected->normal), 0.0f, 1e-3f) << k << "-DOP, ray " << i;
    }
    EXPECT_GT(hits, 300) << k;
  }
}

TEST(Kdop, QueriesMatchThePolytope) {
  std::mt19937 rng(5);
  const Kdop dop = Kdop::fromPoints(18, randomCloud(40, rng));
  const Shape slabs(dop);
  const Shape polytope(std::make_shared<const ConvexHull>(dop.polytope()));
  std::uniform_real_distribution<float> spread(-2.0f, 2.0f);
  for (int i = 0; i < 500; ++i) {
    const Transform t = test::randomTransform(rng);
    const Vec3 p = t.applyToPoint(Vec3(spread(rng), spread(rng), spread(rng)));
    const SurfacePoint nearest = closestPoint(polytope, t, p);
    // Away from the surface, the slab test and the polytope's planes must agree.
    if (std::abs(nearest.signedDistance) > 1e-4f) {
      EXPECT_EQ(containsPoint(slabs, t, p), containsPoint(polytope, t, p)) << "point " << i;
    }
    EXPECT_EQ(closestPoint(slabs, t, p).point, nearest.point);
    const Vec3 d = test::randomUnitVector(rng);
    EXPECT_EQ(support(slabs, d), support(polytope, d));
    const Aabb a = worldBounds(slabs, t), b = worldBounds(polytope, t);
    EXPECT_EQ(a.min, b.min);
    EXPECT_EQ(a.max, b.max);
  }
  const MassProperties m = massProperties(slabs, 3.0f);
  EXPECT_NEAR(m.mass, 3.0f * dop.polytope().volume(), 1e-5f);
}

TEST(Kdop, RejectsBadInput) {
  const std::vector<Vec3> cube = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(1, 1, 1)};
  EXPECT_THAT([] { Kdop::axes(8); },
              ::collide::test::ReportsError(HasSubstr("kdop: k must be 6, 14, 18 or 26, got 8")));
  EXPECT_THAT([&] { Kdop::fromPoints(8, cube); }, ::collide::test::ReportsError(HasSubstr("got 8")));
  EXPECT_THAT([&] { Kdop::fromPoints(-1, cube); }, ::collide::test::ReportsError(HasSubstr("got -1")));
  const std::vector<Vec3> three(cube.begin(), cube.begin() + 3);
  EXPECT_THAT(
      [&] { Kdop::fromPoints(14, three); },
      ::collide::test::ReportsError(AllOf(HasSubstr("kdop: need at least 4 points"), HasSubstr("got 3"))));
  std::vector<Vec3> bad = cube;
  bad[2].z = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THAT([&] { Kdop::fromPoints(18, bad); },
              ::collide::test::ReportsError(HasSubstr("kdop: point 2 is not finite")));
  bad[2].z = -std::numeric_limits<float>::infinity();
  EXPECT_THAT([&] { Kdop::fromPoints(18, bad); },
              ::collide::test::ReportsError(HasSubstr("kdop: point 2 is not finite")));
  const std::vector<Vec3> flat = {Vec3(0, 0, 2), Vec3(1, 0, 2), Vec3(0, 1, 2), Vec3(1, 1, 2),
                                  Vec3(0.5f, 0.2f, 2)};
  EXPECT_THAT([&] { Kdop::fromPoints(26, flat); },
              ::collide::test::ReportsError(HasSubstr("kdop: points are coplanar")));
  const std::vector<Vec3> line = {Vec3(0), Vec3(1), Vec3(2), Vec3(3)};
  EXPECT_THAT([&] { Kdop::fromPoints(6, line); },
              ::collide::test::ReportsError(HasSubstr("kdop: points are collinear")));
  const std::vector<Vec3> same(4, Vec3(1, 2, 3));
  EXPECT_THAT([&] { Kdop::fromPoints(6, same); },
              ::collide::test::ReportsError(HasSubstr("kdop: points are all identical")));

  const std::vector<float> lo = {-1, -1, -1}, hi = {1, 1, 1};
  EXPECT_THAT([&] { Kdop::fromSlabs(8, lo, hi); }, ::collide::test::ReportsError(HasSubstr("got 8")));
  EXPECT_THAT([&] { Kdop::fromSlabs(14, lo, hi); },
              ::collide::test::ReportsError(HasSubstr("needs 7 slab minima")));
  const std::vector<float> flipped = {1, 2, 3}, inverted = {-1, 1, 1};
  EXPECT_THAT([&] { Kdop::fromSlabs(6, flipped, hi); },
              ::collide::test::ReportsError(HasSubstr("kdop: slab 0 must have min < max, got [1, 1]")));
  EXPECT_THAT([&] { Kdop::fromSlabs(6, inverted, lo); },
              ::collide::test::ReportsError(HasSubstr("slab 0 must have min < max, got [-1, -1]")));
  const std::vector<float> nan = {-1, std::numeric_limits<float>::quiet_NaN(), -1};
  EXPECT_THAT([&] { Kdop::fromSlabs(6, nan, hi); },
              ::collide::test::ReportsError(HasSubstr("slab 1 must be finite")));
  // Non-empty slabs whose intersection is empty: the diagonal slab lies beyond the cube's corner.
  const std::vector<float> lo14 = {-1, -1, -1, 5, -1, -1, -1}, hi14 = {1, 1, 1, 6, 1, 1, 1};
  EXPECT_THAT([&] { Kdop::fromSlabs(14, lo14, hi14); },
              ::collide::test::ReportsError(HasSubstr("kdop: the slabs enclose no volume")));
}
