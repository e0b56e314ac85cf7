// The lecture's impact cases with ImpactModel::Newton, against the 1D impact formulas.
#include "world/world_helpers.h"

#include <gtest/gtest.h>

#include <cmath>

namespace collide {
namespace {

using test::sphereBody;
using test::zeroGravityWorld;

constexpr float kDt = 1.0f / 60.0f;

// 1D impact of two bodies along x with restitution e (lecture: Newton's impact law plus
// conservation of momentum).
void impact1d(float m1, float v1, float m2, float v2, float e, float& out1, float& out2) {
  out1 = (m1 * v1 + m2 * v2 + m2 * e * (v2 - v1)) / (m1 + m2);
  out2 = (m1 * v1 + m2 * v2 + m1 * e * (v1 - v2)) / (m1 + m2);
}

struct HeadOn {
  float m1, v1, m2, v2, e;
};

void runHeadOn(const HeadOn& c) {
  World world(zeroGravityWorld());
  BodyDef a = sphereBody(Vec3(-1.0f, 0.0f, 0.0f), 0.5f, c.m1, Vec3(c.v1, 0.0f, 0.0f));
  BodyDef b = sphereBody(Vec3(1.0f, 0.0f, 0.0f), 0.5f, c.m2, Vec3(c.v2, 0.0f, 0.0f));
  a.friction = b.friction = 0.0f;
  a.bounciness = b.bounciness = c.e;
  const BodyId ia = world.createBody(a);
  const BodyId ib = world.createBody(b);
  const Vec3 p0 = world.linearMomentum();
  const float energy0 = world.kineticEnergy();
  for (int i = 0; i < 90; ++i) world.step(kDt);

  float expected1, expected2;
  impact1d(c.m1, c.v1, c.m2, c.v2, c.e, expected1, expected2);
  const float scale = std::max(std::abs(c.v1), std::abs(c.v2));
  EXPECT_NEAR(world.linearVelocity(ia).x, expected1, 0.01f * scale);
  EXPECT_NEAR(world.linearVelocity(ib).x, expected2, 0.01f * scale);
  EXPECT_NEAR(glm::length(world.linearVelocity(ia) - Vec3(world.linearVelocity(ia).x, 0, 0)), 0.0f, 1e-5f);
  const Vec3 p1 = world.linearMomentum();
  const float momentumScale = std::abs(c.m1 * c.v1) + std::abs(c.m2 * c.v2);
  EXPECT_LE(glm::length(p1 - p0), 1e-4f * momentumScale);
  if (c.e == 1.0f) {
    EXPECT_NEAR(world.kineticEnergy(), energy0, 0.01f * energy0);
  }
}

TEST(Impact, EqualSpheresHeadOnElasticSwapVelocities) { runHeadOn({1.0f, 1.0f, 1.0f, -1.0f, 1.0f}); }

TEST(Impact, UnequalMassesElasticMatchTheFormula) {
  runHeadOn({1.0f, 2.0f, 3.0f, -1.0f, 1.0f});
  runHeadOn({5.0f, 1.5f, 0.5f, 0.0f, 1.0f});
}

TEST(Impact, PartlyElasticMatchesTheFormula) { runHeadOn({2.0f, 3.0f, 1.0f, -1.0f, 0.5f}); }

// A wall at x = 1 (solid beyond), the sphere coming obliquely: with e = 1 and no friction the normal
// component flips and the tangential one is kept; with e = 0 the normal component vanishes.
void runWall(float e, float& outNormal, float& outTangent) {
  World world(zeroGravityWorld());
  BodyDef wall;
  wall.type = BodyType::Static;
  wall.shape = Shape(Plane{Vec3(-1.0f, 0.0f, 0.0f), -1.0f});
  wall.friction = 0.0f;
  world.createBody(wall);
  BodyDef ball = sphereBody(Vec3(0.0f), 0.5f, 1.0f, Vec3(2.0f, 0.0f, 1.0f));
  ball.bounciness = e;
  ball.friction = 0.0f;
  const BodyId id = world.createBody(ball);
  for (int i = 0; i < 30; ++i) world.step(kDt);
  outNormal = world.linearVelocity(id).x;
  outTangent = world.linearVelocity(id).z;
}

TEST(Impact, ElasticSphereOnStaticWallFlipsTheNormalComponent) {
  float normal, tangent;
  runWall(1.0f, normal, tangent);
  EXPECT_NEAR(normal, -2.0f, 0.02f);
  EXPECT_NEAR(tangent, 1.0f, 1e-4f);
}

TEST(Impact, InelasticSphereOnStaticWallStops) {
  float normal, tangent;
  runWall(0.0f, normal, tangent);
  EXPECT_NEAR(normal, 0.0f, 0.02f);
  EXPECT_NEAR(tangent, 1.0f, 1e-4f);
}

// Kinetic friction decelerates by mu g: a box sliding at v0 stops after v0^2 / (2 mu g).
void runSliding(const BodyDef& ground, float& outDistance) {
  WorldDef def;
  World world(def);
  BodyDef g = ground;
  g.friction = 0.5f;
  world.createBody(g);
  BodyDef box = test::boxBody(Vec3(0.0f, 0.5f, 0.0f), Vec3(0.5f), 1.0f);
  box.friction = 0.5f;
  box.linearVelocity = Vec3(3.0f, 0.0f, 0.0f);
  const BodyId id = world.createBody(box);
  for (int i = 0; i < 120; ++i) world.step(kDt);
  EXPECT_LT(glm::length(world.linearVelocity(id)), 1e-3f);
  outDistance = world.transform(id).position.x;
}

TEST(Friction, SlidingBoxOnGroundPlaneStopsAfterTheCoulombDistance) {
  const float expected = 9.0f / (2.0f * 0.5f * 9.81f);
  float distance;
  runSliding(test::groundPlane(), distance);
  EXPECT_NEAR(distance, expected, 0.03f * expected);
}

TEST(Friction, SlidingBoxOnGroundBoxStopsAfterTheCoulombDistance) {
  // A single GJK/EPA point cannot hold a box on a box: this needs the SAT face manifold.
  ASSERT_EQ(pairInfo(ShapeType::Box, ShapeType::Box).algorithm, PairAlgorithm::Sat);
  const float expected = 9.0f / (2.0f * 0.5f * 9.81f);
  float distance;
  runSliding(test::groundBox(), distance);
  EXPECT_NEAR(distance, expected, 0.03f * expected);
}

}  // namespace
}  // namespace collide
