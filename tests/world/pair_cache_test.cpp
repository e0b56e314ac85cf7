// The world's shortcuts before the collider test: the manifold cache (a pair that has not moved
// relative to itself keeps its manifold), the bounding-sphere reject and the separating-axis cache
// (a pair found apart is tested first along the axis that separated it). Each may save work; none may
// change what the pair's contact is.
#include "support/world_helpers.h"

#include <collide/narrowphase.h>
#include <collide/world.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

namespace collide {
namespace {

using test::kDt;

Shape rock(unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> normal(0.0f, 1.0f);
  std::vector<Vec3> points;
  for (int i = 0; i < 12; ++i) {
    const float x = normal(rng), y = normal(rng), z = normal(rng);
    points.push_back(0.5f * glm::normalize(Vec3(x, y, z)));
  }
  return Shape(ConvexHull::fromPoints(points));
}

// A kinematic hull sinks slowly onto a resting one; the pair is apart for many steps first (tested
// along its cached axis), then touches. The first step with a contact must be the first step whose
// poses bring the hulls within the speculative margin, by the exact distance query.
TEST(PairCache, ASeparatingAxisNeverDelaysAContact) {
  World world;
  world.createBody(test::groundBox());
  BodyDef lower;
  lower.shape = rock(1);
  lower.position = Vec3(0.0f, 0.6f, 0.0f);
  lower.mass = 1.0f;
  const BodyId a = world.createBody(lower);
  for (int i = 0; i < 120; ++i) world.step(kDt);  // settled
  BodyDef upper;
  upper.type = BodyType::Kinematic;
  upper.shape = rock(2);
  upper.position = world.transform(a).position + Vec3(0.1f, 1.5f, -0.05f);
  upper.linearVelocity = Vec3(0.0f, -0.2f, 0.0f);
  const BodyId b = world.createBody(upper);

  // The pre-solve callback sees the pair exactly when the narrow phase gave it points this step.
  bool touched = false;
  world.setPreSolveCallback([&](BodyId x, BodyId y, const Manifold&) {
    touched = touched || (x == a && y == b) || (x == b && y == a);
    return true;
  });
  int firstContact = -1;
  int firstWithinMargin = -1;
  for (int step = 0; step < 300 && firstContact < 0; ++step) {
    // The margin the world uses for this pair this step: the speculative distance plus what the pair
    // can close within the step (the lower hull is at rest, the upper moves at 0.2 m/s).
    const float gap = distance(lower.shape, world.transform(a), upper.shape, world.transform(b)).distance;
    const float margin = world.def().contact.speculativeDistance +
                         kDt * glm::length(world.linearVelocity(b) - world.linearVelocity(a));
    if (firstWithinMargin < 0 && gap <= margin) firstWithinMargin = step;
    touched = false;
    world.step(kDt);
    if (touched) firstContact = step;
  }
  std::printf("first within margin: step %d, first contact: step %d\n", firstWithinMargin, firstContact);
  ASSERT_GE(firstWithinMargin, 0);
  EXPECT_LE(firstContact, firstWithinMargin + 1);
  EXPECT_GE(firstContact, firstWithinMargin - 1);
}

// Resting bodies reuse their manifolds: the R3-like stack below, once settled, computes almost none.
TEST(PairCache, RestingStackReusesItsManifolds) {
  World world;
  world.createBody(test::groundBox());
  for (int i = 0; i < 5; ++i) world.createBody(test::boxBody(Vec3(0.0f, 0.5f + i, 0.0f), Vec3(0.5f), 1.0f));
  for (int i = 0; i < 120; ++i) world.step(kDt);
  const StepStats& s = world.lastStats();
  EXPECT_EQ(s.narrowPhaseTests, 5u);
  EXPECT_EQ(s.reusedManifolds, 5u);
}

// With the cache off (distance 0), every pair is computed every step; the stack still stands the
// same to within a millimetre after 2 s, so the cache does not change the physics beyond its
// tolerance.
TEST(PairCache, TheCacheChangesAStackByLessThanItsTolerance) {
  const auto top = [](float cacheDistance) {
    WorldDef def;
    def.contact.manifoldCacheDistance = cacheDistance;
    World world(def);
    world.createBody(test::groundBox());
    BodyId last{};
    for (int i = 0; i < 5; ++i)
      last = world.createBody(test::boxBody(Vec3(0.02f * i, 0.5f + i, 0.0f), Vec3(0.5f), 1.0f));
    for (int i = 0; i < 120; ++i) world.step(kDt);
    EXPECT_EQ(world.lastStats().reusedManifolds, cacheDistance > 0.0f ? 5u : 0u);
    return world.transform(last).position;
  };
  const Vec3 cached = top(WorldDef{}.contact.manifoldCacheDistance);
  const Vec3 computed = top(0.0f);
  EXPECT_LT(glm::length(cached - computed), 1e-3f);
}

}  // namespace
}  // namespace collide
