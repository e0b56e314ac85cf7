// Cylinders and ellipsoids against mesh triangles (src/narrowphase/triangle_generic.cpp): the
// manifolds a cylinder gets on a plane (four rim points standing on a cap, two lying on its side)
// on a tessellated floor, with ids that persist from triangle to triangle; no bump on internal
// edges; concave and convex folds; agreement with GJK/EPA on single triangles.
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

using test::angleDegrees;
using test::at;
using test::axisAngle;
using test::randomUnit;
using test::uniformRotation;

// The height of a placed shape's lowest point (its support along -y).
float lowestY(const Shape& shape, const Transform& pose) {
  const Vec3 down = glm::conjugate(pose.rotation) * Vec3(0.0f, -1.0f, 0.0f);
  return pose.applyToPoint(support(shape, down)).y;
}

std::set<std::uint32_t> idsOf(const Manifold& m) {
  std::set<std::uint32_t> ids;
  for (int i = 0; i < m.count; ++i) ids.insert(m.points[i].featureId);
  return ids;
}

TEST(TriangleGeneric, CylinderLyingOnAFlatGridGetsTwoPointsWithStableIds) {
  // A cylinder (radius 0.25, half height 0.6) lying on its side, sunk 0.01, anywhere on the floor
  // and turned about y: one point under the end of each rim (the ends of its lowest line), depth
  // 0.01, normal up, and the same two ids (the floor's flat patch, each rim's lowest point).
  const Shape floor = test::flatGrid(10);
  const Shape cylinder = Cylinder{0.25f, 0.6f};
  const Quat lying = axisAngle({1, 0, 0}, 90.0f);
  std::mt19937 rng(8);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::set<std::uint32_t> first;
  for (int trial = 0; trial < 300; ++trial) {
    const Transform pose =
        at({3.0f * unit(rng), 0.24f, 3.0f * unit(rng)}, axisAngle({0, 1, 0}, 180.0f * unit(rng)) * lying);
    Manifold m;
    ASSERT_TRUE(collide::collide(floor, Transform::identity(), cylinder, pose, m)) << "trial " << trial;
    ASSERT_EQ(m.count, 2) << "trial " << trial;
    EXPECT_LT(angleDegrees(m.normal, {0, 1, 0}), 1e-3f) << "trial " << trial;
    const Vec3 end0 = pose.applyToPoint({0.0f, -0.6f, 0.0f}), end1 = pose.applyToPoint({0.0f, 0.6f, 0.0f});
    for (int i = 0; i < 2; ++i) {
      EXPECT_NEAR(m.points[i].depth, 0.01f, 1e-5f) << "trial " << trial;
      const Vec3 p = m.points[i].pointOnB;
      const float nearest = std::min(glm::length(p - Vec3(end0.x, -0.01f, end0.z)),
                                     glm::length(p - Vec3(end1.x, -0.01f, end1.z)));
      EXPECT_LT(nearest, 1e-4f) << "trial " << trial;
      EXPECT_NEAR(m.points[i].pointOnA.y, 0.0f, 1e-6f);
    }
    const std::set<std::uint32_t> ids = idsOf(m);
    ASSERT_EQ(ids.size(), 2u);
    if (first.empty()) first = ids;
    EXPECT_EQ(ids, first) << "trial " << trial;
  }
  // Tilted by 5° about its middle, only the lower rim touches.
  Manifold m;
  ASSERT_TRUE(collide::collide(floor, Transform::identity(), cylinder,
                               at({0.3f, 0.24f, 0.2f}, axisAngle({1, 0, 0}, 5.0f) * lying), m));
  EXPECT_EQ(m.count, 1);
}

TEST(TriangleGeneric, CylinderStandingOnAFlatGridGetsFourStableRimPoints) {
  // A cylinder (radius 0.4) standing on its cap, sunk 0.02, wobbling by up to 1° anywhere on the
  // floor: its four rim points at local ±x, ±z, each as deep as it is below the floor, normal up,
  // and the same four ids however the cap straddles the quads.
  const Shape floor = test::flatGrid(10);
  const Cylinder cylinder{0.4f, 0.3f};
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::set<std::uint32_t> first;
  for (int trial = 0; trial < 300; ++trial) {
    const Quat wobble =
        axisAngle(randomUnit(rng), 1.0f * unit(rng)) * axisAngle({0, 1, 0}, 10.0f * unit(rng));
    const Transform pose = at({3.0f * unit(rng), 0.28f, 3.0f * unit(rng)}, wobble);
    Manifold m;
    ASSERT_TRUE(collide::collide(floor, Transform::identity(), Shape(cylinder), pose, m))
        << "trial " << trial;
    ASSERT_EQ(m.count, 4) << "trial " << trial;
    EXPECT_LT(angleDegrees(m.normal, {0, 1, 0}), 1e-3f) << "trial " << trial;
    const float r = cylinder.radius, y = -cylinder.halfHeight;
    const Vec3 rim[4] = {{r, y, 0}, {0, y, r}, {-r, y, 0}, {0, y, -r}};
    for (int i = 0; i < 4; ++i) {
      float nearest = 1e30f;
      for (const Vec3& local : rim)
        nearest = std::min(nearest, glm::length(m.points[i].pointOnB - pose.applyToPoint(local)));
      EXPECT_LT(nearest, 1e-5f) << "trial " << trial;
      EXPECT_NEAR(m.points[i].depth, -m.points[i].pointOnB.y, 1e-6f) << "trial " << trial;
    }
    const std::set<std::uint32_t> ids = idsOf(m);
    ASSERT_EQ(ids.size(), 4u);
    if (first.empty()) first = ids;
    EXPECT_EQ(ids, first) << "trial " << trial;
  }
}

TEST(TriangleGeneric, CylinderAndEllipsoidSlidingAcrossAFlatGridPushStraightUp) {
  // Sunk into the floor and moved in small steps across quad edges, diagonals and vertices, turned
  // and slightly tilted: the normal stays +y (no internal edge pushes sideways) and the deepest
  // point is the shape's lowest point; for a cylinder standing on its cap, the lowest of its four
  // rim points at local ±x, ±z (as on a plane: fixed points whose ids survive the wobble).
  const Shape floor = test::flatGrid(6);
  const Shape shapes[] = {Cylinder{0.3f, 0.4f}, Ellipsoid{Vec3(0.5f, 0.2f, 0.3f)}};
  const Quat poses[] = {axisAngle({1, 0, 0}, 90.0f), Quat(1, 0, 0, 0), axisAngle({0, 0, 1}, 90.0f)};
  std::mt19937 rng(12);
  std::uniform_real_distribution<float> small(-1.0f, 1.0f);
  int checked = 0;
  for (const Shape& shape : shapes) {
    for (const Quat& base : poses) {
      for (int step = 0; step <= 200; ++step) {
        const float t = float(step) / 200.0f;
        const Quat rotation =
            axisAngle({0, 1, 0}, 20.0f + 40.0f * t) * axisAngle(randomUnit(rng), 0.5f * small(rng)) * base;
        Transform pose = at(Vec3(-1.7f + 3.4f * t, 0.0f, -1.1f + 2.0f * t), rotation);
        const float depth = 0.03f;
        pose.position.y = -lowestY(shape, pose) - depth;
        float expected = depth;
        if (shape.type() == ShapeType::Cylinder && base == Quat(1, 0, 0, 0)) {
          const float r = shape.cylinder().radius, y = -shape.cylinder().halfHeight;
          float lowestRim = 1e30f;
          for (const Vec3& rim : {Vec3(r, y, 0), Vec3(0, y, r), Vec3(-r, y, 0), Vec3(0, y, -r)})
            lowestRim = std::min(lowestRim, pose.applyToPoint(rim).y);
          expected = -lowestRim;
        }
        Manifold m;
        ASSERT_TRUE(collide::collide(floor, Transform::identity(), shape, pose, m)) << "step " << step;
        EXPECT_LT(angleDegrees(m.normal, Vec3(0, 1, 0)), 1e-3f) << toString(shape.type()) << " step " << step;
        EXPECT_NEAR(m.maxDepth(), expected, 2e-5f) << toString(shape.type()) << " step " << step;
        ++checked;
      }
    }
  }
  EXPECT_EQ(checked, 2 * 3 * 201);
}

TEST(TriangleGeneric, InternalEdgeGivesTheFaceNormalWhereLooseTrianglesBump) {
  // A thin upright cylinder (radius 0.05) straddling the quad edge x = 0, centred at x = 0.01,
  // sunk 0.08: deeper than it overlaps either triangle sideways (0.06 and 0.04), so for each
  // triangle alone the horizontal axis across the shared edge separates best, a bump. The mesh
  // knows the edge is flat: +y, depth 0.08, the four rim points.
  const Shape grid = test::flatGrid(6);
  const Shape cylinder = Cylinder{0.05f, 0.2f};
  const Transform pose = at({0.01f, 0.2f - 0.08f, 0.5f});
  Manifold m;
  ASSERT_TRUE(collide::collide(grid, Transform::identity(), cylinder, pose, m));
  EXPECT_LT(angleDegrees(m.normal, Vec3(0, 1, 0)), 1e-3f);
  EXPECT_NEAR(m.maxDepth(), 0.08f, 1e-5f);
  EXPECT_EQ(m.count, 4);
  const std::array<Vec3, 3> under[] = {{Vec3(0, 0, 0), Vec3(0, 0, 1), Vec3(1, 0, 1)},
                                       {Vec3(-1, 0, 0), Vec3(0, 0, 1), Vec3(0, 0, 0)}};
  Manifold loose;
  ASSERT_TRUE(detail::collideTrianglesConvex(under, Transform::identity(), cylinder, pose, 0.0f, loose));
  EXPECT_GT(angleDegrees(loose.normal, Vec3(0, 1, 0)), 45.0f);
  EXPECT_LT(loose.maxDepth(), 0.07f);
}

using test::fold;

TEST(TriangleGeneric, ConcaveFoldGivesFaceNormalsConvexRidgeKeepsItsEdge) {
  // An ellipsoid (radii 0.3, 0.2, 0.3) resting on the flat half of a valley near the fold, sunk
  // 0.05: the rising half's contact is on the (concave) fold and is dropped; one point, straight up,
  // as deep as it is sunk.
  const Shape ellipsoid = Ellipsoid{Vec3(0.3f, 0.2f, 0.3f)};
  const Shape valley = fold(std::tan(glm::radians(10.0f)));
  Manifold m;
  ASSERT_TRUE(collide::collide(valley, Transform::identity(), ellipsoid, at({-0.12f, 0.15f, 0.0f}), m));
  EXPECT_EQ(m.count, 1);
  EXPECT_LT(angleDegrees(m.normal, {0, 1, 0}), 1e-3f);
  EXPECT_NEAR(m.maxDepth(), 0.05f, 1e-5f);
  // Over a ridge falling away at 30° on both sides (a roof), the ellipsoid's centre straight above
  // the ridge: held by the (convex) ridge edge, normal straight up from it, the depth its lowest
  // point's below the ridge line.
  std::vector<Vec3> vertices{{-1.0f, -0.577f, -1.0f}, {-1.0f, -0.577f, 1.0f}, {0.0f, 0.0f, 1.0f},
                             {0.0f, 0.0f, -1.0f},     {1.0f, -0.577f, 1.0f},  {1.0f, -0.577f, -1.0f}};
  std::vector<MeshTriangle> triangles{{{0, 1, 2}}, {{0, 2, 3}}, {{3, 2, 4}}, {{3, 4, 5}}};
  const Shape roof(TriangleMesh::fromTriangles(std::move(vertices), std::move(triangles)));
  ASSERT_TRUE(collide::collide(roof, Transform::identity(), ellipsoid, at({0.0f, 0.19f, 0.3f}), m));
  EXPECT_LT(angleDegrees(m.normal, {0, 1, 0}), 0.01f);
  EXPECT_NEAR(m.maxDepth(), 0.01f, 1e-5f);
}

// One random triangle and a random cylinder or ellipsoid near it: the verdict is GJK/EPA's
// (outside a 1e-4 band), no point is deeper than the shapes overlap along the manifold's normal,
// the deepest depth is at most the minimum penetration with the face preference's allowance, and
// every point lies on the shape (pointOnB) and on the triangle's plane (pointOnA).
TEST(TriangleGeneric, AgreesWithGjkEpaOnOneTriangle) {
  std::mt19937 rng(31);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  int compared = 0, verdicts = 0, failures = 0, faceNormals = 0;
  std::string first;
  auto fail = [&](int i, const std::string& what) {
    ++failures;
    if (first.empty()) first = "pair " + std::to_string(i) + ": " + what;
  };
  for (int i = 0; i < 3000; ++i) {
    std::array<Vec3, 3> triangle;
    for (Vec3& v : triangle) v = randomUnit(rng) * (0.3f + 1.0f * unit(rng));
    if (glm::length(glm::cross(triangle[1] - triangle[0], triangle[2] - triangle[0])) < 0.05f) continue;
    const Shape shape = test::randomPrimitive(i % 2 ? ShapeType::Cylinder : ShapeType::Ellipsoid, rng);
    const Vec3 target =
        triangle[0] + unit(rng) * (triangle[1] - triangle[0]) + unit(rng) * (triangle[2] - triangle[0]);
    const Transform pose = at(target + randomUnit(rng) * (1.5f * unit(rng)), uniformRotation(rng));
    const float margin = (i % 3 == 0) ? 0.1f * unit(rng) : 0.0f;
    DistanceResult reference;
    const bool near =
        detail::convexSignedDistance(detail::makePointsSupport(triangle.data(), 3, Transform::identity()),
                                     detail::makeConvexSupport(shape, pose), 1.0f, reference);
    Manifold m;
    const bool hit = detail::collideTrianglesConvex(std::span(&triangle, 1), Transform::identity(), shape,
                                                    pose, margin, m);
    const bool touching = near && reference.distance <= margin;
    if (near && std::abs(reference.distance - margin) < 1e-4f) continue;
    if (hit != touching) {
      ++verdicts;
      if (first.empty())
        first = "pair " + std::to_string(i) + ": verdict, distance " + std::to_string(reference.distance);
      continue;
    }
    if (!hit) continue;
    ++compared;
    const Vec3 faceNormal = glm::normalize(glm::cross(triangle[1] - triangle[0], triangle[2] - triangle[0]));
    faceNormals += std::abs(std::abs(glm::dot(m.normal, faceNormal)) - 1.0f) < 1e-6f;
    // The shapes' overlap along the normal (from the triangle to the shape): h(n) = max over the
    // triangle of n·x - min over the shape of n·x.
    float highest = -1e30f;
    for (const Vec3& v : triangle) highest = std::max(highest, glm::dot(m.normal, v));
    const Vec3 localDown = glm::conjugate(pose.rotation) * -m.normal;
    const float overlap = highest - glm::dot(m.normal, pose.applyToPoint(support(shape, localDown)));
    const float size = 1e-3f * 2.0f;
    const float depth = -reference.distance;
    if (m.maxDepth() > overlap + 1e-4f) fail(i, "a point deeper than the overlap along the normal");
    if (m.maxDepth() > (depth + size) / 0.98f + 1e-4f)
      fail(i, "depth " + std::to_string(m.maxDepth()) + ", EPA " + std::to_string(depth));
    for (int k = 0; k < m.count; ++k) {
      if (std::abs(closestPoint(shape, pose, m.points[k].pointOnB).signedDistance) > 1e-4f)
        fail(i, "pointOnB off the shape");
      if (std::abs(glm::dot(m.points[k].pointOnA - triangle[0], faceNormal)) > 1e-4f &&
          std::abs(std::abs(glm::dot(m.normal, faceNormal)) - 1.0f) < 1e-6f)
        fail(i, "face contact's pointOnA off the triangle's plane");
    }
    // An ellipsoid's face contact is its support point, so nothing is shallower than EPA's depth.
    if (shape.type() == ShapeType::Ellipsoid && m.maxDepth() < depth - 1e-4f)
      fail(i, "ellipsoid depth " + std::to_string(m.maxDepth()) + " below EPA's " + std::to_string(depth));
  }
  std::printf(
      "cylinder/ellipsoid x triangle: %d compared (%d face normals), %d verdicts differ, %d failures\n",
      compared, faceNormals, verdicts, failures);
  SCOPED_TRACE(first);
  EXPECT_EQ(verdicts, 0);
  EXPECT_EQ(failures, 0);
  EXPECT_GT(compared, 500);
  EXPECT_GT(faceNormals, 100);
}

}  // namespace
}  // namespace collide
