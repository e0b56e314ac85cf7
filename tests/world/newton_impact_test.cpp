// The lecture's impact cases with ImpactModel::Newton, against the 1D impact formulas.
#include "support/world_helpers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <utility>
#include <vector>

namespace collide {
namespace {

using test::sphereBody;
using test::zeroGravityWorld;

using test::kDt;

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

// Slide 32 in 3D: equal masses meeting obliquely, fully elastic and without friction: the velocity
// components along the impact normal swap, the tangential ones stay. The normal is the one the
// contact's begin event reports (the line of centres when the speculative contact formed).
TEST(Impact, EqualSpheresObliqueElasticSwapNormalComponentsKeepTangential) {
  World world(zeroGravityWorld());
  const Vec3 n = glm::normalize(Vec3(1.0f, 0.5f, -0.25f));
  const Vec3 t = glm::normalize(glm::cross(n, Vec3(0.0f, 0.0f, 1.0f)));
  const Vec3 s = glm::cross(n, t);
  const Vec3 va = 2.0f * n + 0.7f * t - 0.3f * s;
  const Vec3 vb = -1.5f * n - 0.4f * t + 0.6f * s;
  // Centres one diameter apart along n at t = 0.1 s.
  const Vec3 start = n - 0.1f * (vb - va);
  BodyDef a = sphereBody(-0.5f * start, 0.5f, 1.0f, va);
  BodyDef b = sphereBody(0.5f * start, 0.5f, 1.0f, vb);
  a.friction = b.friction = 0.0f;
  a.bounciness = b.bounciness = 1.0f;
  const BodyId ia = world.createBody(a);
  const BodyId ib = world.createBody(b);
  Vec3 normal(0.0f);
  for (int i = 0; i < 40; ++i) {
    world.step(kDt);
    for (const ContactEvent& e : world.contactEvents())
      if (e.type == ContactEvent::Type::Begin) normal = e.normal;
  }
  ASSERT_NEAR(glm::length(normal), 1.0f, 1e-4f);
  EXPECT_GT(glm::dot(normal, n), 0.99f);
  const auto along = [&](const Vec3& v) { return glm::dot(v, normal) * normal; };
  const Vec3 na = world.linearVelocity(ia), nb = world.linearVelocity(ib);
  const float tolerance = 0.01f * glm::length(vb - va);
  EXPECT_LE(glm::length(along(na) - along(vb)), tolerance);
  EXPECT_LE(glm::length(along(nb) - along(va)), tolerance);
  EXPECT_LE(glm::length((na - along(na)) - (va - along(va))), 1e-4f);
  EXPECT_LE(glm::length((nb - along(nb)) - (vb - along(vb))), 1e-4f);
}

// The restitution threshold is a setting, and 0 is allowed: a ball at 0.5 m/s does not bounce off a
// wall under the default threshold (1 m/s, so that resting contacts stay quiet), and with 0 it
// bounces back elastically.
TEST(Impact, RestitutionThresholdIsASettingAndZeroBouncesSlowImpacts) {
  for (float threshold : {1.0f, 0.0f}) {
    SCOPED_TRACE(threshold);
    WorldDef def = zeroGravityWorld();
    def.contact.restitutionThreshold = threshold;
    World world(def);
    BodyDef wall;
    wall.type = BodyType::Static;
    wall.shape = Shape(Plane{Vec3(-1.0f, 0.0f, 0.0f), -1.0f});
    wall.friction = 0.0f;
    wall.bounciness = 1.0f;
    world.createBody(wall);
    BodyDef ball = sphereBody(Vec3(0.3f, 0.0f, 0.0f), 0.5f, 1.0f, Vec3(0.5f, 0.0f, 0.0f));
    ball.bounciness = 1.0f;
    ball.friction = 0.0f;
    const BodyId id = world.createBody(ball);
    for (int i = 0; i < 60; ++i) world.step(kDt);
    EXPECT_NEAR(world.linearVelocity(id).x, threshold > 0.5f ? 0.0f : -0.5f, 0.01f);
  }
}

// Slide 33 in a moving frame: a kinematic wall rising at 1 m/s hit by a ball falling at 3 m/s meets
// it at -4 m/s and sends it off at +4 m/s relative, i.e. 5 m/s upwards; the wall keeps its motion.
TEST(Impact, ElasticSphereOnKinematicWallReflectsTheRelativeVelocity) {
  World world(zeroGravityWorld());
  BodyDef wall;
  wall.type = BodyType::Kinematic;
  wall.shape = Shape(Box{Vec3(5.0f, 0.5f, 5.0f)});
  wall.position = Vec3(0.0f, -0.5f, 0.0f);
  wall.linearVelocity = Vec3(0.0f, 1.0f, 0.0f);
  wall.friction = 0.0f;
  wall.bounciness = 1.0f;
  const BodyId wallId = world.createBody(wall);
  BodyDef ball = sphereBody(Vec3(0.0f, 0.8f, 0.0f), 0.5f, 1.0f, Vec3(0.5f, -3.0f, 0.0f));
  ball.friction = 0.0f;
  ball.bounciness = 1.0f;
  const BodyId ballId = world.createBody(ball);
  for (int i = 0; i < 20; ++i) world.step(kDt);
  EXPECT_NEAR(world.linearVelocity(ballId).y, 5.0f, 0.05f);
  EXPECT_NEAR(world.linearVelocity(ballId).x, 0.5f, 1e-4f);
  EXPECT_EQ(world.linearVelocity(wallId), Vec3(0.0f, 1.0f, 0.0f));
}

// Two turning boxes meeting off-centre, with friction, at several bounciness values: a two-way impact
// keeps the total linear momentum (the impulses are equal and opposite) and never adds kinetic
// energy. (Angular momentum is kept only up to the lever between the two bodies' anchors of a
// point, which the soft step lets be up to the speculative distance apart; the lecture's models in
// isolation keep it exactly: tests/response/impact_test.cpp.)
TEST(Impact, OffCentreBoxImpactsConserveMomentumAndNeverAddEnergy) {
  for (float e : {1.0f, 0.5f, 0.0f}) {
    SCOPED_TRACE(e);
    World world(zeroGravityWorld());
    BodyDef a = test::boxBody(Vec3(-1.2f, 0.3f, 0.1f), Vec3(0.5f, 0.3f, 0.4f), 2.0f);
    a.rotation = glm::angleAxis(0.4f, glm::normalize(Vec3(1.0f, 2.0f, 0.5f)));
    a.linearVelocity = Vec3(3.0f, -0.2f, 0.1f);
    a.angularVelocity = Vec3(0.5f, -1.0f, 2.0f);
    BodyDef b = test::boxBody(Vec3(1.0f, -0.2f, 0.0f), Vec3(0.4f, 0.6f, 0.3f), 3.0f);
    b.linearVelocity = Vec3(-2.0f, 0.3f, 0.0f);
    b.angularVelocity = Vec3(0.0f, 1.5f, -0.5f);
    a.friction = b.friction = 0.3f;
    a.bounciness = b.bounciness = e;
    world.createBody(a);
    world.createBody(b);
    const Vec3 p0 = world.linearMomentum();
    const float energy0 = world.kineticEnergy();
    bool touched = false;
    for (int i = 0; i < 60; ++i) {
      world.step(kDt);
      touched = touched || world.touchingContactCount() > 0;
      EXPECT_LE(world.kineticEnergy(), energy0 * 1.001f) << "step " << i;
    }
    EXPECT_TRUE(touched);
    EXPECT_LE(glm::length(world.linearMomentum() - p0), 1e-4f * glm::length(p0) + 1e-4f);
  }
}

// Newton's cradle (lecture, slide 32, pairwise): a ball at 3 m/s hits the end of a row of five equal
// balls at rest, each touching the next; fully elastic, no friction. The impact passes through the
// row: the hitter and the four first balls stop, the last leaves at 3 m/s, and the hitter stops
// touching the row (the impact happens where the bodies meet, not a gap early).
TEST(Impact, NewtonsCradlePassesTheImpactThroughTheRow) {
  World world(zeroGravityWorld());
  std::vector<BodyId> row;
  for (int i = 0; i < 5; ++i) {
    BodyDef ball = sphereBody(Vec3(float(i), 0.0f, 0.0f), 0.5f, 1.0f);
    ball.bounciness = 1.0f;
    ball.friction = 0.0f;
    row.push_back(world.createBody(ball));
  }
  BodyDef hitter = sphereBody(Vec3(-2.0f, 0.0f, 0.0f), 0.5f, 1.0f, Vec3(3.0f, 0.0f, 0.0f));
  hitter.bounciness = 1.0f;
  hitter.friction = 0.0f;
  const BodyId id = world.createBody(hitter);
  for (int i = 0; i < 30; ++i) world.step(kDt);
  EXPECT_NEAR(world.linearVelocity(id).x, 0.0f, 1e-3f);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(world.linearVelocity(row[i]).x, 0.0f, 1e-3f) << i;
  EXPECT_NEAR(world.linearVelocity(row[4]).x, 3.0f, 1e-3f);
  EXPECT_NEAR(world.transform(id).position.x, -1.0f, 0.005f);  // touching ball 0
  EXPECT_NEAR(world.kineticEnergy(), 4.5f, 1e-3f);
}

// An impact sets a ball approaching another that it would not have reached this step: balls A and
// B meet, B now closes its 6.6 cm gap to C within the step (its 3.5 cm/step before would not), and C
// is 5 mm from the back wall. Each meeting gets its own elastic impact in the same step, so the
// three balls keep their kinetic energy; left to the solver's speculative contact, B-C would be
// stopped at the gap, inelastically, and a fifth of the energy lost.
TEST(Impact, AnImpactThatSetsABallApproachingAnotherIsPassedOnInTheSameStep) {
  WorldDef def = zeroGravityWorld();
  def.contact.restitutionThreshold = 0.0f;
  World world(def);
  for (const auto& [position, half] :
       {std::pair{Vec3(0, -0.5f, 0), Vec3(3, 0.5f, 3)}, std::pair{Vec3(0, 2, -2.5f), Vec3(3, 3, 0.5f)}}) {
    BodyDef wall = test::boxBody(position, half, 1.0f);
    wall.type = BodyType::Static;
    wall.bounciness = 1.0f;
    wall.friction = 0.0f;
    world.createBody(wall);
  }
  const Vec3 positions[3] = {
      {0.8645f, 0.7032f, -1.0318f}, {1.1019f, 0.9523f, -1.334f}, {1.0942f, 0.883f, -1.7947f}};
  const Vec3 velocities[3] = {{1.75f, 3.15f, -3.42f}, {-2.88f, -1.01f, -2.17f}, {1.2f, 1.99f, 0.87f}};
  for (int i = 0; i < 3; ++i) {
    BodyDef ball = sphereBody(positions[i], 0.2f, 1.0f, velocities[i]);
    ball.bounciness = 1.0f;
    ball.friction = 0.0f;
    world.createBody(ball);
  }
  const float energy = world.kineticEnergy();
  for (int i = 0; i < 3; ++i) {
    world.step(kDt);
    EXPECT_NEAR(world.kineticEnergy(), energy, 1e-4f * energy) << "step " << i;
  }
}

// Slide 20, "elastic means elastic": thirty balls in a closed box, bounciness 1, no friction, no
// gravity, the restitution threshold at 0 so that every impact is elastic: balls meeting in pairs,
// in threes and in the box's corners, with several contacts a step, keep the kinetic energy.
TEST(Impact, ElasticBallsInAClosedBoxKeepTheirEnergy) {
  WorldDef def = zeroGravityWorld();
  def.contact.restitutionThreshold = 0.0f;
  World world(def);
  const auto wall = [&](const Vec3& position, const Vec3& half) {
    BodyDef body = test::boxBody(position, half, 1.0f);
    body.type = BodyType::Static;
    body.bounciness = 1.0f;
    body.friction = 0.0f;
    world.createBody(body);
  };
  wall(Vec3(0, -0.5f, 0), Vec3(3, 0.5f, 3));
  wall(Vec3(0, 4.5f, 0), Vec3(3, 0.5f, 3));
  wall(Vec3(-2.5f, 2, 0), Vec3(0.5f, 3, 3));
  wall(Vec3(2.5f, 2, 0), Vec3(0.5f, 3, 3));
  wall(Vec3(0, 2, -2.5f), Vec3(3, 3, 0.5f));
  wall(Vec3(0, 2, 2.5f), Vec3(3, 3, 0.5f));
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  for (int i = 0; i < 30; ++i) {
    const Vec3 p(-1.5f + 1.0f * float(i % 4), 0.5f + 1.0f * float((i / 4) % 4), -1.5f + 1.5f * float(i / 16));
    BodyDef ball = sphereBody(p, 0.2f, 1.0f, 4.0f * Vec3(unit(rng), unit(rng), unit(rng)));
    ball.bounciness = 1.0f;
    ball.friction = 0.0f;
    world.createBody(ball);
  }
  const float energy = world.kineticEnergy();
  int begins = 0;
  for (int i = 0; i < 600; ++i) {
    world.step(kDt);
    for (const ContactEvent& e : world.contactEvents()) begins += e.type == ContactEvent::Type::Begin;
  }
  EXPECT_GT(begins, 100);  // a busy box
  EXPECT_NEAR(world.kineticEnergy(), energy, 0.01f * energy);
}

// A ball thrown into a corner meets both walls in the same step: each contact gets its own impulse,
// and the ball leaves with both normal components flipped and its speed kept.
TEST(Impact, ElasticBallIntoACornerFlipsBothComponents) {
  World world(zeroGravityWorld());
  for (const Vec3& normal : {Vec3(-1, 0, 0), Vec3(0, 0, -1)}) {
    BodyDef wall;
    wall.type = BodyType::Static;
    wall.shape = Shape(Plane{normal, -1.0f});
    wall.bounciness = 1.0f;
    wall.friction = 0.0f;
    world.createBody(wall);
  }
  BodyDef ball = sphereBody(Vec3(0.0f), 0.5f, 1.0f, Vec3(2.0f, 0.0f, 2.0f));  // meets both at once
  ball.bounciness = 1.0f;
  ball.friction = 0.0f;
  const BodyId id = world.createBody(ball);
  for (int i = 0; i < 30; ++i) world.step(kDt);
  EXPECT_NEAR(world.linearVelocity(id).x, -2.0f, 1e-3f);
  EXPECT_NEAR(world.linearVelocity(id).z, -2.0f, 1e-3f);
}

// Under gravity an elastic ball bounces back to the height it fell from: the impact acts at the
// time in the step when the ball meets the floor, on the velocity gravity has given it by then.
TEST(Impact, ElasticBallBouncesBackToItsHeight) {
  World world;
  BodyDef floor = test::groundPlane();
  floor.bounciness = 1.0f;
  floor.friction = 0.0f;
  world.createBody(floor);
  BodyDef ball = sphereBody(Vec3(0.0f, 2.25f, 0.0f), 0.25f, 1.0f);  // falls 2 m
  ball.bounciness = 1.0f;
  ball.friction = 0.0f;
  const BodyId id = world.createBody(ball);
  float highestAfterBounce = 0.0f;
  int bounces = 0;
  float previousVy = 0.0f;
  for (int i = 0; i < 300; ++i) {  // 5 s: about four bounces
    world.step(kDt);
    const float vy = world.linearVelocity(id).y;
    if (previousVy < 0.0f && vy > 0.0f) ++bounces;
    if (bounces > 0) highestAfterBounce = std::max(highestAfterBounce, world.transform(id).position.y);
    previousVy = vy;
  }
  EXPECT_GE(bounces, 3);
  EXPECT_NEAR(highestAfterBounce, 2.25f, 0.02f);
}

}  // namespace
}  // namespace collide
