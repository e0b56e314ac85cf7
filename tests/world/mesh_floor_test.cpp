// A box on a static triangle-mesh floor in the World: the mesh–box cell's clipped four-point
// manifold and its internal-edge handling (src/narrowphase/mesh_pairs.cpp, docs/narrowphase.md).
#include "support/mesh_floor_helpers.h"
#include "support/world_helpers.h"

#include <gtest/gtest.h>

#include <glm/gtc/quaternion.hpp>

namespace collide {
namespace {

TEST(WorldMeshFloor, BoxSlidingAcrossInternalEdgesStaysLevel) {
  // A frictionless box slides at 3 m/s across the floor's quad edges and diagonals, turned 20°
  // about y so its edges cross the mesh's edges at an angle. A bump on an internal edge would
  // push it along the edge's normal: up (vertical velocity) and back (speed lost). Every contact
  // normal must stay within 1° of vertical, the vertical velocity small, the speed kept.
  BodyDef def = test::boxBody(Vec3(-3.5f, 0.25f, 0.3f), Vec3(0.4f, 0.25f, 0.3f), 1.0f);
  def.rotation = glm::angleAxis(glm::radians(20.0f), Vec3(0.0f, 1.0f, 0.0f));
  def.friction = 0.0f;
  def.linearVelocity = Vec3(3.0f, 0.0f, 0.4f);
  const test::FloorSlide slide = test::slideOverMeshFloor(def);
  test::expectLevelSlide(slide);
}

TEST(WorldMeshFloor, BoxRestingOnTheMeshKeepsFourFeatureIds) {
  // A box settles on the floor with its corners in different triangles: after settling, every
  // step's manifold has four points with the same four ids.
  const test::FloorRest rest = test::restOnMeshFloor(
      test::boxBody(Vec3(0.1f, 0.3f, -0.15f), Vec3(0.7f, 0.3f, 0.6f), 2.0f), 0.0f, 4, 120);
  test::expectStableRest(rest, 4, 0.3f);
}

}  // namespace
}  // namespace collide
