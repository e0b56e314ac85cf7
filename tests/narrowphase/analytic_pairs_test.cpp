// Known configurations for the analytic entries of the pair table: touching, separated, deep,
// parallel, resting face-down; depths, normals, points and feature ids checked by hand.
#include <collide/narrowphase.h>
#include <gtest/gtest.h>

#include <set>

#include "narrowphase/pair_functions.h"
#include "support/narrowphase_helpers.h"
#include "support/test_assertions.h"

using namespace collide;
using namespace collide::test;
using detail::boxFeature;
using detail::featurePair;

namespace {

constexpr float kClosedFormTolerance = 1e-5f;

using test::expectVecNear;

// The manifold contract of narrowphase.h: unit normal, depth = (pA - pB)·n, at most four points.
void expectContract(const Manifold& m) {
  ASSERT_LE(m.count, Manifold::kMaxPoints);
  EXPECT_NEAR(glm::length(m.normal), 1.0f, 1e-5f);
  for (int i = 0; i < m.count; ++i) {
    EXPECT_NEAR(m.points[i].depth, glm::dot(m.points[i].pointOnA - m.points[i].pointOnB, m.normal), 1e-5f);
  }
}

std::set<std::uint32_t> featureIds(const Manifold& m) {
  std::set<std::uint32_t> ids;
  for (int i = 0; i < m.count; ++i) ids.insert(m.points[i].featureId);
  return ids;
}

const Transform kIdentity = Transform::identity();

}  // namespace

// ---- Sphere–sphere ----

TEST(SphereSphere, DeepOverlapGivesDepthNormalAndSurfacePoints) {
  Manifold m;
  ASSERT_TRUE(collide::collide(Sphere{1.0f}, kIdentity, Sphere{0.5f}, at({1.0f, 0.0f, 0.0f}), m));
  expectContract(m);
  ASSERT_EQ(m.count, 1);
  expectVecNear(m.normal, {1, 0, 0});
  EXPECT_NEAR(m.points[0].depth, 0.5f, kClosedFormTolerance);
  expectVecNear(m.points[0].pointOnA, {1, 0, 0});
  expectVecNear(m.points[0].pointOnB, {0.5f, 0, 0});
}

TEST(SphereSphere, TouchingHasZeroDepthAndSeparatedHasNone) {
  Manifold m;
  ASSERT_TRUE(collide::collide(Sphere{1.0f}, kIdentity, Sphere{0.5f}, at({0.0f, 1.5f, 0.0f}), m));
  EXPECT_NEAR(m.points[0].depth, 0.0f, kClosedFormTolerance);
  expectVecNear(m.normal, {0, 1, 0});
  EXPECT_FALSE(collide::collide(Sphere{1.0f}, kIdentity, Sphere{0.5f}, at({0.0f, 2.0f, 0.0f}), m));
  EXPECT_EQ(m.count, 0);
}

TEST(SphereSphere, SpeculativeMarginReportsNegativeDepth) {
  Manifold m;
  ASSERT_TRUE(collide::collide(Sphere{1.0f}, kIdentity, Sphere{0.5f}, at({0.0f, 0.0f, 2.0f}), m, 0.6f));
  EXPECT_NEAR(m.points[0].depth, -0.5f, kClosedFormTolerance);
  EXPECT_FALSE(collide::collide(Sphere{1.0f}, kIdentity, Sphere{0.5f}, at({0.0f, 0.0f, 2.0f}), m, 0.4f));
}

TEST(SphereSphere, UniformScaleScalesTheRadius) {
  Manifold m;
  ASSERT_TRUE(collide::collide(Sphere{1.0f}, at({0, 0, 0}, Quat(1, 0, 0, 0), 2.0f), Sphere{1.0f},
                               at({2.5f, 0, 0}), m));
  EXPECT_NEAR(m.points[0].depth, 0.5f, kClosedFormTolerance);
}

TEST(SphereSphere, ConcentricSpheresStillGetAUnitNormal) {
  Manifold m;
  ASSERT_TRUE(collide::collide(Sphere{1.0f}, kIdentity, Sphere{0.5f}, kIdentity, m));
  expectContract(m);
  EXPECT_NEAR(m.points[0].depth, 1.5f, kClosedFormTolerance);
}

// ---- Sphere–capsule ----

TEST(SphereCapsule, SideEndAndSeparated) {
  const Capsule capsule{0.5f, 1.0f};
  Manifold m;
  ASSERT_TRUE(collide::collide(Sphere{0.5f}, at({0.8f, 0.3f, 0.0f}), capsule, kIdentity, m));
  expectContract(m);
  expectVecNear(m.normal, {-1, 0, 0});
  EXPECT_NEAR(m.points[0].depth, 0.2f, kClosedFormTolerance);
  EXPECT_EQ(m.points[0].featureId, featurePair(0, detail::kCapsuleSide));

  ASSERT_TRUE(collide::collide(Sphere{0.5f}, at({0.0f, 1.8f, 0.0f}), capsule, kIdentity, m));
  expectVecNear(m.normal, {0, -1, 0});
  EXPECT_NEAR(m.points[0].depth, 0.2f, kClosedFormTolerance);
  EXPECT_EQ(m.points[0].featureId, featurePair(0, detail::kCapsuleEnd1));

  EXPECT_FALSE(collide::collide(Sphere{0.5f}, at({0.0f, 2.3f, 0.0f}), capsule, kIdentity, m));
}

// ---- Sphere–box ----

TEST(SphereBox, FaceEdgeVertexAndInside) {
  const Box box{Vec3(1.0f, 2.0f, 3.0f)};
  Manifold m;
  // Face +x.
  ASSERT_TRUE(collide::collide(Sphere{0.5f}, at({1.3f, 0.5f, 0.5f}), box, kIdentity, m));
  expectContract(m);
  expectVecNear(m.normal, {-1, 0, 0});
  EXPECT_NEAR(m.points[0].depth, 0.2f, kClosedFormTolerance);
  expectVecNear(m.points[0].pointOnB, {1.0f, 0.5f, 0.5f});
  EXPECT_EQ(m.points[0].featureId, featurePair(0, boxFeature(2, 1, 1)));
  // Vertex (+, +, +), 0.2 beyond on each axis: distance 0.2·√3.
  ASSERT_TRUE(collide::collide(Sphere{0.5f}, at({1.2f, 2.2f, 3.2f}), box, kIdentity, m));
  EXPECT_NEAR(m.points[0].depth, 0.5f - 0.2f * std::sqrt(3.0f), kClosedFormTolerance);
  expectVecNear(m.normal, -glm::normalize(Vec3(1, 1, 1)));
  EXPECT_EQ(m.points[0].featureId, featurePair(0, boxFeature(2, 2, 2)));
  // Edge (-x, +y).
  ASSERT_TRUE(collide::collide(Sphere{0.5f}, at({-1.3f, 2.3f, 0.0f}), box, kIdentity, m));
  EXPECT_NEAR(m.points[0].depth, 0.5f - 0.3f * std::sqrt(2.0f), kClosedFormTolerance);
  EXPECT_EQ(m.points[0].featureId, featurePair(0, boxFeature(0, 2, 1)));
  // Centre inside, nearest face +x 0.1 away: the sphere leaves through +x.
  ASSERT_TRUE(collide::collide(Sphere{0.5f}, at({0.9f, 0.0f, 0.0f}), box, kIdentity, m));
  expectContract(m);
  expectVecNear(m.normal, {-1, 0, 0});
  EXPECT_NEAR(m.points[0].depth, 0.6f, kClosedFormTolerance);
  expectVecNear(m.points[0].pointOnB, {1.0f, 0.0f, 0.0f});
  // Separated.
  EXPECT_FALSE(collide::collide(Sphere{0.5f}, at({2.0f, 0.0f, 0.0f}), box, kIdentity, m));
}

TEST(SphereBox, RotatedAndScaledBox) {
  // A box (1, 0.5, 1) turned 90 degrees about z and scaled by 2.
  Manifold m;
  // Rotated: local y (0.5·2 = 1) lies along world x; the face is at x = 1.
  EXPECT_FALSE(collide::collide(Sphere{0.5f}, at({1.6f, 0.0f, 0.0f}), Box{Vec3(1.0f, 0.5f, 1.0f)},
                                at({0, 0, 0}, axisAngle({0, 0, 1}, 90.0f), 2.0f), m));
  ASSERT_TRUE(collide::collide(Sphere{0.5f}, at({1.3f, 0.0f, 0.0f}), Box{Vec3(1.0f, 0.5f, 1.0f)},
                               at({0, 0, 0}, axisAngle({0, 0, 1}, 90.0f), 2.0f), m));
  EXPECT_NEAR(m.points[0].depth, 0.2f, kClosedFormTolerance);
  expectVecNear(m.normal, {-1, 0, 0});
}

// ---- Capsule–capsule ----

TEST(CapsuleCapsule, ParallelOverlappingGiveTwoPoints) {
  const Capsule capsule{0.5f, 1.0f};
  Manifold m;
  ASSERT_TRUE(collide::collide(capsule, kIdentity, capsule, at({0.9f, 0.0f, 0.0f}), m));
  expectContract(m);
  ASSERT_EQ(m.count, 2);
  expectVecNear(m.normal, {1, 0, 0});
  for (int i = 0; i < 2; ++i) EXPECT_NEAR(m.points[i].depth, 0.1f, kClosedFormTolerance);
  EXPECT_NEAR(std::abs(m.points[0].pointOnA.y - m.points[1].pointOnA.y), 2.0f, kClosedFormTolerance);
  // Shifted by 1 along the axis: the overlap is y in [0, 1].
  ASSERT_TRUE(collide::collide(capsule, kIdentity, capsule, at({0.9f, 1.0f, 0.0f}), m));
  ASSERT_EQ(m.count, 2);
  const float y0 = std::min(m.points[0].pointOnA.y, m.points[1].pointOnA.y);
  const float y1 = std::max(m.points[0].pointOnA.y, m.points[1].pointOnA.y);
  EXPECT_NEAR(y0, 0.0f, kClosedFormTolerance);
  EXPECT_NEAR(y1, 1.0f, kClosedFormTolerance);
  EXPECT_EQ(featureIds(m),
            (std::set<std::uint32_t>{featurePair(detail::kCapsuleSide, detail::kCapsuleEnd0),
                                     featurePair(detail::kCapsuleEnd1, detail::kCapsuleSide)}));
}

TEST(CapsuleCapsule, CrossedEndToEndAndSeparated) {
  const Capsule capsule{0.5f, 1.0f};
  Manifold m;
  // Crossed: B along z at x = 0.9.
  ASSERT_TRUE(
      collide::collide(capsule, kIdentity, capsule, at({0.9f, 0.0f, 0.0f}, axisAngle({1, 0, 0}, 90.0f)), m));
  ASSERT_EQ(m.count, 1);
  expectVecNear(m.normal, {1, 0, 0});
  EXPECT_NEAR(m.points[0].depth, 0.1f, kClosedFormTolerance);
  EXPECT_EQ(m.points[0].featureId, featurePair(detail::kCapsuleSide, detail::kCapsuleSide));
  // End to end along y.
  ASSERT_TRUE(collide::collide(capsule, kIdentity, capsule, at({0.0f, 2.9f, 0.0f}), m));
  ASSERT_EQ(m.count, 1);
  expectVecNear(m.normal, {0, 1, 0});
  EXPECT_NEAR(m.points[0].depth, 0.1f, kClosedFormTolerance);
  EXPECT_EQ(m.points[0].featureId, featurePair(detail::kCapsuleEnd1, detail::kCapsuleEnd0));
  // Separated.
  EXPECT_FALSE(collide::collide(capsule, kIdentity, capsule, at({1.2f, 0.0f, 0.0f}), m));
  // Axes crossing through each other: the normal is perpendicular to both.
  ASSERT_TRUE(collide::collide(capsule, kIdentity, capsule, at({0, 0, 0}, axisAngle({1, 0, 0}, 90.0f)), m));
  expectContract(m);
  EXPECT_NEAR(std::abs(m.normal.x), 1.0f, kClosedFormTolerance);
  EXPECT_NEAR(m.points[0].depth, 1.0f, kClosedFormTolerance);
}

// ---- Capsule–box ----

TEST(CapsuleBox, LyingOnAFaceGivesTwoClippedPoints) {
  const Box box{Vec3(2.0f, 0.5f, 2.0f)};
  const Capsule capsule{0.5f, 1.0f};
  const Quat lying = axisAngle({0, 0, 1}, 90.0f);  // axis along world x
  Manifold m;
  ASSERT_TRUE(collide::collide(capsule, at({0.0f, 0.9f, 0.0f}, lying), box, kIdentity, m));
  expectContract(m);
  ASSERT_EQ(m.count, 2);
  expectVecNear(m.normal, {0, -1, 0});
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(m.points[i].depth, 0.1f, kClosedFormTolerance);
    EXPECT_NEAR(std::abs(m.points[i].pointOnB.x), 1.0f, kClosedFormTolerance);
    EXPECT_NEAR(m.points[i].pointOnB.y, 0.5f, kClosedFormTolerance);
  }
  EXPECT_EQ(featureIds(m), (std::set<std::uint32_t>{featurePair(detail::kCapsuleEnd0, boxFeature(1, 2, 1)),
                                                    featurePair(detail::kCapsuleEnd1, boxFeature(1, 2, 1))}));
  // Hanging over the edge x = 2: the segment x in [1.5, 3.5] is clipped to [1.5, 2].
  ASSERT_TRUE(collide::collide(capsule, at({2.5f, 0.9f, 0.0f}, lying), box, kIdentity, m));
  ASSERT_EQ(m.count, 2);
  const float x0 = std::min(m.points[0].pointOnB.x, m.points[1].pointOnB.x);
  const float x1 = std::max(m.points[0].pointOnB.x, m.points[1].pointOnB.x);
  EXPECT_NEAR(x0, 1.5f, 1e-4f);
  EXPECT_NEAR(x1, 2.0f, 1e-4f);
}

TEST(CapsuleBox, StandingSeparatedAndDeep) {
  const Box box{Vec3(2.0f, 0.5f, 2.0f)};
  const Capsule capsule{0.5f, 1.0f};
  Manifold m;
  ASSERT_TRUE(collide::collide(capsule, at({0.3f, 1.9f, 0.0f}), box, kIdentity, m));
  expectContract(m);
  ASSERT_EQ(m.count, 1);
  expectVecNear(m.normal, {0, -1, 0}, 1e-4f);
  EXPECT_NEAR(m.points[0].depth, 0.1f, 1e-4f);
  EXPECT_EQ(m.points[0].featureId, featurePair(detail::kCapsuleEnd0, boxFeature(1, 2, 1)));
  EXPECT_FALSE(collide::collide(capsule, at({0.3f, 2.4f, 0.0f}), box, kIdentity, m));
  // Deep: the lower end sphere's centre is 0.2 inside the top face.
  ASSERT_TRUE(collide::collide(capsule, at({0.3f, 1.3f, 0.0f}), box, kIdentity, m));
  expectVecNear(m.normal, {0, -1, 0}, 1e-4f);
  EXPECT_NEAR(m.points[0].depth, 0.7f, 1e-4f);
}

// ---- Plane pairs (the plane is the ground y = 0, solid below) ----

namespace {
const Plane kFloorPlane{{0.0f, 1.0f, 0.0f}, 0.0f};
}

TEST(PlanePairs, SphereAboveTouchingAndBelow) {
  Manifold m;
  ASSERT_TRUE(collide::collide(kFloorPlane, kIdentity, Sphere{1.0f}, at({2.0f, 0.8f, 0.0f}), m));
  expectContract(m);
  expectVecNear(m.normal, {0, 1, 0});
  EXPECT_NEAR(m.points[0].depth, 0.2f, kClosedFormTolerance);
  expectVecNear(m.points[0].pointOnA, {2.0f, 0.0f, 0.0f});
  expectVecNear(m.points[0].pointOnB, {2.0f, -0.2f, 0.0f});
  EXPECT_FALSE(collide::collide(kFloorPlane, kIdentity, Sphere{1.0f}, at({0.0f, 1.1f, 0.0f}), m));
}

TEST(PlanePairs, TransformedPlane) {
  // The surface y = 1 with normal +y, moved by +2 along x (no effect) and turned 90° about z: the
  // normal becomes -x and the surface x = -1.
  const Plane plane{{0.0f, 1.0f, 0.0f}, 1.0f};
  Manifold m;
  ASSERT_TRUE(collide::collide(plane, at({0, 0, 0}, axisAngle({0, 0, 1}, 90.0f)), Sphere{0.5f},
                               at({-1.3f, 0, 0}), m));
  expectVecNear(m.normal, {-1, 0, 0});
  EXPECT_NEAR(m.points[0].depth, 0.2f, kClosedFormTolerance);
}

TEST(PlanePairs, CapsuleLyingGivesTwoPointsStandingOne) {
  const Capsule capsule{0.5f, 1.0f};
  Manifold m;
  ASSERT_TRUE(collide::collide(kFloorPlane, kIdentity, capsule,
                               at({0.0f, 0.4f, 0.0f}, axisAngle({0, 0, 1}, 90.0f)), m));
  expectContract(m);
  ASSERT_EQ(m.count, 2);
  for (int i = 0; i < 2; ++i) EXPECT_NEAR(m.points[i].depth, 0.1f, kClosedFormTolerance);
  ASSERT_TRUE(collide::collide(kFloorPlane, kIdentity, capsule, at({0.0f, 1.4f, 0.0f}), m));
  ASSERT_EQ(m.count, 1);
  EXPECT_NEAR(m.points[0].depth, 0.1f, kClosedFormTolerance);
  EXPECT_EQ(m.points[0].featureId, featurePair(0, detail::kCapsuleEnd0));
}

TEST(PlanePairs, BoxFaceDownGivesFourPointsWithDepthAndNormal) {
  const Box box{Vec3(0.5f, 0.5f, 0.5f)};
  Manifold m;
  ASSERT_TRUE(collide::collide(kFloorPlane, kIdentity, box, at({1.0f, 0.45f, -2.0f}), m));
  expectContract(m);
  ASSERT_EQ(m.count, 4);
  expectVecNear(m.normal, {0, 1, 0});
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(m.points[i].depth, 0.05f, kClosedFormTolerance);
    EXPECT_NEAR(m.points[i].pointOnB.y, -0.05f, kClosedFormTolerance);
    EXPECT_NEAR(m.points[i].pointOnA.y, 0.0f, kClosedFormTolerance);
  }
  EXPECT_EQ(featureIds(m), (std::set<std::uint32_t>{
                               featurePair(0, boxFeature(0, 0, 0)), featurePair(0, boxFeature(2, 0, 0)),
                               featurePair(0, boxFeature(0, 0, 2)), featurePair(0, boxFeature(2, 0, 2))}));
  EXPECT_FALSE(collide::collide(kFloorPlane, kIdentity, box, at({0.0f, 0.55f, 0.0f}), m));
}

TEST(PlanePairs, BoxOnPlaneKeepsItsFourFeatureIdsUnderSmallPerturbation) {
  const Box box{Vec3(0.5f, 0.3f, 0.7f)};
  Manifold reference;
  ASSERT_TRUE(collide::collide(kFloorPlane, kIdentity, box, at({0.0f, 0.25f, 0.0f}), reference));
  ASSERT_EQ(reference.count, 4);
  const std::set<std::uint32_t> ids = featureIds(reference);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> wobble(-1.0f, 1.0f);
  for (int trial = 0; trial < 200; ++trial) {
    // Tilts up to 0.5 degrees, slides and bobs of a few millimetres.
    const Quat tilt = axisAngle(randomUnit(rng), 0.5f * wobble(rng));
    const Vec3 position(0.01f * wobble(rng), 0.25f + 0.003f * wobble(rng), 0.01f * wobble(rng));
    Manifold m;
    ASSERT_TRUE(collide::collide(kFloorPlane, kIdentity, box,
                                 at(position, tilt * axisAngle({0, 1, 0}, 2.0f * wobble(rng))), m));
    ASSERT_EQ(m.count, 4);
    EXPECT_EQ(featureIds(m), ids);
  }
}

TEST(PlanePairs, TiltedBoxGivesItsLowestVertex) {
  // Balanced on an edge then tilted further: rotated 30 degrees about z, one edge (two vertices) lowest.
  const Box box{Vec3(0.5f)};
  const Quat tilt = axisAngle({0, 0, 1}, 30.0f);
  const float lowest = 0.5f * (std::cos(glm::radians(30.0f)) + std::sin(glm::radians(30.0f)));
  Manifold m;
  ASSERT_TRUE(collide::collide(kFloorPlane, kIdentity, box, at({0.0f, lowest - 0.1f, 0.0f}, tilt), m));
  expectContract(m);
  ASSERT_EQ(m.count, 2);
  for (int i = 0; i < 2; ++i) EXPECT_NEAR(m.points[i].depth, 0.1f, kClosedFormTolerance);
}

TEST(PlanePairs, CylinderFlatOnCapOnSideAndTilted) {
  const Cylinder cylinder{0.5f, 1.0f};
  Manifold m;
  ASSERT_TRUE(collide::collide(kFloorPlane, kIdentity, cylinder, at({0.0f, 0.95f, 0.0f}), m));
  expectContract(m);
  ASSERT_EQ(m.count, 4);
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(m.points[i].depth, 0.05f, kClosedFormTolerance);
    EXPECT_NEAR(glm::length(Vec3(m.points[i].pointOnB.x, 0, m.points[i].pointOnB.z)), 0.5f,
                kClosedFormTolerance);
  }
  ASSERT_TRUE(collide::collide(kFloorPlane, kIdentity, cylinder,
                               at({0.0f, 0.45f, 0.0f}, axisAngle({1, 0, 0}, 90.0f)), m));
  ASSERT_EQ(m.count, 2);
  for (int i = 0; i < 2; ++i) EXPECT_NEAR(m.points[i].depth, 0.05f, kClosedFormTolerance);
  // Tilted 30 degrees: the lowest rim point is at -(h cos 30 + r sin 30).
  const float lowest = 1.0f * std::cos(glm::radians(30.0f)) + 0.5f * std::sin(glm::radians(30.0f));
  ASSERT_TRUE(collide::collide(kFloorPlane, kIdentity, cylinder,
                               at({0.0f, lowest - 0.1f, 0.0f}, axisAngle({1, 0, 0}, 30.0f)), m));
  ASSERT_EQ(m.count, 1);
  EXPECT_NEAR(m.points[0].depth, 0.1f, kClosedFormTolerance);
}

TEST(PlanePairs, EllipsoidLowestPoint) {
  Manifold m;
  ASSERT_TRUE(
      collide::collide(kFloorPlane, kIdentity, Ellipsoid{Vec3(1.0f, 2.0f, 3.0f)}, at({0.0f, 1.5f, 0.0f}), m));
  ASSERT_EQ(m.count, 1);
  EXPECT_NEAR(m.points[0].depth, 0.5f, kClosedFormTolerance);
  expectVecNear(m.points[0].pointOnB, {0.0f, -0.5f, 0.0f});
  // Turned 90 degrees about x: the 3-radius lies vertical.
  ASSERT_TRUE(collide::collide(kFloorPlane, kIdentity, Ellipsoid{Vec3(1.0f, 2.0f, 3.0f)},
                               at({0.0f, 2.5f, 0.0f}, axisAngle({1, 0, 0}, 90.0f)), m));
  EXPECT_NEAR(m.points[0].depth, 0.5f, kClosedFormTolerance);
}
