// Particles: point masses that collide as spheres and never turn.
#include "support/collide_error.h"
#include "support/test_assertions.h"
#include "support/world_helpers.h"

#include <gtest/gtest.h>

#include <cstring>
#include <string>

namespace collide {
namespace {

using test::kDt;

using test::expectErrorMentions;

TEST(Particle, BadDefinitionsAreErrors) {
  World world;
  BodyDef def = test::particleBody(Vec3(0.0f), 0.1f, 1.0f);
  def.shape = Shape(Box{Vec3(0.1f)});
  expectErrorMentions([&] { world.createBody(def); }, "sphere");
  def = test::particleBody(Vec3(0.0f), 0.1f, 1.0f);
  def.type = BodyType::Static;
  expectErrorMentions([&] { world.createBody(def); }, "dynamic");
  def = test::particleBody(Vec3(0.0f), 0.1f, 1.0f);
  def.angularVelocity = Vec3(0.0f, 1.0f, 0.0f);
  expectErrorMentions([&] { world.createBody(def); }, "angular");
  EXPECT_EQ(world.bodyCount(), 0u);
  const BodyId p = world.createBody(test::particleBody(Vec3(0.0f), 0.1f, 1.0f));
  EXPECT_TRUE(world.isParticle(p));
  expectErrorMentions([&] { world.setAngularVelocity(p, Vec3(1.0f, 0.0f, 0.0f)); }, "particle");
  EXPECT_NO_COLLIDE_ERROR(world.setAngularVelocity(p, Vec3(0.0f)));
}

// An off-centre impulse, a torque and an off-centre force move a particle but never turn it.
TEST(Particle, TakesOnlyTheLinearPartOfImpulsesAndForces) {
  World world(test::zeroGravityWorld());
  const Quat tilt = glm::angleAxis(0.4f, glm::normalize(Vec3(1.0f, 2.0f, 3.0f)));
  BodyDef def = test::particleBody(Vec3(0.0f), 0.1f, 2.0f);
  def.rotation = tilt;
  const BodyId p = world.createBody(def);
  world.applyImpulse(p, Vec3(0.0f, 0.0f, 4.0f), Vec3(1.0f, 0.0f, 0.0f));
  world.applyTorque(p, Vec3(5.0f, 0.0f, 0.0f));
  world.applyForce(p, Vec3(0.0f, 6.0f, 0.0f), Vec3(0.0f, 0.0f, 1.0f));
  world.step(kDt);
  EXPECT_EQ(world.angularVelocity(p), Vec3(0.0f));
  const Quat q = world.transform(p).rotation;
  EXPECT_EQ(std::memcmp(&q, &tilt, sizeof(Quat)), 0);
  EXPECT_NEAR(world.linearVelocity(p).z, 2.0f, 1e-6f);        // 4 N s / 2 kg
  EXPECT_NEAR(world.linearVelocity(p).y, 3.0f * kDt, 1e-6f);  // 6 N / 2 kg for one step
}

// A rigid ball sliding on the ground starts to roll (Coulomb friction turns it, and it keeps 5/7
// of its speed); a particle cannot turn, so it slides to rest after v0^2 / (2 mu g).
TEST(Particle, SlidesToRestAfterTheCoulombDistance) {
  World world;
  world.createBody(test::groundBox());
  const float v0 = 3.0f;
  const float mu = 0.5f;
  BodyDef def = test::particleBody(Vec3(0.0f, 0.1f, 0.0f), 0.1f, 1.0f);
  def.linearVelocity = Vec3(v0, 0.0f, 0.0f);
  def.friction = mu;
  const BodyId p = world.createBody(def);
  const Quat q0 = world.transform(p).rotation;
  for (int i = 0; i < 120; ++i) world.step(kDt);  // 2 s, it stops after 0.61 s
  const float expected = v0 * v0 / (2.0f * mu * 9.81f);
  EXPECT_NEAR(world.transform(p).position.x, expected, 0.03f * expected);
  EXPECT_NEAR(world.transform(p).position.y, 0.1f, 0.01f);
  EXPECT_LT(glm::length(world.linearVelocity(p)), 1e-3f);
  const Quat q = world.transform(p).rotation;
  EXPECT_EQ(std::memcmp(&q, &q0, sizeof(Quat)), 0);
}

// Two particles collide as spheres: equal masses, head on, elastic -> they swap velocities.
TEST(Particle, CollidesAsASphereOfItsRadius) {
  WorldDef wd = test::zeroGravityWorld();
  World world(wd);
  BodyDef a = test::particleBody(Vec3(-1.0f, 0.0f, 0.0f), 0.25f, 1.0f);
  a.linearVelocity = Vec3(2.0f, 0.0f, 0.0f);
  a.bounciness = 1.0f;
  BodyDef b = test::particleBody(Vec3(1.0f, 0.0f, 0.0f), 0.25f, 1.0f);
  b.bounciness = 1.0f;
  const BodyId ia = world.createBody(a);
  const BodyId ib = world.createBody(b);
  for (int i = 0; i < 60; ++i) world.step(kDt);
  EXPECT_NEAR(world.linearVelocity(ia).x, 0.0f, 0.02f);
  EXPECT_NEAR(world.linearVelocity(ib).x, 2.0f, 0.02f);
  // They touched at a centre distance of 2 radii: b started at 1 and has moved since contact.
  EXPECT_GT(world.transform(ib).position.x, 1.0f);
}

}  // namespace
}  // namespace collide
