// What fuzz/world_fuzzer found, each as the smallest story that showed it. The inputs are finite
// but extreme (a 3e38 m sphere, a body at 1e20 m/s, a spin of 1e30 rad/s): a game reaches them by
// a unit error or an uninitialised value, and the world must then go on stepping, refuse the input
// with collide::Error, or freeze the body and report it (docs/reliability.md, "The world guards
// itself"). Each story checks that the step neither throws half-way, hangs, leaves the world unable
// to step, nor leaves a NaN in a state or an event.
#include "support/collide_error.h"
#include "support/test_assertions.h"
#include "support/world_helpers.h"

#include <collide/world.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace collide {
namespace {

using ::testing::HasSubstr;

using test::kDt;
using test::kHuge;

// Every live body's state and every event of the last step is finite; says which is not.
::testing::AssertionResult everythingFinite(const World& world, const std::vector<BodyId>& bodies) {
  for (const BodyId id : bodies) {
    if (!world.isValid(id)) continue;
    const Transform t = world.transform(id);
    const Quat& q = t.rotation;
    if (!test::isFinite(t.position) || !std::isfinite(q.w) || !std::isfinite(q.x) || !std::isfinite(q.y) ||
        !std::isfinite(q.z) || !test::isFinite(world.linearVelocity(id)) ||
        !test::isFinite(world.angularVelocity(id))) {
      return ::testing::AssertionFailure() << "body index " << id.index << " has a non-finite state";
    }
  }
  for (const ContactEvent& e : world.contactEvents()) {
    if (!test::isFinite(e.point) || !test::isFinite(e.normal) || !std::isfinite(e.impulse) ||
        !std::isfinite(e.speed)) {
      return ::testing::AssertionFailure() << "a contact event between bodies " << e.a.index << " and "
                                           << e.b.index << " has non-finite values";
    }
  }
  return ::testing::AssertionSuccess();
}

BodyDef sphere(BodyType type, float radius, const Vec3& position) {
  BodyDef def;
  def.type = type;
  def.shape = Shape(Sphere{radius});
  def.position = position;
  return def;
}

bool reported(const World& world, BodyId id) {
  for (const FaultEvent& f : world.faultEvents()) {
    if (f.body == id) return true;
  }
  return false;
}

// A contact with a 3e38 m sphere overflows in the solve and gives NaN impulses. The guard froze
// the moving body, but a NaN impulse still reaches a zero inverse mass (0 * NaN is NaN): the static
// body's velocity and the frozen body's became NaN after their check, and the NaN impulse stayed in
// the contact for the event and for the next step's warm start.
TEST(WorldFuzzFindings, NanImpulseLeavesNoNanInStaticFrozenBodiesOrEvents) {
  World world;
  std::vector<BodyId> bodies;
  bodies.push_back(world.createBody(sphere(BodyType::Kinematic, kHuge, Vec3(0.0f))));
  bodies.push_back(world.createBody(sphere(BodyType::Static, 0.01f, Vec3(-6.0f))));
  bodies.push_back(world.createBody(sphere(BodyType::Dynamic, 1.95f, Vec3(-6.0f))));
  const Vec3 staticPosition = world.transform(bodies[1]).position;
  for (int step = 0; step < 10; ++step) {
    world.step(kDt);
    ASSERT_TRUE(everythingFinite(world, bodies)) << "step " << step;
  }
  EXPECT_EQ(world.linearVelocity(bodies[1]), Vec3(0.0f));
  EXPECT_EQ(world.transform(bodies[1]).position, staticPosition);
}

// |v| of a finite velocity overflows beyond 1.8e19 m/s, and the speculative margin with it: the
// narrow phase refused the infinite margin, so step() threw collide::Error half-way through.
TEST(WorldFuzzFindings, BodyAt1e20MetresPerSecondDoesNotStopTheStep) {
  World world;
  std::vector<BodyId> bodies;
  bodies.push_back(world.createBody(test::groundBox()));
  BodyDef resting = test::boxBody(Vec3(10.0f, 0.5f, 0.0f), Vec3(0.5f), 1.0f);
  bodies.push_back(world.createBody(resting));
  BodyDef fast = sphere(BodyType::Dynamic, 0.5f, Vec3(0.0f, 0.6f, 0.0f));
  fast.linearVelocity = Vec3(0.0f, -1e20f, 0.0f);
  bodies.push_back(world.createBody(fast));
  for (int step = 0; step < 10; ++step) {
    ASSERT_NO_COLLIDE_ERROR(world.step(kDt)) << "step " << step;
    ASSERT_TRUE(everythingFinite(world, bodies)) << "step " << step;
    EXPECT_FALSE(reported(world, bodies[1])) << "the resting box is not involved, step " << step;
  }
  EXPECT_NEAR(world.transform(bodies[1]).position.y, 0.5f, 0.01f);
}

// createBody computed the mass (infinite for a 3e38 m ellipsoid), then the broad phase refused the
// body's infinite box: the Error left the body allocated without a proxy, and every later step
// threw "null proxy id". Now the mass and the box are checked, and any refusal frees the slot.
TEST(WorldFuzzFindings, ShapeTooLargeOrTooSmallIsRefusedAndTheWorldStillSteps) {
  World world;
  BodyDef huge;
  huge.shape = Shape(Ellipsoid{Vec3(kHuge, 2.0f, 0.01f)});
  EXPECT_THAT([&] { world.createBody(huge); },
              ::collide::test::ReportsError(HasSubstr("mass properties not representable")));
  // A 1e-20 m sphere's mass underflows to 0 (an infinite inverse mass).
  EXPECT_THAT([&] { world.createBody(sphere(BodyType::Dynamic, 1e-20f, Vec3(0.0f))); },
              ::collide::test::ReportsError(HasSubstr("mass properties not representable")));
  // A static shape whose box overflows where it is placed.
  EXPECT_THAT([&] { world.createBody(sphere(BodyType::Static, kHuge, Vec3(kHuge, 0.0f, 0.0f))); },
              ::collide::test::ReportsError(HasSubstr("bounds are not finite")));
  EXPECT_EQ(world.bodyCount(), 0u);
  const BodyId ball = world.createBody(sphere(BodyType::Dynamic, 0.5f, Vec3(0.0f, 2.0f, 0.0f)));
  EXPECT_EQ(ball.index, 0u) << "the refused bodies' slots are free again";
  ASSERT_NO_COLLIDE_ERROR(world.step(kDt));
  EXPECT_LT(world.transform(ball).position.y, 2.0f);
}

// A given mass can be too large or too small for a shape of sane size: 3e38 kg on a 1 m sphere
// overflows the inertia matrix's inverse, 1e-30 kg underflows it. The message blames the mass, not
// the shape; the same shape by density, or with a sane mass, is fine.
TEST(WorldFuzzFindings, GivenMassTheShapeCannotCarryNamesTheMass) {
  World world;
  for (const float mass : {3e38f, 1e-30f}) {
    BodyDef def = sphere(BodyType::Dynamic, 1.0f, Vec3(0.0f));
    def.name = "ball";
    def.mass = mass;
    EXPECT_THAT(
        [&] { world.createBody(def); },
        ::collide::test::ReportsError(HasSubstr("body \"ball\": mass: mass properties not representable in "
                                                "float with mass")))
        << mass;
  }
  EXPECT_EQ(world.bodyCount(), 0u);
  BodyDef def = sphere(BodyType::Dynamic, 1.0f, Vec3(0.0f));
  def.mass = 2.0f;
  EXPECT_FLOAT_EQ(world.mass(world.createBody(def)), 2.0f);
}

// A body created with a spin whose length overflows: the proxy box grew by 0 * infinity (NaN) at
// creation, and by infinity in the step, and the broad phase refused both.
TEST(WorldFuzzFindings, HugeOrFastSpinningBodyKeepsTheBroadPhaseWorking) {
  World world;
  std::vector<BodyId> bodies;
  BodyDef spinningGiant = sphere(BodyType::Kinematic, kHuge, Vec3(0.0f));
  spinningGiant.angularVelocity = Vec3(28.0f, -30.0f, -30.0f);
  bodies.push_back(world.createBody(spinningGiant));
  BodyDef overflowingSpin;
  overflowingSpin.type = BodyType::Kinematic;
  overflowingSpin.shape = Shape(Box{Vec3(1.0f)});
  overflowingSpin.position = Vec3(5.0f, 0.0f, 0.0f);
  overflowingSpin.angularVelocity = Vec3(kHuge, 0.0f, 0.0f);
  ASSERT_NO_COLLIDE_ERROR(bodies.push_back(world.createBody(overflowingSpin)));
  bodies.push_back(world.createBody(sphere(BodyType::Dynamic, 0.1f, Vec3(0.0f, 1.2f, 0.0f))));
  for (int step = 0; step < 5; ++step) {
    ASSERT_NO_COLLIDE_ERROR(world.step(kDt)) << "step " << step;
    ASSERT_TRUE(everythingFinite(world, bodies)) << "step " << step;
  }
}

// A spin of 1e30 rad/s: its length overflows, and with the solver before the SIMD one it
// integrated into a quaternion that normalises to zero, finite, so the guard let it through and
// the next step's shape queries refused the body's transform. Whatever the solver makes of such a
// spin, the step goes on, the rotation stays a unit quaternion, and a body reported for it is
// reported for its rotation or its spin.
TEST(WorldFuzzFindings, OverflowingSpinLeavesAUnitRotation) {
  for (const BodyType type : {BodyType::Kinematic, BodyType::Dynamic}) {
    World world;
    BodyDef spinning;
    spinning.type = type;
    spinning.shape = Shape(Cylinder{0.84f, 0.01f});
    spinning.angularVelocity = Vec3(-19.5f, -1e30f, -19.9f);
    const BodyId id = world.createBody(spinning);
    for (int step = 0; step < 3; ++step) {
      ASSERT_NO_COLLIDE_ERROR(world.step(kDt)) << toString(type) << ", step " << step;
      ASSERT_TRUE(everythingFinite(world, {id})) << toString(type) << ", step " << step;
      EXPECT_NEAR(glm::length(world.transform(id).rotation), 1.0f, 1e-5f)
          << toString(type) << ", step " << step;
      for (const FaultEvent& f : world.faultEvents()) {
        EXPECT_TRUE(f.fields & (FaultEvent::kRotation | FaultEvent::kAngularVelocity)) << toString(type);
      }
    }
  }
}

// With sleeping on, a body frozen by the guard looks asleep; an awake body touching it "woke" it
// (a no-op for a frozen body) and repeated the wake pass, forever: step() never returned.
TEST(WorldFuzzFindings, FrozenBodyTouchedByAnAwakeOneDoesNotHangTheStep) {
  WorldDef def;
  def.sleeping = true;
  World world(def);
  world.createBody(test::groundBox());
  const BodyId frozen = world.createBody(test::boxBody(Vec3(0.0f, 0.5f, 0.0f), Vec3(0.5f), 1.0f));
  for (int step = 0; step < 10; ++step) world.step(kDt);
  world.applyForce(frozen, Vec3(kHuge, 0.0f, 0.0f), world.centerOfMass(frozen));
  world.applyForce(frozen, Vec3(kHuge, 0.0f, 0.0f), world.centerOfMass(frozen));
  world.step(kDt);
  ASSERT_TRUE(reported(world, frozen));
  const BodyId falling = world.createBody(test::boxBody(Vec3(0.0f, 1.6f, 0.0f), Vec3(0.5f), 1.0f));
  for (int step = 0; step < 60; ++step) world.step(kDt);
  // It landed on the frozen box, which held it.
  EXPECT_NEAR(world.transform(falling).position.y, 1.5f, 0.01f);
  EXPECT_NEAR(world.transform(frozen).position.y, 0.5f, 0.01f);
}

// The response stages after the solve validate what they are given (they are public functions
// too), and threw from inside the step when the solve had made a velocity NaN. The damping friction
// model on a prolonged contact, with a static sphere of 1e15 m in the pile (the fuzzer's story):
TEST(WorldFuzzFindings, DampingFrictionDoesNotStopTheStepAfterAFault) {
  WorldDef def;
  def.substeps = 1;
  def.frictionModel = FrictionModel::Damping;
  def.bouncinessCombine = CombineRule::Multiply;
  def.frictionCombine = CombineRule::Max;
  World world(def);
  std::vector<BodyId> bodies;
  BodyDef ball = sphere(BodyType::Dynamic, 1.99f, Vec3(-6.0f, -6.0f, -5.97f));
  ball.linearVelocity = Vec3(8.1f, 8.1f, -19.8f);
  ball.angularVelocity = Vec3(-6.7f, -20.0f, -6.7f);
  ball.bounciness = 0.33f;
  ball.friction = 0.0013f;
  bodies.push_back(world.createBody(ball));
  BodyDef giant = sphere(BodyType::Static, 1e15f, Vec3(-3.66f, -5.72f, -5.97f));
  giant.bounciness = 0.33f;
  giant.friction = 0.33f;
  bodies.push_back(world.createBody(giant));
  BodyDef moving;
  moving.type = BodyType::Kinematic;
  moving.shape = Shape(Cylinder{1.34f, 0.67f});
  moving.position = Vec3(-5.98f, -6.0f, -5.81f);
  moving.rotation = glm::normalize(Quat(-0.577f, -0.577f, -0.009f, -0.577f));
  moving.linearVelocity = Vec3(5.16f, -5.62f, 0.0f);
  moving.friction = 0.0f;
  bodies.push_back(world.createBody(moving));
  for (int step = 0; step < 10; ++step) {
    ASSERT_NO_COLLIDE_ERROR(world.step(kDt)) << "step " << step;
    ASSERT_TRUE(everythingFinite(world, bodies)) << "step " << step;
  }
}

// ... and the interpolated impact model, reached once the broad phase took the overflowing spin.
TEST(WorldFuzzFindings, InterpolatedImpactDoesNotStopTheStepAfterAFault) {
  WorldDef def;
  def.impactModel = ImpactModel::Interpolated;
  World world(def);
  std::vector<BodyId> bodies;
  BodyDef spinning;
  spinning.type = BodyType::Kinematic;
  spinning.shape = Shape(Box{Vec3(1.0f)});
  spinning.angularVelocity = Vec3(kHuge, 0.0f, 0.0f);
  bodies.push_back(world.createBody(spinning));
  bodies.push_back(world.createBody(sphere(BodyType::Dynamic, 0.1f, Vec3(0.0f, 1.05f, 0.0f))));
  for (int step = 0; step < 5; ++step) {
    ASSERT_NO_COLLIDE_ERROR(world.step(kDt)) << "step " << step;
    ASSERT_TRUE(everythingFinite(world, bodies)) << "step " << step;
  }
}

// A part placed 3e38 m from its static body's centre, turned: its offset in the part's frame
// overflows, so continuous collision has no sweep for it. A fast ball still stops on the body's
// floor part (its own sweep is fine), and the far part is passed by rather than refused mid-step.
TEST(WorldFuzzFindings, APartNearFloatsLimitDoesNotStopContinuousCollision) {
  World world;
  BodyDef level;
  level.type = BodyType::Static;
  PartDef floor;
  floor.shape = Shape(Box{Vec3(5.0f, 0.5f, 5.0f)});
  floor.position = Vec3(0.0f, -0.5f, 0.0f);
  PartDef far;
  far.shape = Shape(Sphere{0.5f});
  far.position = Vec3(kHuge, 0.0f, kHuge);
  far.rotation = glm::angleAxis(0.7f, Vec3(0.0f, 1.0f, 0.0f));
  level.parts = {floor, far};
  const BodyId levelId = world.createBody(level);
  BodyDef ball = sphere(BodyType::Dynamic, 0.1f, Vec3(0.0f, 2.0f, 0.0f));
  ball.linearVelocity = Vec3(0.0f, -300.0f, 0.0f);  // 5 m a step: through the 1 m floor without CCD
  const BodyId ballId = world.createBody(ball);
  for (int step = 0; step < 60; ++step) {
    ASSERT_NO_COLLIDE_ERROR(world.step(kDt)) << "step " << step;
    ASSERT_TRUE(everythingFinite(world, {levelId, ballId})) << "step " << step;
  }
  EXPECT_GT(world.transform(ballId).position.y, 0.0f);
  EXPECT_LT(world.transform(ballId).position.y, 0.2f);
}

// A ray near the origin against shapes placed at 3e38 m, scaled down: in their frames the ray's
// origin is beyond float range. A plane through the ray's path still hits where the world frame
// says (a NaN distance before); a bounded shape out there is no hit, and the world's closest and
// all-hits casts agree.
TEST(WorldFuzzFindings, RayCastAgainstShapesPlacedNearFloatsLimit) {
  const Transform farAway{Vec3(kHuge, 0.0f, kHuge), Quat(1.0f, 0.0f, 0.0f, 0.0f), 0.25f};
  const Ray down{Vec3(0.0f, 5.0f, 0.0f), Vec3(0.0f, -1.0f, 0.0f), 1e30f};
  const std::optional<RayHit> ground = rayCast(Shape(Plane{Vec3(0.0f, 1.0f, 0.0f), 0.0f}), farAway, down);
  ASSERT_TRUE(ground.has_value());
  EXPECT_FLOAT_EQ(ground->distance, 5.0f);
  EXPECT_FLOAT_EQ(ground->normal.y, 1.0f);
  EXPECT_FLOAT_EQ(ground->point.y, 0.0f);
  EXPECT_FALSE(rayCast(Shape(Sphere{1.0f}), farAway, down).has_value());

  World world;
  BodyDef plane;
  plane.type = BodyType::Static;
  plane.shape = Shape(Plane{Vec3(0.0f, 1.0f, 0.0f), 0.0f});
  plane.position = farAway.position;
  plane.scale = farAway.scale;
  const BodyId planeId = world.createBody(plane);
  BodyDef ball = sphere(BodyType::Static, 1.0f, farAway.position);
  ball.scale = farAway.scale;
  world.createBody(ball);
  const std::optional<RayCastResult> closest = world.castRay(down);
  const std::vector<RayCastResult> all = world.castRayAll(down);
  ASSERT_TRUE(closest.has_value());
  EXPECT_EQ(closest->body, planeId);
  EXPECT_FLOAT_EQ(closest->distance, 5.0f);
  ASSERT_EQ(all.size(), 1u);
  EXPECT_EQ(all.front().body, planeId);
}

// A part 3e38 m from its body's origin, added at run time, and a body teleported to where its box
// overflows: both are refused as createBody refuses them, with nothing changed, and the world goes
// on stepping (before, addPart let the part in, and the step threw on its box or its sweep).
TEST(WorldFuzzFindings, APartOrAPoseBeyondFloatRangeIsRefusedAtRunTime) {
  World world;
  BodyDef carrier;
  carrier.type = BodyType::Kinematic;
  carrier.shape = Shape(Box{Vec3(1.0f, 0.1f, 1.0f)});
  carrier.angularVelocity = Vec3(0.0f, 1.0f, 0.0f);
  const BodyId id = world.createBody(carrier);
  PartDef far;
  far.shape = Shape(Sphere{0.5f});
  far.position = Vec3(kHuge, 0.0f, kHuge);
  EXPECT_COLLIDE_ERROR(world.addPart(id, far));
  EXPECT_EQ(world.partCount(id), 1u);

  const BodyId giant = world.createBody(sphere(BodyType::Static, 1e38f, Vec3(0.0f)));
  if (const std::optional<std::string> error = ::collide::test::errorOf(
          [&] { world.setTransform(giant, Vec3(kHuge, 0.0f, 0.0f), Quat(1.0f, 0.0f, 0.0f, 0.0f)); });
      !error) {
    ADD_FAILURE() << "a pose where the body's box overflows must be refused";
  } else {
    EXPECT_THAT(error->c_str(), HasSubstr("setTransform"));
    EXPECT_THAT(error->c_str(), HasSubstr("not finite"));
  }
  EXPECT_EQ(world.transform(giant).position, Vec3(0.0f));
  for (int step = 0; step < 10; ++step) {
    ASSERT_NO_COLLIDE_ERROR(world.step(kDt)) << "step " << step;
    ASSERT_TRUE(everythingFinite(world, {id, giant})) << "step " << step;
  }
}

// A linear slop of 3e38 m is finite and accepted; continuous collision grows a fast body's swept box
// by it, which overflows for a body at 3e38 m and was refused by the broad phase mid-step. The box
// is kept within the broad phase's range, as the proxies' boxes are.
TEST(WorldFuzzFindings, AnOverflowingSweptBoxDoesNotStopContinuousCollision) {
  WorldDef def;
  def.contact.linearSlop = kHuge;
  World world(def);
  BodyDef ball = sphere(BodyType::Dynamic, 0.5f, Vec3(0.0f, 0.0f, kHuge));
  ball.linearVelocity = Vec3(0.0f, -600.0f, 0.0f);  // fast: 10 m a step, the continuous pass sweeps it
  const BodyId id = world.createBody(ball);
  const BodyId wall = world.createBody(sphere(BodyType::Static, 1.0f, Vec3(0.0f)));
  for (int step = 0; step < 5; ++step) {
    ASSERT_NO_COLLIDE_ERROR(world.step(kDt)) << "step " << step;
    ASSERT_TRUE(everythingFinite(world, {id, wall})) << "step " << step;
  }
}

}  // namespace
}  // namespace collide
