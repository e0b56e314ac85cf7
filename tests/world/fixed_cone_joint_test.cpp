// Fixed (weld) and cone (swing-twist) joints against known answers: two welded boxes tumble as one
// rigid body (their relative pose, momentum and energy kept), a welded cantilever holds its pose, a
// cone joint keeps its axis within the swing and its twist within the limits.
#include "support/test_assertions.h"
#include "support/world_helpers.h"

#include <collide/world.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace collide {
namespace {

using test::kDegree;
using test::kDt;

using test::boxInertia;

TEST(FixedJoint, TwoWeldedBoxesTumbleAsOneRigidBodyForTenSeconds) {
  World world(test::zeroGravityWorld());
  const Vec3 halfA(0.3f, 0.2f, 0.1f), halfB(0.2f, 0.2f, 0.2f);
  const float massA = 3.0f, massB = 1.0f;
  const Vec3 centreA(0.0f, 0.0f, 0.0f), centreB(0.5f, 0.0f, 0.0f);  // touching at x = 0.3
  const Vec3 centre = (massA * centreA + massB * centreB) / (massA + massB);
  // One rigid motion for both: a spin about no principal axis of the pair, and a drift.
  const Vec3 spin(1.0f, 2.0f, 0.5f), drift(0.3f, -0.2f, 0.1f);
  BodyDef a = test::boxBody(centreA, halfA, massA);
  a.linearVelocity = drift + glm::cross(spin, centreA - centre);
  a.angularVelocity = spin;
  BodyDef b = test::boxBody(centreB, halfB, massB);
  b.linearVelocity = drift + glm::cross(spin, centreB - centre);
  b.angularVelocity = spin;
  const BodyId ba = world.createBody(a);
  const BodyId bb = world.createBody(b);
  world.createFixedJoint({.a = ba, .b = bb, .anchor = Vec3(0.3f, 0.0f, 0.0f)});

  const auto relative = [&] {
    const Transform ta = world.transform(ba), tb = world.transform(bb);
    return std::pair(glm::conjugate(ta.rotation) * (tb.position - ta.position),
                     glm::conjugate(ta.rotation) * tb.rotation);
  };
  const auto angularMomentum = [&] {
    Vec3 l(0.0f);
    for (const auto& [id, mass, half] : {std::tuple(ba, massA, halfA), std::tuple(bb, massB, halfB)}) {
      const Transform t = world.transform(id);
      const Mat3 r = glm::mat3_cast(t.rotation);
      const Mat3 inertia = r * boxInertia(mass, half) * glm::transpose(r);
      l += inertia * world.angularVelocity(id) + mass * glm::cross(t.position, world.linearVelocity(id));
    }
    return l;
  };
  const auto [startOffset, startTurn] = relative();
  const Vec3 startMomentum = angularMomentum();
  float offsetDrift = 0.0f, turnDrift = 0.0f;
  for (int step = 0; step < 600; ++step) {
    world.step(kDt);
    const auto [offset, turn] = relative();
    offsetDrift = std::max(offsetDrift, glm::length(offset - startOffset));
    turnDrift = std::max(turnDrift, glm::angle(glm::conjugate(startTurn) * turn));
  }
  EXPECT_LT(offsetDrift, 1e-3f);  // m
  EXPECT_LT(turnDrift, 2e-3f);    // rad: 1 mm at the 0.5 m between the centres
  const Vec3 momentum = massA * world.linearVelocity(ba) + massB * world.linearVelocity(bb);
  EXPECT_LT(glm::length(momentum - (massA + massB) * drift), 1e-4f);
  // Angular momentum about the origin (total momentum kept, so any fixed point will do).
  EXPECT_LT(glm::length(angularMomentum() - startMomentum), 0.01f * glm::length(startMomentum));
}

TEST(FixedJoint, WeldedCantileverHoldsItsPoseUnderGravity) {
  // A 10 kg beam welded by its end to a static wall, sticking out 1 m.
  World world;
  const BodyId wall = test::staticAnchor(world, Vec3(0.0f, 2.0f, 0.0f));
  const BodyId beam =
      world.createBody(test::boxBody(Vec3(0.5f, 2.0f, 0.0f), Vec3(0.5f, 0.05f, 0.05f), 10.0f));
  const JointId joint = world.createFixedJoint({.a = wall, .b = beam, .anchor = Vec3(0.0f, 2.0f, 0.0f)});
  float sag = 0.0f;
  for (int step = 0; step < 300; ++step) {
    world.step(kDt);
    sag = std::max(sag, 2.0f - world.transform(beam).position.y);
  }
  // Its tip, 1 m out, and its centre stay within a millimetre of their places.
  const Transform t = world.transform(beam);
  EXPECT_LT(sag, 1e-3f);
  EXPECT_LT(glm::length(t.position + t.rotation * Vec3(0.5f, 0.0f, 0.0f) - Vec3(1.0f, 2.0f, 0.0f)), 1e-3f);
  // The joint carries the weight (98 N) and its moment about the wall (49 N m).
  EXPECT_NEAR(world.jointForce(joint), 98.1f, 0.02f * 98.1f);
  EXPECT_NEAR(world.jointTorque(joint), 49.05f, 0.02f * 49.05f);
}

// A 1 m rod (a limb, 0.1 m thick) on a cone joint at its left end, its axis along the rod (+x), released
// level: gravity swings it down until the cone stops it.
struct ConeRod {
  World world;
  BodyId rod;
  JointId joint;
  explicit ConeRod(const ConeJointDef& settings) {
    const BodyId post = test::staticAnchor(world, Vec3(0.0f, 2.0f, 0.0f));
    rod = world.createBody(test::boxBody(Vec3(0.5f, 2.0f, 0.0f), Vec3(0.5f, 0.05f, 0.05f), 1.0f));
    ConeJointDef def = settings;
    def.a = post;
    def.b = rod;
    def.anchor = Vec3(0.0f, 2.0f, 0.0f);
    def.axis = Vec3(1.0f, 0.0f, 0.0f);
    joint = world.createConeJoint(def);
  }
  float swing() const {
    const Vec3 along = world.transform(rod).rotation * Vec3(1.0f, 0.0f, 0.0f);
    return std::acos(std::clamp(along.x, -1.0f, 1.0f));
  }
};

// A windmill's rotor: four 11.5 kg blades welded to a hub of `hubMass` on a hinge whose motor asks
// for `speed`, six substeps (the rigid rows at 90 Hz). Run for 10 s: how far a blade got from where
// the hub's pose puts it, and the fault guard's events.
struct WeldedRotor {
  World world{WorldDef{.substeps = 6}};
  BodyId hub;
  std::vector<BodyId> blades;
  std::vector<Vec3> offsets;  // each blade's centre in the hub's frame
  float drift = 0.0f;
  std::size_t faults = 0;

  WeldedRotor(float hubMass, float speed) {
    const Vec3 centre(0.0f, 4.0f, 0.0f);
    const BodyId tower = test::staticAnchor(world, centre - Vec3(0.0f, 0.0f, 0.2f));
    hub = world.createBody(test::boxBody(centre, Vec3(0.15f, 0.15f, 0.1f), hubMass));
    HingeJointDef axle{.a = tower, .b = hub, .anchor = centre, .axis = Vec3(0.0f, 0.0f, 1.0f)};
    axle.motor = {true, speed, 2000.0f};
    world.createHingeJoint(axle);
    for (int k = 0; k < 4; ++k) {
      const Quat turn = glm::angleAxis(float(k) * kPi / 2.0f, Vec3(0.0f, 0.0f, 1.0f));
      const Vec3 offset = turn * Vec3(0.0f, 1.05f, 0.0f);
      BodyDef def = test::boxBody(centre + offset, Vec3(0.08f, 0.9f, 0.02f), 11.5f);
      def.rotation = turn;
      blades.push_back(world.createBody(def));
      offsets.push_back(offset);
      world.createFixedJoint({.a = hub, .b = blades.back()});
    }
    for (int step = 0; step < 600; ++step) {
      world.step(kDt);
      faults += world.faultEvents().size();
      const Transform h = world.transform(hub);
      for (int k = 0; k < 4; ++k) {
        drift = std::max(
            drift, glm::length(world.transform(blades[k]).position - (h.position + h.rotation * offsets[k])));
      }
    }
  }
};

TEST(FixedJoint, FourHeavyBladesWeldedToALightHubTurnAsOne) {
  // An 18 kg hub. Solved one weld after another at the rigid stiffness, the blades spun themselves
  // apart from rest; as one joint tree they turn with the hub.
  const WeldedRotor rotor(18.0f, 1.0f);
  EXPECT_LT(rotor.drift, 0.001f);
  EXPECT_NEAR(rotor.world.angularVelocity(rotor.hub).z, 1.0f, 0.01f);
}

TEST(FixedJoint, AFeatherweightHubBetweenFourHeavyBladesStaysWhole) {
  // A 0.1 kg hub, 460 times lighter than its blades, driven at 5 rad/s: the welds' rows pull it
  // round by large and opposite amounts, which cancel. The trees' projection steps it by their sum;
  // turned by each row's share in turn, it was thrown off its rows by the steps meant to close them
  // and the rotor flew apart (blades metres from the hub, frozen by the fault guard).
  const WeldedRotor rotor(0.1f, 5.0f);
  EXPECT_EQ(rotor.faults, 0u);
  EXPECT_LT(rotor.drift, 0.002f);  // 1.3 mm
  // Its motor turns the light hub, which drags the blades: they lag a little (4.75 rad/s).
  EXPECT_NEAR(rotor.world.angularVelocity(rotor.hub).z, 5.0f, 0.5f);
}

TEST(ConeJoint, SwingStaysWithinItsCone) {
  ConeJointDef def;
  def.swingLimit = 45.0f * kDegree;
  ConeRod c(def);
  c.world.setLinearVelocity(c.rod, Vec3(0.0f, 0.0f, 1.5f));  // and sideways: round the cone's rim
  float widest = 0.0f;
  for (int step = 0; step < 300; ++step) {
    c.world.step(kDt);
    widest = std::max(widest, c.swing());
    ASSERT_LT(glm::length(c.world.jointAnchorB(c.joint) - c.world.jointAnchorA(c.joint)), 2e-3f);
  }
  EXPECT_LT(widest, 46.0f * kDegree);
  EXPECT_GT(widest, 44.0f * kDegree);  // it reached the rim
  // Without the cone the rod swings down through 90 degrees.
  ConeRod free(ConeJointDef{});
  float lowest = 0.0f;
  for (int step = 0; step < 60; ++step) {
    free.world.step(kDt);
    lowest = std::max(lowest, free.swing());
  }
  EXPECT_GT(lowest, 80.0f * kDegree);
}

TEST(ConeJoint, TwistStaysWithinItsLimits) {
  ConeJointDef def;
  def.twistLimits = {true, -0.3f, 0.5f};
  def.swingLimit = 0.2f;
  ConeRod c(def);
  // 0.5 N m about the rod's own axis (I = 1.7e-3 kg m^2): a rigid row's stiffness there,
  // I (2 pi 60 Hz)^2, gives under it by 0.002 rad (docs/joints.md, "Rigid rows under load").
  for (const float torque : {0.5f, -0.5f}) {
    float extreme = 0.0f;
    for (int step = 0; step < 120; ++step) {
      c.world.applyTorque(c.rod, c.world.transform(c.rod).rotation * Vec3(torque, 0.0f, 0.0f));
      c.world.step(kDt);
      const float twist = c.world.jointPosition(c.joint);
      extreme = torque > 0.0f ? std::max(extreme, twist) : std::min(extreme, twist);
    }
    if (torque > 0.0f) {
      EXPECT_LT(extreme, 0.5f + 1.0f * kDegree);
      EXPECT_NEAR(c.world.jointPosition(c.joint), 0.5f, 1.0f * kDegree);
    } else {
      EXPECT_GT(extreme, -0.3f - 1.0f * kDegree);
      EXPECT_NEAR(c.world.jointPosition(c.joint), -0.3f, 1.0f * kDegree);
    }
  }
  EXPECT_LT(c.swing(), 0.2f + 1.0f * kDegree);
}

}  // namespace
}  // namespace collide
