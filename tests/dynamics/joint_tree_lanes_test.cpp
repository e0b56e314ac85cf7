// The joint trees' lanes (src/dynamics/joint_tree_lanes.h) against the tree-at-a-time solve they
// stand in for: groups of four trees of one shape, factored and solved side by side, leave every
// body bit for bit where the trees solved alone leave it. The figures are small ragdolls thrown
// tumbling onto the ground, each at its own spin, so that their cone and hinge limits are reached at
// different times: in a group, one tree's node has more rows than another's (the padding), and a
// limit that comes out pulling sends one tree into a second round beside the others.
#include "dynamics/joint_tree_lanes.h"

#include <collide/world.h>

#include <gtest/gtest.h>

#include <vector>

#include "support/world_helpers.h"

namespace collide {
namespace {

using test::kDt;

// A torso with four limbs of two boxes each: cone shoulders (swing and twist limits), hinge
// elbows with limits. 9 bodies and 8 joints, one tree.
void addFigure(World& world, const Vec3& at, float spin, std::vector<BodyId>& bodies) {
  BodyDef torsoDef = test::boxBody(at, Vec3(0.15f, 0.25f, 0.1f), 4.0f);
  torsoDef.angularVelocity = Vec3(spin, 0.5f * spin, -0.3f * spin);
  torsoDef.linearVelocity = Vec3(0.2f * spin, -1.0f, 0.0f);
  const BodyId torso = world.createBody(torsoDef);
  bodies.push_back(torso);
  const Vec3 shoulders[] = {
      {0.15f, 0.2f, 0.0f}, {-0.15f, 0.2f, 0.0f}, {0.1f, -0.25f, 0.0f}, {-0.1f, -0.25f, 0.0f}};
  for (const Vec3& shoulder : shoulders) {
    const Vec3 out = glm::normalize(Vec3(shoulder.x, 0.6f * shoulder.y, 0.0f));
    BodyId above = torso;
    Vec3 joint = at + shoulder;
    for (int segment = 0; segment < 2; ++segment) {
      const Vec3 centre = joint + 0.15f * out;
      BodyDef limbDef = test::boxBody(centre, Vec3(0.05f, 0.05f, 0.05f) + 0.1f * glm::abs(out), 1.0f);
      limbDef.angularVelocity = Vec3(0.0f, 0.0f, (segment == 0 ? 2.0f : -3.0f) * spin);
      const BodyId limb = world.createBody(limbDef);
      bodies.push_back(limb);
      if (segment == 0) {
        ConeJointDef cone{.a = above, .b = limb, .anchor = joint, .axis = out};
        cone.swingLimit = 0.5f;
        cone.twistLimits = {true, -0.3f, 0.3f};
        world.createConeJoint(cone);
      } else {
        HingeJointDef elbow{.a = above, .b = limb, .anchor = joint, .axis = Vec3(0.0f, 0.0f, 1.0f)};
        elbow.limits = {true, -0.1f, 1.2f};
        world.createHingeJoint(elbow);
      }
      above = limb;
      joint += 0.3f * out;
    }
  }
}

// Nine figures (two groups of four and one alone), the state after each of `steps` steps. With
// `faultAt` >= 0, a force past the float range on one limb of the second figure (in the first group)
// before that step: the fault guard stops the limb, its tree cannot be filled, and its joints go to
// the Gauss-Seidel passes for the step while the other three trees of its group solve in their lanes.
std::vector<std::vector<unsigned char>> run(int steps, int workers, std::uint32_t* groups = nullptr,
                                            int faultAt = -1, std::size_t* faults = nullptr) {
  WorldDef def;
  def.workerCount = workers;
  World world(def);
  world.createBody(test::groundBox());
  std::vector<BodyId> bodies;
  for (int i = 0; i < 9; ++i)
    addFigure(world, Vec3(1.5f * float(i % 3), 1.0f + 0.4f * float(i), 1.5f * float(i / 3)),
              1.0f + 0.7f * float(i), bodies);
  std::vector<std::vector<unsigned char>> states;
  for (int step = 0; step < steps; ++step) {
    if (step == faultAt) {
      const BodyId limb = bodies[9 + 3];  // the second figure's third limb box
      for (int i = 0; i < 2; ++i) world.applyForce(limb, Vec3(3.0e38f, 0.0f, 0.0f), world.centerOfMass(limb));
    }
    world.step(kDt);
    if (faults != nullptr) *faults += world.faultEvents().size();
    states.push_back(test::stateBytes(world, bodies));
  }
  if (groups != nullptr) *groups = detail::lastTreeLaneGroups();
  return states;
}

// The first step whose state differs, or -1.
int firstDifference(const std::vector<std::vector<unsigned char>>& a,
                    const std::vector<std::vector<unsigned char>>& b) {
  for (std::size_t i = 0; i < a.size(); ++i)
    if (i >= b.size() || a[i] != b[i]) return static_cast<int>(i);
  return -1;
}

constexpr int kSteps = 150;

TEST(JointTreeLanes, GroupsOfTreesEndWhereTheTreesAloneEnd) {
  detail::setTreeLanes(false);
  std::uint32_t groups = 1;
  const auto alone = run(kSteps, 1, &groups);
  detail::setTreeLanes(true);
  EXPECT_EQ(groups, 0u);
  const auto grouped = run(kSteps, 1, &groups);
  EXPECT_EQ(groups, 2u);
  EXPECT_EQ(firstDifference(grouped, alone), -1);
  // The figures did tumble: their limbs moved against the torso (a still world would pass anything).
  EXPECT_NE(alone.front(), alone.back());
  // On two workers the groups are shared out; the same state.
  EXPECT_EQ(firstDifference(run(kSteps, 2), alone), -1);
}

TEST(JointTreeLanes, ATreeOfAGroupThatCannotBeFilledLeavesTheOthersAsAlone) {
  constexpr int kFaultAt = 40;
  std::size_t faults = 0;
  detail::setTreeLanes(false);
  const auto alone = run(kSteps, 1, nullptr, kFaultAt, &faults);
  detail::setTreeLanes(true);
  EXPECT_EQ(faults, 1u);
  faults = 0;
  const auto grouped = run(kSteps, 1, nullptr, kFaultAt, &faults);
  EXPECT_EQ(faults, 1u);
  EXPECT_EQ(firstDifference(grouped, alone), -1);
  // The fault changed the run (it is not the one without it).
  EXPECT_NE(firstDifference(run(kSteps, 1), alone), -1);
}

TEST(JointTreeLanes, TheBaselineKernelsGiveWhatTheAvxOnesGive) {
  const auto chosen = run(kSteps, 1);
  detail::setTreeLanesBaselineOnly(true);
  const auto baseline = run(kSteps, 1);
  detail::setTreeLanesBaselineOnly(false);
  EXPECT_EQ(firstDifference(baseline, chosen), -1);
}

}  // namespace
}  // namespace collide
