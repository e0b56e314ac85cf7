// A box on a static triangle-mesh floor in the World: the mesh–box cell's clipped four-point
// manifold and its internal-edge handling (src/narrowphase/mesh_pairs.cpp, docs/narrowphase.md).
#include "shapes/flat_grid.h"
#include "world/world_helpers.h"

#include <gtest/gtest.h>

#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>
#include <set>

namespace collide {
namespace {

constexpr float kDt = 1.0f / 60.0f;

// The flat tessellated floor (test::flatGrid), static and frictionless.
BodyDef meshFloor(int n) {
  BodyDef def;
  def.type = BodyType::Static;
  def.shape = Shape(test::flatGrid(n));
  def.friction = 0.0f;
  return def;
}

float degreesFromVertical(const Vec3& normal) {
  return glm::degrees(std::acos(std::clamp(std::abs(normal.y) / glm::length(normal), 0.0f, 1.0f)));
}

TEST(WorldMeshFloor, BoxSlidingAcrossInternalEdgesStaysLevel) {
  // A frictionless box slides at 3 m/s across the floor's quad edges and diagonals, turned 20°
  // about y so its edges cross the mesh's edges at an angle. A bump on an internal edge would
  // push it along the edge's normal: up (vertical velocity) and back (speed lost). Every contact
  // normal must stay within 1° of vertical, the vertical velocity small, the speed kept.
  World world;
  const BodyId floor = world.createBody(meshFloor(10));
  BodyDef def = test::boxBody(Vec3(-3.5f, 0.25f, 0.3f), Vec3(0.4f, 0.25f, 0.3f), 1.0f);
  def.rotation = glm::angleAxis(glm::radians(20.0f), Vec3(0.0f, 1.0f, 0.0f));
  def.friction = 0.0f;
  def.linearVelocity = Vec3(3.0f, 0.0f, 0.4f);
  const BodyId box = world.createBody(def);
  float worstNormal = 0.0f;
  int manifolds = 0;
  world.setPreSolveCallback([&](BodyId a, BodyId b, const Manifold& m) {
    if ((a == floor && b == box) || (a == box && b == floor)) {
      ++manifolds;
      worstNormal = std::max(worstNormal, degreesFromVertical(m.normal));
    }
    return true;
  });
  float worstVertical = 0.0f;
  for (int i = 0; i < 120; ++i) {
    world.step(kDt);
    if (i >= 15) worstVertical = std::max(worstVertical, std::abs(world.linearVelocity(box).y));
  }
  const Vec3 end = world.transform(box).position;
  EXPECT_GT(end.x, 2.0f);  // it crossed about six quads
  EXPECT_GT(manifolds, 100);
  EXPECT_LE(worstNormal, 1.0f);
  EXPECT_LT(worstVertical, 0.05f);
  EXPECT_NEAR(world.linearVelocity(box).x, 3.0f, 0.03f);
  EXPECT_NEAR(end.y, 0.25f, 0.01f);
}

TEST(WorldMeshFloor, BoxRestingOnTheMeshKeepsFourFeatureIds) {
  // A box settles on the floor with its corners in different triangles: after settling, every
  // step's manifold has four points with the same four ids.
  World world;
  const BodyId floor = world.createBody(meshFloor(10));
  const BodyId box = world.createBody(test::boxBody(Vec3(0.1f, 0.3f, -0.15f), Vec3(0.7f, 0.3f, 0.6f), 2.0f));
  std::set<std::uint32_t> ids, first;
  int count = 0;
  world.setPreSolveCallback([&](BodyId a, BodyId b, const Manifold& m) {
    if (!((a == floor && b == box) || (a == box && b == floor))) return true;
    ids.clear();
    for (int i = 0; i < m.count; ++i) ids.insert(m.points[i].featureId);
    count = m.count;
    return true;
  });
  int steps = 0, fourPoints = 0, changed = 0;
  for (int i = 0; i < 120; ++i) {
    world.step(kDt);
    if (i < 30) continue;  // settling
    ++steps;
    if (first.empty()) first = ids;
    fourPoints += count == 4;
    changed += ids != first;
  }
  EXPECT_EQ(first.size(), 4u);
  EXPECT_EQ(fourPoints, steps);
  EXPECT_EQ(changed, 0);
  EXPECT_NEAR(world.transform(box).position.y, 0.3f, 0.01f);
}

}  // namespace
}  // namespace collide
