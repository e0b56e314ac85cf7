// Forces, torques and gravity on a rigid body: one step changes the velocities by a = F / m and
// alpha = I^-1 tau times dt (symplectic Euler over the substeps adds up to exactly that for a
// constant force), and the applied force and torque are gone by the next step.
#include <collide/world.h>

#include "support/world_helpers.h"

#include <gtest/gtest.h>

namespace collide {
namespace {

using test::kDt;

TEST(Forces, ForceAndTorqueChangeARigidBodysVelocitiesForOneStep) {
  World world(test::zeroGravityWorld());
  BodyDef def;
  def.shape = Sphere{0.5f};
  def.mass = 2.0f;  // inertia 2/5 m r^2 = 0.2 about every axis
  const BodyId ball = world.createBody(def);
  // 6 N along y at 1 m along z from the centre: torque (0, 0, 1) x (0, 6, 0) = (-6, 0, 0); plus a
  // pure torque of 1 N m about z.
  world.applyForce(ball, Vec3(0.0f, 6.0f, 0.0f), Vec3(0.0f, 0.0f, 1.0f));
  world.applyTorque(ball, Vec3(0.0f, 0.0f, 1.0f));
  world.step(kDt);
  EXPECT_NEAR(world.linearVelocity(ball).x, 0.0f, 1e-6f);
  EXPECT_NEAR(world.linearVelocity(ball).y, 3.0f * kDt, 1e-6f);     // 6 N / 2 kg
  EXPECT_NEAR(world.angularVelocity(ball).x, -30.0f * kDt, 1e-5f);  // -6 N m / 0.2 kg m^2
  EXPECT_NEAR(world.angularVelocity(ball).y, 0.0f, 1e-6f);
  EXPECT_NEAR(world.angularVelocity(ball).z, 5.0f * kDt, 1e-5f);  // 1 N m / 0.2 kg m^2
  const Vec3 v = world.linearVelocity(ball), w = world.angularVelocity(ball);
  world.step(kDt);  // the force and the torque were for one step
  EXPECT_NEAR(glm::length(world.linearVelocity(ball) - v), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::length(world.angularVelocity(ball) - w), 0.0f, 1e-6f);
}

TEST(Forces, GravityAddsGTimesDtEachStep) {
  WorldDef worldDef;
  worldDef.gravity = Vec3(0.0f, -9.81f, 2.0f);
  World world(worldDef);
  const BodyId ball = world.createBody(BodyDef{});
  for (int i = 0; i < 3; ++i) world.step(kDt);
  EXPECT_NEAR(world.linearVelocity(ball).y, -9.81f * 3.0f * kDt, 1e-5f);
  EXPECT_NEAR(world.linearVelocity(ball).z, 2.0f * 3.0f * kDt, 1e-5f);
  EXPECT_EQ(world.angularVelocity(ball), Vec3(0.0f));
}

}  // namespace
}  // namespace collide
