// The joint scenes against what they are built to show: the machine's rotor turns at its motor's
// speed and its lift stops at its limit; the pendulum's whipping chain holds its links; the bridge
// carries its crate and comes to rest; the ragdolls land on the stairs and settle within their limits.
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

// A scene's world stepped `steps` times: the fault guard's events and the widest joint gap seen.
struct WatchedRun {
  std::size_t faults = 0;
  float widestGap = 0.0f;
};

WatchedRun stepWatching(SceneWorld& sw, int steps) {
  WatchedRun run;
  for (int step = 0; step < steps; ++step) {
    sw.world.step(kDt);
    run.faults += sw.world.faultEvents().size();
    run.widestGap = std::max(run.widestGap, widestJointGap(sw));
  }
  return run;
}

TEST(JointScenes, BridgeCarriesItsCrateAtTwoSubsteps) {
  // At 2 substeps (the default is 6) the planks under the crate carry its weight with a third of the
  // iterations. Their contacts with the crate meet them with the inertia their tree solves them
  // with; met with their own, the planks rocked about their hinges, more each step, and the bridge
  // tore at step 32 (docs/joints.md, "One inertia for one body").
  Scene scene = loadBuiltinScene("bridge");
  scene.world.substeps = 2;
  SceneWorld sw = buildWorld(scene);
  const WatchedRun run = stepWatching(sw, 600);
  EXPECT_EQ(run.faults, 0u);
  EXPECT_LT(run.widestGap, 0.1f);  // a torn bridge opens by metres
  // After 10 s, softer than at 6 substeps but whole: the far post's hinge, a loop's Gauss-Seidel
  // joint, the most open (3.2 cm), nothing faster than a few cm/s (2.4).
  EXPECT_LT(widestJointGap(sw), 0.05f);
  EXPECT_LT(fastestSpeed(scene, sw), 0.05f);
  const Vec3 p = sw.world.transform(named(scene, sw, "crate")).position;
  EXPECT_LT(std::abs(p.x), 0.2f);
  EXPECT_GT(p.y, 1.0f);  // on the bridge, not on the ground
}

// How far the ragdolls' joints went past their limits: a hinge's angle or a cone's twist past its
// range, a cone's swing past its cone (rad).
struct LimitExcess {
  float landing = 0.0f;  // over the whole run
  float resting = 0.0f;  // over its last 5 s
};

// The eight ragdolls thrown down the stairs for 20 s with gravity scaled by `gravityScale`.
struct RagdollLanding {
  float widestGap = 0.0f;  // widestJointGap over the run
  LimitExcess excess;
  // The most the kinetic and potential energy (from the ground) rose above their start at any step,
  // over the start; 0 if they never did.
  double energyGain = 0.0;
  std::vector<Vec3> dollPositions;
};

double mechanicalEnergy(const Scene& scene, const SceneWorld& sw) {
  double energy = sw.world.kineticEnergy();
  for (const BodyId body : sw.bodies)
    energy -=
        double(sw.world.mass(body)) * double(glm::dot(scene.world.gravity, sw.world.centerOfMass(body)));
  return energy;
}

RagdollLanding landRagdolls(float gravityScale) {
  Scene scene = loadBuiltinScene("ragdolls");
  scene.world.gravity *= gravityScale;
  SceneWorld sw = buildWorld(scene);
  // A cone's axis as body b carries it: the scene's bodies start unturned, so it is the world axis
  // the joint was made with, in b's frame.
  std::vector<Vec3> coneAxisOnB(sw.constraints.size(), Vec3(0.0f));
  for (std::size_t c = 0; c < sw.constraints.size(); ++c) {
    const JointId j = sw.constraints[c];
    if (sw.world.jointType(j) == JointType::Cone)
      coneAxisOnB[c] =
          glm::conjugate(sw.world.transform(sw.world.jointBodyB(j)).rotation) * sw.world.jointAxis(j);
  }
  constexpr int kSteps = 1200, kRestingFrom = 900;
  RagdollLanding landing;
  const double startEnergy = mechanicalEnergy(scene, sw);
  for (int step = 0; step < kSteps; ++step) {
    sw.world.step(kDt);
    landing.energyGain =
        std::max(landing.energyGain, (mechanicalEnergy(scene, sw) - startEnergy) / startEnergy);
    landing.widestGap = std::max(landing.widestGap, widestJointGap(sw));
    float excess = 0.0f;
    for (std::size_t c = 0; c < sw.constraints.size(); ++c) {
      const JointId j = sw.constraints[c];
      const JointLimits limits = sw.world.jointLimits(j);
      const float angle = sw.world.jointPosition(j);
      excess = std::max({excess, limits.lower - angle, angle - limits.upper});
      if (sw.world.jointType(j) != JointType::Cone) continue;
      const Vec3 axisB = sw.world.transform(sw.world.jointBodyB(j)).rotation * coneAxisOnB[c];
      const float swing = std::acos(std::clamp(glm::dot(axisB, sw.world.jointAxis(j)), -1.0f, 1.0f));
      excess = std::max(excess, swing - sw.world.coneSwingLimit(j));
    }
    landing.excess.landing = std::max(landing.excess.landing, excess);
    if (step >= kRestingFrom) landing.excess.resting = std::max(landing.excess.resting, excess);
  }
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    if (scene.bodies[i].def.name.rfind("doll_", 0) == 0)
      landing.dollPositions.push_back(sw.world.transform(sw.bodies[i]).position);
  }
  return landing;
}

TEST(JointScenes, RagdollsLandOnTheStairsAndRestWithinTheirLimits) {
  // The landing is chaotic: gravity changed by a millionth sends the limbs down other paths. The
  // scene as built and three such neighbours (docs/joints.md, "What the tests hold it to").
  for (int k = 0; k < 4; ++k) {
    SCOPED_TRACE("gravity scaled by 1 + " + std::to_string(k) + "e-6");
    const RagdollLanding landing = landRagdolls(1.0f + static_cast<float>(k) * 1e-6f);
    // Landing from 2 m, no joint opens by 1 cm.
    EXPECT_LT(landing.widestGap, 0.01f);
    // Settled, over the last 5 s, every limit holds within 1 degree, as a hinge's limit holds a door.
    EXPECT_LT(landing.excess.resting, 0.0175f);
    // Struck by a stair, a limb goes a few degrees past its limit for a step or two: the contact,
    // solved after the joint, has the last word on the velocity (docs/joints.md, "Limits"). A limit
    // that stopped holding would let its limb swing on by tens of degrees.
    EXPECT_LT(landing.excess.landing, 0.15f);
    // None thrown off: friction, the landings and the joints' friction take energy, and no step
    // ends with more than the dolls had on the top stair. Every body above the ground.
    EXPECT_EQ(landing.energyGain, 0.0);
    for (const Vec3& p : landing.dollPositions) EXPECT_GT(p.y, 0.0f);
  }
}

TEST(JointScenes, RagdollPileLandsWholeAtFourSubsteps) {
  // 100 ragdolls dropped into a pile at 4 substeps (the default is 6): limbs pressed into the ground
  // by their joints carry large loads through the landing. With the geometric stiffness of every
  // load (not only of the pull along its lever) and the contacts solved with the bodies' own
  // inertia, this pile came apart at step 75, the fault guard freezing its bodies (docs/joints.md,
  // "One inertia for one body").
  Scene scene = loadBuiltinScene("ragdoll-pile");
  scene.world.substeps = 4;
  SceneWorld sw = buildWorld(scene);
  const WatchedRun run = stepWatching(sw, 150);
  EXPECT_EQ(run.faults, 0u);
  EXPECT_LT(run.widestGap, 0.05f);  // no joint torn open
}

}  // namespace
}  // namespace collide::scene
