// World::castRay (picking through the broad phase) against a brute-force cast over every body, on
// each broad-phase type, and World::broadPhasePairs against pairs worked out by hand.
#include <collide/world.h>
#include <gtest/gtest.h>

#include "support/collide_error.h"
#include "support/test_random.h"
#include "support/world_helpers.h"

#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <vector>

using namespace collide;
using namespace collide::test;

namespace {

// The answer castRay must give: every body's shape cast, the closest kept, ties to the lower index.
std::optional<RayCastResult> bruteForceCast(const World& world, const std::vector<BodyId>& bodies,
                                            const Ray& ray) {
  Ray unit = ray;
  unit.direction = ray.direction / glm::length(ray.direction);
  std::optional<RayCastResult> best;
  for (const BodyId id : bodies) {
    if (!world.isValid(id)) continue;
    const std::optional<RayHit> hit = rayCast(world.shape(id), world.transform(id), unit);
    if (!hit) continue;
    if (!best || hit->distance < best->distance ||
        (hit->distance == best->distance && id.index < best->body.index))
      best = RayCastResult{id, hit->distance, hit->point, hit->normal, hit->subShape};
  }
  return best;
}

class WorldRayCast : public ::testing::TestWithParam<BroadPhaseType> {
 protected:
  WorldDef def() const {
    WorldDef d = zeroGravityWorld();
    d.broadPhase.type = GetParam();
    return d;
  }
};

}  // namespace

// A cluster of bodies of several shapes thrown at each other: after the collisions, many bodies
// sit outside the boxes the step predicted for them, and castRay must still see every one.
TEST_P(WorldRayCast, MatchesBruteForceAfterCollisions) {
  WorldDef d = def();
  d.gravity = Vec3(0.0f, -9.81f, 0.0f);
  World world(d);
  std::vector<BodyId> bodies{world.createBody(groundBox())};
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> speed(-12.0f, 12.0f);
  const Shape shapes[] = {Shape(Sphere{0.3f}), Shape(Box{Vec3(0.3f, 0.2f, 0.4f)}), Shape(Capsule{0.2f, 0.3f}),
                          Shape(Cylinder{0.25f, 0.3f})};
  for (int i = 0; i < 40; ++i) {
    BodyDef body;
    body.shape = shapes[i % 4];
    body.position = randomPoint(rng, -2.0f, 2.0f) + Vec3(0.0f, 3.0f, 0.0f);
    body.rotation = randomRotation(rng);
    body.linearVelocity = Vec3(speed(rng), speed(rng), speed(rng));
    bodies.push_back(world.createBody(body));
  }
  int hits = 0;
  for (int round = 0; round < 4; ++round) {
    for (int s = 0; s < 10; ++s) world.step(1.0f / 60.0f);
    for (int r = 0; r < 250; ++r) {
      // Half the rays from far away at the cluster, half from anywhere in any direction.
      Ray ray;
      ray.origin = randomPoint(rng, -8.0f, 8.0f) + Vec3(0.0f, 3.0f, 0.0f);
      const Vec3 aim = r % 2 == 0 ? randomPoint(rng, -2.5f, 2.5f) + Vec3(0.0f, 3.0f, 0.0f) - ray.origin
                                  : randomUnitVector(rng);
      ray.direction = aim;
      ray.maxDistance = r % 5 == 0 ? 4.0f : 100.0f;
      const std::optional<RayCastResult> expected = bruteForceCast(world, bodies, ray);
      const std::optional<RayCastResult> got = world.castRay(ray);
      ASSERT_EQ(got.has_value(), expected.has_value()) << "round " << round << " ray " << r;
      if (!got) continue;
      ++hits;
      EXPECT_EQ(got->body, expected->body) << "round " << round << " ray " << r;
      EXPECT_EQ(got->distance, expected->distance);
      EXPECT_EQ(got->point, expected->point);
      EXPECT_EQ(got->normal, expected->normal);
    }
  }
  EXPECT_GT(hits, 400);  // of 1,000 rays: the comparison is mostly about hits, not misses
}

// The case the end-of-step box refresh is for: a resting ball struck by a fast one leaves the box
// the step predicted for it (it was at rest) within one step.
TEST_P(WorldRayCast, FindsABodyKnockedOutOfItsBoxInOneStep) {
  World world(def());
  const BodyId target = world.createBody(sphereBody(Vec3(0.0f), 0.1f, 1.0f));
  const BodyId striker =
      world.createBody(sphereBody(Vec3(-0.25f, 0.0f, 0.0f), 0.1f, 1.0f, Vec3(30.0f, 0.0f, 0.0f)));
  world.step(1.0f / 60.0f);
  const Vec3 moved = world.transform(target).position;
  // At rest, its box reached x = 0.1 + the speculative distance; a ray straight down through its
  // centre now misses that box.
  ASSERT_GT(moved.x, 0.1f + world.def().contact.speculativeDistance + 0.05f);
  const std::optional<RayCastResult> hit =
      world.castRay(Ray{moved + Vec3(0.0f, 5.0f, 0.0f), Vec3(0.0f, -1.0f, 0.0f)});
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->body, target);
  EXPECT_NEAR(hit->distance, 4.9f, 1e-4f);
  (void)striker;
}

TEST_P(WorldRayCast, ClosestHitWithMaxDistanceAndANormalisedDirection) {
  World world(def());
  const BodyId ground = world.createBody(groundPlane());
  const BodyId near = world.createBody(boxBody(Vec3(0.0f, 2.0f, 0.0f), Vec3(0.5f), 1.0f));
  world.createBody(boxBody(Vec3(0.0f, 5.0f, 0.0f), Vec3(0.5f), 1.0f));  // behind the ray's origin
  // From y = 4 down: the near box's top face at 2.5, then the ground at 0.
  const Ray down{Vec3(0.0f, 4.0f, 0.0f), Vec3(0.0f, -3.0f, 0.0f)};  // not unit: normalised
  const std::optional<RayCastResult> hit = world.castRay(down);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->body, near);
  EXPECT_FLOAT_EQ(hit->distance, 1.5f);
  EXPECT_NEAR(hit->point.y, 2.5f, 1e-5f);
  EXPECT_NEAR(hit->normal.y, 1.0f, 1e-5f);
  EXPECT_FALSE(world.castRay(Ray{down.origin, down.direction, 1.4f}).has_value());
  // Beside the box: the ground plane.
  const std::optional<RayCastResult> floor =
      world.castRay(Ray{Vec3(3.0f, 4.0f, 0.0f), Vec3(0.0f, -1.0f, 0.0f)});
  ASSERT_TRUE(floor.has_value());
  EXPECT_EQ(floor->body, ground);
  EXPECT_FLOAT_EQ(floor->distance, 4.0f);
  // Up into the sky: nothing.
  EXPECT_FALSE(world.castRay(Ray{Vec3(3.0f, 4.0f, 0.0f), Vec3(0.0f, 1.0f, 0.0f)}).has_value());
}

TEST_P(WorldRayCast, SkipsSensorsMaskedLayersAndDestroyedBodies) {
  World world(def());
  BodyDef sensor = sphereBody(Vec3(0.0f, 0.0f, 4.0f), 0.5f, 1.0f);
  sensor.sensor = true;
  world.createBody(sensor);
  BodyDef layered = boxBody(Vec3(0.0f, 0.0f, 2.0f), Vec3(0.5f), 1.0f);
  layered.layer = 2;
  const BodyId onLayer2 = world.createBody(layered);
  const BodyId back = world.createBody(boxBody(Vec3(0.0f), Vec3(0.5f), 1.0f));
  const Ray ray{Vec3(0.0f, 0.0f, 10.0f), Vec3(0.0f, 0.0f, -1.0f)};
  ASSERT_TRUE(world.castRay(ray).has_value());
  EXPECT_EQ(world.castRay(ray)->body, onLayer2);  // the sensor in front is not hit
  EXPECT_EQ(world.castRay(ray, ~LayerMask{2})->body, back);
  world.destroyBody(onLayer2);
  EXPECT_EQ(world.castRay(ray)->body, back);
  world.destroyBody(back);
  EXPECT_FALSE(world.castRay(ray).has_value());
}

TEST_P(WorldRayCast, EqualDistancesGoToTheLowerBodyIndex) {
  World world(def());
  BodyDef wall = boxBody(Vec3(0.0f), Vec3(0.5f), 1.0f);
  wall.type = BodyType::Static;
  const BodyId first = world.createBody(wall);
  world.createBody(wall);  // the same box in the same place
  const std::optional<RayCastResult> hit =
      world.castRay(Ray{Vec3(0.2f, 0.1f, 5.0f), Vec3(0.0f, 0.0f, -1.0f)});
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->body, first);
}

TEST_P(WorldRayCast, BadRaysAreRefused) {
  World world(def());
  world.createBody(sphereBody(Vec3(0.0f), 0.5f, 1.0f));
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  EXPECT_COLLIDE_ERROR((void)world.castRay(Ray{Vec3(nan, 0.0f, 0.0f), Vec3(0.0f, 0.0f, 1.0f)}));
  EXPECT_COLLIDE_ERROR((void)world.castRay(Ray{Vec3(0.0f), Vec3(0.0f)}));
  EXPECT_COLLIDE_ERROR((void)world.castRay(Ray{Vec3(0.0f), Vec3(inf, 0.0f, 0.0f)}));
  EXPECT_COLLIDE_ERROR((void)world.castRay(Ray{Vec3(0.0f), Vec3(0.0f, 0.0f, 1.0f), -1.0f}));
  EXPECT_COLLIDE_ERROR((void)world.castRay(Ray{Vec3(0.0f), Vec3(0.0f, 0.0f, 1.0f), nan}));
  // An infinite reach is fine, as is a ray starting inside a body (distance 0).
  const std::optional<RayCastResult> inside = world.castRay(Ray{Vec3(0.0f), Vec3(0.0f, 0.0f, 1.0f), inf});
  ASSERT_TRUE(inside.has_value());
  EXPECT_EQ(inside->distance, 0.0f);
}

INSTANTIATE_TEST_SUITE_P(EveryBroadPhase, WorldRayCast,
                         ::testing::Values(BroadPhaseType::Tree, BroadPhaseType::SweepAndPrune,
                                           BroadPhaseType::Grid, BroadPhaseType::BruteForce),
                         [](const auto& info) { return std::string(toString(info.param)); });

// Ground plane (index 0) under three balls that sink 5 cm into it: a and b overlap, c is far from
// both. The plane's box is unbounded sideways and below y = 0, so every ball pairs with it.
TEST(WorldBroadPhasePairs, AreTheKeptPairsAsBodyIdsAndDropDestroyedBodies) {
  World world(zeroGravityWorld());
  const BodyId ground = world.createBody(groundPlane());
  const BodyId a = world.createBody(sphereBody(Vec3(0.0f, 0.45f, 0.0f), 0.5f, 1.0f));
  const BodyId b = world.createBody(sphereBody(Vec3(0.9f, 0.45f, 0.0f), 0.5f, 1.0f));
  const BodyId c = world.createBody(sphereBody(Vec3(10.0f, 0.45f, 0.0f), 0.5f, 1.0f));
  EXPECT_TRUE(world.broadPhasePairs().empty());  // no step yet
  world.step(1.0f / 60.0f);
  const std::vector<BodyPair> expected{{ground, a}, {ground, b}, {ground, c}, {a, b}};
  EXPECT_EQ(world.broadPhasePairs(), expected);
  EXPECT_EQ(world.lastStats().keptPairs, expected.size());
  world.destroyBody(b);
  const std::vector<BodyPair> left{{ground, a}, {ground, c}};
  EXPECT_EQ(world.broadPhasePairs(), left);
}
