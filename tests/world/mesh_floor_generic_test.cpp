// A cylinder on a static triangle-mesh floor in the World: the mesh–cylinder cell's rim manifolds
// and internal-edge handling (src/narrowphase/triangle_generic.cpp).
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

BodyDef meshFloor(int n, float friction) {
  BodyDef def;
  def.type = BodyType::Static;
  def.shape = Shape(test::flatGrid(n));
  def.friction = friction;
  return def;
}

float degreesFromVertical(const Vec3& normal) {
  return glm::degrees(std::acos(std::clamp(std::abs(normal.y) / glm::length(normal), 0.0f, 1.0f)));
}

TEST(WorldMeshFloorGeneric, CylinderSlidingOnItsCapStaysLevel) {
  // A frictionless cylinder standing on its cap slides at 3 m/s across the floor's quad edges and
  // diagonals. A bump on an internal edge would push it up and back: every contact normal must stay
  // within 1° of vertical, the vertical velocity small, the speed kept.
  World world;
  const BodyId floor = world.createBody(meshFloor(10, 0.0f));
  BodyDef def;
  def.shape = Cylinder{0.3f, 0.25f};
  def.position = Vec3(-3.5f, 0.25f, 0.3f);
  def.friction = 0.0f;
  def.linearVelocity = Vec3(3.0f, 0.0f, 0.4f);
  const BodyId cylinder = world.createBody(def);
  float worstNormal = 0.0f;
  int manifolds = 0;
  world.setPreSolveCallback([&](BodyId a, BodyId b, const Manifold& m) {
    if ((a == floor && b == cylinder) || (a == cylinder && b == floor)) {
      ++manifolds;
      worstNormal = std::max(worstNormal, degreesFromVertical(m.normal));
    }
    return true;
  });
  float worstVertical = 0.0f;
  for (int i = 0; i < 120; ++i) {
    world.step(kDt);
    if (i >= 15) worstVertical = std::max(worstVertical, std::abs(world.linearVelocity(cylinder).y));
  }
  const Vec3 end = world.transform(cylinder).position;
  EXPECT_GT(end.x, 2.0f);  // it crossed about six quads
  EXPECT_GT(manifolds, 100);
  EXPECT_LE(worstNormal, 1.0f);
  EXPECT_LT(worstVertical, 0.05f);
  EXPECT_NEAR(world.linearVelocity(cylinder).x, 3.0f, 0.03f);
  EXPECT_NEAR(end.y, 0.25f, 0.01f);
}

TEST(WorldMeshFloorGeneric, CylinderLyingOnTheFloorRestsOnTwoPoints) {
  // A cylinder dropped lying on its side settles on its lowest line: two points, the same two ids
  // every step.
  World world;
  const BodyId floor = world.createBody(meshFloor(10, 0.5f));
  BodyDef def;
  def.shape = Cylinder{0.2f, 0.6f};
  def.position = Vec3(0.3f, 0.25f, -0.2f);
  def.rotation = glm::angleAxis(glm::radians(25.0f), Vec3(0.0f, 1.0f, 0.0f)) *
                 glm::angleAxis(glm::radians(90.0f), Vec3(0.0f, 0.0f, 1.0f));
  const BodyId cylinder = world.createBody(def);
  std::set<std::uint32_t> ids, first;
  int count = 0;
  world.setPreSolveCallback([&](BodyId a, BodyId b, const Manifold& m) {
    if (!((a == floor && b == cylinder) || (a == cylinder && b == floor))) return true;
    ids.clear();
    for (int i = 0; i < m.count; ++i) ids.insert(m.points[i].featureId);
    count = m.count;
    return true;
  });
  int steps = 0, twoPoints = 0, changed = 0;
  for (int i = 0; i < 90; ++i) {
    world.step(kDt);
    if (i < 30) continue;  // settling
    ++steps;
    if (first.empty()) first = ids;
    twoPoints += count == 2;
    changed += ids != first;
  }
  EXPECT_EQ(first.size(), 2u);
  EXPECT_EQ(twoPoints, steps);
  EXPECT_EQ(changed, 0);
  EXPECT_NEAR(world.transform(cylinder).position.y, 0.2f, 0.01f);
  EXPECT_LT(glm::length(world.angularVelocity(cylinder)), 0.05f);
}

}  // namespace
}  // namespace collide
