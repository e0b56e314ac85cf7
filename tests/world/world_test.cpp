// The World's API: ids, validation, counters, events, sensors, the pre-solve callback, determinism
// and the penetration responses.
#include "support/collide_error.h"
#include "support/test_assertions.h"
#include "support/world_helpers.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

namespace collide {
namespace {

using test::kDt;

using test::expectErrorMentions;

TEST(World, StaleBodyIdIsAnError) {
  World world;
  const BodyId a = world.createBody(test::sphereBody(Vec3(0.0f), 0.5f, 1.0f));
  world.destroyBody(a);
  EXPECT_FALSE(world.isValid(a));
  EXPECT_COLLIDE_ERROR(world.transform(a));
  EXPECT_COLLIDE_ERROR(world.destroyBody(a));
  const BodyId b = world.createBody(test::sphereBody(Vec3(0.0f), 0.5f, 1.0f));
  EXPECT_EQ(b.index, a.index);  // the slot is reused with a new generation
  EXPECT_NE(b.generation, a.generation);
  EXPECT_COLLIDE_ERROR(world.setLinearVelocity(a, Vec3(1.0f)));
  EXPECT_NO_COLLIDE_ERROR(world.transform(b));
  EXPECT_COLLIDE_ERROR(world.transform(BodyId{}));
}

TEST(World, BadBodyDefsNameTheField) {
  World world;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  BodyDef def = test::sphereBody(Vec3(nan, 0.0f, 0.0f), 0.5f, 1.0f);
  expectErrorMentions([&] { world.createBody(def); }, "position");
  def = test::sphereBody(Vec3(0.0f), 0.5f, 0.0f);
  expectErrorMentions([&] { world.createBody(def); }, "mass");
  def = test::sphereBody(Vec3(0.0f), 0.5f, 1.0f);
  def.shape = Shape(Plane{});
  expectErrorMentions([&] { world.createBody(def); }, "plane");
  def = test::sphereBody(Vec3(0.0f), 0.5f, 1.0f);
  def.bounciness = 1.5f;
  expectErrorMentions([&] { world.createBody(def); }, "bounciness");
  def = test::sphereBody(Vec3(0.0f), 0.5f, 1.0f);
  def.friction = -1.0f;
  expectErrorMentions([&] { world.createBody(def); }, "friction");
  def.friction = std::numeric_limits<float>::infinity();
  expectErrorMentions([&] { world.createBody(def); }, "friction");
  def = test::sphereBody(Vec3(0.0f), 0.5f, 1.0f);
  def.bounciness = nan;
  expectErrorMentions([&] { world.createBody(def); }, "bounciness");
  def.bounciness = -0.1f;
  expectErrorMentions([&] { world.createBody(def); }, "bounciness");
  def = test::sphereBody(Vec3(0.0f), 0.5f, 1.0f);
  def.rotation = Quat(2.0f, 0.0f, 0.0f, 0.0f);
  expectErrorMentions([&] { world.createBody(def); }, "rotation");
  def = test::sphereBody(Vec3(0.0f), 0.5f, 1.0f);
  def.mass.reset();
  def.density = -3.0f;
  expectErrorMentions([&] { world.createBody(def); }, "density");
  def = test::sphereBody(Vec3(0.0f), 0.5f, 1.0f);
  def.linearVelocity = Vec3(0.0f, std::numeric_limits<float>::infinity(), 0.0f);
  expectErrorMentions([&] { world.createBody(def); }, "linearVelocity");
  EXPECT_EQ(world.bodyCount(), 0u);
  expectErrorMentions([&] { world.step(0.0f); }, "dt");
}

TEST(World, BadWorldDefsAreErrors) {
  WorldDef def;
  def.substeps = 0;
  expectErrorMentions([&] { World w(def); }, "substeps");
  def.substeps = kMaxSubsteps + 1;  // each substep is a full solve: more would stall the step
  expectErrorMentions([&] { World w(def); }, "substeps must be 1 to 64");
  def = WorldDef{};
  def.contact.relaxPasses = kMaxRelaxPasses + 1;
  expectErrorMentions([&] { World w(def); }, "relaxPasses");
  def = WorldDef{};
  def.gravity.y = std::numeric_limits<float>::quiet_NaN();
  expectErrorMentions([&] { World w(def); }, "gravity");
  def = WorldDef{};
  def.sleeping = true;
  def.sleep.timeToSleep = -1.0f;
  expectErrorMentions([&] { World w(def); }, "timeToSleep");
  EXPECT_EQ(parseCombineRule("multiply"), CombineRule::Multiply);
  EXPECT_EQ(parsePenetrationResponse("revert"), PenetrationResponse::Revert);
  EXPECT_EQ(parsePenetrationResponse("project"), PenetrationResponse::Project);
  EXPECT_EQ(parsePenetrationResponse("soft"), PenetrationResponse::Soft);
  EXPECT_EQ(WorldDef{}.penetrationResponse, PenetrationResponse::Soft);
  expectErrorMentions([] { parsePenetrationResponse("push"); }, "soft, project, revert");
  expectErrorMentions([] { parseFrictionModel("sticky"); }, "sticky");
}

TEST(World, MassAndDensity) {
  World world;
  BodyDef def = test::boxBody(Vec3(0.0f), Vec3(0.5f), 2.5f);
  EXPECT_FLOAT_EQ(world.mass(world.createBody(def)), 2.5f);
  def.mass.reset();
  def.density = 1000.0f;
  EXPECT_NEAR(world.mass(world.createBody(def)), 1000.0f, 1e-2f);
  EXPECT_EQ(world.mass(world.createBody(test::groundPlane())), 0.0f);
}

TEST(World, StaticStaticAndKinematicStaticPairsAreNeverTested) {
  World world;
  BodyDef wall = test::boxBody(Vec3(0.0f), Vec3(1.0f), 1.0f);
  wall.type = BodyType::Static;
  world.createBody(wall);
  wall.position = Vec3(0.5f, 0.0f, 0.0f);
  world.createBody(wall);  // overlaps the first
  BodyDef mover = wall;
  mover.type = BodyType::Kinematic;
  mover.position = Vec3(0.0f, 0.5f, 0.0f);  // overlaps both
  mover.linearVelocity = Vec3(0.1f, 0.0f, 0.0f);
  world.createBody(mover);
  world.createBody(test::sphereBody(Vec3(50.0f, 0.0f, 0.0f), 0.5f, 1.0f));
  world.step(kDt);
  EXPECT_EQ(world.lastStats().potentialPairs, 6u);
  EXPECT_EQ(world.lastStats().keptPairs, 2u);  // kinematic vs each static; static-static excluded
  EXPECT_EQ(world.lastStats().narrowPhaseTests, 0u);
  EXPECT_EQ(world.lastStats().contactPairs, 0u);
}

TEST(World, CountersFollowTheFunnel) {
  World world;
  world.createBody(test::groundPlane());
  world.createBody(test::sphereBody(Vec3(0.0f, 0.5f, 0.0f), 0.5f, 1.0f));
  world.createBody(test::sphereBody(Vec3(10.0f, 0.5f, 0.0f), 0.5f, 1.0f));
  world.step(kDt);
  EXPECT_EQ(world.lastStats().potentialPairs, 3u);
  EXPECT_EQ(world.lastStats().narrowPhaseTests, 2u);  // each sphere against the plane
  EXPECT_EQ(world.lastStats().contactPairs, 2u);
  EXPECT_EQ(world.touchingContactCount(), 2u);
  world.step(kDt);
  EXPECT_EQ(world.totalStats().narrowPhaseTests, 4u);
  EXPECT_EQ(world.totalStats().potentialPairs, 6u);
  EXPECT_EQ(world.totalStats().proxies, 3u);  // a count, not a sum
}

// Totals add every counter of each step and keep the latest proxy count.
TEST(World, StepStatsTotalsSumTheCountersAndKeepTheProxyCount) {
  BroadPhaseStats broadPhase;
  broadPhase.proxies = 4;
  broadPhase.potentialPairs = 6;
  broadPhase.keptPairs = 3;
  broadPhase.boxTests = 5;
  StepStats first(broadPhase);
  first.narrowPhaseTests = 2;
  first.reusedManifolds = 1;
  first.contactPairs = 1;
  StepStats second = first;
  second.proxies = 5;
  StepStats total;
  total += first;
  total += second;
  EXPECT_EQ(total.proxies, 5u);
  EXPECT_EQ(total.potentialPairs, 12u);
  EXPECT_EQ(total.keptPairs, 6u);
  EXPECT_EQ(total.boxTests, 10u);
  EXPECT_EQ(total.narrowPhaseTests, 4u);
  EXPECT_EQ(total.reusedManifolds, 2u);
  EXPECT_EQ(total.contactPairs, 2u);
  EXPECT_DOUBLE_EQ(total.keptFraction(), 0.5);
}

// The stage timings of a step lie within the wall time around world.step(), every stage of a
// contact-heavy step takes part, and the totals are the sum of the steps'.
TEST(World, StageTimesCoverTheStepAndAddUp) {
  World world;
  world.createBody(test::groundPlane());
  for (int i = 0; i < 64; ++i)
    world.createBody(
        test::boxBody(Vec3(float(i % 8) * 1.1f, 0.5f + float(i / 8) * 1.05f, 0.0f), Vec3(0.5f), 1.0f));
  double sumOfSteps = 0.0;
  for (int step = 0; step < 20; ++step) {
    const auto before = std::chrono::steady_clock::now();
    world.step(kDt);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - before).count();
    const StageTimes& time = world.lastStats().time;
    for (double stage :
         {time.broadPhase, time.narrowPhase, time.solve, time.continuous, time.events, time.islands})
      EXPECT_GE(stage, 0.0);
    EXPECT_GT(time.narrowPhase, 0.0);
    EXPECT_GT(time.solve, 0.0);
    EXPECT_LE(time.total(), wall);
    sumOfSteps += time.total();
  }
  EXPECT_NEAR(world.totalStats().time.total(), sumOfSteps, 1e-9);
}

TEST(World, ContactEventsBeginOnceWithTheImpactSpeed) {
  World world;
  const BodyId ground = world.createBody(test::groundPlane());
  BodyDef ballDef = test::sphereBody(Vec3(0.0f, 1.5f, 0.0f), 0.5f, 1.0f);  // falls 1 m
  const BodyId ball = world.createBody(ballDef);
  int begins = 0;
  ContactEvent first;
  for (int i = 0; i < 120; ++i) {
    world.step(kDt);
    for (const ContactEvent& e : world.contactEvents()) {
      EXPECT_EQ(e.type, ContactEvent::Type::Begin);
      if (begins++ == 0) first = e;
    }
  }
  ASSERT_EQ(begins, 1);
  const bool groundFirst = first.a == ground;
  EXPECT_TRUE(groundFirst || first.a == ball);
  EXPECT_NEAR(std::abs(first.normal.y), 1.0f, 1e-5f);
  // The begin event comes from the speculative manifold of the step that stops the ball: the
  // point lies in the gap, which is less than one step of travel (v dt) wide.
  const float impactSpeed = std::sqrt(2.0f * 9.81f);  // free fall from 1 m
  EXPECT_NEAR(first.point.x, 0.0f, 1e-5f);
  EXPECT_GE(first.point.y, 0.0f);
  EXPECT_LE(first.point.y, 0.5f * impactSpeed * kDt);
  // The speed is measured before that step, when the gap was at most the speculative margin
  // (0.02 m + v dt): up to dt + 0.02 / v before the impact, i.e. g (dt + 0.02 / v) slower.
  EXPECT_NEAR(first.speed, impactSpeed, 9.81f * (kDt + 0.02f / impactSpeed));
  EXPECT_LE(first.speed, impactSpeed);
  // The impulse stops the ball: about m v.
  EXPECT_GT(first.impulse, 0.8f * std::sqrt(2.0f * 9.81f));
}

TEST(World, BouncingBallEndsItsContact) {
  World world;
  world.createBody(test::groundPlane());
  BodyDef ballDef = test::sphereBody(Vec3(0.0f, 1.5f, 0.0f), 0.5f, 1.0f);
  ballDef.bounciness = 0.8f;
  world.createBody(ballDef);
  int begins = 0, ends = 0;
  for (int i = 0; i < 60; ++i) {
    world.step(kDt);
    for (const ContactEvent& e : world.contactEvents())
      (e.type == ContactEvent::Type::Begin ? begins : ends)++;
  }
  EXPECT_GE(begins, 1);
  EXPECT_GE(ends, 1);
}

TEST(World, SensorReportsOverlapAndTakesNoResponse) {
  World world(test::zeroGravityWorld());
  BodyDef sensorDef = test::boxBody(Vec3(0.0f), Vec3(1.0f), 1.0f);
  sensorDef.type = BodyType::Static;
  sensorDef.sensor = true;
  const BodyId sensor = world.createBody(sensorDef);
  const BodyId ball =
      world.createBody(test::sphereBody(Vec3(-3.0f, 0.0f, 0.0f), 0.25f, 1.0f, Vec3(3.0f, 0.0f, 0.0f)));
  int begins = 0, ends = 0;
  for (int i = 0; i < 120; ++i) {
    world.step(kDt);
    for (const SensorEvent& e : world.sensorEvents()) {
      EXPECT_EQ(e.sensor, sensor);
      EXPECT_EQ(e.visitor, ball);
      (e.type == SensorEvent::Type::Begin ? begins : ends)++;
    }
  }
  EXPECT_EQ(begins, 1);
  EXPECT_EQ(ends, 1);
  EXPECT_EQ(world.linearVelocity(ball), Vec3(3.0f, 0.0f, 0.0f));
  EXPECT_TRUE(world.contactEvents().empty());
}

// A ball at 60 m/s moves 1 m a step and crosses a 4 cm sensor between two steps: never inside it at
// a step's start or end, it is still reported, begin and end in the same step (the step that carries
// it across), and only once. A kinematic sensor passing over a resting ball is the same.
TEST(World, BodyCrossingAThinSensorWithinOneStepIsReported) {
  World world(test::zeroGravityWorld());
  BodyDef sensorDef = test::boxBody(Vec3(0.0f), Vec3(0.02f, 1.0f, 1.0f), 1.0f);
  sensorDef.type = BodyType::Static;
  sensorDef.sensor = true;
  const BodyId sensor = world.createBody(sensorDef);
  // Starts 0.23 m short of the slab's near face; after step 1 it is 0.23 m past the far face.
  const BodyId ball =
      world.createBody(test::sphereBody(Vec3(-0.5f, 0.0f, 0.0f), 0.25f, 1.0f, Vec3(60.0f, 0.0f, 0.0f)));
  std::vector<std::pair<int, SensorEvent>> seen;
  for (int i = 1; i <= 10; ++i) {
    world.step(kDt);
    for (const SensorEvent& e : world.sensorEvents()) seen.emplace_back(i, e);
  }
  ASSERT_EQ(seen.size(), 2u);
  EXPECT_EQ(seen[0].first, 1);
  EXPECT_EQ(seen[1].first, 1);
  EXPECT_EQ(seen[0].second.type, SensorEvent::Type::Begin);
  EXPECT_EQ(seen[1].second.type, SensorEvent::Type::End);
  for (const auto& [step, e] : seen) {
    EXPECT_EQ(e.sensor, sensor);
    EXPECT_EQ(e.visitor, ball);
  }
  EXPECT_EQ(world.linearVelocity(ball), Vec3(60.0f, 0.0f, 0.0f));  // no response

  // The sensor moving: a kinematic slab at 60 m/s sweeping over a resting ball.
  World moving(test::zeroGravityWorld());
  BodyDef sweeper = sensorDef;
  sweeper.type = BodyType::Kinematic;
  sweeper.position = Vec3(-0.5f, 0.0f, 0.0f);
  sweeper.linearVelocity = Vec3(60.0f, 0.0f, 0.0f);
  moving.createBody(sweeper);
  moving.createBody(test::sphereBody(Vec3(0.0f), 0.25f, 1.0f));
  moving.step(kDt);
  ASSERT_EQ(moving.sensorEvents().size(), 2u);
  EXPECT_EQ(moving.sensorEvents()[0].type, SensorEvent::Type::Begin);
  EXPECT_EQ(moving.sensorEvents()[1].type, SensorEvent::Type::End);
}

// A ball that ends a step inside a sensor it entered during that step begins there once, from the
// next step's test, and is not reported as crossing.
TEST(World, BodyEndingInsideASensorBeginsOnce) {
  World world(test::zeroGravityWorld());
  BodyDef sensorDef = test::boxBody(Vec3(0.0f), Vec3(2.0f, 1.0f, 1.0f), 1.0f);
  sensorDef.type = BodyType::Static;
  sensorDef.sensor = true;
  world.createBody(sensorDef);
  world.createBody(test::sphereBody(Vec3(-2.5f, 0.0f, 0.0f), 0.25f, 1.0f, Vec3(30.0f, 0.0f, 0.0f)));
  int begins = 0, ends = 0;
  for (int i = 0; i < 20; ++i) {
    world.step(kDt);
    for (const SensorEvent& e : world.sensorEvents()) (e.type == SensorEvent::Type::Begin ? begins : ends)++;
  }
  EXPECT_EQ(begins, 1);
  EXPECT_EQ(ends, 1);
}

TEST(World, PreSolveCallbackMakesAOneWayPlatform) {
  World world;
  BodyDef platform = test::boxBody(Vec3(0.0f, 2.0f, 0.0f), Vec3(2.0f, 0.1f, 2.0f), 1.0f);
  platform.type = BodyType::Static;
  const BodyId platformId = world.createBody(platform);
  // Launched upwards from below: rises to about 0.5 + 8^2 / (2 g) = 3.7 m, then falls back.
  const BodyId ball =
      world.createBody(test::sphereBody(Vec3(0.0f, 0.5f, 0.0f), 0.25f, 1.0f, Vec3(0.0f, 8.0f, 0.0f)));
  world.setPreSolveCallback([&](BodyId a, BodyId b, const Manifold& m) {
    // Solid only from above: the normal from the platform towards the ball points up.
    const Vec3 up = a == platformId ? m.normal : -m.normal;
    (void)b;
    return up.y > 0.5f && world.transform(ball).position.y > 2.1f;
  });
  for (int i = 0; i < 180; ++i) world.step(kDt);
  EXPECT_NEAR(world.transform(ball).position.y, 2.1f + 0.25f, 0.01f);
  EXPECT_LT(glm::length(world.linearVelocity(ball)), 0.05f);
}

// With persistEvents, a box set down on the ground reports Begin once, Persist every following step
// it stays (lecture: the prolonged contact), and End when it is lifted off; without, no Persist.
TEST(World, PersistEventsFollowAProlongedContact) {
  for (const bool persist : {true, false}) {
    WorldDef def;
    def.persistEvents = persist;
    World world(def);
    world.createBody(test::groundBox());
    const BodyId box = world.createBody(test::boxBody(Vec3(0.0f, 0.5f, 0.0f), Vec3(0.5f), 1.0f));
    int begins = 0, persists = 0, ends = 0;
    const auto count = [&] {
      for (const ContactEvent& e : world.contactEvents()) {
        begins += e.type == ContactEvent::Type::Begin;
        ends += e.type == ContactEvent::Type::End;
        if (e.type != ContactEvent::Type::Persist) continue;
        ++persists;
        EXPECT_NEAR(e.impulse, 9.81f * kDt, 0.02f * 9.81f * kDt);  // the box's weight, over one step
        EXPECT_NEAR(e.normal.y, 1.0f, 1e-4f);
      }
    };
    for (int i = 0; i < 30; ++i) {
      world.step(kDt);
      count();
    }
    world.setTransform(box, Vec3(0.0f, 5.0f, 0.0f), Quat(1.0f, 0.0f, 0.0f, 0.0f));
    world.step(kDt);
    count();
    EXPECT_EQ(begins, 1);
    EXPECT_EQ(persists, persist ? 29 : 0);
    EXPECT_EQ(ends, 1);
  }
}

// The pre-solve callback may change a contact: a conveyor belt is a static box whose contacts get a
// surface velocity. A box set on it accelerates at mu g (Coulomb) until it rides at the belt's speed:
// after 1 s, v = 2 m/s and x = v^2 / (2 mu g) + v (1 - v / (mu g)).
TEST(World, PreSolveSurfaceVelocityMakesAConveyorBelt) {
  World world;
  BodyDef belt = test::groundBox();
  belt.friction = 0.5f;
  const BodyId beltId = world.createBody(belt);
  BodyDef box = test::boxBody(Vec3(0.0f, 0.5f, 0.0f), Vec3(0.5f), 1.0f);
  box.friction = 0.5f;
  const BodyId boxId = world.createBody(box);
  const Vec3 beltVelocity(2.0f, 0.0f, 0.0f);
  world.setPreSolveCallback([&](BodyId a, BodyId b, const Manifold&, ContactSettings& settings) {
    (void)b;
    // B's surface relative to A's: the box moves with the belt, the belt against the box.
    settings.surfaceVelocity = a == beltId ? beltVelocity : -beltVelocity;
    return true;
  });
  for (int i = 0; i < 60; ++i) world.step(kDt);
  const float muG = 0.5f * 9.81f;
  const float expectedX = 4.0f / (2.0f * muG) + 2.0f * (1.0f - 2.0f / muG);
  EXPECT_NEAR(world.linearVelocity(boxId).x, 2.0f, 0.02f);
  EXPECT_NEAR(world.transform(boxId).position.x, expectedX, 0.03f * expectedX);
  EXPECT_NEAR(world.transform(boxId).position.y, 0.5f, 0.01f);
}

// ... and its friction and bounciness: a ball dropped on a floor whose callback makes the contact
// perfectly bouncy comes back up to its height (within the soft contact's loss), and the same ball
// with the world's combined bounciness of 0 stays down.
TEST(World, PreSolveChangesBounciness) {
  const auto rebound = [](bool bouncy) {
    World world;
    world.createBody(test::groundPlane());
    const BodyId ball = world.createBody(test::sphereBody(Vec3(0.0f, 2.0f, 0.0f), 0.25f, 1.0f));
    if (bouncy) {
      world.setPreSolveCallback([](BodyId, BodyId, const Manifold&, ContactSettings& settings) {
        settings.bounciness = 1.0f;
        return true;
      });
    }
    float highest = 0.0f;
    bool landed = false;
    for (int i = 0; i < 90; ++i) {
      world.step(kDt);
      const float y = world.transform(ball).position.y;
      if (world.linearVelocity(ball).y > 0.0f) landed = true;
      if (landed) highest = std::max(highest, y);
    }
    return highest;
  };
  EXPECT_GT(rebound(true), 1.9f);
  EXPECT_LT(rebound(false), 0.3f);
}

// Bad settings from the callback are not applied, the step still completes, then step() says so.
TEST(World, PreSolveSettingsOutOfRangeAreRefused) {
  World world;
  world.createBody(test::groundPlane());
  const BodyId ball = world.createBody(test::sphereBody(Vec3(0.0f, 0.24f, 0.0f), 0.25f, 1.0f));
  world.setPreSolveCallback([](BodyId, BodyId, const Manifold&, ContactSettings& settings) {
    settings.friction = std::numeric_limits<float>::quiet_NaN();
    return true;
  });
  if (const std::optional<std::string> error = ::collide::test::errorOf([&] { world.step(kDt); }); !error) {
    ADD_FAILURE() << "a NaN friction was accepted";
  } else {
    EXPECT_NE((*error).find("pre-solve callback"), std::string::npos) << *error;
  }
  // The step happened with the contact's own friction: the ball was pushed out of the floor, finite.
  EXPECT_TRUE(isFinite(world.transform(ball).position));
  EXPECT_GT(world.transform(ball).position.y, 0.24f);
  world.setPreSolveCallback(PreSolveFilter(nullptr));
  world.step(kDt);  // the world goes on
  EXPECT_TRUE(isFinite(world.linearVelocity(ball)));
}

TEST(World, SameSceneTwiceGivesBitIdenticalStates) {
  const auto run = [](std::vector<float>& out) {
    World world;
    world.createBody(test::groundPlane());
    std::vector<BodyId> ids;
    for (int i = 0; i < 12; ++i) {
      BodyDef def = i % 2 ? test::boxBody(Vec3(0.3f * i, 1.0f + 0.9f * i, 0.1f * i), Vec3(0.3f), 1.0f)
                          : test::sphereBody(Vec3(0.2f * i, 1.0f + 0.9f * i, -0.1f * i), 0.3f, 1.0f);
      def.angularVelocity = Vec3(0.1f * i, 0.2f, -0.3f);
      def.bounciness = 0.3f;
      ids.push_back(world.createBody(def));
    }
    for (int s = 0; s < 120; ++s) world.step(kDt);
    for (BodyId id : ids) {
      const Transform t = world.transform(id);
      const Vec3 v = world.linearVelocity(id);
      const Vec3 w = world.angularVelocity(id);
      out.insert(out.end(), {t.position.x, t.position.y, t.position.z, t.rotation.x, t.rotation.y,
                             t.rotation.z, t.rotation.w, v.x, v.y, v.z, w.x, w.y, w.z});
    }
  };
  std::vector<float> first, second;
  run(first);
  run(second);
  ASSERT_EQ(first.size(), second.size());
  EXPECT_EQ(std::memcmp(first.data(), second.data(), first.size() * sizeof(float)), 0);
}

// A sphere created half inside a static box: Soft pushes it out (capped at the push-out speed);
// Revert puts it back where it was created, its last valid pose, and removes its velocity into the
// box; Project moves it out along the normal at once, to the linear slop.
TEST(World, PenetrationResponses) {
  for (PenetrationResponse response :
       {PenetrationResponse::Soft, PenetrationResponse::Project, PenetrationResponse::Revert}) {
    SCOPED_TRACE(std::string(toString(response)));
    WorldDef def = test::zeroGravityWorld();
    def.penetrationResponse = response;
    World world(def);
    BodyDef block = test::boxBody(Vec3(0.0f, -1.0f, 0.0f), Vec3(1.0f), 1.0f);
    block.type = BodyType::Static;
    world.createBody(block);
    const BodyId ball =
        world.createBody(test::sphereBody(Vec3(0.0f, 0.2f, 0.0f), 0.5f, 1.0f, Vec3(1.0f, -1.0f, 0.0f)));
    world.step(kDt);
    const Vec3 p = world.transform(ball).position;
    const Vec3 v = world.linearVelocity(ball);
    if (response == PenetrationResponse::Soft) {
      EXPECT_GT(p.y, 0.2f);  // pushed up, at most 3 m/s x dt = 5 cm of the 30 cm
      EXPECT_LT(p.y, 0.2f + def.contact.pushOutSpeed * kDt + 1e-4f);
    } else if (response == PenetrationResponse::Project) {
      // Out of the box within the step, whatever the depth was: no deeper than the slop (where the
      // projection leaves it; the soft contact takes the rest), and not pushed beyond touching.
      EXPECT_GE(p.y, 0.5f - def.contact.linearSlop - 1e-5f);
      EXPECT_LE(p.y, 0.5f + 1e-4f);
    } else {
      EXPECT_EQ(p, Vec3(0.0f, 0.2f, 0.0f));
      EXPECT_GE(v.y, 0.0f);
    }
  }
}

// The lecture's projection between two movable bodies (slide 11): both move along the normal, the
// displacements inversely proportional to the masses, so that the mass-weighted squared
// displacement is least and the centre of mass stays where it was.
TEST(World, ProjectionSplitsTheCorrectionByMass) {
  WorldDef def = test::zeroGravityWorld();
  def.penetrationResponse = PenetrationResponse::Project;
  World world(def);
  const BodyId light = world.createBody(test::sphereBody(Vec3(-0.4f, 0.0f, 0.0f), 0.5f, 1.0f));
  const BodyId heavy = world.createBody(test::sphereBody(Vec3(0.4f, 0.0f, 0.0f), 0.5f, 3.0f));
  const Vec3 center0 = (1.0f * world.centerOfMass(light) + 3.0f * world.centerOfMass(heavy)) / 4.0f;
  world.step(kDt);  // 0.2 m deep: apart to the slop within the step
  const Vec3 a = world.centerOfMass(light), b = world.centerOfMass(heavy);
  EXPECT_GE(glm::distance(a, b), 1.0f - def.contact.linearSlop - 1e-5f);
  EXPECT_LE(glm::distance(a, b), 1.0f + 1e-4f);
  EXPECT_LE(glm::length((1.0f * a + 3.0f * b) / 4.0f - center0), 1e-5f);
  EXPECT_NEAR((-0.4f - a.x) / (b.x - 0.4f), 3.0f, 1e-3f);  // the light one moved three times as far
  EXPECT_NEAR(a.y, 0.0f, 1e-6f);
  EXPECT_NEAR(b.z, 0.0f, 1e-6f);
}

}  // namespace
}  // namespace collide
