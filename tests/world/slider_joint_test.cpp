// Slider (prismatic) joints against known answers: motion along the axis only under sideways loads
// and torques, free motion along it as F = m a, limits, a motor at its speed and at its force.
#include "support/world_helpers.h"

#include <collide/world.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace collide {
namespace {

using test::kDt;
constexpr float kMass = 2.0f;

// A 2 kg box on a slider along x from a static post, under gravity (a load across the axis).
struct SliderBox {
  World world;
  BodyId box;
  JointId joint;
  Vec3 start{0.0f, 1.0f, 0.0f};
  explicit SliderBox(const SliderJointDef& settings = {}) {
    const BodyId post = test::staticAnchor(world, Vec3(-1.0f, 1.0f, 0.0f));
    box = world.createBody(test::boxBody(start, Vec3(0.2f, 0.1f, 0.15f), kMass));
    SliderJointDef def = settings;
    def.a = post;
    def.b = box;
    def.anchor = start;
    def.axis = Vec3(1.0f, 0.0f, 0.0f);
    joint = world.createSliderJoint(def);
  }
  float offAxis() const {
    const Vec3 p = world.transform(box).position - start;
    return std::sqrt(p.y * p.y + p.z * p.z);
  }
  float turned() const { return glm::angle(world.transform(box).rotation); }
};

TEST(SliderJoint, MovesAlongItsAxisOnlyUnderSidewaysLoadsAndTorques) {
  SliderBox s;
  constexpr float kPush = 5.0f;  // N along the axis: x = (F / m) t^2 / 2
  float drift = 0.0f, turn = 0.0f;
  for (int step = 1; step <= 120; ++step) {
    s.world.applyForce(s.box, Vec3(kPush, 0.0f, 30.0f),
                       s.world.transform(s.box).position + Vec3(0.0f, 0.1f, 0.0f));
    s.world.applyTorque(s.box, Vec3(2.0f, -3.0f, 1.0f));
    s.world.step(kDt);
    drift = std::max(drift, s.offAxis());
    turn = std::max(turn, s.turned());
  }
  EXPECT_LT(drift, 1e-3f);  // m
  EXPECT_LT(turn, 1e-3f);   // rad
  const float t = 120.0f * kDt;
  const float expected = 0.5f * (kPush / kMass) * t * t;
  EXPECT_NEAR(s.world.jointPosition(s.joint), expected, 0.01f * expected);
  EXPECT_NEAR(s.world.jointSpeed(s.joint), (kPush / kMass) * t, 0.01f * (kPush / kMass) * t);
}

TEST(SliderJoint, LimitStopsTheBoxAtItsEnd) {
  SliderJointDef def;
  def.limits = {true, -0.25f, 0.5f};
  SliderBox s(def);
  float farthest = 0.0f;
  for (int step = 0; step < 180; ++step) {
    s.world.applyForce(s.box, Vec3(20.0f, 0.0f, 0.0f), s.world.transform(s.box).position);
    s.world.step(kDt);
    farthest = std::max(farthest, s.world.jointPosition(s.joint));
  }
  EXPECT_LT(farthest, 0.5f + 2e-3f);
  EXPECT_NEAR(s.world.jointPosition(s.joint), 0.5f, 2e-3f);
  EXPECT_LT(std::abs(s.world.jointSpeed(s.joint)), 1e-2f);
  // Pushed back the other way, it stops at the lower end.
  for (int step = 0; step < 180; ++step) {
    s.world.applyForce(s.box, Vec3(-20.0f, 0.0f, 0.0f), s.world.transform(s.box).position);
    s.world.step(kDt);
  }
  EXPECT_NEAR(s.world.jointPosition(s.joint), -0.25f, 2e-3f);
}

TEST(SliderJoint, MotorReachesItsSpeedOrSaturatesAtItsForce) {
  SliderJointDef strong;
  strong.motor = {true, 1.5f, 500.0f};
  SliderBox fast(strong);
  for (int step = 0; step < 60; ++step) fast.world.step(kDt);
  EXPECT_NEAR(fast.world.jointSpeed(fast.joint), 1.5f, 0.015f);
  EXPECT_NEAR(fast.world.linearVelocity(fast.box).x, 1.5f, 0.015f);

  // 3 N on 2 kg: a = 1.5 m/s^2, 0.75 m/s after 0.5 s, short of the 5 m/s asked.
  SliderJointDef weak;
  weak.motor = {true, 5.0f, 3.0f};
  SliderBox slow(weak);
  for (int step = 0; step < 30; ++step) slow.world.step(kDt);
  EXPECT_NEAR(slow.world.jointSpeed(slow.joint) / (30.0f * kDt), 3.0f / kMass, 0.01f * 3.0f / kMass);
  EXPECT_NEAR(slow.world.jointMotorForce(slow.joint), 3.0f, 1e-3f * 3.0f);
}

}  // namespace
}  // namespace collide
