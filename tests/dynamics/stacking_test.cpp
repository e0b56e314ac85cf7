// Resting contact and stacking: what the soft step, warm starting and relaxing are for.
#include "world/world_helpers.h"

#include <collide/narrowphase.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

namespace collide {
namespace {

constexpr float kDt = 1.0f / 60.0f;

// Box on box needs a face manifold (several points); a single GJK/EPA point cannot hold a box up.
bool boxBoxHasFaceManifold() {
  return pairInfo(ShapeType::Box, ShapeType::Box).algorithm == PairAlgorithm::Sat;
}

void expectRestingBoxStill(const BodyDef& ground) {
  World world;
  world.createBody(ground);
  const BodyId box = world.createBody(test::boxBody(Vec3(0.0f, 0.5f, 0.0f), Vec3(0.5f), 1.0f));
  float largestLateSpeed = 0.0f;
  for (int i = 0; i < 600; ++i) {
    world.step(kDt);
    if (i >= 500) largestLateSpeed = std::max(largestLateSpeed, glm::length(world.linearVelocity(box)));
  }
  const Transform t = world.transform(box);
  // Resting penetration settles at about the linear slop's order; drift beyond 1 mm is a bug.
  std::printf("resting box drift %g m, largest late speed %g m/s\n",
              glm::length(t.position - Vec3(0.0f, 0.5f, 0.0f)), largestLateSpeed);
  EXPECT_LT(glm::length(t.position - Vec3(0.0f, 0.5f, 0.0f)), 1e-3f);
  EXPECT_LT(largestLateSpeed, 1e-3f);  // no jitter: under 1 mm/s over the last 100 steps (issue 5)
  EXPECT_LT(glm::length(world.angularVelocity(box)), 1e-2f);
}

TEST(Stacking, BoxRestingOnGroundPlaneDoesNotDrift) { expectRestingBoxStill(test::groundPlane()); }

TEST(Stacking, BoxRestingOnGroundBoxDoesNotDrift) {
  ASSERT_TRUE(boxBoxHasFaceManifold()) << "box-box needs SAT with clipping";
  expectRestingBoxStill(test::groundBox());
}

// The top box of a scene that should stand still: how far it moved per axis after `steps` steps.
struct StandingResult {
  Vec3 topDisplacement{0.0f};
  float largestFinalSpeed = 0.0f;
  double millisecondsPerStep = 0.0;
};

StandingResult runStanding(const std::vector<Vec3>& centres, int steps) {
  World world;
  world.createBody(test::groundBox());
  std::vector<BodyId> boxes;
  std::size_t top = 0;
  for (std::size_t i = 0; i < centres.size(); ++i) {
    boxes.push_back(world.createBody(test::boxBody(centres[i], Vec3(0.5f), 1.0f)));
    if (centres[i].y > centres[top].y) top = i;
  }
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < steps; ++i) world.step(kDt);
  const auto stop = std::chrono::steady_clock::now();
  StandingResult result;
  result.millisecondsPerStep = std::chrono::duration<double, std::milli>(stop - start).count() / steps;
  result.topDisplacement = world.transform(boxes[top]).position - centres[top];
  for (const BodyId id : boxes)
    result.largestFinalSpeed = std::max(result.largestFinalSpeed, glm::length(world.linearVelocity(id)));
  return result;
}

// The stack's sag is the soft contacts' steady state: a resting point carrying force F is compressed
// by F / (m_eff omega^2) (in steady state the biased solve adds no impulse, whatever the damping ratio).
// A unit cube's corner point has m_eff = 1/8 against another cube (inverse masses 1 + 1 plus the
// turning terms 3 + 3) and 1/4 against the ground (whose spring is twice the hertz); each of the four
// points of the contact under k boxes carries k g / 4. Summed over the stack: (2 (1 + ... + 9) + 2.5)
// g / omega^2. A measured sag that differs means the solver is not at rest or not the model it claims.
TEST(Stacking, TenBoxStackSagsByTheSoftContactsPrediction) {
  ASSERT_TRUE(boxBoxHasFaceManifold()) << "box-box needs SAT with clipping";
  std::vector<Vec3> centres;
  for (int i = 0; i < 10; ++i) centres.emplace_back(0.0f, 0.5f + static_cast<float>(i), 0.0f);
  const StandingResult r = runStanding(centres, 600);
  const WorldDef def;
  const float h = kDt / static_cast<float>(def.substeps);
  const float omega = 2.0f * kPi * std::min(def.contact.hertz, 0.25f / h);
  const float predicted = (90.0f + 2.5f) * 9.81f / (omega * omega);
  std::printf("stack sag %g m, predicted %g m\n", -r.topDisplacement.y, predicted);
  EXPECT_NEAR(-r.topDisplacement.y, predicted, 0.05f * predicted);
  EXPECT_LT(r.largestFinalSpeed, 1e-2f);  // no jitter
}

// Disabled until they pass with a margin (no loosened thresholds); run with
// --gtest_also_run_disabled_tests. Release, 600 steps of 1/60 s, with the defaults (90 Hz, damping
// ratio 0.5, 6 substeps, 2 relax passes): the 10-stack's top box ends (0.98, -0.28, 0.40) cm off, the
// R3 pyramid's (0.53, -0.87, -0.65) cm; both under 1 cm but the sideways walk (x, z) is chaotic in the
// settings (0.1 to 1.5 cm across nearby ones), so a pass would be luck. The sag (y) is the soft
// contact's spring and now small; the walk is what is left (docs/architecture.md, "Stacking").
TEST(Stacking, DISABLED_TenBoxStackStandsForTenSeconds) {
  ASSERT_TRUE(boxBoxHasFaceManifold()) << "box-box needs SAT with clipping";
  std::vector<Vec3> centres;
  for (int i = 0; i < 10; ++i) centres.emplace_back(0.0f, 0.5f + static_cast<float>(i), 0.0f);
  const StandingResult r = runStanding(centres, 600);
  std::printf("stack top displacement (%g, %g, %g) largest speed %g, %.3f ms/step\n", r.topDisplacement.x,
              r.topDisplacement.y, r.topDisplacement.z, r.largestFinalSpeed, r.millisecondsPerStep);
  EXPECT_LT(std::abs(r.topDisplacement.x), 1e-2f);
  EXPECT_LT(std::abs(r.topDisplacement.y), 1e-2f);
  EXPECT_LT(std::abs(r.topDisplacement.z), 1e-2f);
}

// Reference scene R3 (/work/shared/reference-scenes.md): 465 unit cubes in rows of 30..1.
TEST(Stacking, DISABLED_PyramidR3StandsForTenSeconds) {
  ASSERT_TRUE(boxBoxHasFaceManifold()) << "box-box needs SAT with clipping";
  std::vector<Vec3> centres;
  for (int r = 0; r < 30; ++r) {
    const int n = 30 - r;
    for (int i = 0; i < n; ++i)
      centres.emplace_back(static_cast<float>(i) - 0.5f * static_cast<float>(n - 1),
                           0.5f + static_cast<float>(r), 0.0f);
  }
  const StandingResult r = runStanding(centres, 600);
  std::printf("pyramid top displacement (%g, %g, %g) largest speed %g, %.3f ms/step\n", r.topDisplacement.x,
              r.topDisplacement.y, r.topDisplacement.z, r.largestFinalSpeed, r.millisecondsPerStep);
  EXPECT_LT(std::abs(r.topDisplacement.x), 1e-2f);
  EXPECT_LT(std::abs(r.topDisplacement.y), 1e-2f);
  EXPECT_LT(std::abs(r.topDisplacement.z), 1e-2f);
}

}  // namespace
}  // namespace collide
