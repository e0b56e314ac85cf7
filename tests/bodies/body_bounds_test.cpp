// The bounds stage (src/bodies/body_bounds.cpp): a body's proxy box holds its shape wherever the
// step can carry it, and the motion bound that lets a resting body keep its old box is a true bound.
#include <collide/broadphase.h>

#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "base/task_runner.h"
#include "bodies/body_bounds.h"
#include "bodies/body_def.h"
#include "support/test_random.h"

namespace collide {
namespace {

using detail::BodyStorage;

std::uint32_t addBody(BodyStorage& bodies, const BodyDef& def) {
  const std::uint32_t index = bodies.allocate();
  detail::initBody(def, bodies.records[index], bodies.states[index]);
  return index;
}

BodyDef crate() {
  BodyDef def;
  def.shape = Shape(Box{Vec3(0.5f, 0.25f, 1.0f)});
  def.position = Vec3(1.0f, 2.0f, -1.0f);
  def.rotation = glm::angleAxis(0.4f, glm::normalize(Vec3(1.0f, 2.0f, 3.0f)));
  return def;
}

// The crate's corners, in the world, at its body's pose.
std::vector<Vec3> corners(const BodyStorage& bodies, std::uint32_t index) {
  const Transform t = detail::bodyTransform(bodies.records[index], bodies.states[index]);
  const Vec3 h = bodies.records[index].shape.box().halfExtents;
  std::vector<Vec3> out;
  for (int i = 0; i < 8; ++i)
    out.push_back(t.applyToPoint(Vec3(i & 1 ? h.x : -h.x, i & 2 ? h.y : -h.y, i & 4 ? h.z : -h.z)));
  return out;
}

TEST(BodyBounds, MotionBoundIsNeverBelowAnyPointsMotion) {
  BodyStorage bodies;
  const std::uint32_t index = addBody(bodies, crate());
  std::mt19937 rng(5);
  for (int trial = 0; trial < 1000; ++trial) {
    detail::BodyState& s = bodies.states[index];
    const Vec3 com0 = s.centerOfMass;
    const Quat q0 = s.rotation;
    const std::vector<Vec3> before = corners(bodies, index);
    s.centerOfMass += 0.1f * test::randomUnitVector(rng) * float(trial % 7);
    s.rotation =
        glm::normalize(glm::angleAxis(0.01f * float(trial % 50), test::randomUnitVector(rng)) * s.rotation);
    const std::vector<Vec3> after = corners(bodies, index);
    const float bound = detail::pointMotionBound(bodies.records[index], com0, q0, s.centerOfMass, s.rotation);
    for (int k = 0; k < 8; ++k) EXPECT_LE(glm::length(after[k] - before[k]), bound * (1.0f + 1e-5f) + 1e-6f);
  }
}

TEST(BodyBounds, ProxyHoldsTheShapeAlongTheStepsMotion) {
  BodyStorage bodies;
  BodyDef def = crate();
  def.linearVelocity = Vec3(3.0f, -1.0f, 0.5f);
  const std::uint32_t index = addBody(bodies, def);
  auto broadPhase = createBroadPhase();
  ProxyDef proxy;
  proxy.bounds = detail::proxyBounds(bodies, index, 0.0f, 0.02f);
  proxy.motion = MotionType::Movable;
  proxy.userValue = index;
  bodies.records[index].proxy = broadPhase->add(proxy);
  const float dt = 1.0f / 60.0f, speculative = 0.02f;
  detail::TaskRunner tasks;
  detail::ProxyUpdate update;
  update.run(bodies, *broadPhase, dt, speculative, tasks);
  const Aabb box = broadPhase->bounds(bodies.records[index].proxy);
  // The crate where it is and where the step's velocity takes it, plus the speculative distance.
  for (const Vec3& c : corners(bodies, index)) {
    // (The box is grown by exactly the speculative distance: 1 % less keeps rounding out of it.)
    const Vec3 reach(0.99f * speculative);
    EXPECT_TRUE(box.contains(Aabb{c - reach, c + reach}));
    const Vec3 moved = c + dt * def.linearVelocity;
    EXPECT_TRUE(box.contains(Aabb{moved - reach, moved + reach}));
  }
}

// The boxes are computed in parallel ranges: at 1 and at 3 workers every proxy gets the same box,
// bit for bit, and each holds its body's box computed anew (many bodies, so that many ranges run;
// some moved less than the reuse distance since their box, some more, some asleep).
TEST(BodyBounds, ProxiesAreTheSameAtEveryWorkerCount) {
  constexpr std::uint32_t kBodies = 5000;
  const float dt = 1.0f / 60.0f, speculative = 0.02f;
  std::vector<Aabb> boxes[2];
  for (int run = 0; run < 2; ++run) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    BodyStorage bodies;
    auto broadPhase = createBroadPhase();
    for (std::uint32_t i = 0; i < kBodies; ++i) {
      BodyDef def = crate();
      def.position = Vec3(40.0f * unit(rng), 40.0f * unit(rng), 40.0f * unit(rng));
      def.linearVelocity = Vec3(5.0f * unit(rng), 5.0f * unit(rng), 5.0f * unit(rng));
      def.angularVelocity = Vec3(3.0f * unit(rng), 0.0f, 3.0f * unit(rng));
      const std::uint32_t index = addBody(bodies, def);
      ProxyDef proxy;
      proxy.bounds = detail::proxyBounds(bodies, index, 0.0f, speculative);
      proxy.motion = MotionType::Movable;
      proxy.userValue = index;
      bodies.records[index].proxy = broadPhase->add(proxy);
      // A third moved under the reuse distance since that box, a third well past it.
      if (i % 3 == 1) bodies.states[index].centerOfMass += Vec3(0.0005f, 0.0f, 0.0f);
      if (i % 3 == 2) bodies.states[index].centerOfMass += Vec3(0.0f, 0.3f, 0.0f);
      if (i % 11 == 0) bodies.records[index].awake = false;
    }
    detail::TaskRunner tasks;
    tasks.configure(run == 0 ? 1 : 3, nullptr, nullptr, nullptr);
    detail::ProxyUpdate update;
    update.run(bodies, *broadPhase, dt, speculative, tasks);
    for (std::uint32_t i = 0; i < kBodies; ++i) {
      boxes[run].push_back(broadPhase->bounds(bodies.records[i].proxy));
      const Aabb exact =
          worldBounds(bodies.records[i].shape, detail::bodyTransform(bodies.records[i], bodies.states[i]));
      if (bodies.records[i].awake) {
        EXPECT_TRUE(boxes[run].back().contains(exact)) << "body " << i;
      }
    }
  }
  for (std::uint32_t i = 0; i < kBodies; ++i) {
    EXPECT_EQ(std::memcmp(&boxes[0][i], &boxes[1][i], sizeof(Aabb)), 0) << "body " << i;
  }
}

TEST(BodyBounds, ABarelyMovedBodyKeepsABoxThatStillHoldsIt) {
  BodyStorage bodies;
  const std::uint32_t index = addBody(bodies, crate());
  const Aabb exact0 = detail::recomputeBounds(bodies, index);
  // Moved 1 mm and turned a little: under the 2 mm reuse distance, the old box grown stands in.
  bodies.states[index].centerOfMass += Vec3(0.001f, 0.0f, 0.0f);
  bodies.states[index].rotation =
      glm::normalize(glm::angleAxis(1e-4f, Vec3(0, 1, 0)) * bodies.states[index].rotation);
  const Aabb box = detail::currentBounds(bodies, index);
  EXPECT_TRUE(box.contains(exact0));
  for (const Vec3& c : corners(bodies, index)) EXPECT_TRUE(box.contains(c));
  // Moved 5 cm: computed anew, and exact again.
  bodies.states[index].centerOfMass += Vec3(0.05f, 0.0f, 0.0f);
  const Aabb fresh = detail::currentBounds(bodies, index);
  const Aabb exact = worldBounds(bodies.records[index].shape,
                                 detail::bodyTransform(bodies.records[index], bodies.states[index]));
  EXPECT_EQ(fresh.min, exact.min);
  EXPECT_EQ(fresh.max, exact.max);
}

}  // namespace
}  // namespace collide
