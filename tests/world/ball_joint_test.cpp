// Ball (spherical) joints against known answers: the physical pendulum's period and energy,
// momentum between two free bodies, the pair filter of jointed bodies, refused definitions.
#include "support/collide_error.h"
#include "support/world_helpers.h"

#include <collide/world.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace collide {
namespace {

using ::testing::HasSubstr;

using test::kDt;
using test::kG;

// A uniform rod of length L and square section t x t hung from a pivot by its top end, turned by
// `angle` about z.
struct Pendulum {
  static constexpr float kLength = 1.0f;
  static constexpr float kThickness = 0.02f;
  static constexpr float kMass = 1.0f;
  World world;
  BodyId rod;
  JointId joint;
  Vec3 pivot{0.0f, 2.0f, 0.0f};

  explicit Pendulum(float angle) {
    const BodyId top = test::staticAnchor(world, pivot);
    const Quat turn = glm::angleAxis(angle, Vec3(0.0f, 0.0f, 1.0f));
    BodyDef def = test::boxBody(pivot + turn * Vec3(0.0f, -0.5f * kLength, 0.0f),
                                Vec3(0.5f * kThickness, 0.5f * kLength, 0.5f * kThickness), kMass);
    def.rotation = turn;
    rod = world.createBody(def);
    joint = world.createBallJoint({top, rod, pivot});
  }
  float angle() const {
    const Vec3 d = world.transform(rod).position - pivot;
    return std::atan2(d.x, -d.y);
  }
  // The rod's moment of inertia about the pivot (z axis): its own plus the parallel axis term.
  static float pivotInertia() {
    return kMass * (kLength * kLength + kThickness * kThickness) / 12.0f + kMass * 0.25f * kLength * kLength;
  }
  // Kinetic plus potential energy, zero at rest hanging straight down.
  float energy() const {
    const Vec3 v = world.linearVelocity(rod);
    const Vec3 w = world.angularVelocity(rod);
    const float ownInertia = kMass * (kLength * kLength + kThickness * kThickness) / 12.0f;
    const float height = world.transform(rod).position.y - (pivot.y - 0.5f * kLength);
    return 0.5f * kMass * glm::dot(v, v) + 0.5f * ownInertia * glm::dot(w, w) + kMass * kG * height;
  }
};

TEST(BallJoint, RodPendulumSwingsWithThePhysicalPendulumPeriod) {
  // Small amplitude (5 degrees): T = 2 pi sqrt(I_pivot / (m g L/2)), 2 pi sqrt(2L / 3g) for a thin
  // rod; the amplitude's correction (1 + theta^2 / 16) is 0.05 %.
  Pendulum p(5.0f * kPi / 180.0f);
  const float expected = 2.0f * kPi * std::sqrt(Pendulum::pivotInertia() / (Pendulum::kMass * kG * 0.5f));
  EXPECT_NEAR(expected, 2.0f * kPi * std::sqrt(2.0f * Pendulum::kLength / (3.0f * kG)), 1e-3f * expected);
  // Times the angle crosses zero going positive, interpolated within the step.
  std::vector<float> crossings;
  float previous = p.angle();
  for (int step = 1; step <= 600; ++step) {
    p.world.step(kDt);
    const float now = p.angle();
    if (previous < 0.0f && now >= 0.0f) crossings.push_back((step - 1 + previous / (previous - now)) * kDt);
    previous = now;
  }
  ASSERT_GE(crossings.size(), 4u);
  const float period = (crossings.back() - crossings.front()) / static_cast<float>(crossings.size() - 1);
  EXPECT_NEAR(period, expected, 0.01f * expected);
}

TEST(BallJoint, RodPendulumKeepsItsEnergyOverTenSeconds) {
  Pendulum p(30.0f * kPi / 180.0f);
  const float start = p.energy();
  EXPECT_NEAR(start, Pendulum::kMass * kG * 0.5f * (1.0f - std::cos(30.0f * kPi / 180.0f)), 1e-3f * start);
  float lowest = start, highest = start;
  for (int step = 0; step < 600; ++step) {
    p.world.step(kDt);
    lowest = std::min(lowest, p.energy());
    highest = std::max(highest, p.energy());
  }
  EXPECT_GT(lowest, 0.98f * start);
  EXPECT_LT(highest, 1.02f * start);
  // The rod stays on its pivot.
  EXPECT_LT(p.world.constraintCurrentLength(p.joint), 0.005f);
}

TEST(BallJoint, TwoFreeBodiesKeepTheirMomentumAndShareTheAnchor) {
  // Zero gravity; a box spinning and moving, jointed at a corner to a sphere at rest: the joint's
  // impulses are equal and opposite, so the total linear momentum is the box's initial one.
  World world(test::zeroGravityWorld());
  BodyDef boxDef = test::boxBody(Vec3(0.0f), Vec3(0.5f), 2.0f);
  boxDef.linearVelocity = Vec3(1.0f, 0.5f, 0.0f);
  boxDef.angularVelocity = Vec3(0.0f, 0.0f, 3.0f);
  const BodyId box = world.createBody(boxDef);
  const BodyId ball = world.createBody(test::sphereBody(Vec3(1.0f, 1.0f, 0.5f), 0.5f, 1.0f));
  const JointId joint = world.createBallJoint({box, ball, Vec3(0.5f, 0.5f, 0.5f)});
  EXPECT_EQ(world.jointType(joint), JointType::Ball);
  EXPECT_EQ(world.constraintLength(joint), 0.0f);
  const Vec3 momentum = 2.0f * boxDef.linearVelocity;
  for (int step = 0; step < 120; ++step) {
    world.step(kDt);
    const Vec3 now = 2.0f * world.linearVelocity(box) + 1.0f * world.linearVelocity(ball);
    ASSERT_NEAR(glm::length(now - momentum), 0.0f, 1e-4f) << "step " << step;
    ASSERT_LT(world.constraintCurrentLength(joint), 0.005f) << "step " << step;
  }
  // The ball was swung round: the joint did act.
  EXPECT_GT(glm::length(world.linearVelocity(ball)), 0.1f);
}

TEST(BallJoint, JointedBodiesDoNotCollideUnlessTold) {
  // Two boxes overlapping by 0.2 m at the joint: kept apart from each other, they have no contact
  // and stay as placed; told to collide, they touch.
  for (const bool collide : {false, true}) {
    World world(test::zeroGravityWorld());
    const BodyId a = world.createBody(test::boxBody(Vec3(0.0f), Vec3(0.5f), 1.0f));
    const BodyId b = world.createBody(test::boxBody(Vec3(0.8f, 0.0f, 0.0f), Vec3(0.5f), 1.0f));
    world.createBallJoint({a, b, Vec3(0.4f, 0.0f, 0.0f), collide});
    int touching = 0;
    for (int step = 0; step < 30; ++step) {
      world.step(kDt);
      world.visitContacts(
          [&](const ContactData& c) { touching += (c.a == a && c.b == b) || (c.a == b && c.b == a); });
    }
    if (collide) {
      EXPECT_EQ(touching, 30);
    } else {
      EXPECT_EQ(touching, 0);
      EXPECT_NEAR(world.transform(b).position.x - world.transform(a).position.x, 0.8f, 1e-3f);
    }
  }
}

TEST(BallJoint, FrictionHoldsARodBelowItsTorque) {
  // At 30 degrees gravity turns the rod about the pivot with m g (L/2) sin 30 = 2.45 N m: a friction
  // of 3 N m holds it, one of 2 N m does not; a fixed joint has no friction to set.
  Pendulum held(30.0f * kPi / 180.0f);
  held.world.setJointFriction(held.joint, 3.0f);
  Pendulum slipping(30.0f * kPi / 180.0f);
  slipping.world.setJointFriction(slipping.joint, 2.0f);
  for (int step = 0; step < 120; ++step) {
    held.world.step(kDt);
    slipping.world.step(kDt);
  }
  EXPECT_NEAR(held.angle(), 30.0f * kPi / 180.0f, 1e-3f);
  EXPECT_LT(slipping.angle(), 25.0f * kPi / 180.0f);
  EXPECT_EQ(held.world.jointFriction(held.joint), 3.0f);
  EXPECT_COLLIDE_ERROR(held.world.setJointFriction(held.joint, -0.5f));
  const BodyId other = held.world.createBody(test::boxBody(Vec3(5.0f, 2.0f, 0.0f), Vec3(0.1f), 1.0f));
  const JointId weld = held.world.createFixedJoint({.a = held.rod, .b = other});
  EXPECT_COLLIDE_ERROR(held.world.setJointFriction(weld, 1.0f));
}

TEST(BallJoint, BadDefinitionsAreRefusedNamingTheField) {
  World world;
  const BodyId ground = world.createBody(test::groundBox());
  const BodyId box = world.createBody(test::boxBody(Vec3(0.0f, 2.0f, 0.0f), Vec3(0.5f), 1.0f));
  BodyDef particleDef = test::sphereBody(Vec3(3.0f, 2.0f, 0.0f), 0.1f, 1.0f);
  particleDef.particle = true;
  const BodyId particle = world.createBody(particleDef);
  const auto refused = [&](const BallJointDef& def, const char* what) {
    if (const std::optional<std::string> error =
            ::collide::test::errorOf([&] { world.createBallJoint(def); });
        !error) {
      ADD_FAILURE() << "accepted: " << what;
    } else {
      EXPECT_THAT(error->c_str(), HasSubstr("ball joint"));
      EXPECT_THAT(error->c_str(), HasSubstr(what));
    }
  };
  refused({box, box, Vec3(0.0f)}, "same body");
  refused({ground, BodyId{77, 1}, Vec3(0.0f)}, "b: invalid or stale");
  refused({box, ground, Vec3(NAN, 0.0f, 0.0f)}, "anchor must be finite");
  refused({box, particle, Vec3(0.0f, 2.0f, 0.0f)}, "particle's anchor must be its centre");
  const BodyId otherStatic = test::staticAnchor(world, Vec3(5.0f));
  refused({ground, otherStatic, Vec3(0.0f)}, "at least one body must be dynamic");
  BallJointDef rough{box, ground, Vec3(0.0f, 2.0f, 0.0f)};
  rough.frictionTorque = -1.0f;
  refused(rough, "frictionTorque must be finite and >= 0, got -1");
  EXPECT_EQ(world.constraintCount(), 0u);
  // A particle at its centre is a ball joint of the lecture's particles.
  EXPECT_NO_COLLIDE_ERROR(world.createBallJoint({box, particle, Vec3(3.0f, 2.0f, 0.0f)}));
  EXPECT_EQ(world.constraintCount(), 1u);
}

}  // namespace
}  // namespace collide
