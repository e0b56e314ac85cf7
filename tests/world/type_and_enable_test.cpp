// A body's type changed at run time (World::setType) and a body taken out of the simulation and put
// back (World::setEnabled), each checked against what the type or state means: a body made static
// stops and holds what rests on it, a static body made dynamic falls with the mass of its shape, a
// disabled body is found by nothing and moves not at all.
#include "support/collide_error.h"
#include "support/world_helpers.h"

#include <collide/world.h>

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace collide {
namespace {

using test::kDt;

TEST(SetType, AStaticBodyMadeDynamicFallsWithTheMassOfItsShape) {
  World world;
  BodyDef def = test::boxBody(Vec3(0.0f, 10.0f, 0.0f), Vec3(0.5f, 0.25f, 1.0f), 1.0f);
  def.type = BodyType::Static;
  def.mass.reset();
  def.density = 500.0f;
  const BodyId id = world.createBody(def);
  EXPECT_EQ(world.mass(id), 0.0f);
  world.step(kDt);
  EXPECT_EQ(world.transform(id).position.y, 10.0f);
  world.setType(id, BodyType::Dynamic);
  EXPECT_EQ(world.type(id), BodyType::Dynamic);
  EXPECT_FLOAT_EQ(world.mass(id), 500.0f * 1.0f * 0.5f * 2.0f);
  EXPECT_TRUE(world.isAwake(id));
  const int steps = 30;
  for (int s = 0; s < steps; ++s) world.step(kDt);
  EXPECT_NEAR(world.linearVelocity(id).y, -9.81f * steps * kDt, 1e-4f);  // free fall from rest
}

TEST(SetType, ADynamicBodyMadeStaticStopsAndHoldsWhatRestsOnIt) {
  // A plank falling with a box on it is made static in mid air: it stops where it is, and the box,
  // which went on falling, lands on it and rests there.
  World world;
  world.createBody(test::groundBox());
  const BodyId plank = world.createBody(test::boxBody(Vec3(0.0f, 5.0f, 0.0f), Vec3(2.0f, 0.1f, 2.0f), 10.0f));
  const BodyId box = world.createBody(test::boxBody(Vec3(0.0f, 5.6f, 0.0f), Vec3(0.5f), 1.0f));
  for (int s = 0; s < 10; ++s) world.step(kDt);
  const Vec3 stopped = world.transform(plank).position;
  world.setType(plank, BodyType::Static);
  EXPECT_EQ(world.linearVelocity(plank), Vec3(0.0f));
  EXPECT_EQ(world.mass(plank), 0.0f);
  EXPECT_FALSE(world.isAwake(plank));  // static bodies are never awake
  for (int s = 0; s < 180; ++s) world.step(kDt);
  EXPECT_EQ(world.transform(plank).position, stopped);
  EXPECT_NEAR(world.transform(box).position.y, stopped.y + 0.1f + 0.5f, 0.01f);
  EXPECT_NEAR(world.linearVelocity(box).y, 0.0f, 0.05f);
}

TEST(SetType, AKinematicBodyKeepsItsVelocityAndPushes) {
  // A dynamic box made kinematic moves on at its velocity, whatever it meets, and a dynamic ball in
  // its way is pushed ahead of it.
  World world(test::zeroGravityWorld());
  const BodyId pusher = world.createBody(test::boxBody(Vec3(0.0f), Vec3(0.5f), 1.0f));
  world.setLinearVelocity(pusher, Vec3(2.0f, 0.0f, 0.0f));
  world.setType(pusher, BodyType::Kinematic);
  const BodyId ball = world.createBody(test::sphereBody(Vec3(2.0f, 0.0f, 0.0f), 0.25f, 1.0f));
  for (int s = 0; s < 120; ++s) world.step(kDt);
  EXPECT_EQ(world.linearVelocity(pusher), Vec3(2.0f, 0.0f, 0.0f));
  EXPECT_NEAR(world.transform(pusher).position.x, 2.0f * 120 * kDt, 1e-3f);
  EXPECT_GT(world.transform(ball).position.x, world.transform(pusher).position.x + 0.5f + 0.25f - 0.02f);
}

TEST(SetType, ImpossibleTypesAreRefusedAndChangeNothing) {
  World world;
  const BodyId ground = world.createBody(test::groundPlane());
  EXPECT_COLLIDE_ERROR(world.setType(ground, BodyType::Dynamic));
  EXPECT_COLLIDE_ERROR(world.setType(ground, BodyType::Kinematic));
  EXPECT_EQ(world.type(ground), BodyType::Static);
  BodyDef particle = test::sphereBody(Vec3(0.0f, 1.0f, 0.0f), 0.1f, 1.0f);
  particle.particle = true;
  const BodyId p = world.createBody(particle);
  EXPECT_COLLIDE_ERROR(world.setType(p, BodyType::Static));
  EXPECT_EQ(world.type(p), BodyType::Dynamic);
  EXPECT_FLOAT_EQ(world.mass(p), 1.0f);
}

TEST(SetEnabled, ADisabledBodyIsFoundByNothingAndDoesNotMove) {
  World world;
  world.createBody(test::groundBox());
  const BodyId crate = world.createBody(test::boxBody(Vec3(0.0f, 0.5f, 0.0f), Vec3(0.5f), 1.0f));
  for (int s = 0; s < 30; ++s) world.step(kDt);
  EXPECT_EQ(world.touchingContactCount(), 1u);
  const Ray down{Vec3(0.0f, 5.0f, 0.0f), Vec3(0.0f, -1.0f, 0.0f), 10.0f};
  EXPECT_EQ(world.castRay(down)->body, crate);

  world.setEnabled(crate, false);
  EXPECT_FALSE(world.isEnabled(crate));
  EXPECT_FALSE(world.isAwake(crate));
  world.setTransform(crate, Vec3(0.0f, 3.0f, 0.0f), Quat(1, 0, 0, 0));  // set while disabled
  world.applyImpulse(crate, Vec3(0.0f, 0.0f, 0.0f), Vec3(0.0f));
  world.step(kDt);
  // Its contact ended (reported with this step's events), no query finds it, it did not fall.
  ASSERT_EQ(world.contactEvents().size(), 1u);
  EXPECT_EQ(world.contactEvents()[0].type, ContactEvent::Type::End);
  EXPECT_EQ(world.touchingContactCount(), 0u);
  EXPECT_NE(world.castRay(down)->body, crate);
  EXPECT_TRUE(world.overlapPoint(Vec3(0.0f, 3.0f, 0.0f)).empty());
  for (int s = 0; s < 30; ++s) world.step(kDt);
  EXPECT_EQ(world.transform(crate).position, Vec3(0.0f, 3.0f, 0.0f));

  // Enabled again, it falls from where it was put and lands.
  world.setEnabled(crate, true);
  EXPECT_TRUE(world.isAwake(crate));
  EXPECT_EQ(world.castRay(down)->body, crate);
  for (int s = 0; s < 120; ++s) world.step(kDt);
  EXPECT_NEAR(world.transform(crate).position.y, 0.5f, 0.01f);
  EXPECT_EQ(world.touchingContactCount(), 1u);
}

TEST(SetEnabled, ADisabledBodysConstraintRestsAndItsPartnerFalls) {
  // A ball hanging from a static anchor by a rope: with the anchor disabled the rope rests, so the
  // ball falls freely; enabled again, the rope holds it once more.
  WorldDef def;
  World world(def);
  BodyDef anchor = test::sphereBody(Vec3(0.0f, 10.0f, 0.0f), 0.1f, 1.0f);
  anchor.type = BodyType::Static;
  const BodyId a = world.createBody(anchor);
  const BodyId ball = world.createBody(test::sphereBody(Vec3(0.0f, 8.0f, 0.0f), 0.2f, 1.0f));
  DistanceConstraintDef rope;
  rope.a = a;
  rope.b = ball;
  world.createDistanceConstraint(rope);
  world.setEnabled(a, false);
  const int steps = 20;
  for (int s = 0; s < steps; ++s) world.step(kDt);
  EXPECT_NEAR(world.linearVelocity(ball).y, -9.81f * steps * kDt, 1e-4f);
  world.setEnabled(a, true);
  for (int s = 0; s < 120; ++s) world.step(kDt);
  EXPECT_NEAR(glm::length(world.transform(ball).position - Vec3(0.0f, 10.0f, 0.0f)), 2.0f, 0.02f);
}

}  // namespace
}  // namespace collide
