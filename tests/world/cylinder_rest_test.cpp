// Cylinders come to rest on flat faces and on each other. A cylinder standing on a
// box, or on another cylinder, is held by a manifold of four rim points (narrowphase/cylinder_pairs);
// on GJK's single point it would rock, tilt and roll off.
#include "support/world_helpers.h"

#include <collide/world.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace collide {
namespace {

using test::kDt;

BodyDef cylinderBody(const Vec3& position, float radius, float halfHeight,
                     const Quat& rotation = Quat(1, 0, 0, 0)) {
  BodyDef def;
  def.shape = Shape(Cylinder{radius, halfHeight});
  def.position = position;
  def.rotation = rotation;
  def.density = 1000.0f;
  return def;
}

float speed(const World& world, BodyId id) {
  return glm::length(world.linearVelocity(id)) + glm::length(world.angularVelocity(id));
}

// The angle between the cylinder's axis and the vertical, in degrees.
float tiltDegrees(const World& world, BodyId id) {
  const Vec3 axis = world.transform(id).rotation * Vec3(0.0f, 1.0f, 0.0f);
  return glm::degrees(std::acos(std::clamp(axis.y, -1.0f, 1.0f)));
}

TEST(CylinderRest, UprightOnABoxStaysUprightAndStillForTenSeconds) {
  World world;
  world.createBody(test::groundBox());
  const BodyId id = world.createBody(cylinderBody(Vec3(0.3f, 0.5f, -0.2f), 0.5f, 0.5f));
  const Vec3 start = world.transform(id).position;
  float energy = 0.0f;
  for (int i = 0; i < 600; ++i) {
    world.step(kDt);
    energy = std::max(energy, world.kineticEnergy());
  }
  EXPECT_LT(tiltDegrees(world, id), 0.5f);
  EXPECT_LT(speed(world, id), 0.01f);
  EXPECT_LT(glm::length(world.transform(id).position - start), 0.01f);
  EXPECT_LT(energy, 0.5f);  // no rocking: it never gains more than a settling joule fraction
}

TEST(CylinderRest, ThreeStackedCapToCapRestWithinThreeSeconds) {
  World world;
  world.createBody(test::groundBox());
  BodyId ids[3];
  for (int k = 0; k < 3; ++k)
    ids[k] = world.createBody(cylinderBody(Vec3(0.0f, 0.5f + 1.0f * k, 0.0f), 0.4f, 0.5f));
  for (int i = 0; i < 180; ++i) world.step(kDt);
  for (int k = 0; k < 3; ++k) {
    SCOPED_TRACE(k);
    EXPECT_LT(glm::length(world.linearVelocity(ids[k])), 0.01f);
    EXPECT_LT(glm::length(world.angularVelocity(ids[k])), 0.01f);
    EXPECT_LT(tiltDegrees(world, ids[k]), 0.5f);
    EXPECT_NEAR(world.transform(ids[k]).position.x, 0.0f, 0.01f);
    EXPECT_NEAR(world.transform(ids[k]).position.z, 0.0f, 0.01f);
  }
}

TEST(CylinderRest, OnItsSideItRollsStraight) {
  // Lying along z, rolling along x at 2 m/s without slipping (w = v / r): after 2 s it has rolled
  // about 4 m along x (rolling friction is not modelled) and not drifted along its axis.
  World world;
  world.createBody(test::groundBox());
  BodyDef def = cylinderBody(Vec3(0.0f, 0.5f, 0.0f), 0.5f, 0.6f, glm::angleAxis(0.5f * kPi, Vec3(1, 0, 0)));
  def.linearVelocity = Vec3(2.0f, 0.0f, 0.0f);
  def.angularVelocity = Vec3(0.0f, 0.0f, -4.0f);
  const BodyId id = world.createBody(def);
  for (int i = 0; i < 120; ++i) world.step(kDt);
  const Vec3 p = world.transform(id).position;
  EXPECT_NEAR(p.x, 4.0f, 0.2f);
  EXPECT_NEAR(p.z, 0.0f, 0.01f);
  EXPECT_NEAR(p.y, 0.5f, 0.01f);
  const Vec3 axis = world.transform(id).rotation * Vec3(0.0f, 1.0f, 0.0f);
  EXPECT_GT(std::abs(axis.z), 0.999f);  // still lying across the motion
}

}  // namespace
}  // namespace collide
