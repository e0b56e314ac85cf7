// The world guards itself (src/dynamics/fault_guard.h): non-finite input is refused at the API, and
// a state that becomes non-finite inside a step is frozen and reported instead of reaching the
// bodies it touches.
#include "support/collide_error.h"
#include "support/test_assertions.h"
#include "support/world_helpers.h"

#include <collide/world.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>

namespace collide {
namespace {

using ::testing::HasSubstr;

using test::kHuge;
using test::kInf;
using test::kNan;

bool finiteState(const World& world, BodyId id) {
  const Transform t = world.transform(id);
  const Quat& q = t.rotation;
  return test::isFinite(t.position) && std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z) &&
         std::isfinite(q.w) && test::isFinite(world.linearVelocity(id)) &&
         test::isFinite(world.angularVelocity(id));
}

// Two boxes side by side on the ground, touching, settled.
struct TwoBoxes {
  World world;
  BodyId ground, a, b;
  TwoBoxes() {
    ground = world.createBody(test::groundBox());
    a = world.createBody(test::boxBody(Vec3(-0.5f, 0.5f, 0.0f), Vec3(0.5f), 1.0f));
    b = world.createBody(test::boxBody(Vec3(0.5f, 0.5f, 0.0f), Vec3(0.5f), 1.0f));
    for (int i = 0; i < 30; ++i) world.step(1.0f / 60.0f);
  }
};

TEST(FaultGuard, OverflowingForceIsFrozenAndReportedAndDoesNotInfectItsNeighbour) {
  TwoBoxes s;
  ASSERT_GT(s.world.touchingContactCount(), 1u);  // a-b and both on the ground
  const Transform before = s.world.transform(s.a);
  const Vec3 bBefore = s.world.transform(s.b).position;
  // Each call is finite and accepted; the accumulated force is +infinity.
  const Vec3 center = s.world.centerOfMass(s.a);
  s.world.applyForce(s.a, Vec3(kHuge, 0.0f, 0.0f), center);
  s.world.applyForce(s.a, Vec3(kHuge, 0.0f, 0.0f), center);
  s.world.step(1.0f / 60.0f);

  ASSERT_EQ(s.world.faultEvents().size(), 1u);
  const FaultEvent& fault = s.world.faultEvents()[0];
  EXPECT_EQ(fault.body, s.a);
  EXPECT_TRUE(fault.fields & FaultEvent::kLinearVelocity);
  // Frozen where the step began, stopped, asleep; its mass is still its own.
  EXPECT_EQ(s.world.transform(s.a).position, before.position);
  EXPECT_EQ(s.world.linearVelocity(s.a), Vec3(0.0f));
  EXPECT_EQ(s.world.angularVelocity(s.a), Vec3(0.0f));
  EXPECT_FALSE(s.world.isAwake(s.a));
  EXPECT_EQ(s.world.mass(s.a), 1.0f);

  // The neighbour is untouched by the fault: finite, still resting where it was, for a second more.
  for (int i = 0; i < 60; ++i) {
    ASSERT_TRUE(finiteState(s.world, s.b)) << "step " << i;
    ASSERT_TRUE(finiteState(s.world, s.a)) << "step " << i;
    s.world.step(1.0f / 60.0f);
    EXPECT_TRUE(s.world.faultEvents().empty());
  }
  EXPECT_NEAR(glm::length(s.world.transform(s.b).position - bBefore), 0.0f, 0.01f);
  EXPECT_TRUE(std::isfinite(s.world.kineticEnergy()));
  EXPECT_EQ(s.world.transform(s.a).position, before.position);
}

// A fault in a step that has an impact and prolonged contacts to resolve, under every impact and
// friction model: no error leaves the step, and the guard freezes the faulted body.
TEST(FaultGuard, AFaultMidStepPassesEveryImpactAndFrictionModelWithoutAnError) {
  for (const ImpactModel impact : {ImpactModel::Newton, ImpactModel::Interpolated}) {
    for (const FrictionModel friction :
         {FrictionModel::Coulomb, FrictionModel::Viscous, FrictionModel::Damping}) {
      SCOPED_TRACE(std::string(toString(impact)) + ", " + std::string(toString(friction)));
      WorldDef def;
      def.impactModel = impact;
      def.frictionModel = friction;
      World world(def);
      world.createBody(test::groundBox());
      BodyDef left = test::boxBody(Vec3(-0.5f, 0.5f, 0.0f), Vec3(0.5f), 1.0f);
      BodyDef right = test::boxBody(Vec3(0.5f, 0.5f, 0.0f), Vec3(0.5f), 1.0f);
      left.bounciness = right.bounciness = 0.5f;
      const BodyId a = world.createBody(left);
      const BodyId b = world.createBody(right);
      for (int i = 0; i < 30; ++i) world.step(1.0f / 60.0f);
      world.setLinearVelocity(b, Vec3(-4.0f, 0.0f, 0.0f));  // an impact on a this step
      world.applyForce(a, Vec3(kHuge, 0.0f, 0.0f), world.centerOfMass(a));
      world.applyForce(a, Vec3(kHuge, 0.0f, 0.0f), world.centerOfMass(a));
      EXPECT_NO_COLLIDE_ERROR(world.step(1.0f / 60.0f));
      ASSERT_EQ(world.faultEvents().size(), 1u);
      EXPECT_EQ(world.faultEvents()[0].body, a);
      for (int i = 0; i < 30; ++i) {
        EXPECT_NO_COLLIDE_ERROR(world.step(1.0f / 60.0f));
        ASSERT_TRUE(finiteState(world, b)) << "step " << i;
      }
    }
  }
}

// A frozen body is an immovable obstacle until the user gives it a state: then it falls again.
TEST(FaultGuard, FrozenBodyStaysUntilTheUserSetsItsState) {
  World world;
  const BodyId ball = world.createBody(test::sphereBody(Vec3(0.0f, 5.0f, 0.0f), 0.5f, 1.0f));
  const Vec3 center = world.centerOfMass(ball);
  world.applyForce(ball, Vec3(0.0f, kHuge, 0.0f), center);
  world.applyForce(ball, Vec3(0.0f, kHuge, 0.0f), center);
  world.step(1.0f / 60.0f);
  ASSERT_EQ(world.faultEvents().size(), 1u);
  // Gravity does not move it, and forces or impulses are ignored while frozen.
  world.applyImpulse(ball, Vec3(0.0f, -10.0f, 0.0f), center);
  for (int i = 0; i < 10; ++i) world.step(1.0f / 60.0f);
  EXPECT_EQ(world.transform(ball).position, Vec3(0.0f, 5.0f, 0.0f));
  EXPECT_EQ(world.linearVelocity(ball), Vec3(0.0f));

  world.setLinearVelocity(ball, Vec3(0.0f));
  EXPECT_TRUE(world.isAwake(ball));
  for (int i = 0; i < 30; ++i) world.step(1.0f / 60.0f);
  // Free fall for half a second: y = 5 - g t^2 / 2 (symplectic Euler lands within a few cm).
  EXPECT_NEAR(world.transform(ball).position.y, 5.0f - 0.5f * 9.81f * 0.25f, 0.05f);
  EXPECT_TRUE(world.faultEvents().empty());
}

// Something resting on a frozen body stays on it: the solver sees it as immovable, not as NaN.
TEST(FaultGuard, BodyRestingOnAFrozenBodyStaysFiniteAndSupported) {
  World world;
  world.createBody(test::groundBox());
  const BodyId base = world.createBody(test::boxBody(Vec3(0.0f, 0.5f, 0.0f), Vec3(0.5f), 1.0f));
  const BodyId top = world.createBody(test::boxBody(Vec3(0.0f, 1.5f, 0.0f), Vec3(0.5f), 1.0f));
  for (int i = 0; i < 30; ++i) world.step(1.0f / 60.0f);
  const Vec3 center = world.centerOfMass(base);
  world.applyForce(base, Vec3(0.0f, kHuge, 0.0f), center);
  world.applyForce(base, Vec3(0.0f, kHuge, 0.0f), center);
  world.step(1.0f / 60.0f);
  ASSERT_EQ(world.faultEvents().size(), 1u);
  EXPECT_EQ(world.faultEvents()[0].body, base);
  for (int i = 0; i < 120; ++i) {
    world.step(1.0f / 60.0f);
    ASSERT_TRUE(finiteState(world, top)) << "step " << i;
  }
  // Resting on the frozen base (top face y = 1): centre at 1.5, within the contact slop.
  EXPECT_NEAR(world.transform(top).position.y, 1.5f, 0.01f);
}

// Every setter refuses NaN and infinity with an Error naming the call, and leaves the body as it was.
TEST(FaultGuard, SettersRefuseNonFiniteValues) {
  World world;
  const BodyId id =
      world.createBody(test::sphereBody(Vec3(1.0f, 2.0f, 3.0f), 0.5f, 1.0f, Vec3(0.5f, 0.0f, 0.0f)));
  const Quat identity(1.0f, 0.0f, 0.0f, 0.0f);
  const Vec3 p = world.centerOfMass(id);
  using Call = std::function<void(const Vec3&)>;
  const std::pair<const char*, Call> calls[] = {
      {"setTransform", [&](const Vec3& v) { world.setTransform(id, v, identity); }},
      {"setLinearVelocity", [&](const Vec3& v) { world.setLinearVelocity(id, v); }},
      {"setAngularVelocity", [&](const Vec3& v) { world.setAngularVelocity(id, v); }},
      {"applyForce", [&](const Vec3& v) { world.applyForce(id, v, p); }},
      {"applyForce", [&](const Vec3& v) { world.applyForce(id, Vec3(1.0f), v); }},  // the point
      {"applyImpulse", [&](const Vec3& v) { world.applyImpulse(id, v, p); }},
      {"applyImpulse", [&](const Vec3& v) { world.applyImpulse(id, Vec3(1.0f), v); }},
      {"applyTorque", [&](const Vec3& v) { world.applyTorque(id, v); }},
  };
  for (const float bad : {kNan, kInf, -kInf}) {
    for (const auto& entry : calls) {
      const std::string name = entry.first;
      SCOPED_TRACE(name + " with " + std::to_string(bad));
      if (const std::optional<std::string> error =
              ::collide::test::errorOf([&] { entry.second(Vec3(0.0f, bad, 0.0f)); });
          !error) {
        ADD_FAILURE() << "no Error";
      } else {
        EXPECT_THAT(error->c_str(), HasSubstr(name));
        EXPECT_THAT(error->c_str(), HasSubstr("must be finite"));
      }
    }
    EXPECT_COLLIDE_ERROR(world.setTransform(id, Vec3(0.0f), Quat(bad, 0.0f, 0.0f, 0.0f)));
    if (const std::optional<std::string> error = ::collide::test::errorOf([&] { world.step(bad); }); !error) {
      ADD_FAILURE() << "step(" << bad << "): no Error";
    } else {
      EXPECT_THAT(error->c_str(), HasSubstr("dt must be finite and > 0"));
    }
  }
  EXPECT_COLLIDE_ERROR(world.step(0.0f));
  EXPECT_COLLIDE_ERROR(world.step(-1.0f / 60.0f));
  // Nothing was applied: the state is the creation state, and a step moves it as it would have.
  EXPECT_EQ(world.transform(id).position, Vec3(1.0f, 2.0f, 3.0f));
  EXPECT_EQ(world.linearVelocity(id), Vec3(0.5f, 0.0f, 0.0f));
  EXPECT_EQ(world.angularVelocity(id), Vec3(0.0f));
  world.step(1.0f / 60.0f);
  EXPECT_TRUE(world.faultEvents().empty());
  EXPECT_TRUE(finiteState(world, id));
}

}  // namespace
}  // namespace collide
