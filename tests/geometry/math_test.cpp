// Math: Transform composition and inverse, box transforms, the slab test, plane classification,
// frustum extraction from a view-projection matrix, and orthonormal bases.
#include <collide/math.h>
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <random>
#include "support/test_assertions.h"

namespace collide {
namespace {

constexpr float kEps = 1e-5f;

using test::expectVecNear;

Transform makeTransform(const Vec3& position, float angle, const Vec3& axis, float scale) {
  return {position, glm::angleAxis(angle, glm::normalize(axis)), scale};
}

TEST(Transform, AppliesScaleThenRotationThenTranslation) {
  // 90° about z maps x to y: (1, 0, 0) scaled by 2 and moved by (1, 1, 1) is (1, 3, 1).
  const Transform t = makeTransform(Vec3(1.0f), kPi / 2.0f, Vec3(0, 0, 1), 2.0f);
  expectVecNear(Vec3(1.0f, 3.0f, 1.0f), t.applyToPoint(Vec3(1.0f, 0.0f, 0.0f)));
  expectVecNear(Vec3(0.0f, 2.0f, 0.0f), t.applyToVector(Vec3(1.0f, 0.0f, 0.0f)));
  expectVecNear(Vec3(0.0f, 1.0f, 0.0f), t.applyToDirection(Vec3(1.0f, 0.0f, 0.0f)));
  expectVecNear(Vec3(1.0f, 0.0f, 0.0f), t.inverseApplyToPoint(Vec3(1.0f, 3.0f, 1.0f)));
  expectVecNear(Vec3(1.0f, 0.0f, 0.0f), t.inverseApplyToDirection(Vec3(0.0f, 1.0f, 0.0f)));
}

TEST(Transform, CompositionAppliesTheRightOperandFirst) {
  const Transform a = makeTransform(Vec3(1.0f, -2.0f, 0.5f), 0.8f, Vec3(1, 2, 3), 1.5f);
  const Transform b = makeTransform(Vec3(-0.3f, 4.0f, 2.0f), -1.9f, Vec3(-2, 0.5, 1), 0.7f);
  const Transform ab = a * b;
  for (const Vec3& p : {Vec3(0.0f), Vec3(1.0f, 2.0f, 3.0f), Vec3(-4.0f, 0.5f, 2.0f)}) {
    expectVecNear(a.applyToPoint(b.applyToPoint(p)), ab.applyToPoint(p), 1e-4f);
  }
  EXPECT_NEAR(ab.scale, 1.05f, kEps);
  EXPECT_NEAR(glm::length(ab.rotation), 1.0f, kEps);
  EXPECT_TRUE(isValid(ab));
}

TEST(Transform, InverseUndoesTheTransform) {
  const Transform t = makeTransform(Vec3(3.0f, -1.0f, 2.0f), 2.2f, Vec3(0.3, -1, 0.2), 2.5f);
  const Transform inverse = t.inverse();
  for (const Vec3& p : {Vec3(0.0f), Vec3(1.0f, 2.0f, 3.0f), Vec3(-4.0f, 0.5f, 2.0f)}) {
    expectVecNear(p, inverse.applyToPoint(t.applyToPoint(p)), 1e-4f);
    expectVecNear(p, t.applyToPoint(inverse.applyToPoint(p)), 1e-4f);
    expectVecNear(t.inverseApplyToPoint(p), inverse.applyToPoint(p), 1e-4f);
  }
  const Transform identity = t * inverse;
  expectVecNear(Vec3(0.0f), identity.position, 1e-4f);
  EXPECT_NEAR(identity.scale, 1.0f, kEps);
  EXPECT_NEAR(std::abs(identity.rotation.w), 1.0f, kEps);
}

TEST(Transform, ValidityChecks) {
  EXPECT_TRUE(isValid(Transform{}));
  Transform t;
  t.scale = 0.0f;
  EXPECT_FALSE(isValid(t));
  t = Transform{};
  t.rotation = Quat(1.1f, 0.0f, 0.0f, 0.0f);
  EXPECT_FALSE(isValid(t));
  t = Transform{};
  t.position.y = std::numeric_limits<float>::infinity();
  EXPECT_FALSE(isValid(t));
}

TEST(TransformAabb, IsTheBoxOfTheTransformedCorners) {
  const Aabb local{Vec3(-1.0f, -2.0f, 0.5f), Vec3(2.0f, 1.0f, 3.0f)};
  const Transform t = makeTransform(Vec3(5.0f, 0.0f, -2.0f), 1.1f, Vec3(1, 1, -0.5), 1.7f);
  Aabb corners;
  for (int i = 0; i < 8; ++i) {
    corners.grow(t.applyToPoint(Vec3(i & 1 ? local.max.x : local.min.x, i & 2 ? local.max.y : local.min.y,
                                     i & 4 ? local.max.z : local.min.z)));
  }
  const Aabb world = transformAabb(local, t);
  expectVecNear(corners.min, world.min, 1e-4f);
  expectVecNear(corners.max, world.max, 1e-4f);
}

TEST(TransformAabb, RightAngleSwapsExtentsAndEmptyStaysEmpty) {
  const Aabb box = transformAabb({Vec3(-1.0f, -2.0f, -3.0f), Vec3(1.0f, 2.0f, 3.0f)},
                                 makeTransform(Vec3(0.0f), kPi / 2.0f, Vec3(0, 0, 1), 1.0f));
  expectVecNear(Vec3(2.0f, 1.0f, 3.0f), box.max);
  EXPECT_TRUE(transformAabb(Aabb::empty(), makeTransform(Vec3(1.0f), 0.3f, Vec3(1, 0, 0), 2.0f)).isEmpty());
}

TEST(RayAabbEntry, KnownEntriesMissesAndInside) {
  const Aabb box{Vec3(-1.0f), Vec3(1.0f)};
  EXPECT_NEAR(rayAabbEntry(Ray{Vec3(-5.0f, 0.0f, 0.0f), Vec3(1.0f, 0.0f, 0.0f)}, box), 4.0f, kEps);
  // Diagonal towards the corner region: enters when the last slab is entered, x = -1 at t = 4 sqrt 2.
  EXPECT_NEAR(rayAabbEntry(Ray{Vec3(-5.0f, -4.5f, 0.0f), glm::normalize(Vec3(1.0f, 1.0f, 0.0f))}, box),
              4.0f * std::sqrt(2.0f), kEps);
  EXPECT_EQ(rayAabbEntry(Ray{Vec3(0.5f, 0.0f, 0.0f), Vec3(1.0f, 0.0f, 0.0f)}, box), 0.0f);
  EXPECT_LT(rayAabbEntry(Ray{Vec3(-5.0f, 0.0f, 0.0f), Vec3(-1.0f, 0.0f, 0.0f)}, box), 0.0f);
  EXPECT_LT(rayAabbEntry(Ray{Vec3(-5.0f, 1.5f, 0.0f), Vec3(1.0f, 0.0f, 0.0f)}, box), 0.0f);
  EXPECT_LT(rayAabbEntry(Ray{Vec3(-5.0f, 0.0f, 0.0f), Vec3(1.0f, 0.0f, 0.0f), 3.9f}, box), 0.0f);
  EXPECT_LT(rayAabbEntry(Ray{Vec3(-5.0f, 0.0f, 0.0f), glm::normalize(Vec3(1.0f, 1.0f, 0.0f))}, box), 0.0f);
}

TEST(Classify, BoxesAndSpheresAgainstAHalfSpace) {
  const Plane plane{glm::normalize(Vec3(1.0f, 1.0f, 0.0f)), 0.0f};  // solid where x + y < 0
  EXPECT_EQ(classify(plane, Aabb{Vec3(-3.0f), Vec3(-2.0f)}), Side::Inside);
  EXPECT_EQ(classify(plane, Aabb{Vec3(2.0f), Vec3(3.0f)}), Side::Outside);
  EXPECT_EQ(classify(plane, Aabb{Vec3(-1.0f), Vec3(1.0f)}), Side::Straddling);
  // The unit box's projection radius on (1, 1, 0)/sqrt 2 is sqrt 2: centred at (1.5, 0, 0) it
  // reaches 1.5/sqrt 2 - sqrt 2 < 0.
  EXPECT_EQ(classify(plane, Aabb::fromCenterHalfExtents(Vec3(1.5f, 0.0f, 0.0f), Vec3(1.0f))),
            Side::Straddling);
  EXPECT_EQ(classify(plane, Aabb::fromCenterHalfExtents(Vec3(3.0f, 0.0f, 0.0f), Vec3(1.0f))), Side::Outside);
  EXPECT_EQ(classify(plane, BoundingSphere{Vec3(2.0f, 2.0f, 0.0f), 1.0f}), Side::Outside);
  EXPECT_EQ(classify(plane, BoundingSphere{Vec3(-2.0f, -2.0f, 0.0f), 1.0f}), Side::Inside);
  EXPECT_EQ(classify(plane, BoundingSphere{Vec3(0.5f, 0.0f, 0.0f), 1.0f}), Side::Straddling);
}

// A camera at `eye` looking at `target`, 90° vertical field of view, square, near 1, far 100.
Frustum makeFrustum(const Vec3& eye, const Vec3& target) {
  const Mat4 projection = glm::perspective(kPi / 2.0f, 1.0f, 1.0f, 100.0f);
  return Frustum::fromViewProjection(projection * glm::lookAt(eye, target, Vec3(0.0f, 1.0f, 0.0f)));
}

TEST(Frustum, PointsInsideAndOutsideAnAxisAlignedView) {
  // Looking down -z from the origin: at depth d the view spans |x|, |y| <= d.
  const Frustum f = makeFrustum(Vec3(0.0f), Vec3(0.0f, 0.0f, -1.0f));
  for (const Plane& plane : f.planes) EXPECT_NEAR(glm::length(plane.normal), 1.0f, kEps);
  EXPECT_TRUE(f.contains(Vec3(0.0f, 0.0f, -10.0f)));
  EXPECT_TRUE(f.contains(Vec3(9.9f, -9.9f, -10.0f)));
  EXPECT_FALSE(f.contains(Vec3(10.1f, 0.0f, -10.0f)));
  EXPECT_FALSE(f.contains(Vec3(0.0f, -10.1f, -10.0f)));
  EXPECT_FALSE(f.contains(Vec3(0.0f, 0.0f, -0.9f)));  // before the near plane
  EXPECT_TRUE(f.contains(Vec3(0.0f, 0.0f, -1.1f)));
  EXPECT_FALSE(f.contains(Vec3(0.0f, 0.0f, -100.5f)));  // beyond the far plane
  EXPECT_TRUE(f.contains(Vec3(0.0f, 0.0f, -99.5f)));
  EXPECT_FALSE(f.contains(Vec3(0.0f, 0.0f, 10.0f)));  // behind
  // Near and far planes are at distance 1 and 100 along the view axis.
  EXPECT_NEAR(f.planes[4].signedDistance(Vec3(0.0f, 0.0f, -1.0f)), 0.0f, 1e-4f);
  EXPECT_NEAR(f.planes[5].signedDistance(Vec3(0.0f, 0.0f, -100.0f)), 0.0f, 1e-2f);
}

TEST(Frustum, ZeroToOneDepthProjectionsGiveTheSameVolume) {
  // Direct3D's and Vulkan's depth range: glm::perspectiveZO maps the near plane to z = 0. Read with
  // the matching ClipDepth, the frustum is the one the [-1, 1] projection gives; read as [-1, 1], its
  // near plane comes halfway to the eye.
  const Mat4 view = glm::lookAt(Vec3(0.0f), Vec3(0.0f, 0.0f, -1.0f), Vec3(0.0f, 1.0f, 0.0f));
  const Mat4 zeroToOne = glm::perspectiveZO(kPi / 2.0f, 1.0f, 1.0f, 100.0f) * view;
  const Frustum f = Frustum::fromViewProjection(zeroToOne, Frustum::ClipDepth::ZeroToOne);
  const Frustum reference = makeFrustum(Vec3(0.0f), Vec3(0.0f, 0.0f, -1.0f));
  for (int i = 0; i < 6; ++i) {
    EXPECT_NEAR(glm::length(f.planes[i].normal - reference.planes[i].normal), 0.0f, 1e-5f) << "plane " << i;
    EXPECT_NEAR(f.planes[i].distance, reference.planes[i].distance, 1e-2f) << "plane " << i;
  }
  EXPECT_FALSE(f.contains(Vec3(0.0f, 0.0f, -0.9f)));  // before the near plane
  EXPECT_TRUE(f.contains(Vec3(0.0f, 0.0f, -1.1f)));
  const Frustum misread = Frustum::fromViewProjection(zeroToOne);
  EXPECT_TRUE(misread.contains(Vec3(0.0f, 0.0f, -0.75f)));
  EXPECT_NEAR(misread.planes[4].signedDistance(Vec3(0.0f, 0.0f, -100.0f / 199.0f)), 0.0f, 1e-4f);
}

TEST(Frustum, BoxesAndSpheresOfAMovedCamera) {
  // The same camera at (10, 5, 0) looking along +x: depth is x - 10.
  const Frustum f = makeFrustum(Vec3(10.0f, 5.0f, 0.0f), Vec3(20.0f, 5.0f, 0.0f));
  EXPECT_TRUE(f.contains(Vec3(30.0f, 5.0f, 0.0f)));
  EXPECT_TRUE(f.contains(Vec3(30.0f, 5.0f + 19.0f, 19.0f)));
  EXPECT_FALSE(f.contains(Vec3(30.0f, 5.0f + 21.0f, 0.0f)));
  EXPECT_FALSE(f.contains(Vec3(0.0f, 5.0f, 0.0f)));
  EXPECT_TRUE(f.intersects(Aabb::fromCenterHalfExtents(Vec3(50.0f, 5.0f, 0.0f), Vec3(1.0f))));
  EXPECT_FALSE(f.intersects(Aabb::fromCenterHalfExtents(Vec3(5.0f, 5.0f, 0.0f), Vec3(1.0f))));    // behind
  EXPECT_FALSE(f.intersects(Aabb::fromCenterHalfExtents(Vec3(20.0f, 5.0f, 30.0f), Vec3(2.0f))));  // far aside
  EXPECT_FALSE(f.intersects(Aabb::fromCenterHalfExtents(Vec3(200.0f, 5.0f, 0.0f), Vec3(5.0f))));  // too far
  // Straddling the side plane z = depth: centre outside, box reaches in.
  EXPECT_TRUE(f.intersects(Aabb::fromCenterHalfExtents(Vec3(20.0f, 5.0f, 11.0f), Vec3(2.0f))));
  EXPECT_TRUE(f.intersects(BoundingSphere{Vec3(20.0f, 5.0f, 11.0f), 1.5f}));
  EXPECT_FALSE(f.intersects(BoundingSphere{Vec3(20.0f, 5.0f, 13.0f), 1.5f}));
  EXPECT_TRUE(f.intersects(BoundingSphere{Vec3(10.5f, 5.0f, 0.0f), 0.6f}));  // reaches past the near plane
  EXPECT_FALSE(f.intersects(BoundingSphere{Vec3(10.0f, 5.0f, 0.0f), 0.5f}));
}

TEST(OrthonormalBasis, CompletesARightHandedFrameForAnyUnitVector) {
  std::mt19937 rng(99);
  std::normal_distribution<float> normal(0.0f, 1.0f);
  std::vector<Vec3> normals = {Vec3(0, 0, 1),
                               Vec3(0, 0, -1),
                               Vec3(1, 0, 0),
                               Vec3(0, -1, 0),
                               glm::normalize(Vec3(1e-4f, 0.0f, -1.0f)),
                               glm::normalize(Vec3(0.0f, 1e-7f, -1.0f)),
                               Vec3(0.0f, 0.0f, -0.0f) + Vec3(0, 0, -1)};
  for (int i = 0; i < 1000; ++i)
    normals.push_back(glm::normalize(Vec3(normal(rng), normal(rng), normal(rng))));
  for (const Vec3& n : normals) {
    Vec3 t, b;
    orthonormalBasis(n, t, b);
    EXPECT_NEAR(glm::length(t), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::length(b), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(t, n), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(b, n), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(t, b), 0.0f, 1e-5f);
    expectVecNear(n, glm::cross(t, b), 1e-5f);
  }
}

}  // namespace
}  // namespace collide
