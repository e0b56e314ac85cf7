// The viewer's mouse, without a window: the cursor's ray (OrbitCamera::rayThrough), dragging a body
// with the MouseSpring, and shooting spheres.
#include "interaction.h"
#include "orbit_camera.h"

#include <gtest/gtest.h>

#include <glm/ext/matrix_projection.hpp>

#include <cmath>
#include <random>

using namespace collide;
using namespace collide::viewer;

namespace {

constexpr float kDt = 1.0f / 60.0f;

BodyDef groundBox() {
  BodyDef def;
  def.type = BodyType::Static;
  def.shape = Shape(Box{Vec3(20.0f, 0.5f, 20.0f)});
  def.position = Vec3(0.0f, -0.5f, 0.0f);
  return def;
}

// A 1 m cube resting on the ground (its centre at y = 0.5), of the given density.
BodyDef crate(float x, float density) {
  BodyDef def;
  def.shape = Shape(Box{Vec3(0.5f)});
  def.position = Vec3(x, 0.5f, 0.0f);
  def.density = density;
  return def;
}

// A ray from far in front (+z) of the point, looking along -z: the camera of these tests.
Ray rayAt(const Vec3& point) { return Ray{point + Vec3(0.0f, 0.0f, 10.0f), Vec3(0.0f, 0.0f, -1.0f), 1e30f}; }
const Vec3 kForward(0.0f, 0.0f, -1.0f);

}  // namespace

TEST(OrbitCamera, TheRayThroughAProjectedPointPassesThroughIt) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (int i = 0; i < 200; ++i) {
    OrbitCamera camera;
    camera.target = Vec3(5.0f * u(rng), 5.0f * u(rng), 5.0f * u(rng));
    camera.yaw = 3.0f * u(rng);
    camera.pitch = 1.4f * u(rng);
    camera.distance = 12.0f + 5.0f * u(rng);  // the point (within 5.2 of the target) stays in front
    const float width = 640.0f, height = 360.0f;
    const Vec3 point = camera.target + 3.0f * Vec3(u(rng), u(rng), u(rng));
    // Where the renderer's matrices put the point, in window coordinates (y down).
    const glm::vec3 projected = glm::projectNO(point, camera.view(), camera.projection(width / height),
                                               glm::vec4(0.0f, 0.0f, width, height));
    const Ray ray = camera.rayThrough(projected.x, height - projected.y, width, height);
    EXPECT_NEAR(glm::length(ray.direction), 1.0f, 1e-5f);
    const Vec3 offset = point - ray.origin;
    const float along = glm::dot(offset, ray.direction);
    EXPECT_GT(along, 0.0f);
    EXPECT_LT(glm::length(offset - along * ray.direction), 1e-4f * glm::length(offset)) << "camera " << i;
  }
  OrbitCamera camera;
  const Ray centre = camera.rayThrough(320.0f, 180.0f, 640.0f, 360.0f);
  EXPECT_LT(glm::length(centre.direction - camera.forward()), 1e-6f);
}

TEST(MouseSpring, PullsTheGrabbedPointToTheCursorAndLetsGo) {
  World world;
  world.createBody(groundBox());
  const BodyId box = world.createBody(crate(0.0f, 500.0f));
  MouseSpring spring;
  ASSERT_TRUE(spring.grab(world, rayAt(Vec3(0.0f, 0.5f, 0.0f)), kForward));
  EXPECT_EQ(spring.body(), box);
  EXPECT_LT(glm::length(spring.grabbedPoint(world) - Vec3(0.0f, 0.5f, 0.5f)), 1e-5f);  // the front face
  EXPECT_EQ(world.bodyCount(), 3u);                                                    // the anchor
  EXPECT_EQ(world.constraintCount(), 1u);

  // The cursor moves 2 m up: the target is on the plane z = 0.5 (the hit's depth), 2 m higher.
  const Vec3 eye(0.0f, 0.5f, 10.0f);
  spring.drag(world, Ray{eye, glm::normalize(Vec3(0.0f, 2.5f, 0.5f) - eye), 1e30f}, kForward);
  EXPECT_LT(glm::length(spring.target() - Vec3(0.0f, 2.5f, 0.5f)), 1e-5f);
  for (int i = 0; i < 120; ++i) world.step(kDt);
  // A 4 Hz spring stiff as m omega^2 sags g / omega^2 = 1.6 cm under the weight; the box swinging
  // on it moves that by a little, so within three times the sag.
  EXPECT_LT(glm::length(spring.grabbedPoint(world) - spring.target()), 0.05f);
  EXPECT_GT(world.centerOfMass(box).y, 1.5f);  // it hangs from the point, well off the ground

  spring.release(world);
  EXPECT_FALSE(spring.active());
  EXPECT_EQ(world.bodyCount(), 2u);
  EXPECT_EQ(world.constraintCount(), 0u);
  for (int i = 0; i < 120; ++i) world.step(kDt);
  EXPECT_LT(world.centerOfMass(box).y, 0.6f);  // back on the ground
}

TEST(MouseSpring, LightAndHeavyBodiesFollowAlike) {
  World world;
  world.createBody(groundBox());
  const BodyId light = world.createBody(crate(-3.0f, 50.0f));
  const BodyId heavy = world.createBody(crate(3.0f, 5000.0f));
  MouseSpring lightSpring, heavySpring;
  ASSERT_TRUE(lightSpring.grab(world, rayAt(Vec3(-3.0f, 0.5f, 0.0f)), kForward));
  ASSERT_TRUE(heavySpring.grab(world, rayAt(Vec3(3.0f, 0.5f, 0.0f)), kForward));
  ASSERT_EQ(lightSpring.body(), light);
  ASSERT_EQ(heavySpring.body(), heavy);
  lightSpring.drag(world, rayAt(Vec3(-3.0f, 2.0f, 0.0f)), kForward);
  heavySpring.drag(world, rayAt(Vec3(3.0f, 2.0f, 0.0f)), kForward);
  for (int i = 0; i < 30; ++i) {
    world.step(kDt);
    // A stiffness independent of mass would leave the 100 times heavier box 100 times lower.
    const float lightHeight = lightSpring.grabbedPoint(world).y;
    const float heavyHeight = heavySpring.grabbedPoint(world).y;
    EXPECT_NEAR(lightHeight, heavyHeight, 0.01f) << "step " << i;
  }
  EXPECT_GT(heavySpring.grabbedPoint(world).y, 1.5f);
}

TEST(MouseSpring, GrabsOnlyDynamicBodiesAndSurvivesTheirDestruction) {
  World world;
  world.createBody(groundBox());
  const BodyId box = world.createBody(crate(0.0f, 500.0f));
  MouseSpring spring;
  // The ground (static) and the sky: nothing grabbed, nothing created.
  EXPECT_FALSE(spring.grab(world, Ray{Vec3(5.0f, 5.0f, 0.0f), Vec3(0.0f, -1.0f, 0.0f), 1e30f}, kForward));
  EXPECT_FALSE(spring.grab(world, Ray{Vec3(5.0f, 5.0f, 0.0f), Vec3(0.0f, 1.0f, 0.0f), 1e30f}, kForward));
  EXPECT_FALSE(spring.active());
  EXPECT_EQ(world.bodyCount(), 2u);

  ASSERT_TRUE(spring.grab(world, rayAt(Vec3(0.0f, 0.5f, 0.0f)), kForward));
  world.destroyBody(box);  // e.g. a shot that the viewer removes while it is held
  EXPECT_NO_THROW(spring.drag(world, rayAt(Vec3(0.0f, 2.0f, 0.0f)), kForward));
  EXPECT_FALSE(spring.active());
  EXPECT_EQ(world.bodyCount(), 1u);  // the anchor went too
  EXPECT_NO_THROW(world.step(kDt));
}

TEST(SphereShot, LeavesFromTheRayOriginAlongItWithTheChosenSpeedAndSpin) {
  WorldDef def;
  def.gravity = Vec3(0.0f);
  World world(def);
  SphereShot shot;
  shot.speed = 80.0f;
  shot.radius = 0.1f;
  shot.spin = 300.0f;
  const Ray ray{Vec3(1.0f, 2.0f, 3.0f), Vec3(0.0f, 0.0f, -4.0f), 1e30f};  // not unit
  const BodyId id = shootSphere(world, ray, shot);
  EXPECT_EQ(world.transform(id).position, ray.origin);
  EXPECT_EQ(world.linearVelocity(id), Vec3(0.0f, 0.0f, -80.0f));
  EXPECT_NEAR(glm::length(world.angularVelocity(id)), 300.0f, 1e-3f);
  EXPECT_NEAR(glm::dot(world.angularVelocity(id), Vec3(0.0f, 0.0f, 1.0f)), 0.0f, 1e-3f);  // across the shot
  EXPECT_EQ(world.shape(id).sphere().radius, 0.1f);
  // Straight up, the spin axis is still across the shot.
  const BodyId up = shootSphere(world, Ray{Vec3(0.0f), Vec3(0.0f, 1.0f, 0.0f), 1e30f}, shot);
  EXPECT_NEAR(glm::dot(world.angularVelocity(up), Vec3(0.0f, 1.0f, 0.0f)), 0.0f, 1e-3f);
  EXPECT_NEAR(glm::length(world.angularVelocity(up)), 300.0f, 1e-3f);
  // A bad shot is the World's error, not a crash.
  shot.radius = -1.0f;
  EXPECT_THROW(shootSphere(world, ray, shot), Error);
}
