// Known answers, bad input and ids of the broad-phase interface, run on each algorithm.
#include <collide/broadphase.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "support/collide_error.h"

using namespace collide;

namespace {

class BroadPhaseKnownAnswers : public ::testing::TestWithParam<BroadPhaseType> {
 protected:
  std::unique_ptr<BroadPhase> make() {
    BroadPhaseSettings settings;
    settings.type = GetParam();
    return createBroadPhase(settings);
  }
};

Aabb cube(const Vec3& center, float half) { return Aabb::fromCenterHalfExtents(center, Vec3(half)); }

}  // namespace

TEST_P(BroadPhaseKnownAnswers, LabelsOneWayTwoWayAndNeverStaticStatic) {
  auto bp = make();
  const ProxyId wallA = bp->add({cube(Vec3(0.0f), 1.0f), MotionType::Static});
  const ProxyId wallB =
      bp->add({cube(Vec3(0.5f, 0.0f, 0.0f), 1.0f), MotionType::Static});  // interpenetrating walls
  const ProxyId ball = bp->add({cube(Vec3(1.8f, 0.0f, 0.0f), 0.5f), MotionType::Movable});
  const ProxyId other =
      bp->add({cube(Vec3(2.5f, 0.0f, 0.0f), 0.5f), MotionType::Movable});  // overlaps ball on [2.0, 2.3]
  const ProxyId far = bp->add({cube(Vec3(50.0f), 0.5f), MotionType::Movable});
  Array<ProxyPair> pairs;
  const BroadPhaseStats& stats = bp->findPairs(pairs);
  // ball [1.3, 2.3] overlaps wallB [-0.5, 1.5] and other [2.0, 3.0]; wallA ends at 1.0.
  ASSERT_EQ(pairs.size(), 2u);
  EXPECT_EQ(pairs[0], (ProxyPair{wallB, ball, PairKind::OneWay}));
  EXPECT_EQ(pairs[1], (ProxyPair{ball, other, PairKind::TwoWay}));
  EXPECT_EQ(stats.proxies, 5u);
  EXPECT_EQ(stats.potentialPairs, 10u);
  EXPECT_EQ(stats.keptPairs, 2u);
  (void)wallA;
  (void)far;
}

TEST_P(BroadPhaseKnownAnswers, TouchingBoxesOverlapAndPairsFollowMotion) {
  auto bp = make();
  const ProxyId a = bp->add({Aabb{Vec3(0.0f), Vec3(1.0f)}});
  const ProxyId b = bp->add({Aabb{Vec3(1.0f, 0.0f, 0.0f), Vec3(2.0f, 1.0f, 1.0f)}});  // shares the face x = 1
  Array<ProxyPair> pairs;
  bp->findPairs(pairs);
  ASSERT_EQ(pairs.size(), 1u);
  // Move b away by less than any margin: the pair must go at once (exact, tight-box semantics).
  bp->update(b, Aabb{Vec3(1.01f, 0.0f, 0.0f), Vec3(2.01f, 1.0f, 1.0f)});
  bp->findPairs(pairs);
  EXPECT_TRUE(pairs.empty());
  bp->update(b, Aabb{Vec3(0.5f, 0.5f, 0.5f), Vec3(1.5f, 1.5f, 1.5f)});
  bp->findPairs(pairs);
  ASSERT_EQ(pairs.size(), 1u);
  bp->remove(a);
  bp->findPairs(pairs);
  EXPECT_TRUE(pairs.empty());
  // The freed slot is reused with a new generation; the old pair does not come back.
  const ProxyId c = bp->add({Aabb{Vec3(10.0f), Vec3(11.0f)}});
  EXPECT_EQ(c.index, a.index);
  EXPECT_NE(c.generation, a.generation);
  bp->findPairs(pairs);
  EXPECT_TRUE(pairs.empty());
  bp->validate();
}

TEST_P(BroadPhaseKnownAnswers, RayHitsBoxesAtTheirEntryDistance) {
  auto bp = make();
  const ProxyId near = bp->add({cube(Vec3(5.0f, 0.0f, 0.0f), 0.5f), MotionType::Static, 7, 1});
  const ProxyId farther = bp->add({cube(Vec3(9.0f, 0.0f, 0.0f), 1.0f), MotionType::Movable, 8, 2});
  bp->add({cube(Vec3(5.0f, 3.0f, 0.0f), 0.5f)});  // off the ray
  const Ray ray{Vec3(0.0f), Vec3(1.0f, 0.0f, 0.0f), 100.0f};
  const auto hit = bp->rayCastClosest(ray);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->id, near);
  EXPECT_FLOAT_EQ(hit->distance, 4.5f);
  const auto all = bp->rayCastAll(ray);
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[1].id, farther);
  EXPECT_FLOAT_EQ(all[1].distance, 8.0f);
  // The layer mask skips the near box; a short ray stops before both.
  EXPECT_EQ(bp->rayCastClosest(ray, 2)->id, farther);
  EXPECT_FALSE(bp->rayCastClosest(Ray{Vec3(0.0f), Vec3(1.0f, 0.0f, 0.0f), 4.4f}).has_value());
  // A direction that is not unit length is normalised: distances stay in world units.
  EXPECT_FLOAT_EQ(bp->rayCastClosest(Ray{Vec3(0.0f), Vec3(3.0f, 0.0f, 0.0f), 100.0f})->distance, 4.5f);
  // Starting inside a box: distance 0.
  EXPECT_FLOAT_EQ(bp->rayCastClosest(Ray{Vec3(9.0f, 0.0f, 0.0f), Vec3(0.0f, 1.0f, 0.0f), 1.0f})->distance,
                  0.0f);
}

TEST_P(BroadPhaseKnownAnswers, RayCallbackCanStopTheCast) {
  auto bp = make();
  for (int i = 0; i < 10; ++i) bp->add({cube(Vec3(2.0f * static_cast<float>(i) + 3.0f, 0.0f, 0.0f), 0.5f)});
  int calls = 0;
  bp->rayCast(Ray{Vec3(0.0f), Vec3(1.0f, 0.0f, 0.0f), 1e30f}, kAllLayers, [&](ProxyId, float) {
    ++calls;
    return -1.0f;
  });
  EXPECT_EQ(calls, 1);
}

TEST_P(BroadPhaseKnownAnswers, OverlapQueriesAndLineOfSight) {
  auto bp = make();
  const ProxyId a = bp->add({cube(Vec3(0.0f), 1.0f), MotionType::Static, 0, 1});
  const ProxyId b = bp->add({cube(Vec3(3.0f, 0.0f, 0.0f), 1.0f), MotionType::Movable, 0, 2});
  // Sphere at (5,0,0) radius 1 touches b's face x = 4 exactly; radius 0.99 does not.
  EXPECT_EQ(bp->overlapSphere({Vec3(5.0f, 0.0f, 0.0f), 1.0f}), std::vector<ProxyId>{b});
  EXPECT_TRUE(bp->overlapSphere({Vec3(5.0f, 0.0f, 0.0f), 0.99f}).empty());
  // The corner region: the sphere's box overlaps a's box but the sphere does not touch it.
  EXPECT_TRUE(bp->overlapSphere({Vec3(-1.8f, -1.8f, -1.8f), 1.0f}).empty());
  EXPECT_EQ(bp->overlapAabb(Aabb{Vec3(0.5f), Vec3(2.5f)}), (std::vector<ProxyId>{a, b}));
  EXPECT_EQ(bp->overlapAabb(Aabb{Vec3(0.5f), Vec3(2.5f)}, 2), std::vector<ProxyId>{b});
  // Line of sight across a gap between the boxes (y = 2 passes above both), through a, through a point.
  EXPECT_TRUE(bp->hasLineOfSight(Vec3(-5.0f, 2.0f, 0.0f), Vec3(5.0f, 2.0f, 0.0f)));
  EXPECT_TRUE(bp->isSegmentBlocked(Vec3(-5.0f, 0.0f, 0.0f), Vec3(-0.5f, 0.0f, 0.0f)));
  EXPECT_FALSE(bp->isSegmentBlocked(Vec3(-5.0f, 0.0f, 0.0f), Vec3(-1.5f, 0.0f, 0.0f)));  // stops short
  EXPECT_FALSE(bp->isSegmentBlocked(Vec3(-5.0f, 0.0f, 0.0f), Vec3(0.0f), 2));            // a is on layer 1
  EXPECT_TRUE(bp->isSegmentBlocked(Vec3(3.0f, 0.0f, 0.0f), Vec3(3.0f, 0.0f, 0.0f)));     // inside b
}

TEST_P(BroadPhaseKnownAnswers, FrustumKeepsWhatTheCameraSees) {
  auto bp = make();
  // Camera at the origin looking down -z (glm convention), 90° field of view, near 1, far 50.
  const Frustum frustum =
      Frustum::fromViewProjection(glm::perspective(glm::radians(90.0f), 1.0f, 1.0f, 50.0f) *
                                  glm::lookAt(Vec3(0.0f), Vec3(0.0f, 0.0f, -1.0f), Vec3(0.0f, 1.0f, 0.0f)));
  const ProxyId ahead = bp->add({cube(Vec3(0.0f, 0.0f, -10.0f), 1.0f)});
  bp->add({cube(Vec3(0.0f, 0.0f, 10.0f), 1.0f)});    // behind
  bp->add({cube(Vec3(30.0f, 0.0f, -10.0f), 1.0f)});  // far to the right of the 45° half-angle
  bp->add({cube(Vec3(0.0f, 0.0f, -80.0f), 1.0f)});   // beyond the far plane
  const ProxyId edge = bp->add({cube(Vec3(10.5f, 0.0f, -10.0f), 1.0f)});  // straddles the right plane
  EXPECT_EQ(bp->cullFrustum(frustum), (std::vector<ProxyId>{ahead, edge}));
}

TEST_P(BroadPhaseKnownAnswers, StaleAndUnknownIdsAreErrors) {
  auto bp = make();
  const ProxyId a = bp->add({cube(Vec3(0.0f), 1.0f)});
  bp->remove(a);
  EXPECT_COLLIDE_ERROR(bp->update(a, cube(Vec3(1.0f), 1.0f)));
  EXPECT_COLLIDE_ERROR(bp->remove(a));
  EXPECT_COLLIDE_ERROR(bp->bounds(a));
  EXPECT_FALSE(bp->contains(a));
  const ProxyId b = bp->add({cube(Vec3(0.0f), 1.0f)});  // reuses a's slot
  EXPECT_EQ(b.index, a.index);
  EXPECT_COLLIDE_ERROR(bp->remove(a));       // the old id must not remove the new proxy
  EXPECT_COLLIDE_ERROR(bp->setMask(a, 2u));  // nor change its filter
  EXPECT_COLLIDE_ERROR(bp->setLayer(a, 2u));
  EXPECT_COLLIDE_ERROR(bp->mask(a));
  EXPECT_EQ(bp->mask(b), kAllLayers);
  EXPECT_TRUE(bp->contains(b));
  EXPECT_COLLIDE_ERROR(bp->update(ProxyId{57, 1}, cube(Vec3(0.0f), 1.0f)));
  EXPECT_COLLIDE_ERROR(bp->update(ProxyId{}, cube(Vec3(0.0f), 1.0f)));
  EXPECT_THAT([&] { bp->remove(a); }, ::collide::test::ReportsError(::testing::HasSubstr("stale")));
}

TEST_P(BroadPhaseKnownAnswers, BadBoxesAndRaysAreErrors) {
  auto bp = make();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  EXPECT_COLLIDE_ERROR(bp->add({Aabb{Vec3(0.0f), Vec3(nan, 1.0f, 1.0f)}}));
  EXPECT_COLLIDE_ERROR(bp->add({Aabb{Vec3(-inf), Vec3(1.0f)}}));
  EXPECT_COLLIDE_ERROR(bp->add({Aabb{Vec3(1.0f), Vec3(0.0f)}}));  // inverted
  EXPECT_COLLIDE_ERROR(bp->add({Aabb::empty()}));
  const ProxyId a = bp->add({cube(Vec3(0.0f), 1.0f)});
  EXPECT_COLLIDE_ERROR(bp->update(a, Aabb{Vec3(0.0f, 2.0f, 0.0f), Vec3(1.0f)}));
  EXPECT_EQ(bp->bounds(a).min, Vec3(-1.0f));  // a failed update leaves the proxy as it was
  auto ignore = [](ProxyId, float) { return 1.0f; };
  EXPECT_COLLIDE_ERROR(bp->rayCast(Ray{Vec3(0.0f), Vec3(0.0f), 1.0f}, kAllLayers, ignore));
  EXPECT_COLLIDE_ERROR(bp->rayCast(Ray{Vec3(0.0f), Vec3(nan, 0.0f, 1.0f), 1.0f}, kAllLayers, ignore));
  EXPECT_COLLIDE_ERROR(bp->rayCast(Ray{Vec3(inf), Vec3(1.0f, 0.0f, 0.0f), 1.0f}, kAllLayers, ignore));
  EXPECT_COLLIDE_ERROR(bp->rayCast(Ray{Vec3(0.0f), Vec3(1.0f, 0.0f, 0.0f), -1.0f}, kAllLayers, ignore));
  EXPECT_COLLIDE_ERROR(bp->overlapAabb(Aabb{Vec3(1.0f), Vec3(0.0f)}));
  EXPECT_COLLIDE_ERROR(bp->overlapSphere({Vec3(0.0f), -1.0f}));
  EXPECT_COLLIDE_ERROR(bp->isSegmentBlocked(Vec3(nan), Vec3(0.0f)));
}

INSTANTIATE_TEST_SUITE_P(AllAlgorithms, BroadPhaseKnownAnswers,
                         ::testing::Values(BroadPhaseType::Tree, BroadPhaseType::SweepAndPrune,
                                           BroadPhaseType::Grid, BroadPhaseType::BruteForce),
                         [](const auto& info) { return std::string(toString(info.param)); });

TEST(BroadPhase, TypeNamesRoundTrip) {
  for (int i = 0; i < kBroadPhaseTypeCount; ++i) {
    const auto type = static_cast<BroadPhaseType>(i);
    EXPECT_EQ(parseBroadPhaseType(toString(type)), type);
  }
  EXPECT_EQ(parseBroadPhaseType("sap"), BroadPhaseType::SweepAndPrune);
  EXPECT_COLLIDE_ERROR(parseBroadPhaseType("octree"));
}

TEST(BroadPhase, BadSettingsAreErrors) {
  BroadPhaseSettings settings;
  settings.treeMargin = -0.1f;
  EXPECT_COLLIDE_ERROR(createBroadPhase(settings));
  settings = {};
  settings.gridCellSize = std::numeric_limits<float>::quiet_NaN();
  EXPECT_COLLIDE_ERROR(createBroadPhase(settings));
  settings = {};
  settings.gridMaxCellsPerAxis = 0;
  EXPECT_COLLIDE_ERROR(createBroadPhase(settings));
}

// The counters are those of the last findPairs alone: each call starts afresh (the world adds its
// narrow-phase figures in its own StepStats).
TEST(BroadPhase, CountersAreThoseOfTheLastCall) {
  auto bp = createBroadPhase();
  std::vector<ProxyId> ids;
  for (int i = 0; i < 4; ++i) ids.push_back(bp->add({cube(Vec3(static_cast<float>(i)), 0.6f)}));
  Array<ProxyPair> pairs;
  bp->findPairs(pairs);
  EXPECT_EQ(bp->lastStats().potentialPairs, 6u);
  EXPECT_EQ(bp->lastStats().keptPairs, 3u);  // neighbours along the diagonal: 0-1, 1-2, 2-3
  bp->findPairs(pairs);
  EXPECT_EQ(bp->lastStats().potentialPairs, 6u);
  EXPECT_EQ(bp->lastStats().keptPairs, 3u);
  bp->remove(ids[3]);
  bp->findPairs(pairs);
  EXPECT_EQ(bp->lastStats().proxies, 3u);
  EXPECT_EQ(bp->lastStats().potentialPairs, 3u);
  EXPECT_EQ(bp->lastStats().keptPairs, 2u);
}
