// Spheres and capsules against mesh triangles by closest points (src/narrowphase/triangle_rounded.cpp):
// agreement with GJK/EPA on one triangle, a capsule's two points on a tessellated floor with stable
// ids, and the internal-edge handling on flat, concave and convex folds.
#include <collide/narrowphase.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <set>
#include <string>

#include "narrowphase/convex_distance.h"
#include "narrowphase/convex_support.h"
#include "narrowphase/pair_functions.h"
#include "support/flat_grid.h"
#include "support/narrowphase_helpers.h"
#include "support/simple_geometry.h"

namespace collide {
namespace {

using test::at;
using test::axisAngle;
using test::randomUnit;
using test::uniformRotation;

float degreesBetween(const Vec3& a, const Vec3& b) {
  return glm::degrees(std::acos(std::clamp(glm::dot(a, b) / (glm::length(a) * glm::length(b)), -1.0f, 1.0f)));
}

struct RoundedTally {
  int pairs = 0, hits = 0, faceHits = 0, edgeHits = 0, piercing = 0, normalsCompared = 0, failures = 0;
  std::string firstFailure;
  void fail(const std::string& text) {
    ++failures;
    if (firstFailure.empty()) firstFailure = text;
  }
};

// One random triangle (edges 0.5 to 2.5) and the shape placed near it, by closest points and by
// GJK/EPA on the triangle as a three-point polytope: the same verdict, the deepest depth within
// 1e-3 relative, and the normal within 1° wherever the core stays clear of the triangle (there the
// normal is unique; where the core pierces the triangle both go through EPA).
void compareWithGjk(const Shape& shape, int pairs, std::uint32_t seed, RoundedTally& tally) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (int i = 0; i < pairs; ++i) {
    std::array<Vec3, 3> triangle;
    for (Vec3& v : triangle) v = randomUnit(rng) * (0.3f + 1.0f * unit(rng));
    if (glm::length(glm::cross(triangle[1] - triangle[0], triangle[2] - triangle[0])) < 0.05f) continue;
    const float radius = shape.type() == ShapeType::Sphere ? shape.sphere().radius : shape.capsule().radius;
    const float reach = radius + (shape.type() == ShapeType::Capsule ? shape.capsule().halfHeight : 0.0f);
    const Vec3 target =
        triangle[0] + unit(rng) * (triangle[1] - triangle[0]) + unit(rng) * (triangle[2] - triangle[0]);
    const Transform pose = at(target + randomUnit(rng) * (1.6f * reach * unit(rng)), uniformRotation(rng));
    const float margin = (i % 3 == 0) ? 0.1f * unit(rng) : 0.0f;
    ++tally.pairs;

    Manifold ours;
    const std::array<std::array<Vec3, 3>, 1> one{triangle};
    const bool hit = detail::collideTrianglesConvex(one, Transform::identity(), shape, pose, margin, ours);
    const detail::ConvexSupport triangleSupport =
        detail::makePointsSupport(triangle.data(), 3, Transform::identity());
    const detail::ConvexSupport shapeSupport = detail::makeConvexSupport(shape, pose);
    DistanceResult reference;
    bool referenceHit = detail::convexSignedDistance(triangleSupport, shapeSupport, margin, reference);
    referenceHit = referenceHit && reference.distance <= margin;
    // The core's own distance to the triangle: the reference without the radius.
    const float coreDistance = reference.distance + radius;
    char where[96];
    std::snprintf(where, sizeof where, "pair %d (distance %.6f, margin %.4f)", i, reference.distance, margin);
    if (hit != referenceHit) {
      // A verdict may only differ where the distance is the margin to GJK's tolerance.
      if (std::abs(reference.distance - margin) > 1e-5f) tally.fail(std::string(where) + ": verdicts differ");
      continue;
    }
    if (!hit) continue;
    ++tally.hits;
    const float depth = -reference.distance;
    if (std::abs(ours.maxDepth() - depth) > 1e-3f * std::abs(depth) + 1e-5f) {
      tally.fail(std::string(where) + ": depth " + std::to_string(ours.maxDepth()) + ", GJK/EPA " +
                 std::to_string(depth));
      continue;
    }
    if (coreDistance <= 1e-3f) {
      ++tally.piercing;
      continue;
    }
    const Vec3 faceNormal = glm::normalize(glm::cross(triangle[1] - triangle[0], triangle[2] - triangle[0]));
    const bool onFace = std::abs(std::abs(glm::dot(reference.normal, faceNormal)) - 1.0f) < 1e-6f;
    (onFace ? tally.faceHits : tally.edgeHits) += 1;
    ++tally.normalsCompared;
    if (degreesBetween(ours.normal, reference.normal) > 1.0f) {
      tally.fail(std::string(where) + ": normals " +
                 std::to_string(degreesBetween(ours.normal, reference.normal)) + "° apart");
    }
  }
}

TEST(TriangleRounded, SphereAgreesWithGjkEpaOnOneTriangle) {
  RoundedTally tally;
  std::mt19937 sizes(3);
  std::uniform_real_distribution<float> size(0.1f, 1.0f);
  for (int round = 0; round < 6; ++round) {
    compareWithGjk(Sphere{size(sizes)}, 500, 100 + round, tally);
  }
  std::printf("sphere x triangle: %d pairs, %d hits (%d face, %d edge/vertex, %d piercing), %d failures\n",
              tally.pairs, tally.hits, tally.faceHits, tally.edgeHits, tally.piercing, tally.failures);
  SCOPED_TRACE(tally.firstFailure);
  EXPECT_EQ(tally.failures, 0);
  EXPECT_GT(tally.faceHits, tally.pairs / 20);
  EXPECT_GT(tally.edgeHits, tally.pairs / 20);
}

TEST(TriangleRounded, CapsuleAgreesWithGjkEpaOnOneTriangle) {
  RoundedTally tally;
  std::mt19937 sizes(4);
  std::uniform_real_distribution<float> size(0.1f, 1.0f);
  for (int round = 0; round < 6; ++round) {
    compareWithGjk(Capsule{size(sizes), size(sizes)}, 500, 200 + round, tally);
  }
  std::printf("capsule x triangle: %d pairs, %d hits (%d face, %d edge/vertex, %d piercing), %d failures\n",
              tally.pairs, tally.hits, tally.faceHits, tally.edgeHits, tally.piercing, tally.failures);
  SCOPED_TRACE(tally.firstFailure);
  EXPECT_EQ(tally.failures, 0);
  EXPECT_GT(tally.faceHits, tally.pairs / 50);
  EXPECT_GT(tally.edgeHits, tally.pairs / 20);
  EXPECT_GT(tally.piercing, 0);
}

TEST(TriangleRounded, CapsuleLyingOnTheFloorGetsTwoPointsWithStableIds) {
  // A capsule (radius 0.2, half height 0.6) lying along a horizontal direction, sunk 0.01 into the
  // floor: one point under each end, depth 0.01, normal up. Moved over many triangles and turned
  // about y, the two ids (the floor's flat patch, each capsule end) never change.
  const Shape floor = test::flatGrid(10);
  const Shape capsule = Capsule{0.2f, 0.6f};
  const Quat lying = axisAngle({0, 0, 1}, 90.0f);
  std::mt19937 rng(8);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::set<std::uint32_t> first;
  for (int trial = 0; trial < 300; ++trial) {
    const Quat turn = axisAngle({0, 1, 0}, 180.0f * unit(rng));
    const Transform pose = at({3.0f * unit(rng), 0.19f, 3.0f * unit(rng)}, turn * lying);
    Manifold m;
    ASSERT_TRUE(collide::collide(floor, Transform::identity(), capsule, pose, m)) << "trial " << trial;
    ASSERT_EQ(m.count, 2) << "trial " << trial;
    EXPECT_NEAR(m.normal.y, 1.0f, 1e-6f);
    std::set<std::uint32_t> ids;
    for (int i = 0; i < 2; ++i) {
      EXPECT_NEAR(m.points[i].depth, 0.01f, 1e-5f);
      ids.insert(m.points[i].featureId);
      // Under one of the ends.
      const Vec3 end0 = pose.applyToPoint({0.0f, -0.6f, 0.0f}), end1 = pose.applyToPoint({0.0f, 0.6f, 0.0f});
      const Vec3 p = m.points[i].pointOnA;
      const float nearest =
          std::min(glm::length(p - Vec3(end0.x, 0.0f, end0.z)), glm::length(p - Vec3(end1.x, 0.0f, end1.z)));
      EXPECT_LT(nearest, 1e-4f) << "trial " << trial;
    }
    ASSERT_EQ(ids.size(), 2u);
    if (first.empty()) first = ids;
    EXPECT_EQ(ids, first) << "trial " << trial;
  }
  // Tilted by 5°: only the lower end.
  Manifold m;
  ASSERT_TRUE(collide::collide(floor, Transform::identity(), capsule,
                               at({0.3f, 0.19f, 0.2f}, axisAngle({0, 0, 1}, 5.0f) * lying), m));
  EXPECT_EQ(m.count, 1);
}

TEST(TriangleRounded, SphereOverInternalEdgesAndVerticesPushesStraightUp) {
  // A sphere sunk into the flat floor anywhere, in particular right beside an internal edge or
  // vertex, where the triangle next door finds its nearest point on that edge and a normal tilted
  // towards the sphere's centre: one contact, straight up, as deep as the sphere is sunk.
  const Shape floor = test::flatGrid(4);
  const Shape sphere = Sphere{0.3f};
  std::mt19937 rng(12);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  for (int trial = 0; trial < 500; ++trial) {
    // Near grid lines and vertices: fractional parts within 0.05 of 0 half of the time.
    Vec3 c(1.5f * unit(rng), 0.3f - 0.05f * (0.5f + 0.5f * unit(rng)), 1.5f * unit(rng));
    if (trial % 2 == 0) c.x = std::round(c.x) + 0.05f * unit(rng);
    if (trial % 4 == 0) c.z = std::round(c.z) + 0.05f * unit(rng);
    Manifold m;
    ASSERT_TRUE(collide::collide(floor, Transform::identity(), sphere, at(c), m)) << "trial " << trial;
    EXPECT_EQ(m.count, 1) << "trial " << trial;
    EXPECT_LT(degreesBetween(m.normal, {0, 1, 0}), 1e-3f) << "trial " << trial;
    EXPECT_NEAR(m.maxDepth(), 0.3f - c.y, 1e-5f) << "trial " << trial;
  }
}

using test::fold;

TEST(TriangleRounded, ConcaveFoldGivesFaceNormalsConvexRidgeKeepsItsEdge) {
  const Shape sphere = Sphere{0.3f};
  Manifold m;
  // Valley (the right half rises at 10°): a sphere on the flat half, 0.06 from the fold, sunk 0.1.
  // The rising triangle's nearest point is on the fold (its plane's nearest point lies beyond it,
  // x < 0), 0.209 away along a normal tilted 17° (within the merge's 25°): a concave edge, so that
  // contact is dropped and the flat face's is the only one. As GJK points per triangle, the fold
  // gave a second point on the edge.
  const float shallow = std::tan(glm::radians(10.0f));
  const Shape valley = fold(shallow);
  const Vec3 centre(-0.06f, 0.2f, 0.0f);
  ASSERT_LT(glm::length(centre), 0.3f);  // the sphere reaches the fold
  ASSERT_TRUE(collide::collide(valley, Transform::identity(), sphere, at(centre), m));
  EXPECT_EQ(m.count, 1);
  EXPECT_LT(degreesBetween(m.normal, {0, 1, 0}), 1e-3f);
  EXPECT_NEAR(m.maxDepth(), 0.1f, 1e-5f);

  // Ridge (the right half falls at 30°): the sphere just over the fold's far side is held by the
  // convex edge, with the normal from the edge to its centre.
  const Shape ridge = fold(-std::tan(glm::radians(30.0f)));
  const Vec3 over(0.1f, 0.25f, 0.0f);
  ASSERT_TRUE(collide::collide(ridge, Transform::identity(), sphere, at(over), m));
  // Both triangles' nearest points are on the fold (the centre projects beyond each): the edge's
  // contact, the normal from the fold to the centre.
  const Vec3 expected = glm::normalize(over);
  EXPECT_LT(degreesBetween(m.normal, expected), 0.01f);
  EXPECT_NEAR(m.maxDepth(), 0.3f - glm::length(over), 1e-5f);
}

}  // namespace
}  // namespace collide
