// The joint scenes against what they are built to show: the machine's rotor turns at its motor's
// speed and its lift stops at its limit; the pendulum's whipping chain holds its links. (The bridge
// and the ragdolls do not yet do what they are built to show: docs/joints.md, "Limits".)
#include <collide/scene/builtin_scenes.h>
#include <collide/scene/scene.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace collide::scene {
namespace {

constexpr float kDt = 1.0f / 60.0f;

BodyId named(const Scene& scene, const SceneWorld& sw, const std::string& name) {
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    if (scene.bodies[i].def.name == name) return sw.bodies[i];
  }
  ADD_FAILURE() << "no body " << name;
  return {};
}

// The largest gap between a joint's anchors, over every joint of the world.
float widestJointGap(const SceneWorld& sw) {
  float widest = 0.0f;
  for (const JointId j : sw.constraints) {
    // A distance joint's anchors are its length apart, a slider's its offset.
    if (sw.world.jointType(j) == JointType::Distance || sw.world.jointType(j) == JointType::Slider) continue;
    widest = std::max(widest, glm::length(sw.world.jointAnchorB(j) - sw.world.jointAnchorA(j)));
  }
  return widest;
}

TEST(JointScenes, MachineRotorTurnsAtItsMotorSpeedAndTheLiftStopsAtItsLimit) {
  const Scene scene = loadBuiltinScene("machine");
  SceneWorld sw = buildWorld(scene);
  for (int step = 0; step < 300; ++step) sw.world.step(kDt);
  const JointId axle = sw.constraints[0], lift = sw.constraints[1];
  EXPECT_NEAR(sw.world.jointSpeed(axle), 1.0f, 0.01f);
  EXPECT_NEAR(sw.world.angularVelocity(named(scene, sw, "rotor")).z, 1.0f, 0.01f);
  EXPECT_NEAR(sw.world.jointPosition(lift), 2.0f, 0.005f);  // 0.5 m/s for 5 s, stopped at 2 m
  EXPECT_LT(std::abs(sw.world.jointSpeed(lift)), 0.01f);
  EXPECT_LT(widestJointGap(sw), 0.005f);
}

TEST(JointScenes, PendulumChainHoldsItsLinks) {
  const Scene scene = loadBuiltinScene("pendulum");
  SceneWorld sw = buildWorld(scene);
  float widest = 0.0f;
  for (int step = 0; step < 300; ++step) {
    sw.world.step(kDt);
    widest = std::max(widest, widestJointGap(sw));
  }
  EXPECT_LT(widest, 0.01f);
}

}  // namespace
}  // namespace collide::scene
