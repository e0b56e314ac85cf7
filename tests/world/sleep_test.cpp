// Islands and sleeping: resting islands sleep after timeToSleep and then do not move at all;
// contacts, the API and destruction wake them.
#include "support/collide_error.h"
#include "support/world_helpers.h"

#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <vector>

namespace collide {
namespace {

using test::kDt;

WorldDef sleepingWorld() {
  WorldDef def;
  def.sleeping = true;
  return def;
}

bool sameBits(const Transform& a, const Transform& b) {
  return std::memcmp(&a.position, &b.position, sizeof(Vec3)) == 0 &&
         std::memcmp(&a.rotation, &b.rotation, sizeof(Quat)) == 0;
}

// Steps until every body in `ids` sleeps; returns the time taken, or -1 after maxSeconds.
float timeToSleep(World& world, const std::vector<BodyId>& ids, float maxSeconds) {
  for (int step = 1; step <= static_cast<int>(maxSeconds / kDt); ++step) {
    world.step(kDt);
    bool asleep = true;
    for (const BodyId id : ids) asleep = asleep && !world.isAwake(id);
    if (asleep) return step * kDt;
  }
  return -1.0f;
}

TEST(Sleep, BadSleepTuningIsAnError) {
  WorldDef def = sleepingWorld();
  def.sleep.timeToSleep = 0.0f;
  EXPECT_COLLIDE_ERROR(World w(def));
  def = sleepingWorld();
  def.sleep.linearSpeed = std::numeric_limits<float>::quiet_NaN();
  EXPECT_COLLIDE_ERROR(World w(def));
  def = sleepingWorld();
  def.sleep.angularSpeed = -1.0f;
  EXPECT_COLLIDE_ERROR(World w(def));
}

TEST(Sleep, DroppedBoxFallsAsleepAndItsPoseStaysBitIdentical) {
  World world(sleepingWorld());
  const BodyId ground = world.createBody(test::groundBox());
  const BodyId box = world.createBody(test::boxBody(Vec3(0.0f, 1.0f, 0.0f), Vec3(0.5f), 1.0f));
  EXPECT_FALSE(world.isAwake(ground));  // static bodies are never awake
  EXPECT_TRUE(world.isAwake(box));
  const float slept = timeToSleep(world, {box}, 2.0f);
  ASSERT_GT(slept, 0.0f) << "not asleep after 2 s";
  EXPECT_GT(slept, 0.5f);  // it fell for 0.3 s and must rest 0.5 s
  EXPECT_NEAR(world.transform(box).position.y, 0.5f, 0.01f);
  EXPECT_EQ(world.linearVelocity(box), Vec3(0.0f));
  const Transform pose = world.transform(box);
  for (int step = 0; step < 120; ++step) world.step(kDt);
  EXPECT_FALSE(world.isAwake(box));
  EXPECT_TRUE(sameBits(world.transform(box), pose));
  EXPECT_EQ(world.touchingContactCount(), 1u);  // the sleeping contact still touches
  EXPECT_TRUE(world.contactEvents().empty());   // and ends nothing
}

TEST(Sleep, WithSleepingOffNothingSleeps) {
  World world;  // sleeping = false
  world.createBody(test::groundBox());
  const BodyId box = world.createBody(test::boxBody(Vec3(0.0f, 1.0f, 0.0f), Vec3(0.5f), 1.0f));
  for (int step = 0; step < 180; ++step) {
    world.step(kDt);
    ASSERT_TRUE(world.isAwake(box));
  }
}

// Two separate piles are separate islands: one sleeps while the other still moves.
TEST(Sleep, IslandsSleepSeparately) {
  World world(sleepingWorld());
  world.createBody(test::groundBox());
  const BodyId low = world.createBody(test::boxBody(Vec3(0.0f, 0.5f, 0.0f), Vec3(0.5f), 1.0f));
  const BodyId high = world.createBody(test::boxBody(Vec3(5.0f, 20.0f, 0.0f), Vec3(0.5f), 1.0f));
  ASSERT_GT(timeToSleep(world, {low}, 1.5f), 0.0f);
  EXPECT_TRUE(world.isAwake(high));  // still falling (2 s to the ground)
}

TEST(Sleep, BallRollingIntoASleepingStackWakesIt) {
  World world(sleepingWorld());
  world.createBody(test::groundBox());
  std::vector<BodyId> stack;
  for (int i = 0; i < 3; ++i)
    stack.push_back(world.createBody(test::boxBody(Vec3(0.0f, 0.5f + i * 1.0f, 0.0f), Vec3(0.5f), 1.0f)));
  ASSERT_GT(timeToSleep(world, stack, 4.0f), 0.0f);
  const Vec3 bottom = world.transform(stack[0]).position;
  BodyDef ball = test::sphereBody(Vec3(-4.0f, 0.3f, 0.0f), 0.3f, 20.0f, Vec3(6.0f, 0.0f, 0.0f));
  world.createBody(ball);
  bool woke = false;
  for (int step = 0; step < 90 && !woke; ++step) {
    world.step(kDt);
    woke = world.isAwake(stack[0]);
  }
  ASSERT_TRUE(woke);
  for (const BodyId id : stack) EXPECT_TRUE(world.isAwake(id));  // the whole island
  for (int step = 0; step < 10; ++step) world.step(kDt);
  EXPECT_GT(world.transform(stack[0]).position.x - bottom.x, 0.05f);  // pushed, not passed through
}

TEST(Sleep, TheApiAndConstraintsWakeAnIsland) {
  World world(sleepingWorld());
  world.createBody(test::groundBox());
  const BodyId a = world.createBody(test::boxBody(Vec3(0.0f, 0.5f, 0.0f), Vec3(0.5f), 1.0f));
  const BodyId b = world.createBody(test::boxBody(Vec3(0.0f, 1.5f, 0.0f), Vec3(0.5f), 1.0f));
  const auto sleepBoth = [&] { return timeToSleep(world, {a, b}, 3.0f) > 0.0f; };
  ASSERT_TRUE(sleepBoth());
  world.applyImpulse(b, Vec3(0.0f, 0.1f, 0.0f), world.centerOfMass(b));
  EXPECT_TRUE(world.isAwake(a));  // b's island is the stack
  ASSERT_TRUE(sleepBoth());
  world.setLinearVelocity(a, Vec3(0.0f));
  EXPECT_TRUE(world.isAwake(b));
  ASSERT_TRUE(sleepBoth());
  world.wakeBody(a);
  EXPECT_TRUE(world.isAwake(a) && world.isAwake(b));
  ASSERT_TRUE(sleepBoth());
  const BodyId c = world.createBody(test::boxBody(Vec3(5.0f, 0.5f, 0.0f), Vec3(0.5f), 1.0f));
  ASSERT_GT(timeToSleep(world, {a, b, c}, 3.0f), 0.0f);
  DistanceConstraintDef joint;
  joint.a = b;
  joint.b = c;
  const JointId j = world.createDistanceConstraint(joint);
  EXPECT_TRUE(world.isAwake(a) && world.isAwake(c));
  ASSERT_GT(timeToSleep(world, {a, b, c}, 3.0f), 0.0f);  // one island now
  world.destroyConstraint(j);
  EXPECT_TRUE(world.isAwake(a) && world.isAwake(b) && world.isAwake(c));
}

// Destroying what a sleeping stack rests on wakes it: it falls.
TEST(Sleep, DestroyingTheGroundWakesWhatRestedOnIt) {
  World world(sleepingWorld());
  const BodyId ground = world.createBody(test::groundBox());
  const BodyId box = world.createBody(test::boxBody(Vec3(0.0f, 0.5f, 0.0f), Vec3(0.5f), 1.0f));
  ASSERT_GT(timeToSleep(world, {box}, 2.0f), 0.0f);
  world.destroyBody(ground);
  EXPECT_TRUE(world.isAwake(box));
  for (int step = 0; step < 30; ++step) world.step(kDt);
  EXPECT_LT(world.transform(box).position.y, 0.0f);
}

}  // namespace
}  // namespace collide
