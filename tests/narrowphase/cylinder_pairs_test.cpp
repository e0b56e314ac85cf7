// Cylinder against box, k-DOP, convex hull and cylinder (src/narrowphase/cylinder_pairs.cpp): a cap
// or a side meeting a face gives the face's manifold, as the plane pair does, not GJK's one point.
// The expected points and depths follow from the placements by hand.
#include <collide/narrowphase.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <vector>

#include "support/narrowphase_helpers.h"

namespace collide {
namespace {

using test::at;
using test::axisAngle;

constexpr float kDepth = 0.01f;  // every resting placement below sinks 1 cm

// A 4 x 1 x 4 slab whose top face is y = 0, as each polyhedral type.
Shape slab(ShapeType type) {
  const Vec3 h(2.0f, 0.5f, 2.0f);
  std::vector<Vec3> corners;
  for (int i = 0; i < 8; ++i)
    corners.push_back(Vec3((i & 1) ? h.x : -h.x, (i & 2) ? h.y : -h.y, (i & 4) ? h.z : -h.z));
  if (type == ShapeType::Box) return Box{h};
  if (type == ShapeType::Kdop) return Kdop::fromPoints(6, corners);
  return ConvexHull::fromPoints(corners);
}
const Transform kSlabPlace = at(Vec3(0.0f, -0.5f, 0.0f));

TEST(CylinderPairs, StandingOnAFaceTouchesAtFourRimPoints) {
  const Shape cylinder = Cylinder{0.5f, 0.5f};
  for (const ShapeType type : {ShapeType::Box, ShapeType::Kdop, ShapeType::ConvexHull}) {
    SCOPED_TRACE(std::string(toString(type)));
    const Shape other = slab(type);
    Manifold m;
    ASSERT_TRUE(collide(cylinder, at(Vec3(0.3f, 0.5f - kDepth, -0.2f)), other, kSlabPlace, m));
    ASSERT_EQ(m.count, 4);
    EXPECT_NEAR(m.normal.y, -1.0f, 1e-5f);  // from the cylinder into the slab
    std::vector<Vec3> expected = {
        {0.8f, 0.0f, -0.2f}, {-0.2f, 0.0f, -0.2f}, {0.3f, 0.0f, 0.3f}, {0.3f, 0.0f, -0.7f}};
    for (int i = 0; i < m.count; ++i) {
      EXPECT_NEAR(m.points[i].depth, kDepth, 1e-5f);
      EXPECT_NEAR(m.points[i].pointOnB.y, 0.0f, 1e-5f);
      const Vec3 p = m.points[i].pointOnB;
      EXPECT_TRUE(std::any_of(expected.begin(), expected.end(),
                              [&](const Vec3& e) { return glm::length(e - p) < 1e-4f; }))
          << p.x << " " << p.y << " " << p.z;
    }
    // The same pair the other way round: the normal flips, the points stay.
    Manifold mirrored;
    ASSERT_TRUE(collide(other, kSlabPlace, cylinder, at(Vec3(0.3f, 0.5f - kDepth, -0.2f)), mirrored));
    EXPECT_EQ(mirrored.count, 4);
    EXPECT_NEAR(mirrored.normal.y, 1.0f, 1e-5f);
  }
}

TEST(CylinderPairs, LyingOnAFaceTouchesAlongItsSide) {
  // Axis along x (turned 90 degrees about z), 2 m long: the side line from x = -1 to x = 1.
  const Shape cylinder = Cylinder{0.5f, 1.0f};
  const Transform lying = at(Vec3(0.0f, 0.5f - kDepth, 0.4f), axisAngle(Vec3(0, 0, 1), 90.0f));
  for (const ShapeType type : {ShapeType::Box, ShapeType::Kdop, ShapeType::ConvexHull}) {
    SCOPED_TRACE(std::string(toString(type)));
    Manifold m;
    ASSERT_TRUE(collide(cylinder, lying, slab(type), kSlabPlace, m));
    ASSERT_EQ(m.count, 2);
    std::array<float, 2> xs{m.points[0].pointOnB.x, m.points[1].pointOnB.x};
    std::sort(xs.begin(), xs.end());
    EXPECT_NEAR(xs[0], -1.0f, 1e-4f);
    EXPECT_NEAR(xs[1], 1.0f, 1e-4f);
    for (int i = 0; i < 2; ++i) {
      EXPECT_NEAR(m.points[i].depth, kDepth, 1e-5f);
      EXPECT_NEAR(m.points[i].pointOnB.z, 0.4f, 1e-4f);
    }
  }
}

TEST(CylinderPairs, WiderThanTheFaceTouchesWhereTheyOverlap) {
  // A cylinder of radius 3 on the 4 x 4 face: the rim square (corners at radius 3 on the axes) cut
  // by the face's edges: every point lies on the face, within its 2 m half extents.
  const Shape cylinder = Cylinder{3.0f, 0.5f};
  Manifold m;
  ASSERT_TRUE(collide(cylinder, at(Vec3(0.0f, 0.5f - kDepth, 0.0f)), slab(ShapeType::Box), kSlabPlace, m));
  ASSERT_EQ(m.count, 4);
  for (int i = 0; i < m.count; ++i) {
    EXPECT_NEAR(m.points[i].depth, kDepth, 1e-5f);
    EXPECT_LE(std::abs(m.points[i].pointOnB.x), 2.0f + 1e-4f);
    EXPECT_LE(std::abs(m.points[i].pointOnB.z), 2.0f + 1e-4f);
  }
}

TEST(CylinderPairs, CapOnCapTouchesAtRimPointsInsideBothDiscs) {
  // Equal cylinders stacked: the rim points of both caps lie on both discs' edge.
  const Shape lower = Cylinder{0.5f, 0.5f};
  Manifold m;
  ASSERT_TRUE(collide(lower, at(Vec3(0.0f, 1.0f - kDepth, 0.0f)), lower, at(Vec3(0.0f)), m));
  ASSERT_EQ(m.count, 4);
  EXPECT_NEAR(m.normal.y, -1.0f, 1e-5f);
  for (int i = 0; i < m.count; ++i) {
    EXPECT_NEAR(m.points[i].depth, kDepth, 1e-5f);
    const Vec3 p = m.points[i].pointOnB;
    EXPECT_NEAR(std::sqrt(p.x * p.x + p.z * p.z), 0.5f, 1e-4f);
  }
  // A thin one on a wide one, off-centre: its own four rim points, 0.2 m in radius around (0.1, 0).
  const Shape thin = Cylinder{0.2f, 0.5f};
  ASSERT_TRUE(collide(thin, at(Vec3(0.1f, 1.0f - kDepth, 0.0f)), lower, at(Vec3(0.0f)), m));
  ASSERT_EQ(m.count, 4);
  for (int i = 0; i < m.count; ++i) {
    const Vec3 p = m.points[i].pointOnB - Vec3(0.1f, 0.0f, 0.0f);
    EXPECT_NEAR(std::sqrt(p.x * p.x + p.z * p.z), 0.2f, 1e-4f);
    EXPECT_NEAR(m.points[i].depth, kDepth, 1e-5f);
  }
}

TEST(CylinderPairs, LyingAcrossACapTouchesWhereItsSideCrossesTheDisc) {
  // A 4 m long cylinder lying along x on a standing one of radius 0.5: its side line cut by the cap's
  // rim at x = -0.5 and x = 0.5.
  const Shape lying = Cylinder{0.25f, 2.0f};
  const Shape standing = Cylinder{0.5f, 0.5f};
  Manifold m;
  ASSERT_TRUE(collide(lying, at(Vec3(0.0f, 0.75f - kDepth, 0.0f), axisAngle(Vec3(0, 0, 1), 90.0f)), standing,
                      at(Vec3(0.0f)), m));
  ASSERT_EQ(m.count, 2);
  std::array<float, 2> xs{m.points[0].pointOnB.x, m.points[1].pointOnB.x};
  std::sort(xs.begin(), xs.end());
  EXPECT_NEAR(xs[0], -0.5f, 1e-3f);
  EXPECT_NEAR(xs[1], 0.5f, 1e-3f);
  for (int i = 0; i < 2; ++i) EXPECT_NEAR(m.points[i].depth, kDepth, 1e-5f);
}

TEST(CylinderPairs, TiltedOnAnEdgeIsOnePoint) {
  // Tilted 30 degrees, resting on its rim: no face within the tolerance, GJK's single point.
  const Shape cylinder = Cylinder{0.5f, 0.5f};
  const Quat tilt = axisAngle(Vec3(0, 0, 1), 30.0f);
  // The lowest rim point of the tilted cylinder, then lowered 1 cm into the face y = 0.
  const Vec3 a = tilt * Vec3(0.5f, -0.5f, 0.0f), b = tilt * Vec3(-0.5f, -0.5f, 0.0f);
  const Vec3 lowest = a.y < b.y ? a : b;
  Manifold m;
  ASSERT_TRUE(
      collide(cylinder, at(Vec3(0.0f, -lowest.y - kDepth, 0.0f), tilt), slab(ShapeType::Box), kSlabPlace, m));
  EXPECT_EQ(m.count, 1);
  EXPECT_NEAR(m.points[0].depth, kDepth, 1e-4f);
}

TEST(CylinderPairs, TheTableNamesTheClippedPairs) {
  for (const ShapeType other :
       {ShapeType::Box, ShapeType::Kdop, ShapeType::ConvexHull, ShapeType::Cylinder}) {
    EXPECT_EQ(pairInfo(ShapeType::Cylinder, other).algorithm, PairAlgorithm::GjkEpaClip);
    EXPECT_EQ(pairInfo(other, ShapeType::Cylinder).algorithm, PairAlgorithm::GjkEpaClip);
  }
}

}  // namespace
}  // namespace collide
