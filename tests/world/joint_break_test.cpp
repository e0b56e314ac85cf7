// Joint loads and breaking, and the distance joint's limits and spring: a joint carries its body's
// weight, breaks in the step its load passes the break force (an event, the id stale, the body
// falling freely), and a rope (limits, no spring) lets a ball fall freely until it is taut.
#include "support/collide_error.h"
#include "support/world_helpers.h"

#include <collide/world.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace collide {
namespace {

using ::testing::HasSubstr;

using test::kDt;
using test::kG;

struct Hanging {
  World world;
  BodyId box;
  JointId joint;
  explicit Hanging(float breakForce) {
    const BodyId hook = test::staticAnchor(world, Vec3(0.0f, 3.0f, 0.0f));
    box = world.createBody(test::boxBody(Vec3(0.0f, 2.5f, 0.0f), Vec3(0.2f), 10.0f));
    BallJointDef def{hook, box, Vec3(0.0f, 3.0f, 0.0f)};
    def.breakForce = breakForce;
    joint = world.createBallJoint(def);
  }
};

TEST(JointBreak, AJointStrongEnoughCarriesTheWeightAndHolds) {
  Hanging h(200.0f);
  for (int step = 0; step < 120; ++step) {
    h.world.step(kDt);
    ASSERT_TRUE(h.world.jointBreakEvents().empty());
  }
  EXPECT_TRUE(h.world.isValid(h.joint));
  EXPECT_NEAR(h.world.jointForce(h.joint), 10.0f * kG, 1e-3f * 10.0f * kG);
  EXPECT_NEAR(h.world.transform(h.box).position.y, 2.5f, 1e-3f);
}

TEST(JointBreak, AJointTooWeakBreaksInTheFirstStepWithAnEvent) {
  Hanging h(50.0f);
  const BodyId hook = h.world.jointBodyA(h.joint);
  h.world.step(kDt);
  ASSERT_EQ(h.world.jointBreakEvents().size(), 1u);
  const JointBreakEvent e = h.world.jointBreakEvents()[0];
  EXPECT_EQ(e.joint, h.joint);
  EXPECT_EQ(e.a, hook);
  EXPECT_EQ(e.b, h.box);
  EXPECT_GT(e.force, 50.0f);
  EXPECT_FALSE(h.world.isValid(h.joint));
  EXPECT_EQ(h.world.constraintCount(), 0u);
  // From the next step on the box falls freely, and no second event comes.
  const float v0 = h.world.linearVelocity(h.box).y;
  for (int step = 0; step < 30; ++step) {
    h.world.step(kDt);
    ASSERT_TRUE(h.world.jointBreakEvents().empty());
  }
  EXPECT_NEAR(h.world.linearVelocity(h.box).y, v0 - 30.0f * kDt * kG, 1e-3f);
}

TEST(JointBreak, AHingeBreaksOnTorque) {
  // A 2 kg, 1 m beam held level by a hinge whose axis is vertical: the hinge holds its weight's
  // moment (9.81 N m) with its axis rows, and breaks when that passes its break torque.
  for (const float limit : {5.0f, 20.0f}) {
    World world;
    const BodyId wall = test::staticAnchor(world, Vec3(0.0f, 2.0f, 0.0f));
    const BodyId beam =
        world.createBody(test::boxBody(Vec3(0.5f, 2.0f, 0.0f), Vec3(0.5f, 0.05f, 0.05f), 2.0f));
    HingeJointDef def{.a = wall, .b = beam, .anchor = Vec3(0.0f, 2.0f, 0.0f), .axis = Vec3(0.0f, 1.0f, 0.0f)};
    def.breakTorque = limit;
    const JointId joint = world.createHingeJoint(def);
    for (int step = 0; step < 30; ++step) world.step(kDt);
    EXPECT_EQ(world.isValid(joint), limit > 9.81f) << limit;
  }
}

TEST(DistanceJoint, ARopeLetsTheBallFallFreelyUntilTaut) {
  // A rope of 1 m (limits [0, 1], no spring) from a hook to a ball released beside the hook.
  World world;
  const BodyId hook = test::staticAnchor(world, Vec3(0.0f, 3.0f, 0.0f));
  const BodyId ball = world.createBody(test::sphereBody(Vec3(0.0f, 2.8f, 0.0f), 0.05f, 1.0f));
  DistanceConstraintDef def{.a = hook, .b = ball};
  def.limits = {true, 0.0f, 1.0f};
  const JointId rope = world.createDistanceConstraint(def);
  float longest = 0.0f;
  bool taut = false;
  for (int step = 1; step <= 120; ++step) {
    world.step(kDt);
    const float length = world.jointPosition(rope);
    longest = std::max(longest, length);
    if (length < 0.99f) {
      // Slack: free fall, y = 2.8 - g t^2 / 2 (the solver's symplectic Euler over substeps).
      const float t = step * kDt;
      ASSERT_NEAR(world.transform(ball).position.y, 2.8f - 0.5f * kG * t * t, 0.01f) << step;
    } else {
      taut = true;
    }
  }
  EXPECT_TRUE(taut);
  EXPECT_LT(longest, 1.0f + 0.005f + 1e-4f);  // the projection's slop
  EXPECT_NEAR(world.transform(ball).position.y, 2.0f, 0.01f);
}

TEST(DistanceJoint, ASpringInHertzStretchesByItsLoad) {
  // A 1 kg ball on a 1 Hz spring of rest length 0.5 m: k = m (2 pi)^2 = 39.5 N/m stretches by
  // m g / k = 0.248 m at rest.
  World world;
  const BodyId hook = test::staticAnchor(world, Vec3(0.0f, 3.0f, 0.0f));
  const BodyId ball = world.createBody(test::sphereBody(Vec3(0.0f, 2.5f, 0.0f), 0.05f, 1.0f));
  DistanceConstraintDef def{.a = hook, .b = ball};
  def.spring = {true, 1.0f, 1.0f, 0.0f};
  const JointId spring = world.createDistanceConstraint(def);
  for (int step = 0; step < 600; ++step) world.step(kDt);
  const float k = 1.0f * (2.0f * kPi) * (2.0f * kPi);
  EXPECT_NEAR(world.jointPosition(spring), 0.5f + kG / k, 0.01f * kG / k);
  def.compliance = 0.01f;
  EXPECT_THAT([&] { world.createDistanceConstraint(def); },
              ::collide::test::ReportsError(HasSubstr("spring and compliance")));
}

}  // namespace
}  // namespace collide
