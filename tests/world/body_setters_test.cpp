// What a game changes on a body after creating it: gravity scale and damping (each against its
// closed form), the material (a ball's bounce follows it), a teleport that does not wake, and the
// iteration over the live bodies.
#include "support/collide_error.h"
#include "support/world_helpers.h"

#include <collide/world.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace collide {
namespace {

using test::kDt;

TEST(BodySetters, GravityScaleScalesTheFall) {
  // Three spheres far apart, scales 0, 2 and -1: after n steps of symplectic Euler each one's speed
  // is scale g t exactly as the integrator sums it, and the unscaled world gravity is unchanged.
  World world;
  const float scales[] = {0.0f, 2.0f, -1.0f, 1.0f};
  std::vector<BodyId> ids;
  for (int i = 0; i < 4; ++i) {
    BodyDef def = test::sphereBody(Vec3(10.0f * float(i), 100.0f, 0.0f), 0.5f, 1.0f);
    def.gravityScale = scales[i];
    ids.push_back(world.createBody(def));
  }
  world.setGravityScale(ids[3], 0.5f);
  EXPECT_EQ(world.gravityScale(ids[3]), 0.5f);
  const int steps = 30;
  for (int s = 0; s < steps; ++s) world.step(kDt);
  const float t = steps * kDt;
  const float g = -9.81f;
  EXPECT_EQ(world.linearVelocity(ids[0]), Vec3(0.0f));
  EXPECT_EQ(world.transform(ids[0]).position.y, 100.0f);
  EXPECT_NEAR(world.linearVelocity(ids[1]).y, 2.0f * g * t, 1e-4f);
  EXPECT_NEAR(world.linearVelocity(ids[2]).y, -g * t, 1e-4f);
  EXPECT_NEAR(world.linearVelocity(ids[3]).y, 0.5f * g * t, 1e-4f);
  EXPECT_GT(world.transform(ids[2]).position.y, 100.0f);  // it rises
  EXPECT_COLLIDE_ERROR(world.setGravityScale(ids[0], NAN));
  EXPECT_EQ(world.gravityScale(ids[0]), 0.0f);  // a refused value changes nothing
}

TEST(BodySetters, DampingDecaysVelocitiesByItsFactorPerSubstep) {
  // No gravity: each substep h multiplies the velocities by 1 / (1 + h c), so after n steps of
  // `substeps` substeps the speed is v0 (1 + h c)^-(n substeps), close to v0 e^(-c t).
  WorldDef worldDef = test::zeroGravityWorld();
  World world(worldDef);
  BodyDef def = test::sphereBody(Vec3(0.0f), 0.5f, 1.0f, Vec3(10.0f, 0.0f, 0.0f));
  def.angularVelocity = Vec3(0.0f, 4.0f, 0.0f);
  def.linearDamping = 0.5f;
  const BodyId damped = world.createBody(def);
  const BodyId changed =
      world.createBody(test::sphereBody(Vec3(0.0f, 0.0f, 50.0f), 0.5f, 1.0f, Vec3(10.0f, 0.0f, 0.0f)));
  world.setDamping(changed, 2.0f, 0.0f);
  world.setDamping(damped, 0.5f, 1.5f);
  EXPECT_EQ(world.linearDamping(damped), 0.5f);
  EXPECT_EQ(world.angularDamping(damped), 1.5f);
  const int steps = 60;
  for (int s = 0; s < steps; ++s) world.step(kDt);
  const float h = kDt / float(worldDef.substeps);
  const float n = float(steps * worldDef.substeps);
  EXPECT_NEAR(world.linearVelocity(damped).x, 10.0f * std::pow(1.0f + h * 0.5f, -n), 1e-3f);
  EXPECT_NEAR(world.angularVelocity(damped).y, 4.0f * std::pow(1.0f + h * 1.5f, -n), 1e-3f);
  EXPECT_NEAR(world.linearVelocity(changed).x, 10.0f * std::pow(1.0f + h * 2.0f, -n), 1e-3f);
  // Close to the exponential it stands for.
  EXPECT_NEAR(world.linearVelocity(changed).x, 10.0f * std::exp(-2.0f * 1.0f), 0.01f);
  EXPECT_COLLIDE_ERROR(world.setDamping(damped, -1.0f, 0.0f));
  EXPECT_COLLIDE_ERROR(world.setDamping(damped, 0.0f, INFINITY));
  EXPECT_EQ(world.linearDamping(damped), 0.5f);
}

// The highest the ball's centre rises after its first bounce, dropped from 1 m onto the ground.
float reboundHeight(World& world, BodyId ball) {
  float top = 0.0f;
  bool bounced = false;
  for (int s = 0; s < 120; ++s) {
    world.step(kDt);
    const float vy = world.linearVelocity(ball).y;
    bounced = bounced || vy > 0.5f;
    if (bounced) top = std::max(top, world.transform(ball).position.y);
  }
  return top;
}

TEST(BodySetters, ABallBouncesAsItsNewMaterialSays) {
  // The same drop twice: bounciness 0 from creation stays on the ground; set to 1 before the fall
  // (the ground's 0 combined by the world's Max rule), it comes back to within 3 % of its 1 m.
  for (const bool elastic : {false, true}) {
    SCOPED_TRACE(elastic);
    World world;
    world.createBody(test::groundBox());
    const BodyId ball = world.createBody(test::sphereBody(Vec3(0.0f, 1.0f, 0.0f), 0.1f, 1.0f));
    if (elastic) {
      world.setMaterial(ball, BodyMaterial{0.5f, 1.0f, 0.0f});  // the floor keeps its 0: Max gives 1
      EXPECT_EQ(world.material(ball), (BodyMaterial{0.5f, 1.0f, 0.0f}));
    }
    const float top = reboundHeight(world, ball);
    if (elastic) {
      EXPECT_NEAR(top, 1.0f, 0.03f);
    } else {
      EXPECT_LT(top, 0.11f);
    }
  }
  World world;
  const BodyId ball = world.createBody(test::sphereBody(Vec3(0.0f), 0.1f, 1.0f));
  EXPECT_COLLIDE_ERROR(world.setMaterial(ball, BodyMaterial{0.5f, 1.5f, 0.0f}));
  EXPECT_COLLIDE_ERROR(world.setMaterial(ball, BodyMaterial{-0.1f, 0.0f, 0.0f}));
  EXPECT_COLLIDE_ERROR(world.setMaterial(ball, BodyMaterial{0.5f, 0.0f, NAN}));
  EXPECT_EQ(world.material(ball), BodyMaterial{});
}

TEST(BodySetters, ATeleportWithoutWakingLeavesASleeperAsleep) {
  WorldDef worldDef;
  worldDef.sleeping = true;
  World world(worldDef);
  world.createBody(test::groundBox());
  const BodyId box = world.createBody(test::boxBody(Vec3(0.0f, 0.5f, 0.0f), Vec3(0.5f), 1.0f));
  for (int s = 0; s < 240 && world.isAwake(box); ++s) world.step(kDt);
  ASSERT_FALSE(world.isAwake(box));
  world.setTransform(box, Vec3(3.0f, 0.5f, 0.0f), Quat(1.0f, 0.0f, 0.0f, 0.0f), /*wake=*/false);
  EXPECT_FALSE(world.isAwake(box));
  world.step(kDt);
  EXPECT_FALSE(world.isAwake(box));
  EXPECT_EQ(world.transform(box).position, Vec3(3.0f, 0.5f, 0.0f));
  world.setTransform(box, Vec3(-3.0f, 0.5f, 0.0f), Quat(1.0f, 0.0f, 0.0f, 0.0f), /*wake=*/true);
  EXPECT_TRUE(world.isAwake(box));
}

TEST(BodySetters, BodiesListsTheLiveOnesInSlotOrder) {
  World world(test::zeroGravityWorld());
  std::vector<BodyId> ids;
  for (int i = 0; i < 5; ++i)
    ids.push_back(world.createBody(test::sphereBody(Vec3(3.0f * float(i), 0, 0), 0.5f, 1.0f)));
  world.destroyBody(ids[1]);
  world.destroyBody(ids[3]);
  EXPECT_EQ(world.bodies(), (std::vector<BodyId>{ids[0], ids[2], ids[4]}));
  const BodyId again = world.createBody(test::sphereBody(Vec3(0, 9, 0), 0.5f, 1.0f));  // reuses a slot
  const std::vector<BodyId> now = world.bodies();
  ASSERT_EQ(now.size(), 4u);
  EXPECT_TRUE(std::is_sorted(now.begin(), now.end(), [](BodyId a, BodyId b) { return a.index < b.index; }));
  EXPECT_NE(std::find(now.begin(), now.end(), again), now.end());
  for (const BodyId id : now) EXPECT_TRUE(world.isValid(id));
}

TEST(BodySetters, BadGravityScaleOrDampingInADefinitionIsRefused) {
  World world;
  BodyDef def = test::sphereBody(Vec3(0.0f), 0.5f, 1.0f);
  def.gravityScale = INFINITY;
  EXPECT_COLLIDE_ERROR(world.createBody(def));
  def.gravityScale = 1.0f;
  def.linearDamping = -0.1f;
  EXPECT_COLLIDE_ERROR(world.createBody(def));
  def.linearDamping = 0.0f;
  def.angularDamping = NAN;
  EXPECT_COLLIDE_ERROR(world.createBody(def));
  EXPECT_EQ(world.bodyCount(), 0u);
}

}  // namespace
}  // namespace collide
