// The lecture's response models inside the World (src/response/contact_response.cpp): the
// interpolated impact on new contacts, viscous and damping friction on prolonged ones. Expected
// values are the lecture's closed forms (docs/response.md), not values read off a run.
#include "support/world_helpers.h"

#include <gtest/gtest.h>

#include <cmath>
#include "support/test_assertions.h"

namespace collide {
namespace {

using test::kDt;

WorldDef interpolatedWorld() {
  WorldDef def = test::zeroGravityWorld();
  def.impactModel = ImpactModel::Interpolated;
  return def;
}

// Two unit-mass spheres of radius 0.5 approaching along x; enough steps to meet and separate.
std::pair<Vec3, Vec3> headOn(float bounciness, const Vec3& vA, const Vec3& vB) {
  World world(interpolatedWorld());
  BodyDef a = test::sphereBody(Vec3(-1.0f, 0.0f, 0.0f), 0.5f, 1.0f, vA);
  BodyDef b = test::sphereBody(Vec3(1.0f, 0.0f, 0.0f), 0.5f, 1.0f, vB);
  a.bounciness = b.bounciness = bounciness;
  const BodyId ia = world.createBody(a);
  const BodyId ib = world.createBody(b);
  for (int i = 0; i < 40; ++i) world.step(kDt);
  return {world.linearVelocity(ia), world.linearVelocity(ib)};
}

using test::expectVecNear;

TEST(WorldResponse, InterpolatedElasticHeadOnSwapsVelocities) {
  const auto [va, vb] = headOn(1.0f, Vec3(3.0f, 0.0f, 0.0f), Vec3(-1.0f, 0.0f, 0.0f));
  expectVecNear(va, Vec3(-1.0f, 0.0f, 0.0f), 0.03f);  // 1% of the 3 m/s
  expectVecNear(vb, Vec3(3.0f, 0.0f, 0.0f), 0.03f);
}

TEST(WorldResponse, InterpolatedInelasticHeadOnLeavesWithTheAverage) {
  const auto [va, vb] = headOn(0.0f, Vec3(3.0f, 0.0f, 0.0f), Vec3(-1.0f, 0.0f, 0.0f));
  expectVecNear(va, Vec3(1.0f, 0.0f, 0.0f), 0.03f);
  expectVecNear(vb, Vec3(1.0f, 0.0f, 0.0f), 0.03f);
}

// Two equal bodies of radius 0.5 meeting off-centre: A moves along +x at 3 m/s, B rests 0.6 m higher
// (the line of centres 37 degrees off the motion). Returns both after the impact.
struct OffCentre {
  Vec3 va, vb, wa, wb;
  Vec3 normal;  // the impact's normal, from the begin event
};
OffCentre offCentre(float bounciness, bool particles) {
  World world(interpolatedWorld());
  BodyDef a = test::sphereBody(Vec3(-1.5f, 0.0f, 0.0f), 0.5f, 1.0f, Vec3(3.0f, 0.0f, 0.0f));
  BodyDef b = test::sphereBody(Vec3(0.0f, 0.6f, 0.0f), 0.5f, 1.0f);
  a.bounciness = b.bounciness = bounciness;
  a.particle = b.particle = particles;
  const BodyId ia = world.createBody(a);
  const BodyId ib = world.createBody(b);
  int begins = 0;
  OffCentre out{};
  for (int i = 0; i < 40; ++i) {
    world.step(kDt);
    for (const ContactEvent& e : world.contactEvents()) {
      if (e.type != ContactEvent::Type::Begin) continue;
      ++begins;
      out.normal = e.normal;
    }
  }
  EXPECT_EQ(begins, 1);
  out.va = world.linearVelocity(ia);
  out.vb = world.linearVelocity(ib);
  out.wa = world.angularVelocity(ia);
  out.wb = world.angularVelocity(ib);
  return out;
}

// Slide 32 off the line of centres: fully inelastic particles leave with the average of their
// velocities, the tangential part included (not only the normal component).
TEST(WorldResponse, InterpolatedInelasticParticlesOffCentreLeaveWithTheAverage) {
  const OffCentre out = offCentre(0.0f, true);
  expectVecNear(out.va, Vec3(1.5f, 0.0f, 0.0f), 0.03f);
  expectVecNear(out.vb, Vec3(1.5f, 0.0f, 0.0f), 0.03f);
}

// Rigid spheres (slide 34): glued, the two move as one rigid body: the same angular velocity, their
// centres' velocities those of one rigid motion, and linear and angular momentum kept.
TEST(WorldResponse, InterpolatedInelasticRigidSpheresOffCentreMoveAsOneBody) {
  const OffCentre out = offCentre(0.0f, false);
  expectVecNear(out.wa, out.wb, 0.03f);
  // The centres' velocities differ by w x (their offset): one rigid motion.
  // At the impact the centres are one diameter apart along the impact's normal.
  expectVecNear(out.vb - out.va, glm::cross(out.wa, out.normal * 1.0f), 0.05f);
  expectVecNear(out.va + out.vb, Vec3(3.0f, 0.0f, 0.0f), 1e-3f);  // momentum, unit masses
  EXPECT_GT(glm::length(out.wa), 0.1f);                           // off-centre: the glued pair turns
}

// Mixed (slide 20): bounciness b mixes the elastic and the inelastic answers, b of the first.
TEST(WorldResponse, InterpolatedHalfBouncyParticlesOffCentreMixBothEnds) {
  const OffCentre elastic = offCentre(1.0f, true);
  const OffCentre inelastic = offCentre(0.0f, true);
  const OffCentre half = offCentre(0.5f, true);
  expectVecNear(half.va, 0.5f * (elastic.va + inelastic.va), 0.05f);
  expectVecNear(half.vb, 0.5f * (elastic.vb + inelastic.vb), 0.05f);
  // The elastic end swaps the normal components and keeps the tangential ones (equal masses): B
  // leaves along the impact normal with A's normal speed, A keeps its tangential velocity.
  const Vec3 n = elastic.normal;
  EXPECT_GT(glm::dot(n, glm::normalize(Vec3(0.8f, 0.6f, 0.0f))), 0.99f);  // centres at contact
  expectVecNear(elastic.vb, glm::dot(Vec3(3.0f, 0.0f, 0.0f), n) * n, 0.03f);
  expectVecNear(elastic.va, Vec3(3.0f, 0.0f, 0.0f) - glm::dot(Vec3(3.0f, 0.0f, 0.0f), n) * n, 0.03f);
}

// A static wall whose face is the plane x = 1.5, a sphere of radius 0.5 at the origin.
BodyDef wall(float bounciness) {
  BodyDef def;
  def.type = BodyType::Static;
  def.shape = Shape(Box{Vec3(0.5f, 5.0f, 5.0f)});
  def.position = Vec3(2.0f, 0.0f, 0.0f);
  def.bounciness = bounciness;
  return def;
}

TEST(WorldResponse, InterpolatedInelasticAgainstStaticWallStopsDead) {
  World world(interpolatedWorld());
  world.createBody(wall(0.0f));
  const BodyId ball = world.createBody(test::sphereBody(Vec3(0.0f), 0.5f, 1.0f, Vec3(3.0f, 1.0f, 0.0f)));
  for (int i = 0; i < 30; ++i) world.step(kDt);
  // The lecture's "B stops dead": glued to an infinite mass, normal AND tangential velocity vanish.
  EXPECT_LT(glm::length(world.linearVelocity(ball)), 0.03f);
  EXPECT_LT(glm::length(world.angularVelocity(ball)), 0.03f);
  EXPECT_LT(world.transform(ball).position.x, 1.0f + 0.01f);  // it reached the wall
}

TEST(WorldResponse, InterpolatedBouncinessFollowsTheCombineRule) {
  const float ballBounciness = 0.2f;
  const float wallBounciness = 0.8f;
  const struct {
    CombineRule rule;
    float expected;
  } cases[] = {{CombineRule::Average, 0.5f},
               {CombineRule::Min, 0.2f},
               {CombineRule::Max, 0.8f},
               {CombineRule::Multiply, 0.16f}};
  for (const auto& c : cases) {
    WorldDef def = interpolatedWorld();
    def.bouncinessCombine = c.rule;
    World world(def);
    world.createBody(wall(wallBounciness));
    BodyDef ballDef = test::sphereBody(Vec3(0.0f), 0.5f, 1.0f, Vec3(3.0f, 0.0f, 0.0f));
    ballDef.bounciness = ballBounciness;
    const BodyId ball = world.createBody(ballDef);
    for (int i = 0; i < 30; ++i) world.step(kDt);
    // Against an infinite mass: elastic -v, glued 0, interpolated -e v.
    EXPECT_NEAR(world.linearVelocity(ball).x, -c.expected * 3.0f, 0.03f) << toString(c.rule);
  }
}

TEST(WorldResponse, InterpolatedTwoWayImpactConservesMomentum) {
  for (const float e : {0.0f, 0.5f, 1.0f}) {
    World world(interpolatedWorld());
    BodyDef a = test::sphereBody(Vec3(-1.0f, 0.0f, 0.0f), 0.5f, 1.0f, Vec3(3.0f, 0.0f, 0.0f));
    BodyDef b = test::sphereBody(Vec3(1.0f, 0.3f, 0.0f), 0.5f, 3.0f, Vec3(-1.0f, 0.5f, 0.0f));
    a.bounciness = b.bounciness = e;
    const BodyId ia = world.createBody(a);
    world.createBody(b);
    const Vec3 before = world.linearMomentum();
    for (int i = 0; i < 40; ++i) world.step(kDt);
    expectVecNear(world.linearMomentum(), before, 0.01f * glm::length(before));
    // The impact happened: A no longer moves at its initial velocity.
    EXPECT_GT(glm::length(world.linearVelocity(ia) - Vec3(3.0f, 0.0f, 0.0f)), 0.5f) << e;
  }
}

// A thin plate (half height 0.02) sliding along x on a ground plane under gravity: the friction
// impulse at the plate's bottom barely spins it (h^2 / (I / m) = 0.0012), so the centre of mass takes
// the contact point's velocity change to 0.2%.
struct Slide {
  World world;
  BodyId plate;
};

std::unique_ptr<Slide> slidingPlate(FrictionModel model, float friction) {
  WorldDef def;
  def.frictionModel = model;
  auto slide = std::unique_ptr<Slide>(new Slide{World(def), {}});
  BodyDef ground = test::groundPlane();
  ground.friction = friction;
  slide->world.createBody(ground);
  BodyDef plate = test::boxBody(Vec3(0.0f, 0.02f, 0.0f), Vec3(1.0f, 0.02f, 1.0f), 1.0f);
  plate.linearVelocity = Vec3(2.0f, 0.0f, 0.0f);
  plate.friction = friction;
  slide->plate = slide->world.createBody(plate);
  return slide;
}

TEST(WorldResponse, DampingFrictionTaxesTheProlongedContact) {
  const float tax = 0.2f;
  auto s = slidingPlate(FrictionModel::Damping, tax);
  s->world.step(kDt);
  // The first contact step is the impact: no friction yet.
  EXPECT_NEAR(s->world.linearVelocity(s->plate).x, 2.0f, 0.002f);
  for (int k = 1; k <= 10; ++k) {
    s->world.step(kDt);
    const float expected = 2.0f * std::pow(1.0f - tax, static_cast<float>(k));
    EXPECT_NEAR(s->world.linearVelocity(s->plate).x, expected, 0.02f * expected) << "step " << k;
  }
}

TEST(WorldResponse, DampingFrictionAboveOneIsClampedToAFullStop) {
  auto s = slidingPlate(FrictionModel::Damping, 1.5f);
  s->world.step(kDt);
  s->world.step(kDt);
  EXPECT_NEAR(s->world.linearVelocity(s->plate).x, 0.0f, 0.01f);
}

TEST(WorldResponse, ViscousFrictionSlowsMonotonicallyAndNeverReverses) {
  // k = 1 N s/m on a 1 kg plate: each step removes k dt / m of the velocity (explicit force).
  {
    auto s = slidingPlate(FrictionModel::Viscous, 1.0f);
    float previous = 2.0f;
    for (int k = 0; k < 60; ++k) {
      s->world.step(kDt);
      const float v = s->world.linearVelocity(s->plate).x;
      EXPECT_LE(v, previous + 1e-4f) << "step " << k;
      EXPECT_GE(v, 0.0f);
      previous = v;
    }
    const float expected = 2.0f * std::pow(1.0f - kDt, 59.0f);
    EXPECT_NEAR(previous, expected, 0.02f * expected);
  }
  // A huge coefficient: the explicit force would overshoot; the clamp stops it at zero instead.
  {
    auto s = slidingPlate(FrictionModel::Viscous, 500.0f);
    for (int k = 0; k < 30; ++k) {
      s->world.step(kDt);
      EXPECT_GE(s->world.linearVelocity(s->plate).x, -1e-4f) << "step " << k;
    }
    EXPECT_NEAR(s->world.linearVelocity(s->plate).x, 0.0f, 0.01f);
  }
}

}  // namespace
}  // namespace collide
