// The world's queries (castRayAll/Any/Collect, castShape/castShapeAll, overlapShape, overlapPoint)
// against brute-force references that skip the broad phase: every body, the narrow-phase function
// called directly. Random worlds hold every shape type at random poses; then hand-worked cases,
// filters and bad input.
#include <collide/narrowphase.h>
#include <collide/world.h>
#include <gtest/gtest.h>

#include "support/collide_error.h"
#include "support/test_meshes.h"
#include "support/test_random.h"
#include "support/world_helpers.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <vector>

using namespace collide;
using namespace collide::test;

namespace {

constexpr float kQueryTolerance = 1e-5f;

std::vector<Vec3> randomCloud(std::mt19937& rng, int count, float size) {
  std::vector<Vec3> points;
  for (int i = 0; i < count; ++i) points.push_back(randomPoint(rng, -size, size));
  return points;
}

// One shape of each type; `i` picks the type (ShapeType's order), the rest is random.
Shape randomShape(std::mt19937& rng, int i) {
  std::uniform_real_distribution<float> size(0.2f, 1.0f);
  switch (static_cast<ShapeType>(i % kShapeTypeCount)) {
    case ShapeType::Sphere:
      return Sphere{size(rng)};
    case ShapeType::Capsule:
      return Capsule{size(rng) * 0.6f, size(rng)};
    case ShapeType::Plane:
      return Plane{Vec3(0.0f, 1.0f, 0.0f), 0.0f};
    case ShapeType::Box:
      return Box{Vec3(size(rng), size(rng), size(rng))};
    case ShapeType::Kdop: {
      const std::vector<Vec3> cloud = randomCloud(rng, 12, 0.8f);
      return Kdop::fromPoints(18, cloud);
    }
    case ShapeType::Ellipsoid:
      return Ellipsoid{Vec3(size(rng), size(rng), size(rng))};
    case ShapeType::Cylinder:
      return Cylinder{size(rng) * 0.7f, size(rng)};
    case ShapeType::ConvexHull: {
      const std::vector<Vec3> cloud = randomCloud(rng, 14, 0.9f);
      return ConvexHull::fromPoints(cloud);
    }
    case ShapeType::Mesh:
      return i % 2 == 0 ? icosphere(1) : boxMesh(Vec3(0.8f, 0.3f, 0.6f));
    case ShapeType::Compound: {
      std::vector<Compound::Child> children;
      children.push_back({Shape(Sphere{0.4f}), Transform{Vec3(-0.5f, 0.0f, 0.0f)}});
      children.push_back(
          {Shape(Box{Vec3(0.3f, 0.5f, 0.3f)}), Transform{Vec3(0.5f, 0.0f, 0.0f), randomRotation(rng)}});
      return Compound::fromChildren(std::move(children));
    }
  }
  return Sphere{};
}

// A world of ~40 static and dynamic bodies of every shape type, a tilted ground plane below, a few
// sensors and a few bodies on layer 2.
struct RandomWorld {
  World world;
  std::vector<BodyId> bodies;
  std::vector<bool> sensors;  // by position in `bodies`
  std::vector<std::uint32_t> layers;

  RandomWorld(BroadPhaseType type, unsigned seed) : world(makeDef(type)) {
    std::mt19937 rng(seed);
    BodyDef ground;
    ground.type = BodyType::Static;
    ground.shape =
        Shape(Plane::fromPointNormal(Vec3(0.0f, -7.0f, 0.0f), glm::normalize(Vec3(0.1f, 1.0f, -0.2f))));
    add(ground);
    for (int i = 0; i < 45; ++i) {
      if (i % kShapeTypeCount == static_cast<int>(ShapeType::Plane)) continue;
      BodyDef def;
      def.shape = randomShape(rng, i);
      const bool canMove = def.shape.type() != ShapeType::Mesh;
      def.type = canMove && i % 3 == 0 ? BodyType::Dynamic : BodyType::Static;
      def.position = randomPoint(rng, -6.0f, 6.0f);
      def.rotation = randomRotation(rng);
      def.scale = std::uniform_real_distribution<float>(0.6f, 1.6f)(rng);
      def.sensor = i % 11 == 5;
      def.layer = i % 7 == 3 ? 2u : 1u;
      add(def);
    }
  }

  void add(const BodyDef& def) {
    bodies.push_back(world.createBody(def));
    sensors.push_back(def.sensor);
    layers.push_back(def.layer);
  }

  static WorldDef makeDef(BroadPhaseType type) {
    WorldDef d = zeroGravityWorld();
    d.broadPhase.type = type;
    return d;
  }
};

Ray unitRay(const Ray& ray) {
  Ray unit = ray;
  unit.direction = ray.direction / glm::length(ray.direction);
  return unit;
}

// The references: every body, no broad phase, the narrow phase called directly.
std::vector<RayCastResult> bruteRayAll(const RandomWorld& w, const Ray& ray, const QueryFilter& filter = {}) {
  const Ray unit = unitRay(ray);
  std::vector<RayCastResult> hits;
  for (std::size_t i = 0; i < w.bodies.size(); ++i) {
    const BodyId id = w.bodies[i];
    if ((w.layers[i] & filter.mask) == 0 || (w.sensors[i] && !filter.includeSensors)) continue;
    if (filter.accept && !filter.accept(id)) continue;
    if (const std::optional<RayHit> hit = rayCast(w.world.shape(id), w.world.transform(id), unit)) {
      hits.push_back({id, hit->distance, hit->point, hit->normal, hit->subShape, 0.0f});
    }
  }
  std::sort(hits.begin(), hits.end(), [](const RayCastResult& a, const RayCastResult& b) {
    return a.distance < b.distance || (a.distance == b.distance && a.body.index < b.body.index);
  });
  return hits;
}

ToiSettings castSettings() {
  ToiSettings settings;
  settings.targetSeparation = 0.0f;
  return settings;
}

std::vector<ShapeCastResult> bruteCastAll(const RandomWorld& w, const Shape& shape, const Transform& pose,
                                          const Vec3& translation) {
  Transform end = pose;
  end.position += translation;
  std::vector<ShapeCastResult> hits;
  for (std::size_t i = 0; i < w.bodies.size(); ++i) {
    const BodyId id = w.bodies[i];
    if (w.sensors[i]) continue;
    const ToiResult toi = timeOfImpact(shape, Sweep::between(pose, end), w.world.shape(id),
                                       Sweep::fixed(w.world.transform(id)), castSettings());
    if (toi.state == ToiResult::State::Separated) continue;
    ShapeCastResult hit;
    hit.body = id;
    hit.initiallyOverlapping = toi.state == ToiResult::State::Overlapping;
    hit.fraction = hit.initiallyOverlapping ? 0.0f : toi.t;
    hit.point = toi.point;
    hit.normal = -toi.normal;
    hits.push_back(hit);
  }
  std::sort(hits.begin(), hits.end(), [](const ShapeCastResult& a, const ShapeCastResult& b) {
    return a.fraction < b.fraction || (a.fraction == b.fraction && a.body.index < b.body.index);
  });
  return hits;
}

std::vector<BodyId> bruteOverlap(const RandomWorld& w, const Shape& shape, const Transform& pose) {
  std::vector<BodyId> out;
  for (std::size_t i = 0; i < w.bodies.size(); ++i) {
    const BodyId id = w.bodies[i];
    if (w.sensors[i]) continue;
    Manifold m;
    if (collide::collide(shape, pose, w.world.shape(id), w.world.transform(id), m) && m.maxDepth() >= 0.0f) {
      out.push_back(id);
    }
  }
  return out;  // created in index order
}

std::vector<BodyId> brutePoint(const RandomWorld& w, const Vec3& point) {
  std::vector<BodyId> out;
  for (std::size_t i = 0; i < w.bodies.size(); ++i) {
    const BodyId id = w.bodies[i];
    if (!w.sensors[i] && containsPoint(w.world.shape(id), w.world.transform(id), point)) out.push_back(id);
  }
  return out;
}

Ray randomRay(std::mt19937& rng, int r) {
  Ray ray;
  ray.origin = randomPoint(rng, -10.0f, 10.0f);
  ray.direction = r % 3 == 0 ? randomUnitVector(rng) * 2.0f : randomPoint(rng, -6.0f, 6.0f) - ray.origin;
  ray.maxDistance = r % 4 == 0 ? std::numeric_limits<float>::infinity()
                               : std::uniform_real_distribution<float>(3.0f, 25.0f)(rng);
  return ray;
}

class WorldQueries : public ::testing::TestWithParam<BroadPhaseType> {};

}  // namespace

TEST_P(WorldQueries, RaysMatchBruteForceInRandomWorlds) {
  int hits = 0;
  for (unsigned seed = 1; seed <= 3; ++seed) {
    const RandomWorld w(GetParam(), seed);
    std::mt19937 rng(100 + seed);
    for (int r = 0; r < 300; ++r) {
      const Ray ray = randomRay(rng, r);
      const std::vector<RayCastResult> expected = bruteRayAll(w, ray);
      const std::vector<RayCastResult> all = w.world.castRayAll(ray);
      ASSERT_EQ(all.size(), expected.size()) << "seed " << seed << " ray " << r;
      for (std::size_t i = 0; i < all.size(); ++i) {
        EXPECT_EQ(all[i].body, expected[i].body) << "seed " << seed << " ray " << r << " hit " << i;
        EXPECT_NEAR(all[i].distance, expected[i].distance, kQueryTolerance);
        EXPECT_NEAR(glm::length(all[i].point - expected[i].point), 0.0f, kQueryTolerance);
        EXPECT_NEAR(glm::length(all[i].normal - expected[i].normal), 0.0f, kQueryTolerance);
        EXPECT_EQ(all[i].subShape, expected[i].subShape);
        const float fraction = std::isinf(ray.maxDistance) ? 0.0f : all[i].distance / ray.maxDistance;
        EXPECT_FLOAT_EQ(all[i].fraction, fraction);
      }
      hits += static_cast<int>(all.size());
      // The closest is the first of all; any is one of all; none when all is empty.
      const std::optional<RayCastResult> closest = w.world.castRay(ray, QueryFilter{});
      const std::optional<RayCastResult> any = w.world.castRayAny(ray);
      ASSERT_EQ(closest.has_value(), !expected.empty());
      ASSERT_EQ(any.has_value(), !expected.empty());
      if (expected.empty()) continue;
      EXPECT_EQ(closest->body, expected.front().body);
      EXPECT_NEAR(closest->distance, expected.front().distance, kQueryTolerance);
      const auto same = std::find_if(expected.begin(), expected.end(),
                                     [&](const RayCastResult& e) { return e.body == any->body; });
      ASSERT_NE(same, expected.end());
      EXPECT_NEAR(any->distance, same->distance, kQueryTolerance);
      // A collector that clips to each hit ends with the closest distance.
      float nearest = std::numeric_limits<float>::infinity();
      w.world.castRayCollect(ray, [&](const RayCastResult& hit) {
        nearest = std::min(nearest, hit.distance);
        return hit.distance;
      });
      EXPECT_NEAR(nearest, expected.front().distance, kQueryTolerance);
    }
  }
  EXPECT_GT(hits, 500);
}

TEST_P(WorldQueries, ShapeCastsMatchBruteForceInRandomWorlds) {
  const int convexTypes[] = {0, 1, 3, 4, 5, 6, 7};  // sphere, capsule, box, k-DOP, ellipsoid, cylinder, hull
  int hits = 0;
  for (unsigned seed = 1; seed <= 2; ++seed) {
    const RandomWorld w(GetParam(), seed);
    std::mt19937 rng(200 + seed);
    for (int q = 0; q < 70; ++q) {
      const Shape shape = randomShape(rng, convexTypes[q % 7]);
      const Transform pose{randomPoint(rng, -8.0f, 8.0f), randomRotation(rng), 1.0f};
      const Vec3 translation = randomPoint(rng, -6.0f, 6.0f) - pose.position;
      const std::vector<ShapeCastResult> expected = bruteCastAll(w, shape, pose, translation);
      const std::vector<ShapeCastResult> all = w.world.castShapeAll(shape, pose, translation);
      ASSERT_EQ(all.size(), expected.size()) << "seed " << seed << " cast " << q;
      for (std::size_t i = 0; i < all.size(); ++i) {
        EXPECT_EQ(all[i].body, expected[i].body) << "seed " << seed << " cast " << q << " hit " << i;
        EXPECT_NEAR(all[i].fraction, expected[i].fraction, kQueryTolerance);
        EXPECT_NEAR(all[i].distance, expected[i].fraction * glm::length(translation), 1e-4f);
        EXPECT_NEAR(glm::length(all[i].point - expected[i].point), 0.0f, kQueryTolerance);
        EXPECT_NEAR(glm::length(all[i].normal - expected[i].normal), 0.0f, kQueryTolerance);
        EXPECT_EQ(all[i].initiallyOverlapping, expected[i].initiallyOverlapping);
      }
      hits += static_cast<int>(all.size());
      const std::optional<ShapeCastResult> closest = w.world.castShape(shape, pose, translation);
      ASSERT_EQ(closest.has_value(), !expected.empty());
      if (closest) {
        EXPECT_EQ(closest->body, expected.front().body);
      }
    }
  }
  EXPECT_GT(hits, 50);
}

TEST_P(WorldQueries, OverlapsAndPointsMatchBruteForceInRandomWorlds) {
  int found = 0;
  for (unsigned seed = 1; seed <= 2; ++seed) {
    const RandomWorld w(GetParam(), seed);
    std::mt19937 rng(300 + seed);
    for (int q = 0; q < 120; ++q) {
      int type = q % kShapeTypeCount;
      if (type == static_cast<int>(ShapeType::Plane)) type = static_cast<int>(ShapeType::Box);
      const Shape shape = randomShape(rng, type);
      const Transform pose{randomPoint(rng, -7.0f, 7.0f), randomRotation(rng), 1.0f};
      const std::vector<BodyId> expected = bruteOverlap(w, shape, pose);
      const std::vector<OverlapResult> got = w.world.overlapShape(shape, pose);
      ASSERT_EQ(got.size(), expected.size()) << "seed " << seed << " query " << q;
      for (std::size_t i = 0; i < got.size(); ++i) EXPECT_EQ(got[i].body, expected[i]) << "query " << q;
      found += static_cast<int>(got.size());
    }
    for (int q = 0; q < 400; ++q) {
      const Vec3 point = randomPoint(rng, -8.0f, 8.0f);
      const std::vector<BodyId> expected = brutePoint(w, point);
      EXPECT_EQ(w.world.overlapPoint(point), expected) << "seed " << seed << " point " << q;
      found += static_cast<int>(expected.size());
    }
  }
  EXPECT_GT(found, 100);
}

TEST_P(WorldQueries, CollectorsSeeWhatTheListsHoldAndStopWhenAsked) {
  // Each collector, let run, hands out exactly the list's answers (by body index); told to stop at
  // the k-th answer, it is handed k; a cast clipped at a hit's fraction is handed no later hit.
  const RandomWorld w(GetParam(), 3);
  std::mt19937 rng(400);
  int checked = 0;
  for (int q = 0; q < 60; ++q) {
    const Shape shape = randomShape(rng, q % 2 == 0 ? 0 : 3);
    const Transform pose{randomPoint(rng, -7.0f, 7.0f), randomRotation(rng), 3.0f};  // large: many answers
    std::vector<OverlapResult> all = w.world.overlapShape(shape, pose);
    std::vector<OverlapResult> collected;
    w.world.overlapShapeCollect(shape, pose, [&](const OverlapResult& o) {
      collected.push_back(o);
      return true;
    });
    EXPECT_EQ(collected, all) << "query " << q;
    if (all.size() >= 2) {
      std::size_t handed = 0;
      w.world.overlapShapeCollect(shape, pose, [&](const OverlapResult&) { return ++handed < 2; });
      EXPECT_EQ(handed, 2u);
      ++checked;
    }

    const Vec3 translation = randomPoint(rng, -6.0f, 6.0f) - pose.position;
    std::vector<ShapeCastResult> casts = w.world.castShapeAll(shape, pose, translation);
    std::vector<std::uint32_t> castBodies;
    w.world.castShapeCollect(shape, pose, translation, [&](const ShapeCastResult& hit) {
      castBodies.push_back(hit.body.index);
      return 1.0f;
    });
    std::vector<std::uint32_t> expectedBodies;
    for (const ShapeCastResult& hit : casts) expectedBodies.push_back(hit.body.index);
    std::sort(expectedBodies.begin(), expectedBodies.end());
    EXPECT_EQ(castBodies, expectedBodies) << "cast " << q;
    // Clipped at each hit as it comes: what is handed out never goes later than the clip so far, and
    // the last clip is the earliest hit.
    float clip = 1.0f;
    w.world.castShapeCollect(shape, pose, translation, [&](const ShapeCastResult& hit) {
      EXPECT_LE(hit.fraction, clip);
      clip = hit.fraction;
      return hit.fraction;
    });
    if (!casts.empty()) {
      EXPECT_EQ(clip, casts.front().fraction) << "cast " << q;
    }
  }
  EXPECT_GT(checked, 5);
  for (int q = 0; q < 100; ++q) {
    const Vec3 point = randomPoint(rng, -8.0f, 8.0f);
    std::vector<BodyId> collected;
    w.world.overlapPointCollect(point, [&](BodyId id) {
      collected.push_back(id);
      return true;
    });
    EXPECT_EQ(collected, w.world.overlapPoint(point));
  }
  EXPECT_COLLIDE_ERROR(w.world.overlapShapeCollect(Shape(Sphere{1.0f}), Transform{}, OverlapCollector{}));
  EXPECT_COLLIDE_ERROR(
      w.world.castShapeCollect(Shape(Sphere{1.0f}), Transform{}, Vec3(1.0f), ShapeCastCollector{}));
  EXPECT_COLLIDE_ERROR(w.world.overlapPointCollect(Vec3(0.0f), PointCollector{}));
}

TEST_P(WorldQueries, ExactLineOfSightIsTheShapesNotTheirBoxes) {
  // Between random points: blocked exactly when the brute force finds a shape on the segment, and
  // the boxes' test (BroadPhase::hasLineOfSight) never sees where the shapes block; some segments
  // pass between shapes through their boxes, where the two differ.
  const RandomWorld w(GetParam(), 4);
  std::mt19937 rng(500);
  int blocked = 0, boxesOnly = 0;
  for (int q = 0; q < 300; ++q) {
    const Vec3 from = randomPoint(rng, -9.0f, 9.0f), to = randomPoint(rng, -9.0f, 9.0f);
    const float length = glm::length(to - from);
    const Ray ray{from, (to - from) / length, length};
    const bool expected = bruteRayAll(w, ray).empty();
    const bool sight = w.world.hasLineOfSight(from, to);
    EXPECT_EQ(sight, expected) << "segment " << q;
    const bool boxSight = w.world.broadPhase().hasLineOfSight(from, to);
    if (!sight) {
      ++blocked;
      EXPECT_FALSE(boxSight) << "segment " << q;
    }
    if (sight && !boxSight) ++boxesOnly;
  }
  EXPECT_GT(blocked, 30);
  EXPECT_GT(boxesOnly, 5);
  EXPECT_COLLIDE_ERROR((void)w.world.hasLineOfSight(Vec3(NAN), Vec3(0.0f)));
}

INSTANTIATE_TEST_SUITE_P(EveryBroadPhase, WorldQueries,
                         ::testing::Values(BroadPhaseType::Tree, BroadPhaseType::SweepAndPrune,
                                           BroadPhaseType::Grid, BroadPhaseType::BruteForce),
                         [](const auto& info) { return std::string(toString(info.param)); });

// A unit box resting on the ground plane y = 0 (top face at y = 1), a ray straight down from y = 5.
TEST(WorldQueriesByHand, RayDownOntoABoxOnAPlane) {
  World world(zeroGravityWorld());
  const BodyId ground = world.createBody(groundPlane());
  BodyDef box = boxBody(Vec3(0.0f, 0.5f, 0.0f), Vec3(0.5f), 1.0f);
  box.type = BodyType::Static;
  const BodyId crate = world.createBody(box);
  const Ray down{Vec3(0.1f, 5.0f, -0.2f), Vec3(0.0f, -2.0f, 0.0f), 10.0f};
  const std::vector<RayCastResult> all = world.castRayAll(down);
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[0].body, crate);
  EXPECT_FLOAT_EQ(all[0].distance, 4.0f);
  EXPECT_FLOAT_EQ(all[0].fraction, 0.4f);
  EXPECT_NEAR(glm::length(all[0].point - Vec3(0.1f, 1.0f, -0.2f)), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::length(all[0].normal - Vec3(0.0f, 1.0f, 0.0f)), 0.0f, 1e-6f);
  EXPECT_EQ(all[1].body, ground);
  EXPECT_FLOAT_EQ(all[1].distance, 5.0f);
  EXPECT_FLOAT_EQ(all[1].fraction, 0.5f);
  ASSERT_TRUE(world.castRayAny(down).has_value());
  // A collector that stops at the first hit is called once.
  int calls = 0;
  world.castRayCollect(down, [&](const RayCastResult&) {
    ++calls;
    return -1.0f;
  });
  EXPECT_EQ(calls, 1);
  // Too short to reach the box: nothing.
  EXPECT_TRUE(world.castRayAll(Ray{down.origin, down.direction, 3.9f}).empty());
  EXPECT_FALSE(world.castRayAny(Ray{down.origin, down.direction, 3.9f}).has_value());
}

// A ball of radius 0.5 at y = 3 swept 5 m down onto the plane y = 0 touches it once it has gone 2.5 m.
TEST(WorldQueriesByHand, SphereCastOntoAPlane) {
  World world(zeroGravityWorld());
  const BodyId ground = world.createBody(groundPlane());
  const Shape ball(Sphere{0.5f});
  const std::optional<ShapeCastResult> hit =
      world.castShape(ball, Transform{Vec3(1.0f, 3.0f, 2.0f)}, Vec3(0.0f, -5.0f, 0.0f));
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->body, ground);
  EXPECT_FALSE(hit->initiallyOverlapping);
  EXPECT_NEAR(hit->fraction, 0.5f, 5e-4f);
  EXPECT_NEAR(hit->distance, 2.5f, 2.5e-3f);
  EXPECT_NEAR(glm::length(hit->normal - Vec3(0.0f, 1.0f, 0.0f)), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::length(hit->point - Vec3(1.0f, 0.0f, 2.0f)), 0.0f, 2e-3f);
  // Too short: no hit. Starting in the plane: fraction 0, overlapping.
  EXPECT_FALSE(world.castShape(ball, Transform{Vec3(1.0f, 3.0f, 2.0f)}, Vec3(0.0f, -2.0f, 0.0f)).has_value());
  const std::optional<ShapeCastResult> inside =
      world.castShape(ball, Transform{Vec3(0.0f, 0.2f, 0.0f)}, Vec3(0.0f, -1.0f, 0.0f));
  ASSERT_TRUE(inside.has_value());
  EXPECT_TRUE(inside->initiallyOverlapping);
  EXPECT_EQ(inside->fraction, 0.0f);
}

// The ground plane, a unit box on it and a closed icosphere mesh: which solids hold which points, and
// what a box placed among them overlaps.
TEST(WorldQueriesByHand, OverlapsAndPoints) {
  World world(zeroGravityWorld());
  const BodyId ground = world.createBody(groundPlane());
  BodyDef box = boxBody(Vec3(0.0f, 0.5f, 0.0f), Vec3(0.5f), 1.0f);
  box.type = BodyType::Static;
  const BodyId crate = world.createBody(box);
  BodyDef ball;
  ball.type = BodyType::Static;
  ball.shape = Shape(icosphere(2));
  ball.position = Vec3(5.0f, 3.0f, 0.0f);
  const BodyId mesh = world.createBody(ball);
  BodyDef open;
  open.type = BodyType::Static;
  open.shape =
      Shape(TriangleMesh::fromTriangles({Vec3(-1, 0, -1), Vec3(1, 0, -1), Vec3(0, 0, 1)}, {{{0, 2, 1}}}));
  open.position = Vec3(-5.0f, 3.0f, 0.0f);
  world.createBody(open);

  EXPECT_EQ(world.overlapPoint(Vec3(0.0f, 0.5f, 0.0f)), std::vector<BodyId>{crate});
  EXPECT_EQ(world.overlapPoint(Vec3(0.0f, -1.0f, 0.0f)), std::vector<BodyId>{ground});
  EXPECT_EQ(world.overlapPoint(Vec3(5.0f, 3.0f, 0.0f)), std::vector<BodyId>{mesh});  // inside the closed mesh
  EXPECT_TRUE(world.overlapPoint(Vec3(-5.0f, 3.0f, 0.0f)).empty());  // on an open mesh: no inside
  EXPECT_TRUE(world.overlapPoint(Vec3(0.0f, 5.0f, 0.0f)).empty());

  const std::vector<OverlapResult> touching =
      world.overlapShape(Shape(Box{Vec3(0.2f)}), Transform{Vec3(0.6f, 0.15f, 0.0f)});
  ASSERT_EQ(touching.size(), 2u);
  EXPECT_EQ(touching[0].body, ground);
  EXPECT_EQ(touching[1].body, crate);
  // Inside the closed mesh but clear of its surface: a mesh is its surface for overlaps.
  EXPECT_TRUE(world.overlapShape(Shape(Sphere{0.2f}), Transform{Vec3(5.0f, 3.0f, 0.0f)}).empty());
  EXPECT_EQ(world.overlapShape(Shape(Sphere{0.2f}), Transform{Vec3(5.0f, 4.0f, 0.0f)}).size(), 1u);
}

TEST(WorldQueriesByHand, CompoundPartsAreReported) {
  World world(zeroGravityWorld());
  std::vector<Compound::Child> children;
  children.push_back({Shape(Sphere{0.5f}), Transform{Vec3(-2.0f, 0.0f, 0.0f)}});
  children.push_back({Shape(Box{Vec3(0.5f)}), Transform{Vec3(2.0f, 0.0f, 0.0f)}});
  BodyDef def;
  def.type = BodyType::Static;
  def.shape = Shape(Compound::fromChildren(std::move(children)));
  const BodyId body = world.createBody(def);
  const std::vector<RayCastResult> ray =
      world.castRayAll(Ray{Vec3(2.0f, 5.0f, 0.0f), Vec3(0.0f, -1.0f, 0.0f)});
  ASSERT_EQ(ray.size(), 1u);
  EXPECT_EQ(ray[0].subShape, 1u);
  const std::optional<ShapeCastResult> cast =
      world.castShape(Shape(Sphere{0.25f}), Transform{Vec3(2.0f, 5.0f, 0.0f)}, Vec3(0.0f, -10.0f, 0.0f));
  ASSERT_TRUE(cast.has_value());
  EXPECT_EQ(cast->subShape, 1u);
  EXPECT_NEAR(cast->distance, 5.0f - 0.5f - 0.25f, 3e-3f);
  const std::vector<OverlapResult> overlap =
      world.overlapShape(Shape(Sphere{0.3f}), Transform{Vec3(-2.0f, 0.6f, 0.0f)});
  ASSERT_EQ(overlap.size(), 1u);
  EXPECT_EQ(overlap[0], (OverlapResult{body, 0u}));
}

TEST(WorldQueriesFilter, MaskCallbackAndSensors) {
  World world(zeroGravityWorld());
  BodyDef def = boxBody(Vec3(0.0f, 0.0f, 0.0f), Vec3(0.5f), 1.0f);
  const BodyId a = world.createBody(def);
  def.position.z = 2.0f;
  def.layer = 2;
  const BodyId b = world.createBody(def);
  def.position.z = 4.0f;
  def.layer = 1;
  def.sensor = true;
  const BodyId sensor = world.createBody(def);
  const Ray ray{Vec3(0.0f, 0.0f, 10.0f), Vec3(0.0f, 0.0f, -1.0f)};
  auto bodiesOf = [](const std::vector<RayCastResult>& hits) {
    std::vector<BodyId> out;
    for (const RayCastResult& h : hits) out.push_back(h.body);
    return out;
  };
  EXPECT_EQ(bodiesOf(world.castRayAll(ray)), (std::vector<BodyId>{b, a}));
  EXPECT_EQ(bodiesOf(world.castRayAll(ray, QueryFilter{.includeSensors = true})),
            (std::vector<BodyId>{sensor, b, a}));
  EXPECT_EQ(bodiesOf(world.castRayAll(ray, QueryFilter{.mask = 1})), (std::vector<BodyId>{a}));
  const QueryFilter notB{.accept = [&](BodyId id) { return id != b; }};
  EXPECT_EQ(bodiesOf(world.castRayAll(ray, notB)), (std::vector<BodyId>{a}));
  EXPECT_EQ(world.castRay(ray, notB)->body, a);
  EXPECT_EQ(world.castRayAny(ray, notB)->body, a);
  EXPECT_EQ(world.castShape(Shape(Sphere{0.1f}), Transform{ray.origin}, Vec3(0.0f, 0.0f, -20.0f), notB)->body,
            a);
  EXPECT_EQ(world.castShapeAll(Shape(Sphere{0.1f}), Transform{ray.origin}, Vec3(0.0f, 0.0f, -20.0f)).size(),
            2u);
  const Shape rod(Box{Vec3(0.1f, 0.1f, 3.0f)});
  EXPECT_EQ(world.overlapShape(rod, Transform{Vec3(0.0f, 0.0f, 2.0f)}).size(), 2u);
  EXPECT_EQ(
      world.overlapShape(rod, Transform{Vec3(0.0f, 0.0f, 2.0f)}, QueryFilter{.includeSensors = true}).size(),
      3u);
  EXPECT_EQ(world.overlapShape(rod, Transform{Vec3(0.0f, 0.0f, 2.0f)}, notB).size(), 1u);
  EXPECT_EQ(world.overlapPoint(Vec3(0.0f, 0.0f, 2.0f), QueryFilter{.mask = 1}).size(), 0u);
  EXPECT_EQ(world.overlapPoint(Vec3(0.0f, 0.0f, 4.0f), QueryFilter{.includeSensors = true}),
            std::vector<BodyId>{sensor});
}

TEST(WorldQueriesInput, BadInputIsRefusedWithAMessage) {
  World world(zeroGravityWorld());
  world.createBody(sphereBody(Vec3(0.0f), 0.5f, 1.0f));
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const Vec3 z(0.0f, 0.0f, 1.0f);
  auto message = [](auto&& f) { return ::collide::test::errorOf([&] { f(); }).value_or("no error"); };
  EXPECT_NE(message([&] {
              (void)world.castRayAll(Ray{Vec3(nan), z});
            }).find("castRayAll: origin must be finite"),
            std::string::npos);
  EXPECT_NE(message([&] {
              (void)world.castRayAny(Ray{Vec3(0.0f), Vec3(0.0f)});
            }).find("direction must be finite"),
            std::string::npos);
  EXPECT_NE(message([&] {
              (void)world.castRayAll(Ray{Vec3(0.0f), z, -1.0f});
            }).find("maxDistance must be >= 0"),
            std::string::npos);
  EXPECT_COLLIDE_ERROR(
      world.castRayCollect(Ray{Vec3(0.0f), z, nan}, [](const RayCastResult&) { return 0.0f; }));
  EXPECT_COLLIDE_ERROR(world.castRayCollect(Ray{Vec3(0.0f), z}, RayHitCollector{}));
  const Shape ball(Sphere{0.5f});
  EXPECT_NE(message([&] {
              (void)world.castShape(Shape(boxMesh(Vec3(1.0f))), Transform{}, z);
            }).find("castShape: the cast shape must be convex"),
            std::string::npos);
  EXPECT_COLLIDE_ERROR((void)world.castShapeAll(ball, Transform{Vec3(nan)}, z));
  EXPECT_COLLIDE_ERROR((void)world.castShape(ball, Transform{Vec3(0.0f), Quat(2.0f, 0.0f, 0.0f, 0.0f)}, z));
  EXPECT_NE(message([&] {
              (void)world.castShape(ball, Transform{}, Vec3(inf, 0.0f, 0.0f));
            }).find("translation must be finite"),
            std::string::npos);
  EXPECT_NE(
      message([&] { (void)world.overlapShape(Shape(Plane{}), Transform{}); }).find("overlapShape: a plane"),
      std::string::npos);
  EXPECT_COLLIDE_ERROR(
      (void)world.overlapShape(ball, Transform{Vec3(0.0f), Quat(1.0f, 0.0f, 0.0f, 0.0f), 0.0f}));
  EXPECT_NE(message([&] {
              (void)world.overlapPoint(Vec3(0.0f, inf, 0.0f));
            }).find("overlapPoint: point must be finite"),
            std::string::npos);
}
