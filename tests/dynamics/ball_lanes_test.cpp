// The ball joints' SIMD lanes (src/dynamics/joints/ball_joint.cpp) against the joint-at-a-time
// path they stand in for: four joints of a wave, warm-started and solved in lanes, leave the bodies'
// velocities and the joints' impulses bit for bit as warmStartBall and solveBall do one after
// another, for every kind of end (dynamic, static, kinematic, stopped by the fault guard), soft and
// rigid joints, the biased and the relax pass, and a joint between two bodies without mass (its
// block is singular: it changes nothing).
#include "dynamics/joints/joint_rows.h"

#include <gtest/gtest.h>

#include <cstring>
#include <random>

namespace collide {
namespace {

using detail::Joint;
using detail::SolverBody;

// What one end is.
enum class End { Dynamic, Static, Kinematic, Stopped };

struct Bench {
  detail::BodyStorage storage;
  Array<SolverBody> bodies;
  Array<detail::SolverBodyInfo> infos;
  Array<detail::SolverBodyStart> starts;
  Array<std::int32_t> solverOf;
  Array<Joint> joints;

  detail::JointSolverView view() { return {bodies, infos, starts, solverOf, storage}; }
};

Quat randomRotation(std::mt19937& rng) {
  std::normal_distribution<float> n(0.0f, 1.0f);
  return glm::normalize(Quat(n(rng), n(rng), n(rng), n(rng)));
}

Vec3 randomVec(std::mt19937& rng, float scale) {
  std::uniform_real_distribution<float> u(-scale, scale);
  return {u(rng), u(rng), u(rng)};
}

// A body of the given kind, at a random pose and motion; returns its storage index.
std::uint32_t addEnd(Bench& b, End kind, std::mt19937& rng) {
  const auto index = static_cast<std::uint32_t>(b.storage.states.size());
  b.storage.records.emplace_back();
  detail::BodyState& state = b.storage.states.emplace_back();
  state.centerOfMass = randomVec(rng, 5.0f);
  state.rotation = randomRotation(rng);
  if (kind == End::Static) {
    b.solverOf.push_back(detail::kNoSolverBody);
    return index;
  }
  b.solverOf.push_back(static_cast<std::int32_t>(b.bodies.size()));
  SolverBody& body = b.bodies.emplace_back();
  body.linearVelocity = randomVec(rng, 3.0f);
  body.angularVelocity = randomVec(rng, 2.0f);
  body.deltaPosition = randomVec(rng, 0.05f);
  body.deltaRotation =
      glm::normalize(glm::angleAxis(0.03f, glm::normalize(randomVec(rng, 1.0f) + Vec3(0.01f))));
  detail::SolverBodyInfo& info = b.infos.emplace_back();
  info.body = index;
  info.dynamic = kind != End::Kinematic;
  info.faulted = kind == End::Stopped;
  if (info.dynamic) {
    info.inverseMass = 1.0f / (0.5f + std::uniform_real_distribution<float>(0.0f, 4.0f)(rng));
    const Mat3 r = glm::mat3_cast(randomRotation(rng));
    const Vec3 principal = Vec3(0.5f) + glm::abs(randomVec(rng, 3.0f));
    info.inverseInertiaWorld =
        r * Mat3(principal.x, 0, 0, 0, principal.y, 0, 0, 0, principal.z) * glm::transpose(r);
  }
  detail::SolverBodyStart& start = b.starts.emplace_back();
  start.centerOfMass = state.centerOfMass;
  start.rotation = state.rotation;
  return index;
}

// Four ball joints with the given ends (one new body per end, so that no two share a body).
Bench fourJoints(const End (&ends)[4][2], std::uint32_t seed) {
  std::mt19937 rng(seed);
  Bench b;
  for (int j = 0; j < 4; ++j) {
    Joint& joint = b.joints.emplace_back();
    joint.type = JointType::Ball;
    joint.alive = joint.active = true;
    joint.bodyA = addEnd(b, ends[j][0], rng);
    joint.bodyB = addEnd(b, ends[j][1], rng);
    joint.localAnchorA = randomVec(rng, 0.6f);
    joint.localAnchorB = randomVec(rng, 0.6f);
    joint.linearImpulse = randomVec(rng, 2.0f);
    joint.frictionImpulse = j == 1 ? Vec3(0.0f) : randomVec(rng, 0.1f);
    if (j == 2) joint.softness = JointSoftness{5.0f, 0.7f};
  }
  return b;
}

bool sameBits(const Bench& a, const Bench& b) {
  if (std::memcmp(a.bodies.data(), b.bodies.data(), a.bodies.size() * sizeof(SolverBody)) != 0) return false;
  for (std::size_t j = 0; j < a.joints.size(); ++j) {
    if (std::memcmp(&a.joints[j].linearImpulse, &b.joints[j].linearImpulse, sizeof(Vec3)) != 0) return false;
  }
  return true;
}

// The lanes on the joints themselves, as the waves take them: gathered into a group, solved, the
// impulses stored back.
void warmStartInLanes(Bench& bench, const std::uint32_t (&which)[4]) {
  detail::BallLaneGroup group;
  detail::loadBallGroup(bench.joints, which, group);
  detail::warmStartBalls(bench.view(), group);
}
void solveInLanes(Bench& bench, const std::uint32_t (&which)[4], float h, float rigidHertz, bool useBias) {
  detail::BallLaneGroup group;
  detail::loadBallGroup(bench.joints, which, group);
  detail::solveBalls(bench.view(), group, h, rigidHertz, useBias);
  detail::storeBallGroup(group, bench.joints);
}

void expectLanesMatchOneAtATime(const End (&ends)[4][2]) {
  constexpr float kH = 1.0f / 360.0f;
  constexpr float kRigidHertz = 60.0f;
  for (std::uint32_t seed = 1; seed <= 20; ++seed) {
    SCOPED_TRACE(seed);
    Bench one = fourJoints(ends, seed);
    Bench lanes = fourJoints(ends, seed);
    const std::uint32_t which[4] = {0, 1, 2, 3};
    for (Joint& joint : one.joints) detail::warmStartBall(one.view(), joint);
    warmStartInLanes(lanes, which);
    EXPECT_TRUE(sameBits(one, lanes)) << "warm start";
    for (const bool useBias : {true, false}) {
      for (Joint& joint : one.joints) detail::solveBall(one.view(), joint, kH, kRigidHertz, useBias);
      solveInLanes(lanes, which, kH, kRigidHertz, useBias);
      EXPECT_TRUE(sameBits(one, lanes)) << (useBias ? "biased pass" : "relax pass");
    }
  }
}

TEST(BallLanes, FourJointsInLanesGiveWhatOneAfterAnotherGives) {
  expectLanesMatchOneAtATime({{End::Dynamic, End::Dynamic},
                              {End::Static, End::Dynamic},
                              {End::Dynamic, End::Kinematic},
                              {End::Stopped, End::Dynamic}});
}

TEST(BallLanes, AJointWithoutMassChangesNothingAndItsNeighboursStillSolve) {
  // Lane 1 joins a static body to a kinematic one: its point block is zero, its determinant 0.
  expectLanesMatchOneAtATime({{End::Dynamic, End::Static},
                              {End::Static, End::Kinematic},
                              {End::Kinematic, End::Dynamic},
                              {End::Dynamic, End::Stopped}});
  const End ends[4][2] = {{End::Static, End::Kinematic},
                          {End::Static, End::Kinematic},
                          {End::Stopped, End::Static},
                          {End::Kinematic, End::Kinematic}};
  Bench lanes = fourJoints(ends, 3);
  const Bench before = fourJoints(ends, 3);
  const std::uint32_t which[4] = {0, 1, 2, 3};
  solveInLanes(lanes, which, 1.0f / 360.0f, 60.0f, true);
  EXPECT_TRUE(sameBits(before, lanes));
}

}  // namespace
}  // namespace collide
