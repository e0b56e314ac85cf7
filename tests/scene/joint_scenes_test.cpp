// The joint scenes against what they are built to show: the machine's rotor turns at its motor's
// speed and its lift stops at its limit; the pendulum's whipping chain holds its links; the bridge
// carries its crate and comes to rest; the ragdolls land on the stairs within their limits.
#include <collide/scene/builtin_scenes.h>
#include <collide/scene/scene.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "support/world_helpers.h"

namespace collide::scene {
namespace {

using test::kDt;

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

// The sum of the chain's joint gaps (the pendulum's joints but its first, the rod's hinge).
float chainStretch(const SceneWorld& sw) {
  float total = 0.0f;
  for (std::size_t k = 1; k < sw.constraints.size(); ++k)
    total += glm::length(sw.world.jointAnchorB(sw.constraints[k]) - sw.world.jointAnchorA(sw.constraints[k]));
  return total;
}

TEST(JointScenes, PendulumChainStretchesLessThanOnePercent) {
  // Released level, the 5 m chain whips and its tip strikes the rod's post: continuous collision
  // stops the links it catches, with their chain.
  const Scene scene = loadBuiltinScene("pendulum");
  SceneWorld sw = buildWorld(scene);
  float widest = 0.0f;
  for (int step = 0; step < 300; ++step) {
    sw.world.step(kDt);
    widest = std::max(widest, chainStretch(sw));
  }
  EXPECT_LT(widest, 0.01f * 5.0f);
}

float fastestSpeed(const Scene& scene, const SceneWorld& sw) {
  float fastest = 0.0f;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    fastest = std::max(fastest, glm::length(sw.world.linearVelocity(sw.bodies[i])));
  }
  return fastest;
}

TEST(JointScenes, BridgeCarriesItsCrateAndComesToRest) {
  const Scene scene = loadBuiltinScene("bridge");
  SceneWorld sw = buildWorld(scene);
  const BodyId crate = named(scene, sw, "crate");
  const float start = sw.world.transform(crate).position.y;
  for (int step = 0; step < 720; ++step) sw.world.step(kDt);
  // Settled after 12 s: nothing moves faster than 1 cm/s, and the joints are closed.
  EXPECT_LT(fastestSpeed(scene, sw), 0.01f);
  EXPECT_LT(widestJointGap(sw), 0.005f);
  // The crate rides the planks down as they take its weight, and stays in the middle.
  const Vec3 p = sw.world.transform(crate).position;
  EXPECT_LT(std::abs(p.x), 0.2f);
  EXPECT_LT(std::abs(p.z), 0.05f);
  EXPECT_GT(p.y, start - 1.0f);
  EXPECT_GT(p.y, 1.0f);  // on the bridge, not on the ground
}

TEST(JointScenes, RagdollsLandOnTheStairsWithinTheirLimits) {
  const Scene scene = loadBuiltinScene("ragdolls");
  SceneWorld sw = buildWorld(scene);
  float widest = 0.0f;
  float overshoot = 0.0f;  // the farthest a hinge's angle or a cone's twist went past its limits
  for (int step = 0; step < 1200; ++step) {
    sw.world.step(kDt);
    widest = std::max(widest, widestJointGap(sw));
    for (const JointId j : sw.constraints) {
      const JointLimits limits = sw.world.jointLimits(j);
      const float angle = sw.world.jointPosition(j);
      overshoot = std::max({overshoot, limits.lower - angle, angle - limits.upper});
    }
  }
  // Landing from 2 m, no joint opens by 1 cm and no limb turns 2 degrees past its limit.
  EXPECT_LT(widest, 0.01f);
  EXPECT_LT(overshoot, 0.035f);
  // After 20 s every doll lies on or past the stairs, none thrown off (the flight is 3 m deep, 6 m
  // wide). (Not all at rest yet: docs/joints.md, "Limits".)
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    if (scene.bodies[i].def.name.rfind("doll_", 0) != 0) continue;
    const Vec3 p = sw.world.transform(sw.bodies[i]).position;
    EXPECT_GT(p.y, 0.0f) << scene.bodies[i].def.name;
    EXPECT_LT(std::abs(p.x), 3.5f) << scene.bodies[i].def.name;
  }
}

}  // namespace
}  // namespace collide::scene
