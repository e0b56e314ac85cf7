// Box proxy, half extents (1, 2, 3): mass properties, rays onto faces, edges and corners, closest
// points on faces, edges and corners, and support.
#include <collide/shapes.h>
#include <gtest/gtest.h>

#include <cmath>
#include "support/test_assertions.h"

namespace collide {
namespace {

using test::kEps;

using test::expectVecNear;

const Box kBox{Vec3(1.0f, 2.0f, 3.0f)};

TEST(Box, MassPropertiesAreTheCuboidFormulas) {
  // Sides a, b, c = 2, 4, 6: V = 48, I_x = m (b² + c²) / 12.
  const MassProperties m = massProperties(kBox, 0.5f);
  EXPECT_NEAR(m.volume, 48.0f, 1e-4f);
  EXPECT_NEAR(m.mass, 24.0f, 1e-4f);
  expectVecNear(Vec3(0.0f), m.centerOfMass);
  EXPECT_NEAR(m.inertia[0][0], 24.0f * (16.0f + 36.0f) / 12.0f, 1e-3f);
  EXPECT_NEAR(m.inertia[1][1], 24.0f * (4.0f + 36.0f) / 12.0f, 1e-3f);
  EXPECT_NEAR(m.inertia[2][2], 24.0f * (4.0f + 16.0f) / 12.0f, 1e-3f);
  EXPECT_EQ(m.inertia[0][1], 0.0f);
  EXPECT_EQ(m.inertia[0][2], 0.0f);
  EXPECT_EQ(m.inertia[1][2], 0.0f);
}

TEST(Box, RaysHitEachFaceHeadOn) {
  for (int axis = 0; axis < 3; ++axis) {
    for (float sign : {-1.0f, 1.0f}) {
      Vec3 origin(0.1f, -0.2f, 0.3f), direction(0.0f), normal(0.0f);
      origin[axis] = sign * 10.0f;
      direction[axis] = -sign;
      normal[axis] = sign;
      const auto hit = rayCast(kBox, Transform{}, Ray{origin, direction});
      ASSERT_TRUE(hit) << axis << " " << sign;
      EXPECT_NEAR(hit->distance, 10.0f - kBox.halfExtents[axis], kEps);
      expectVecNear(normal, hit->normal);
    }
  }
}

TEST(Box, ObliqueRayHitsTheFaceItCrossesFirst) {
  // From (-3, 0, 0) towards +x and +y at 45°: x = -1 at y = 2, exactly the edge; start lower.
  const auto hit =
      rayCast(kBox, Transform{}, Ray{Vec3(-3.0f, -1.0f, 0.0f), glm::normalize(Vec3(1.0f, 1.0f, 0.0f))});
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->distance, 2.0f * std::sqrt(2.0f), kEps);
  expectVecNear(Vec3(-1.0f, 1.0f, 0.0f), hit->point);
  expectVecNear(Vec3(-1.0f, 0.0f, 0.0f), hit->normal);
  // From above, steeply: y = 2 is reached at x = 0.6, inside the top face.
  const auto top =
      rayCast(kBox, Transform{}, Ray{Vec3(0.0f, 5.0f, 0.0f), glm::normalize(Vec3(0.2f, -1.0f, 0.0f))});
  ASSERT_TRUE(top);
  EXPECT_NEAR(top->distance, 3.0f * std::sqrt(1.04f), kEps);
  expectVecNear(Vec3(0.6f, 2.0f, 0.0f), top->point);
  expectVecNear(Vec3(0.0f, 1.0f, 0.0f), top->normal);
}

TEST(Box, RayAtTheCornerHitsWithAFaceNormalThere) {
  const Vec3 direction = -glm::normalize(Vec3(1.0f));
  const auto hit = rayCast(kBox, Transform{}, Ray{Vec3(5.0f, 6.0f, 7.0f), direction});
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->distance, 4.0f * std::sqrt(3.0f), 1e-4f);
  expectVecNear(Vec3(1.0f, 2.0f, 3.0f), hit->point, 1e-4f);
  // Any of the three faces meeting at the corner is right; it must be one of them.
  EXPECT_NEAR(glm::length(hit->normal), 1.0f, kEps);
  EXPECT_NEAR(hit->normal.x + hit->normal.y + hit->normal.z, 1.0f, kEps);
  EXPECT_GE(glm::min(hit->normal.x, glm::min(hit->normal.y, hit->normal.z)), 0.0f);
}

TEST(Box, GrazingRayAlongAFaceTouchesAndOneAboveMisses) {
  const auto touch = rayCast(kBox, Transform{}, Ray{Vec3(-5.0f, 2.0f, 0.0f), Vec3(1.0f, 0.0f, 0.0f)});
  ASSERT_TRUE(touch);
  EXPECT_NEAR(touch->distance, 4.0f, kEps);
  EXPECT_FALSE(rayCast(kBox, Transform{}, Ray{Vec3(-5.0f, 2.001f, 0.0f), Vec3(1.0f, 0.0f, 0.0f)}));
}

TEST(Box, RayFromInsideBehindAndBeyondMaxDistance) {
  const auto inside = rayCast(kBox, Transform{}, Ray{Vec3(0.5f, 0.5f, 0.5f), Vec3(0.0f, 0.0f, 1.0f)});
  ASSERT_TRUE(inside);
  EXPECT_EQ(inside->distance, 0.0f);
  expectVecNear(Vec3(0.0f, 0.0f, -1.0f), inside->normal);
  EXPECT_FALSE(rayCast(kBox, Transform{}, Ray{Vec3(-5.0f, 0.0f, 0.0f), Vec3(-1.0f, 0.0f, 0.0f)}));
  EXPECT_FALSE(rayCast(kBox, Transform{}, Ray{Vec3(-5.0f, 0.0f, 0.0f), Vec3(1.0f, 0.0f, 0.0f), 3.99f}));
  EXPECT_TRUE(rayCast(kBox, Transform{}, Ray{Vec3(-5.0f, 0.0f, 0.0f), Vec3(1.0f, 0.0f, 0.0f), 4.01f}));
}

TEST(Box, RayAgainstARotatedScaledBox) {
  // 90° about z maps the x half extent 1 onto y; at scale 2 the box spans y in [-2, 2], x in [-4, 4].
  const Transform t{Vec3(0.0f, 0.0f, 0.0f), glm::angleAxis(kPi / 2.0f, Vec3(0.0f, 0.0f, 1.0f)), 2.0f};
  const auto fromAbove = rayCast(kBox, t, Ray{Vec3(0.0f, 10.0f, 0.0f), Vec3(0.0f, -1.0f, 0.0f)});
  ASSERT_TRUE(fromAbove);
  EXPECT_NEAR(fromAbove->distance, 8.0f, 1e-4f);
  expectVecNear(Vec3(0.0f, 1.0f, 0.0f), fromAbove->normal, 1e-5f);
  const auto fromSide = rayCast(kBox, t, Ray{Vec3(10.0f, 0.0f, 0.0f), Vec3(-1.0f, 0.0f, 0.0f)});
  ASSERT_TRUE(fromSide);
  EXPECT_NEAR(fromSide->distance, 6.0f, 1e-4f);
}

TEST(Box, ClosestPointOnFacesEdgesAndCorners) {
  const Shape box(kBox);
  const SurfacePoint face = closestPoint(box, Transform{}, Vec3(4.0f, 0.5f, -1.0f));
  expectVecNear(Vec3(1.0f, 0.5f, -1.0f), face.point);
  expectVecNear(Vec3(1.0f, 0.0f, 0.0f), face.normal);
  EXPECT_NEAR(face.signedDistance, 3.0f, kEps);
  // Beyond the edge x = 1, y = 2: nearest is on the edge, normal along the offset.
  const SurfacePoint edge = closestPoint(box, Transform{}, Vec3(4.0f, 6.0f, 1.0f));
  expectVecNear(Vec3(1.0f, 2.0f, 1.0f), edge.point);
  expectVecNear(Vec3(0.6f, 0.8f, 0.0f), edge.normal);
  EXPECT_NEAR(edge.signedDistance, 5.0f, kEps);
  const SurfacePoint corner = closestPoint(box, Transform{}, Vec3(-2.0f, -4.0f, 5.0f));
  expectVecNear(Vec3(-1.0f, -2.0f, 3.0f), corner.point);
  expectVecNear(Vec3(-1.0f, -2.0f, 2.0f) / 3.0f, corner.normal);
  EXPECT_NEAR(corner.signedDistance, 3.0f, kEps);
}

TEST(Box, ClosestPointFromInsideLeavesThroughTheNearestFace) {
  const Shape box(kBox);
  const SurfacePoint nearX = closestPoint(box, Transform{}, Vec3(0.8f, 0.0f, 0.0f));
  expectVecNear(Vec3(1.0f, 0.0f, 0.0f), nearX.point);
  EXPECT_NEAR(nearX.signedDistance, -0.2f, kEps);
  const SurfacePoint nearZ = closestPoint(box, Transform{}, Vec3(0.0f, 0.5f, -2.9f));
  expectVecNear(Vec3(0.0f, 0.5f, -3.0f), nearZ.point);
  expectVecNear(Vec3(0.0f, 0.0f, -1.0f), nearZ.normal);
  EXPECT_NEAR(nearZ.signedDistance, -0.1f, kEps);
  const SurfacePoint centre = closestPoint(box, Transform{}, Vec3(0.0f));
  EXPECT_NEAR(centre.signedDistance, -1.0f, kEps);
  // Exactly on an edge: distance 0 and a normal of one of the two faces.
  const SurfacePoint onEdge = closestPoint(box, Transform{}, Vec3(1.0f, 2.0f, 0.0f));
  EXPECT_NEAR(onEdge.signedDistance, 0.0f, kEps);
  EXPECT_TRUE(onEdge.normal == Vec3(1.0f, 0.0f, 0.0f) || onEdge.normal == Vec3(0.0f, 1.0f, 0.0f));
}

TEST(Box, SupportIsTheCornerInTheDirectionsOctant) {
  expectVecNear(Vec3(1.0f, -2.0f, 3.0f), support(kBox, Vec3(0.1f, -5.0f, 2.0f)));
  expectVecNear(Vec3(-1.0f, -2.0f, -3.0f), support(kBox, Vec3(-1.0f)));
}

TEST(Box, WorldBoundsOfARotatedBoxAreExact) {
  // 45° about z: x and y extents become (1 + 2) / sqrt(2); z stays 3; at scale 2 all double.
  const Transform t{Vec3(1.0f, 1.0f, 1.0f), glm::angleAxis(kPi / 4.0f, Vec3(0.0f, 0.0f, 1.0f)), 2.0f};
  const Aabb box = worldBounds(kBox, t);
  const float xy = 2.0f * 3.0f / std::sqrt(2.0f);
  expectVecNear(Vec3(1.0f - xy, 1.0f - xy, 1.0f - 6.0f), box.min, 1e-4f);
  expectVecNear(Vec3(1.0f + xy, 1.0f + xy, 1.0f + 6.0f), box.max, 1e-4f);
}

}  // namespace
}  // namespace collide
