// The World on a static triangle-mesh floor, shared by the box, generic (cylinder) and rounded
// (sphere, capsule) mesh-floor tests: the floor, and the two scenarios they run with their shapes
// (sliding across the internal edges, resting with stable contact ids).
#pragma once

#include <collide/world.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <set>

#include "support/flat_grid.h"

namespace collide::test {

inline constexpr float kMeshFloorDt = 1.0f / 60.0f;

// The flat tessellated floor of n x n quads (test::flatGrid), static.
inline BodyDef meshFloor(int n, float friction) {
  BodyDef def;
  def.type = BodyType::Static;
  def.shape = Shape(flatGrid(n));
  def.friction = friction;
  return def;
}

inline float degreesFromVertical(const Vec3& normal) {
  return glm::degrees(std::acos(std::clamp(std::abs(normal.y) / glm::length(normal), 0.0f, 1.0f)));
}

struct FloorSlide {
  Vec3 end{0.0f};              // where the mover ended
  Vec3 velocity{0.0f};         // its final velocity
  int manifolds = 0;           // floor manifolds the pre-solve callback saw
  float worstNormal = 0.0f;    // degrees from vertical, the worst of their normals
  float worstVertical = 0.0f;  // the largest |vertical velocity| after the first 15 steps
};

// Slides `mover` over a frictionless 10 x 10 floor for 120 steps.
inline FloorSlide slideOverMeshFloor(const BodyDef& mover) {
  World world;
  const BodyId floor = world.createBody(meshFloor(10, 0.0f));
  const BodyId body = world.createBody(mover);
  FloorSlide slide;
  world.setPreSolveCallback([&](BodyId a, BodyId b, const Manifold& m) {
    if ((a == floor && b == body) || (a == body && b == floor)) {
      ++slide.manifolds;
      slide.worstNormal = std::max(slide.worstNormal, degreesFromVertical(m.normal));
    }
    return true;
  });
  for (int i = 0; i < 120; ++i) {
    world.step(kMeshFloorDt);
    if (i >= 15) slide.worstVertical = std::max(slide.worstVertical, std::abs(world.linearVelocity(body).y));
  }
  slide.end = world.transform(body).position;
  slide.velocity = world.linearVelocity(body);
  return slide;
}

// What every shape's slide must show: it crossed about six quads with every floor normal within 1°
// of vertical, hardly a vertical velocity, its speed kept and its height (0.25 m) held.
inline void expectLevelSlide(const FloorSlide& slide) {
  EXPECT_GT(slide.end.x, 2.0f);  // it crossed about six quads
  EXPECT_GT(slide.manifolds, 100);
  EXPECT_LE(slide.worstNormal, 1.0f);
  EXPECT_LT(slide.worstVertical, 0.05f);
  EXPECT_NEAR(slide.velocity.x, 3.0f, 0.03f);
  EXPECT_NEAR(slide.end.y, 0.25f, 0.01f);
}

struct FloorRest {
  std::size_t firstIds = 0;  // distinct contact ids in the first manifold after settling
  int steps = 0;             // steps after settling
  int withPoints = 0;        // of them, steps whose manifold had the expected point count
  int changed = 0;           // of them, steps whose ids differ from the first
  Vec3 end{0.0f};
  Vec3 spin{0.0f};
};

// Drops `body` on a 10 x 10 floor of the given friction and, after 30 settling steps, records its
// floor manifold every step until `steps`.
inline FloorRest restOnMeshFloor(const BodyDef& body, float floorFriction, int points, int steps) {
  World world;
  const BodyId floor = world.createBody(meshFloor(10, floorFriction));
  const BodyId id = world.createBody(body);
  std::set<std::uint32_t> ids, first;
  int count = 0;
  world.setPreSolveCallback([&](BodyId a, BodyId b, const Manifold& m) {
    if (!((a == floor && b == id) || (a == id && b == floor))) return true;
    ids.clear();
    for (int i = 0; i < m.count; ++i) ids.insert(m.points[i].featureId);
    count = m.count;
    return true;
  });
  FloorRest rest;
  for (int i = 0; i < steps; ++i) {
    world.step(kMeshFloorDt);
    if (i < 30) continue;  // settling
    ++rest.steps;
    if (first.empty()) first = ids;
    rest.withPoints += count == points;
    rest.changed += ids != first;
  }
  rest.firstIds = first.size();
  rest.end = world.transform(id).position;
  rest.spin = world.angularVelocity(id);
  return rest;
}

// What every resting shape must show: after settling, every step's manifold has `points` points
// with the same ids, and the body rests with its centre at `height`.
inline void expectStableRest(const FloorRest& rest, std::size_t points, float height) {
  EXPECT_EQ(rest.firstIds, points);
  EXPECT_EQ(rest.withPoints, rest.steps);
  EXPECT_EQ(rest.changed, 0);
  EXPECT_NEAR(rest.end.y, height, 0.01f);
}

}  // namespace collide::test
