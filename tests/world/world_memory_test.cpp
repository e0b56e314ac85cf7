// World::memoryUse: each stage's arrays, counted where they are held. Lower bounds from what the
// world must store (a record per body, a contact per touching pair, a joint record per joint), and
// the world's promise that a running scene stops allocating once it has grown to its work.
#include "support/collide_error.h"
#include "support/world_helpers.h"

#include "bodies/body_storage.h"
#include "contacts/contact_cache.h"
#include "contacts/contact_update.h"
#include "dynamics/joint_solver.h"

#include <collide/world.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

namespace collide {
namespace {

using test::kDt;

// Sixteen columns of four unit boxes, 0.1 m apart, on a ground box; sleeping off (so that it keeps
// its contacts awake).
World boxStack() {
  WorldDef def;
  def.sleeping = false;
  World world(def);
  world.createBody(test::groundBox());
  for (int x = 0; x < 4; ++x)
    for (int y = 0; y < 4; ++y)
      for (int z = 0; z < 4; ++z)
        world.createBody(test::boxBody(Vec3(1.1f * x, 0.5f + 1.0f * y, 1.1f * z), Vec3(0.5f), 1.0f));
  return world;
}

TEST(WorldMemory, TheCategoriesAddUpToTheTotal) {
  World world = boxStack();
  for (int i = 0; i < 10; ++i) world.step(kDt);
  const WorldMemory memory = world.memoryUse();
  std::size_t sum = 0;
  for (const WorldMemory::Category& category : WorldMemory::kCategories) sum += memory.*category.bytes;
  EXPECT_EQ(memory.total(), sum);
  EXPECT_EQ(sum, memory.bodies + memory.broadPhase + memory.contacts + memory.solver + memory.joints +
                     memory.islands);
}

TEST(WorldMemory, BodiesHoldARecordAndAStateEachAndTheirLongNames) {
  World world;
  const WorldMemory empty = world.memoryUse();
  constexpr int kBodies = 500;
  for (int i = 0; i < kBodies; ++i)
    world.createBody(test::sphereBody(Vec3(3.0f * i, 0.0f, 0.0f), 0.5f, 1.0f));
  const WorldMemory filled = world.memoryUse();
  EXPECT_GE(filled.bodies, kBodies * (sizeof(detail::BodyRecord) + sizeof(detail::BodyState)));
  EXPECT_GE(filled.broadPhase, kBodies * sizeof(BroadPhase::ProxyRecord));
  EXPECT_GT(filled.broadPhase, empty.broadPhase);

  // A name longer than the string's own buffer is a heap block of its length and the terminator.
  BodyDef named = test::sphereBody(Vec3(0.0f, 10.0f, 0.0f), 0.5f, 1.0f);
  named.name = std::string(300, 'n');
  const std::size_t before = world.memoryUse().bodies;
  world.createBody(named);
  EXPECT_GE(world.memoryUse().bodies, before + 301);
}

// Room reserved for the bodies up front: creating them then allocates no body storage and no
// proxy record, and the world steps exactly as one that grew as they came.
TEST(WorldMemory, ReservedBodiesAreCreatedWithoutGrowing) {
  const auto build = [](World& world) {
    world.createBody(test::groundBox());
    for (int i = 0; i < 300; ++i)
      world.createBody(test::sphereBody(
          Vec3(0.6f * float(i % 10), 1.0f + 0.6f * float(i / 100), 0.6f * float((i / 10) % 10)), 0.25f,
          1.0f));
  };
  World reserved;
  reserved.reserveBodies(301);
  const WorldMemory before = reserved.memoryUse();
  EXPECT_GE(before.bodies, 301 * (sizeof(detail::BodyRecord) + sizeof(detail::BodyState)));
  build(reserved);
  EXPECT_EQ(reserved.memoryUse().bodies, before.bodies) << "no body array grew";
  reserved.reserveBodies(10);  // less than there is: nothing changes
  EXPECT_EQ(reserved.memoryUse().bodies, before.bodies);
  World grown;
  build(grown);
  EXPECT_GT(grown.memoryUse().bodies, before.bodies) << "grown by doubling, to room for 512";
  for (int i = 0; i < 60; ++i) {
    reserved.step(kDt);
    grown.step(kDt);
  }
  EXPECT_TRUE(reserved.saveSnapshot() == grown.saveSnapshot()) << "room changes no result";
  EXPECT_THAT([&] { reserved.reserveBodies(World::kMaxReservedBodies + 1); },
              test::ReportsError(::testing::HasSubstr("world: reserveBodies: 16777217 bodies")));
  EXPECT_EQ(reserved.memoryUse().bodies, before.bodies);
}

TEST(WorldMemory, ContactsAreHeldOnce) {
  World world = boxStack();
  for (int i = 0; i < 30; ++i) world.step(kDt);
  const std::size_t touching = world.touchingContactCount();
  ASSERT_EQ(touching, 64u);  // sixteen columns of four, each box on the one below (or the ground)
  ASSERT_EQ(world.lastStats().contactPairs, touching);
  // One array, which each step rewrites in place (last step's contacts read ahead of this step's
  // written), not a second one for last step's: at least a contact each, less than two.
  const std::size_t contacts = world.memoryUse().contacts;
  EXPECT_GE(contacts, touching * sizeof(detail::Contact));
  EXPECT_LT(contacts, 2 * touching * sizeof(detail::Contact));
  // A steady stack writes each contact over its own last one: nothing grows.
  for (int i = 0; i < 30; ++i) world.step(kDt);
  EXPECT_EQ(world.memoryUse().contacts, contacts);
  EXPECT_GT(world.memoryUse().solver, 0u);
}

// Pairs the narrow phase finds apart keep their cache alone, not a whole contact: a grid of spheres
// 3 cm apart (their boxes, grown by the 2 cm speculative distance, overlap; the spheres are beyond
// it) holds less for its pairs than one Contact each would.
TEST(WorldMemory, PairsApartHoldLessThanAContact) {
  World world(test::zeroGravityWorld());
  for (int x = 0; x < 10; ++x)
    for (int z = 0; z < 10; ++z)
      world.createBody(test::sphereBody(Vec3(1.03f * x, 0.0f, 1.03f * z), 0.5f, 1.0f));
  world.step(kDt);
  world.step(kDt);
  const std::uint64_t tested = world.lastStats().narrowPhaseTests;
  // The grid's 180 side-by-side neighbours and 162 diagonal ones (their boxes overlap at a corner).
  ASSERT_EQ(tested, 342u);
  EXPECT_EQ(world.touchingContactCount(), 0u);
  EXPECT_LT(world.memoryUse().contacts, tested * sizeof(detail::Contact));
}

TEST(WorldMemory, JointsHoldTheirRecords) {
  World world;
  const BodyId anchor = test::staticAnchor(world, Vec3(0.0f, 20.0f, 0.0f));
  BodyId previous = anchor;
  constexpr int kLinks = 40;
  for (int i = 0; i < kLinks; ++i) {
    const BodyId link = world.createBody(test::sphereBody(Vec3(0.0f, 19.5f - i, 0.0f), 0.25f, 1.0f));
    BallJointDef joint;
    joint.a = previous;
    joint.b = link;
    joint.anchor = Vec3(0.0f, 20.0f - i, 0.0f);
    world.createBallJoint(joint);
    previous = link;
  }
  world.step(kDt);
  EXPECT_GE(world.memoryUse().joints, kLinks * sizeof(detail::Joint));
}

// Once a scene has grown its arrays to its work, the steps reuse them: a resting stack holds the
// same memory, category by category, after 120 more steps.
TEST(WorldMemory, ASettledSceneStopsGrowing) {
  World world = boxStack();
  for (int i = 0; i < 240; ++i) world.step(kDt);
  const WorldMemory settled = world.memoryUse();
  for (int i = 0; i < 120; ++i) world.step(kDt);
  const WorldMemory later = world.memoryUse();
  for (const WorldMemory::Category& category : WorldMemory::kCategories)
    EXPECT_EQ(later.*category.bytes, settled.*category.bytes) << category.label;
}

}  // namespace
}  // namespace collide

namespace collide {
namespace {

// At two workers the narrow phase tests the pairs ahead of its walk, each worker into its own list
// (a manifold a pair). A burst of new pairs grows those lists past a megabyte; once the burst is
// over they are handed back, not kept for the rest of the run.
TEST(WorldMemory, ABurstOfStagedTestsIsNotKeptOnceItIsOver) {
  WorldDef def = test::zeroGravityWorld();
  def.workerCount = 2;
  World world(def);
  // 20 x 20 x 20 spheres of radius 0.3, 0.5 apart: each overlaps its six neighbours, a new pair each.
  std::vector<BodyId> spheres;
  for (int x = 0; x < 20; ++x)
    for (int y = 0; y < 20; ++y)
      for (int z = 0; z < 20; ++z)
        spheres.push_back(world.createBody(test::sphereBody(0.5f * Vec3(x, y, z), 0.3f, 1.0f)));
  world.step(kDt);
  const std::size_t burst = world.memoryUse().contacts;
  // Each touching pair's test was staged (its manifold in a worker's list).
  const std::size_t staged = world.touchingContactCount();
  ASSERT_EQ(staged, 3u * 20u * 20u * 19u);
  // The spheres far apart: no pair, and the next step's lists are empty.
  for (std::size_t i = 0; i < spheres.size(); ++i)
    world.setTransform(spheres[i], Vec3(10.0f * float(i), 0.0f, 0.0f), Quat(1.0f, 0.0f, 0.0f, 0.0f));
  world.step(kDt);
  const std::size_t quiet = world.memoryUse().contacts;
  EXPECT_GT(burst, quiet + staged * sizeof(detail::ContactUpdate::StagedTest));
}

}  // namespace
}  // namespace collide
