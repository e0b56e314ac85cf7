// World::setDef: settings changed between steps take effect from the next step, and nothing else
// changes: bodies, handles, contacts and their warm start are kept.
#include "support/collide_error.h"
#include "support/world_helpers.h"

#include <collide/world.h>

#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <vector>

namespace collide {
namespace {

using test::kDt;

// A small pile: a 3 x 4 x 3 lattice of boxes, slightly turned, dropped on the ground.
std::vector<BodyId> buildBoxStack(World& world) {
  std::vector<BodyId> ids;
  ids.push_back(world.createBody(test::groundBox()));
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 3; ++x) {
      for (int z = 0; z < 3; ++z) {
        BodyDef def =
            test::boxBody(Vec3(1.1f * x - 1.1f, 0.5f + 1.05f * y, 1.1f * z - 1.1f), Vec3(0.5f), 1.0f);
        def.rotation = glm::angleAxis(0.05f * (x + 2 * y + 3 * z), glm::normalize(Vec3(1.0f, 2.0f, 3.0f)));
        ids.push_back(world.createBody(def));
      }
    }
  }
  return ids;
}

bool sameBits(const Vec3& a, const Vec3& b) { return std::memcmp(&a, &b, sizeof a) == 0; }
bool sameBits(const Quat& a, const Quat& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(WorldSetDef, GravityChangesFromTheNextStep) {
  WorldDef def;
  def.gravity = Vec3(0.0f, -10.0f, 0.0f);
  World world(def);
  const BodyId ball = world.createBody(test::sphereBody(Vec3(0.0f, 100.0f, 0.0f), 0.5f, 1.0f));
  world.step(kDt);
  const float v1 = world.linearVelocity(ball).y;
  EXPECT_NEAR(v1, -10.0f * kDt, 1e-5f);
  def.gravity = Vec3(0.0f, -2.0f, 0.0f);
  world.setDef(def);
  EXPECT_EQ(world.def().gravity, def.gravity);
  world.step(kDt);
  // Free fall: the step adds exactly gravity times the step, now the new gravity.
  EXPECT_NEAR(world.linearVelocity(ball).y - v1, -2.0f * kDt, 1e-5f);
}

TEST(WorldSetDef, ARefusedDefChangesNothing) {
  World world, twin;
  const std::vector<BodyId> a = buildBoxStack(world), b = buildBoxStack(twin);
  for (int i = 0; i < 30; ++i) {
    world.step(kDt);
    twin.step(kDt);
  }
  const WorldDef before = world.def();
  WorldDef bad = before;
  bad.substeps = 0;
  EXPECT_COLLIDE_ERROR(world.setDef(bad));
  bad = before;
  bad.gravity.x = std::numeric_limits<float>::quiet_NaN();
  EXPECT_COLLIDE_ERROR(world.setDef(bad));
  bad = before;
  bad.broadPhase.type = BroadPhaseType::Grid;
  bad.broadPhase.gridCellSize = -1.0f;  // refused by the new broad phase, after the other checks
  EXPECT_COLLIDE_ERROR(world.setDef(bad));
  EXPECT_EQ(world.def().substeps, before.substeps);
  EXPECT_EQ(world.broadPhase().type(), BroadPhaseType::Tree);
  for (int i = 0; i < 30; ++i) {
    world.step(kDt);
    twin.step(kDt);
  }
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_TRUE(sameBits(world.transform(a[i]).position, twin.transform(b[i]).position)) << "body " << i;
  }
}

// Every broad phase finds the same pairs (those whose boxes overlap), so a world that switches
// broad phase every 20 steps must end bit for bit where one that never switches does; with a
// destroyed body first, so that the proxy table has a hole the switch must keep.
TEST(WorldSetDef, SwitchingTheBroadPhaseChangesNoResult) {
  World switched, kept;
  std::vector<BodyId> a = buildBoxStack(switched), b = buildBoxStack(kept);
  switched.destroyBody(a[5]);
  kept.destroyBody(b[5]);
  const BroadPhaseType types[] = {BroadPhaseType::SweepAndPrune, BroadPhaseType::Grid,
                                  BroadPhaseType::BruteForce, BroadPhaseType::Tree};
  for (int step = 0; step < 160; ++step) {
    if (step % 20 == 10) {
      WorldDef def = switched.def();
      def.broadPhase.type = types[(step / 20) % 4];
      switched.setDef(def);
      EXPECT_EQ(switched.broadPhase().type(), def.broadPhase.type);
      EXPECT_EQ(switched.broadPhase().proxyCount(), kept.broadPhase().proxyCount());
    }
    if (step == 75) {  // a body created after a switch takes the freed slot in both worlds
      a.push_back(switched.createBody(test::sphereBody(Vec3(0.3f, 6.0f, 0.2f), 0.4f, 1.0f)));
      b.push_back(kept.createBody(test::sphereBody(Vec3(0.3f, 6.0f, 0.2f), 0.4f, 1.0f)));
      EXPECT_EQ(a.back().index, b.back().index);
    }
    switched.step(kDt);
    kept.step(kDt);
  }
  EXPECT_EQ(switched.broadPhasePairs().size(), kept.broadPhasePairs().size());
  int checked = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (i == 5) continue;
    ASSERT_TRUE(switched.isValid(a[i]));
    const Transform ta = switched.transform(a[i]), tb = kept.transform(b[i]);
    EXPECT_TRUE(sameBits(ta.position, tb.position)) << "body " << i;
    EXPECT_TRUE(sameBits(ta.rotation, tb.rotation)) << "body " << i;
    EXPECT_TRUE(sameBits(switched.linearVelocity(a[i]), kept.linearVelocity(b[i]))) << "body " << i;
    ++checked;
  }
  EXPECT_EQ(checked, 37);
  // Queries go through the new broad phase: a ray down the middle hits the pile's top, the body and
  // the point the world that never switched finds.
  const Ray down{Vec3(0.0f, 20.0f, 0.0f), Vec3(0.0f, -1.0f, 0.0f), 100.0f};
  const auto hit = switched.castRay(down);
  const auto expected = kept.castRay(down);
  ASSERT_TRUE(hit.has_value());
  ASSERT_TRUE(expected.has_value());
  EXPECT_EQ(hit->body.index, expected->body.index);
  EXPECT_NE(switched.type(hit->body), BodyType::Static);  // a box of the pile, not the ground
  EXPECT_TRUE(sameBits(hit->point, expected->point));
}

TEST(WorldSetDef, SleepingOffWakesSleepingBodies) {
  WorldDef def;
  def.sleeping = true;
  World world(def);
  world.createBody(test::groundBox());
  const BodyId box = world.createBody(test::boxBody(Vec3(0.0f, 0.5f, 0.0f), Vec3(0.5f), 1.0f));
  for (int i = 0; i < 120 && world.isAwake(box); ++i) world.step(kDt);
  ASSERT_FALSE(world.isAwake(box));
  def.sleeping = false;
  world.setDef(def);
  EXPECT_TRUE(world.isAwake(box));
  for (int i = 0; i < 120; ++i) world.step(kDt);
  EXPECT_TRUE(world.isAwake(box));  // sleeping is off: it stays awake, resting
  EXPECT_NEAR(world.transform(box).position.y, 0.5f, 0.01f);
}

}  // namespace
}  // namespace collide
