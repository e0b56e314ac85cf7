// A cylinder on a static triangle-mesh floor in the World: the mesh–cylinder cell's rim manifolds
// and internal-edge handling (src/narrowphase/triangle_generic.cpp).
#include "support/mesh_floor_helpers.h"

#include <gtest/gtest.h>

#include <glm/gtc/quaternion.hpp>

namespace collide {
namespace {

TEST(WorldMeshFloorGeneric, CylinderSlidingOnItsCapStaysLevel) {
  // A frictionless cylinder standing on its cap slides at 3 m/s across the floor's quad edges and
  // diagonals. A bump on an internal edge would push it up and back: every contact normal must stay
  // within 1° of vertical, the vertical velocity small, the speed kept.
  BodyDef def;
  def.shape = Cylinder{0.3f, 0.25f};
  def.position = Vec3(-3.5f, 0.25f, 0.3f);
  def.friction = 0.0f;
  def.linearVelocity = Vec3(3.0f, 0.0f, 0.4f);
  const test::FloorSlide slide = test::slideOverMeshFloor(def);
  test::expectLevelSlide(slide);
}

TEST(WorldMeshFloorGeneric, CylinderLyingOnTheFloorRestsOnTwoPoints) {
  // A cylinder dropped lying on its side settles on its lowest line: two points, the same two ids
  // every step.
  BodyDef def;
  def.shape = Cylinder{0.2f, 0.6f};
  def.position = Vec3(0.3f, 0.25f, -0.2f);
  def.rotation = glm::angleAxis(glm::radians(25.0f), Vec3(0.0f, 1.0f, 0.0f)) *
                 glm::angleAxis(glm::radians(90.0f), Vec3(0.0f, 0.0f, 1.0f));
  const test::FloorRest rest = test::restOnMeshFloor(def, 0.5f, 2, 90);
  test::expectStableRest(rest, 2, 0.2f);
  EXPECT_LT(glm::length(rest.spin), 0.05f);
}

}  // namespace
}  // namespace collide
