// A sphere and a capsule on a static triangle-mesh floor in the World: the mesh–sphere and
// mesh–capsule cells' closest-point contacts with internal-edge handling
// (src/narrowphase/triangle_rounded.cpp).
#include "support/mesh_floor_helpers.h"
#include "support/world_helpers.h"

#include <gtest/gtest.h>

#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace collide {
namespace {

using test::kDt;

TEST(WorldMeshFloorRounded, SphereRollingAcrossInternalEdgesStaysOnTheFloor) {
  // A sphere (radius 0.3) rolls at 3 m/s across the floor's quad edges, diagonals and vertices, at
  // an angle to the grid. A bump at an internal edge would kick it up: every contact normal must
  // stay within 1° of vertical, and once it has landed its height may change by less than
  // 0.01 m/s × dt per step. The same ball rolls on a plane in a second world, in lockstep: the
  // solver's velocity of a resting ball is not exactly zero (it reads -g·dt/2 after the step), so
  // the mesh's vertical velocity is compared with the plane's, within 0.01 m/s.
  World world, reference;
  const BodyId floor = world.createBody(test::meshFloor(10, 0.5f));
  reference.createBody(test::groundPlane());
  BodyDef def = test::sphereBody(Vec3(-3.5f, 0.3f, -0.7f), 0.3f, 1.0f, Vec3(3.0f, 0.0f, 0.7f));
  def.angularVelocity = Vec3(0.7f, 0.0f, -3.0f) / 0.3f;  // rolling: v + ω × (0, -r, 0) = 0
  const BodyId ball = world.createBody(def);
  const BodyId referenceBall = reference.createBody(def);
  float worstNormal = 0.0f;
  int manifolds = 0;
  world.setPreSolveCallback([&](BodyId a, BodyId b, const Manifold& m) {
    if ((a == floor && b == ball) || (a == ball && b == floor)) {
      ++manifolds;
      worstNormal = std::max(worstNormal, test::degreesFromVertical(m.normal));
    }
    return true;
  });
  float worstVertical = 0.0f, worstHeightRate = 0.0f;
  float height = world.transform(ball).position.y;
  for (int i = 0; i < 120; ++i) {
    world.step(kDt);
    reference.step(kDt);
    const float now = world.transform(ball).position.y;
    if (i >= 10) {
      worstVertical = std::max(
          worstVertical, std::abs(world.linearVelocity(ball).y - reference.linearVelocity(referenceBall).y));
      worstHeightRate = std::max(worstHeightRate, std::abs(now - height) / kDt);
    }
    height = now;
  }
  const Vec3 end = world.transform(ball).position;
  std::printf(
      "sphere rolling on the mesh floor: end (%.3f, %.3f, %.3f), worst normal %.5f deg, vertical "
      "velocity off the plane's by %.6f m/s, height rate %.6f m/s\n",
      end.x, end.y, end.z, worstNormal, worstVertical, worstHeightRate);
  EXPECT_GT(end.x, 2.0f);  // it crossed about six quads
  EXPECT_GT(manifolds, 100);
  EXPECT_LE(worstNormal, 1.0f);
  EXPECT_LT(worstVertical, 0.01f);
  EXPECT_LT(worstHeightRate, 0.01f);
  EXPECT_NEAR(end.y, reference.transform(referenceBall).position.y, 1e-3f);
}

TEST(WorldMeshFloorRounded, CapsuleLyingOnTheFloorRestsOnTwoPoints) {
  // A capsule dropped lying flat settles on both ends: two points, the same two ids every step.
  BodyDef def;
  def.shape = Capsule{0.2f, 0.6f};
  def.position = Vec3(0.3f, 0.25f, -0.2f);
  // Lying along a horizontal line turned 25° from the grid's x axis.
  def.rotation = glm::angleAxis(glm::radians(25.0f), Vec3(0.0f, 1.0f, 0.0f)) *
                 glm::angleAxis(glm::radians(90.0f), Vec3(0.0f, 0.0f, 1.0f));
  const test::FloorRest rest = test::restOnMeshFloor(def, 0.5f, 2, 90);
  test::expectStableRest(rest, 2, 0.2f);
  EXPECT_LT(glm::length(rest.spin), 0.05f);
}

}  // namespace
}  // namespace collide
