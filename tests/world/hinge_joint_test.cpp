// Hinge (revolute) joints against known answers: the physical pendulum's period and energy, a
// door held at its limit, a motor at its speed and at its torque, a spring at its frequency, a car
// on motorised wheels rolling at their spin times their radius.
#include "support/collide_error.h"
#include "support/test_assertions.h"
#include "support/world_helpers.h"

#include <collide/world.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace collide {
namespace {

using ::testing::HasSubstr;

using test::kDegree;
using test::kDt;
using test::kG;

// A uniform rod of length L hinged at its top end about z, turned by `angle` about z.
struct HingedRod {
  static constexpr float kLength = 1.0f;
  static constexpr float kThickness = 0.02f;
  static constexpr float kMass = 1.0f;
  World world;
  BodyId rod;
  JointId joint;
  Vec3 pivot{0.0f, 2.0f, 0.0f};

  explicit HingedRod(float angle) {
    const BodyId top = test::staticAnchor(world, pivot);
    const Quat turn = glm::angleAxis(angle, Vec3(0.0f, 0.0f, 1.0f));
    BodyDef def = test::boxBody(pivot + turn * Vec3(0.0f, -0.5f * kLength, 0.0f),
                                Vec3(0.5f * kThickness, 0.5f * kLength, 0.5f * kThickness), kMass);
    def.rotation = turn;
    rod = world.createBody(def);
    joint = world.createHingeJoint({.a = top, .b = rod, .anchor = pivot, .axis = Vec3(0.0f, 0.0f, 1.0f)});
  }
  float swing() const {
    const Vec3 d = world.transform(rod).position - pivot;
    return std::atan2(d.x, -d.y);
  }
  float energy() const {
    const Vec3 v = world.linearVelocity(rod);
    const Vec3 w = world.angularVelocity(rod);
    const float ownInertia = kMass * (kLength * kLength + kThickness * kThickness) / 12.0f;
    const float height = world.transform(rod).position.y - (pivot.y - 0.5f * kLength);
    return 0.5f * kMass * glm::dot(v, v) + 0.5f * ownInertia * glm::dot(w, w) + kMass * kG * height;
  }
};

TEST(HingeJoint, RodPendulumSwingsWithThePhysicalPendulumPeriod) {
  // Small amplitude (5 degrees): T = 2 pi sqrt(2L / 3g) for a thin rod hinged at its end.
  HingedRod p(5.0f * kDegree);
  const float thin = 2.0f * kPi * std::sqrt(2.0f * HingedRod::kLength / (3.0f * kG));
  // The rod's own thickness adds t^2 / 12 to its inertia: 0.01 % here.
  const float expected = thin * std::sqrt(1.0f + HingedRod::kThickness * HingedRod::kThickness /
                                                     (4.0f * HingedRod::kLength * HingedRod::kLength));
  std::vector<float> crossings;
  float previous = p.swing();
  for (int step = 1; step <= 600; ++step) {
    p.world.step(kDt);
    const float now = p.swing();
    if (previous < 0.0f && now >= 0.0f) crossings.push_back((step - 1 + previous / (previous - now)) * kDt);
    previous = now;
    // The hinge's angle is the swing (the rod turns with it), within a hundredth of a degree.
    ASSERT_NEAR(p.world.jointPosition(p.joint), now - 5.0f * kDegree, 0.01f * kDegree);
  }
  ASSERT_GE(crossings.size(), 4u);
  const float period = (crossings.back() - crossings.front()) / static_cast<float>(crossings.size() - 1);
  EXPECT_NEAR(period, expected, 0.01f * expected);
}

TEST(HingeJoint, RodPendulumKeepsItsEnergyAndItsPlaneOverTenSeconds) {
  HingedRod p(30.0f * kDegree);
  // Pushed out of the hinge's plane at the start: the joint takes that velocity away at once.
  p.world.setLinearVelocity(p.rod, Vec3(0.0f, 0.0f, 0.5f));
  p.world.step(kDt);
  const float start = p.energy();
  float lowest = start, highest = start, outOfPlane = 0.0f;
  for (int step = 0; step < 600; ++step) {
    p.world.step(kDt);
    lowest = std::min(lowest, p.energy());
    highest = std::max(highest, p.energy());
    outOfPlane = std::max(outOfPlane, std::abs(p.world.transform(p.rod).position.z));
    // The rod's long axis stays in the xy plane: its z component is zero.
    const Vec3 along = p.world.transform(p.rod).rotation * Vec3(0.0f, 1.0f, 0.0f);
    ASSERT_LT(std::abs(along.z), 1e-3f);
  }
  EXPECT_GT(lowest, 0.98f * start);
  EXPECT_LT(highest, 1.02f * start);
  EXPECT_LT(outOfPlane, 1e-3f);  // m
  EXPECT_LT(glm::length(p.world.jointAnchorB(p.joint) - p.world.jointAnchorA(p.joint)), 1e-3f);
}

TEST(HingeJoint, LimitHoldsATenKilogramDoorWithLessThanADegreeOfOvershoot) {
  // A trapdoor: a 1 m x 0.05 m x 0.8 m plate of 10 kg hinged along z at its left edge, released
  // level. Gravity turns it down (negative angle) onto its lower limit of -45 degrees.
  World world;
  const Vec3 hinge(0.0f, 1.0f, 0.0f);
  const BodyId frame = test::staticAnchor(world, hinge);
  const BodyId door =
      world.createBody(test::boxBody(hinge + Vec3(0.5f, 0.0f, 0.0f), Vec3(0.5f, 0.025f, 0.4f), 10.0f));
  HingeJointDef def{.a = frame, .b = door, .anchor = hinge, .axis = Vec3(0.0f, 0.0f, 1.0f)};
  def.limits = {true, -kPi / 4.0f, kPi / 4.0f};
  const JointId joint = world.createHingeJoint(def);
  float lowest = 0.0f;
  for (int step = 0; step < 240; ++step) {
    world.step(kDt);
    lowest = std::min(lowest, world.jointPosition(joint));
  }
  EXPECT_GT(lowest, -kPi / 4.0f - 1.0f * kDegree);
  EXPECT_NEAR(world.jointPosition(joint), -kPi / 4.0f, 1.0f * kDegree);
  EXPECT_LT(std::abs(world.jointSpeed(joint)), 1e-2f);
  // Resting on its stop, the joint carries the door's weight: 98 N at the hinge.
  EXPECT_NEAR(world.jointForce(joint), 10.0f * kG, 0.02f * 10.0f * kG);
}

// A 0.5 m box of 2 kg on a vertical hinge through its centre, driven by a motor.
struct MotorWheel {
  static constexpr float kMass = 2.0f;
  static constexpr float kSide = 0.5f;
  World world;
  BodyId wheel;
  JointId joint;
  explicit MotorWheel(const JointMotor& motor) {
    const BodyId post = test::staticAnchor(world, Vec3(0.0f, 1.0f, 0.0f));
    wheel = world.createBody(test::boxBody(Vec3(0.0f, 1.0f, 0.0f), Vec3(0.5f * kSide), kMass));
    HingeJointDef def{
        .a = post, .b = wheel, .anchor = Vec3(0.0f, 1.0f, 0.0f), .axis = Vec3(0.0f, 1.0f, 0.0f)};
    def.motor = motor;
    joint = world.createHingeJoint(def);
  }
  static float inertia() { return kMass * kSide * kSide / 6.0f; }
};

TEST(HingeJoint, MotorWithEnoughTorqueReachesAndKeepsItsSpeed) {
  MotorWheel w({true, 3.0f, 100.0f});
  for (int step = 0; step < 60; ++step) w.world.step(kDt);
  for (int step = 0; step < 120; ++step) {
    w.world.step(kDt);
    ASSERT_NEAR(w.world.jointSpeed(w.joint), 3.0f, 0.03f);
    ASSERT_NEAR(w.world.angularVelocity(w.wheel).y, 3.0f, 0.03f);
  }
}

TEST(HingeJoint, MotorWithoutEnoughTorqueSaturatesAtItsMaximum) {
  // 0.5 N m on I = m s^2 / 6: alpha = 6 rad/s^2, 1.5 rad/s after 0.25 s, short of the 3 rad/s asked.
  constexpr float kTorque = 0.5f;
  MotorWheel w({true, 3.0f, kTorque});
  for (int step = 0; step < 15; ++step) w.world.step(kDt);
  const float alpha = w.world.jointSpeed(w.joint) / (15.0f * kDt);
  EXPECT_NEAR(alpha, kTorque / MotorWheel::inertia(), 0.01f * kTorque / MotorWheel::inertia());
  EXPECT_NEAR(w.world.jointMotorForce(w.joint), kTorque, 1e-3f * kTorque);
}

TEST(HingeJoint, FrictionHoldsBelowItsTorqueAndSlowsAboveIt) {
  // A rod hinged at its top, at 30 degrees: gravity's torque about the pivot is m g (L/2) sin 30
  // = 2.45 N m. A friction of 3 N m holds it where it is; one of 1 N m lets it swing with angular
  // acceleration (2.45 - 1) / I_pivot.
  const float gravityTorque = HingedRod::kMass * kG * 0.5f * HingedRod::kLength * std::sin(30.0f * kDegree);
  const float pivotInertia =
      HingedRod::kMass *
          (HingedRod::kLength * HingedRod::kLength + HingedRod::kThickness * HingedRod::kThickness) / 12.0f +
      HingedRod::kMass * 0.25f * HingedRod::kLength * HingedRod::kLength;
  {
    HingedRod held(30.0f * kDegree);
    held.world.setJointFriction(held.joint, 3.0f);
    for (int step = 0; step < 120; ++step) held.world.step(kDt);
    EXPECT_NEAR(held.swing(), 30.0f * kDegree, 0.1f * kDegree);
    EXPECT_NEAR(held.world.jointTorque(held.joint), gravityTorque, 0.02f * gravityTorque);
  }
  {
    constexpr float kFriction = 1.0f;
    HingedRod slipping(30.0f * kDegree);
    slipping.world.setJointFriction(slipping.joint, kFriction);
    for (int step = 0; step < 6; ++step) slipping.world.step(kDt);  // 0.1 s: it turns 0.4 degrees
    const float alpha = slipping.world.jointSpeed(slipping.joint) / (6.0f * kDt);
    // The swing is a turn about -z (toward the bottom), the joint's angle about +z.
    EXPECT_NEAR(-alpha, (gravityTorque - kFriction) / pivotInertia,
                0.02f * (gravityTorque - kFriction) / pivotInertia);
  }
}

TEST(HingeJoint, SpringSwingsAtItsFrequency) {
  // A spring of 1 Hz on the wheel's own inertia: the angle oscillates with a period of 1 s.
  MotorWheel w({});
  w.world.setJointSpring(w.joint, {true, 1.0f, 0.0f, 0.0f});
  w.world.setAngularVelocity(w.wheel, Vec3(0.0f, 1.0f, 0.0f));
  std::vector<float> crossings;
  float previous = w.world.jointPosition(w.joint);
  for (int step = 1; step <= 360; ++step) {
    w.world.step(kDt);
    const float now = w.world.jointPosition(w.joint);
    if (previous < 0.0f && now >= 0.0f) crossings.push_back((step - 1 + previous / (previous - now)) * kDt);
    previous = now;
  }
  ASSERT_GE(crossings.size(), 4u);
  const float period = (crossings.back() - crossings.front()) / static_cast<float>(crossings.size() - 1);
  EXPECT_NEAR(period, 1.0f, 0.01f);
}

TEST(HingeJoint, AMotorisedCarRollsItsWheelsWithoutSlipping) {
  // A 1,500 kg chassis on four 20 kg ball wheels of radius 0.4 m, each on a hinge across the car
  // whose motor asks for 5 rad/s (at most 2,000 N m). From 2 s on, every step: each motor keeps its
  // speed within 1 %, and each wheel rolls without slipping, its centre moving at its spin times
  // its height (the radius it rolls on) within 0.5 %; the chassis stays level at its height, and
  // straight. With the contacts' static anchor fixed in the wheel, the anchor went round with it,
  // the friction braked the wheel until the patch slid, and the speed swung by 3 % every 6 steps.
  World world;
  world.createBody(test::groundBox());
  const BodyId chassis =
      world.createBody(test::boxBody(Vec3(0.0f, 0.9f, 0.0f), Vec3(1.0f, 0.25f, 2.0f), 1500.0f));
  std::vector<BodyId> wheels;
  for (const float x : {-1.2f, 1.2f}) {
    for (const float z : {-1.5f, 1.5f}) {
      wheels.push_back(world.createBody(test::sphereBody(Vec3(x, 0.4f, z), 0.4f, 20.0f)));
      HingeJointDef axle{
          .a = chassis, .b = wheels.back(), .anchor = Vec3(x, 0.4f, z), .axis = Vec3(1.0f, 0.0f, 0.0f)};
      axle.motor = {true, 5.0f, 2000.0f};
      world.createHingeJoint(axle);
    }
  }
  float lowest = 1.0f;
  float highest = 0.0f;
  for (int step = 0; step < 600; ++step) {
    world.step(kDt);
    if (step < 120) continue;  // under way after 2 s
    const float y = world.transform(chassis).position.y;
    lowest = std::min(lowest, y);
    highest = std::max(highest, y);
    for (const BodyId wheel : wheels) {
      const float spin = (world.angularVelocity(wheel) - world.angularVelocity(chassis)).x;
      ASSERT_NEAR(spin, 5.0f, 0.05f) << "step " << step;
      const float rolling = spin * world.transform(wheel).position.y;
      ASSERT_NEAR(world.linearVelocity(wheel).z, rolling, 0.005f * rolling) << "step " << step;
    }
  }
  EXPECT_LT(highest - lowest, 0.005f);
  EXPECT_NEAR(lowest, 0.9f, 0.005f);
  EXPECT_LT(std::abs(world.transform(chassis).position.x), 0.01f);
}

TEST(HingeJoint, SettersTakeEffectAndRefuseWhatDoesNotApply) {
  MotorWheel w({});
  w.world.setJointMotor(w.joint, {true, -2.0f, 50.0f});
  for (int step = 0; step < 60; ++step) w.world.step(kDt);
  EXPECT_NEAR(w.world.jointSpeed(w.joint), -2.0f, 0.02f);
  EXPECT_EQ(w.world.jointMotor(w.joint), (JointMotor{true, -2.0f, 50.0f}));
  EXPECT_EQ(w.world.jointType(w.joint), JointType::Hinge);
  EXPECT_THAT(
      [&] {
        w.world.setJointLimits(w.joint, {true, 1.0f, -1.0f});
      },
      ::collide::test::ReportsError(HasSubstr("lower <= upper")));
  EXPECT_THAT(
      [&] {
        w.world.setJointLimits(w.joint, {true, -4.0f, 1.0f});
      },
      ::collide::test::ReportsError(HasSubstr("within [-pi, pi]")));
  EXPECT_THAT(
      [&] {
        w.world.setJointMotor(w.joint, {true, 1.0f, -1.0f});
      },
      ::collide::test::ReportsError(HasSubstr("motor.maxForce")));
  EXPECT_THAT([&] { w.world.setConeSwingLimit(w.joint, 1.0f); },
              ::collide::test::ReportsError(HasSubstr("does not apply to a hinge joint")));
  EXPECT_EQ(w.world.jointMotor(w.joint), (JointMotor{true, -2.0f, 50.0f}));  // unchanged
}

TEST(HingeJoint, BadDefinitionsAreRefusedNamingTheField) {
  World world;
  const BodyId post = test::staticAnchor(world, Vec3(0.0f));
  const BodyId box = world.createBody(test::boxBody(Vec3(1.0f, 0.0f, 0.0f), Vec3(0.1f), 1.0f));
  const auto refused = [&](HingeJointDef def, const char* text) {
    EXPECT_THAT([&] { world.createHingeJoint(def); }, ::collide::test::ReportsError(HasSubstr(text))) << text;
  };
  refused({.a = post, .b = box, .anchor = Vec3(0.0f), .axis = Vec3(0.0f)},
          "hinge joint: axis must be finite and non-zero");
  refused({.a = post, .b = box, .anchor = Vec3(NAN), .axis = Vec3(0.0f, 0.0f, 1.0f)},
          "anchor must be finite");
  refused({.a = post, .b = post, .anchor = Vec3(0.0f)}, "the same body");
  HingeJointDef def{.a = post, .b = box, .anchor = Vec3(0.0f)};
  def.breakTorque = 0.0f;
  refused(def, "breakTorque must be > 0");
  BodyDef particle = test::sphereBody(Vec3(0.0f, 1.0f, 0.0f), 0.1f, 1.0f);
  particle.particle = true;
  const BodyId dot = world.createBody(particle);
  refused({.a = post, .b = dot, .anchor = Vec3(0.0f, 1.0f, 0.0f)}, "b: a particle cannot turn");
  EXPECT_EQ(world.constraintCount(), 0u);
}

}  // namespace
}  // namespace collide
