// The contact solver's own promises: the colouring, lanes that give what one constraint alone gives,
// and the friction patch (static friction that holds on a slope, sliding at the Coulomb rate, twist).
#include "dynamics/contact_solver.h"
#include "dynamics/constraint_graph.h"
#include "support/collide_error.h"
#include "support/world_helpers.h"

#include <collide/world.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <set>
#include <vector>

namespace collide {
namespace {

using test::kDt;

TEST(ConstraintGraph, NoColourHasTwoConstraintsOnOneDynamicBody) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> body(-3, 199);  // negative: a body the solver never writes
  Array<std::array<std::int32_t, 2>> constraints(3000);
  for (auto& c : constraints) {
    do c = {body(rng), body(rng)};
    while (c[0] == c[1]);  // a contact joins two bodies
  }
  Array<std::uint8_t> colors;
  Array<std::uint64_t> bits;
  detail::colorConstraints(constraints, 200, colors, bits);
  ASSERT_EQ(colors.size(), constraints.size());
  Array<std::set<std::int32_t>> used(detail::kGraphColors);
  for (std::size_t i = 0; i < constraints.size(); ++i) {
    if (colors[i] == detail::kOverflowColor) continue;
    for (const std::int32_t b : constraints[i]) {
      if (b < 0) continue;
      EXPECT_TRUE(used[colors[i]].insert(b).second) << "body " << b << " twice in colour " << int(colors[i]);
    }
    // Box2D v3's rule: a constraint on a static or kinematic body never takes colour 0.
    if (constraints[i][0] < 0 || constraints[i][1] < 0) {
      EXPECT_NE(colors[i], 0);
    }
  }
  // The same input gives the same colours.
  Array<std::uint8_t> again;
  detail::colorConstraints(constraints, 200, again, bits);
  EXPECT_EQ(colors, again);
}

TEST(ConstraintGraph, ABodyInMoreConstraintsThanColoursOverflows) {
  // 30 constraints all on body 0: the first colours hold one each, the rest overflow.
  Array<std::array<std::int32_t, 2>> constraints;
  for (int i = 1; i <= 30; ++i) constraints.push_back({0, i});
  Array<std::uint8_t> colors;
  Array<std::uint64_t> bits;
  detail::colorConstraints(constraints, 31, colors, bits);
  for (int i = 0; i < 30; ++i)
    EXPECT_EQ(colors[i], i < detail::kGraphColors ? i : detail::kOverflowColor) << "constraint " << i;
  // Static partners never conflict: all of them fit in colour 1.
  for (auto& c : constraints) c[1] = -1;
  for (int i = 0; i < 30; ++i) constraints[i][0] = i;
  detail::colorConstraints(constraints, 31, colors, bits);
  for (const std::uint8_t c : colors) EXPECT_EQ(c, 1);
}

// Four boxes falling onto the ground far apart land in one colour, hence in one batch of four lanes.
// Each must end bit for bit as it does alone in its own world: the lanes are independent solves.
TEST(ContactSolver, LanesGiveWhatEachContactGivesAlone) {
  Array<BodyDef> boxes;
  for (int i = 0; i < 4; ++i) {
    BodyDef def =
        test::boxBody(Vec3(10.0f * static_cast<float>(i), 0.6f + 0.1f * static_cast<float>(i), 0.0f),
                      Vec3(0.5f, 0.25f + 0.05f * static_cast<float>(i), 0.4f), 1.0f + static_cast<float>(i));
    def.rotation = glm::normalize(Quat(1.0f, 0.05f * static_cast<float>(i), 0.1f, -0.02f));
    def.linearVelocity = Vec3(0.5f * static_cast<float>(i), 0.0f, -0.3f);
    def.angularVelocity = Vec3(0.0f, 1.0f, 0.2f * static_cast<float>(i));
    boxes.push_back(def);
  }
  World together;
  together.createBody(test::groundBox());
  Array<BodyId> ids;
  for (const BodyDef& def : boxes) ids.push_back(together.createBody(def));
  for (int s = 0; s < 120; ++s) together.step(kDt);
  for (int i = 0; i < 4; ++i) {
    World alone;
    alone.createBody(test::groundBox());
    const BodyId id = alone.createBody(boxes[i]);
    for (int s = 0; s < 120; ++s) alone.step(kDt);
    const Transform a = alone.transform(id);
    const Transform t = together.transform(ids[i]);
    EXPECT_EQ(std::memcmp(&a.position, &t.position, sizeof(Vec3)), 0) << "box " << i;
    EXPECT_EQ(std::memcmp(&a.rotation, &t.rotation, sizeof(Quat)), 0) << "box " << i;
    const Vec3 va = alone.linearVelocity(id), vt = together.linearVelocity(ids[i]);
    EXPECT_EQ(std::memcmp(&va, &vt, sizeof(Vec3)), 0) << "box " << i;
  }
}

// Four and eight lanes (where the processor runs the AVX2 kernel) solve the same pile of boxes, bit
// for bit: the batches differ, the colours and every lane's arithmetic do not.
TEST(ContactSolver, EveryLaneWidthGivesTheSameResult) {
  const auto run = [](int laneWidth) {
    detail::setDefaultContactLanes(laneWidth);
    World world;
    detail::setDefaultContactLanes(0);
    world.createBody(test::groundBox());
    Array<BodyId> ids;
    for (int i = 0; i < 60; ++i) {
      BodyDef def =
          test::boxBody(Vec3(0.3f * static_cast<float>(i % 5), 0.5f + 1.05f * static_cast<float>(i / 5),
                             0.2f * static_cast<float>(i % 3)),
                        Vec3(0.5f, 0.4f, 0.45f), 1.0f + 0.1f * static_cast<float>(i % 4));
      def.angularVelocity = Vec3(0.1f * static_cast<float>(i % 3), 0.0f, 0.05f);
      ids.push_back(world.createBody(def));
    }
    for (int s = 0; s < 200; ++s) world.step(kDt);
    Array<float> state;
    for (const BodyId id : ids) {
      const Transform t = world.transform(id);
      const Vec3 v = world.linearVelocity(id);
      state.insert(state.end(), {t.position.x, t.position.y, t.position.z, t.rotation.x, t.rotation.y,
                                 t.rotation.z, t.rotation.w, v.x, v.y, v.z});
    }
    return state;
  };
  const Array<float> four = run(4);
  if (detail::widestContactLanes() < 8) GTEST_SKIP() << "no AVX2 here: only the four-lane kernel runs";
  const Array<float> eight = run(8);
  ASSERT_EQ(four.size(), eight.size());
  EXPECT_EQ(std::memcmp(four.data(), eight.data(), four.size() * sizeof(float)), 0);
}

TEST(ContactSolver, AnUnavailableLaneWidthIsRefused) {
  EXPECT_COLLIDE_ERROR(detail::ContactSolver(3));
  EXPECT_COLLIDE_ERROR(detail::ContactSolver(16));
}

// A static ramp of slope theta (the reference scenes' ground box, turned about z) and a unit cube
// resting on it; returns how far the cube moved down the slope in `seconds`.
float slideDownRamp(float slopeRadians, float friction, float seconds) {
  World world;
  const Quat turn = glm::angleAxis(slopeRadians, Vec3(0.0f, 0.0f, 1.0f));
  BodyDef ramp = test::groundBox();
  ramp.position = Vec3(0.0f);
  ramp.rotation = turn;
  ramp.friction = friction;
  world.createBody(ramp);
  BodyDef box = test::boxBody(turn * Vec3(0.0f, 1.0f, 0.0f), Vec3(0.5f), 1.0f);
  box.rotation = turn;
  box.friction = friction;
  const BodyId id = world.createBody(box);
  const int steps = static_cast<int>(std::lround(seconds / kDt));
  for (int i = 0; i < steps; ++i) world.step(kDt);
  const Vec3 downhill = turn * Vec3(-1.0f, 0.0f, 0.0f);
  return glm::dot(world.transform(id).position - box.position, downhill);
}

// Static friction: on a 20 degree slope (tan 20 = 0.36) a box with mu = 0.5 holds. Velocity-level
// friction alone lets it creep by the solver's residual every step; the static anchor holds it.
TEST(ContactSolver, BoxBelowTheFrictionAngleStaysPutForTenSeconds) {
  const float moved = slideDownRamp(20.0f * kPi / 180.0f, 0.5f, 10.0f);
  EXPECT_LT(std::abs(moved), 1e-3f) << "moved " << moved << " m down the slope";
}

// Kinetic friction: above the friction angle the box slides with a = g (sin theta - mu cos theta).
TEST(ContactSolver, BoxAboveTheFrictionAngleSlidesAtTheCoulombRate) {
  const float theta = 20.0f * kPi / 180.0f;
  const float mu = 0.2f;
  const float t = 1.0f;
  const float expected = 0.5f * 9.81f * (std::sin(theta) - mu * std::cos(theta)) * t * t;
  const float moved = slideDownRamp(theta, mu, t);
  EXPECT_NEAR(moved, expected, 0.03f * expected);
}

// Twist friction: a unit cube spun about the vertical on the ground stops after turning
// w0^2 / (2 alpha), alpha = mu m g r / I. For a uniformly pressed square r is the mean distance of
// its area from the centre, 0.3826 of the side (docs: kTwistRadiusScale), and I = m / 6.
TEST(ContactSolver, SpinningBoxStopsByTwistFriction) {
  World world;
  BodyDef ground = test::groundBox();
  ground.friction = 0.5f;
  world.createBody(ground);
  BodyDef box = test::boxBody(Vec3(0.0f, 0.5f, 0.0f), Vec3(0.5f), 1.0f);
  box.friction = 0.5f;
  box.angularVelocity = Vec3(0.0f, 4.0f, 0.0f);
  const BodyId id = world.createBody(box);
  float angle = 0.0f;
  Quat previous = world.transform(id).rotation;
  for (int i = 0; i < 120; ++i) {
    world.step(kDt);
    const Quat now = world.transform(id).rotation;
    angle += 2.0f * std::asin(std::min(1.0f, std::abs((now * glm::conjugate(previous)).y)));
    previous = now;
  }
  EXPECT_LT(glm::length(world.angularVelocity(id)), 1e-2f);
  const float alpha = 0.5f * 9.81f * 0.3826f / (1.0f / 6.0f);
  const float expected = 16.0f / (2.0f * alpha);
  EXPECT_NEAR(angle, expected, 0.05f * expected);
}

}  // namespace
}  // namespace collide
