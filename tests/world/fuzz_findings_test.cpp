// What fuzz/world_fuzzer found, each as the smallest story that showed it. The inputs are finite
// but extreme (a 3e38 m sphere, a body at 1e20 m/s, a spin of 1e30 rad/s): a game reaches them by
// a unit error or an uninitialised value, and the world must then go on stepping, refuse the input
// with collide::Error, or freeze the body and report it (docs/reliability.md, "The world guards
// itself"). Before the fixes, each story below crashed the step (an Error thrown half-way through
// it), hung it, bricked the world, or left a NaN in a state or an event.
#include "world/world_helpers.h"

#include <collide/world.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace collide {
namespace {

using ::testing::HasSubstr;

constexpr float kDt = 1.0f / 60.0f;
constexpr float kHuge = 3.0e38f;  // finite, near the largest float

BodyDef sphere(BodyType type, float radius, const Vec3& position) {
  BodyDef def;
  def.type = type;
  def.shape = Shape(Sphere{radius});
  def.position = position;
  return def;
}

// createBody computed the mass (infinite for a 3e38 m ellipsoid), then the broad phase refused the
// body's infinite box: the Error left the body allocated without a proxy, and every later step
// threw "null proxy id". Now the mass and the box are checked, and any refusal frees the slot.
TEST(WorldFuzzFindings, ShapeTooLargeOrTooSmallIsRefusedAndTheWorldStillSteps) {
  World world;
  BodyDef huge;
  huge.shape = Shape(Ellipsoid{Vec3(kHuge, 2.0f, 0.01f)});
  EXPECT_THAT([&] { world.createBody(huge); },
              ::testing::ThrowsMessage<Error>(HasSubstr("mass properties not representable")));
  // A 1e-20 m sphere's mass underflows to 0 (an infinite inverse mass).
  EXPECT_THAT([&] { world.createBody(sphere(BodyType::Dynamic, 1e-20f, Vec3(0.0f))); },
              ::testing::ThrowsMessage<Error>(HasSubstr("mass properties not representable")));
  // A static shape whose box overflows where it is placed.
  EXPECT_THAT([&] { world.createBody(sphere(BodyType::Static, kHuge, Vec3(kHuge, 0.0f, 0.0f))); },
              ::testing::ThrowsMessage<Error>(HasSubstr("bounds are not finite")));
  EXPECT_EQ(world.bodyCount(), 0u);
  const BodyId ball = world.createBody(sphere(BodyType::Dynamic, 0.5f, Vec3(0.0f, 2.0f, 0.0f)));
  EXPECT_EQ(ball.index, 0u) << "the refused bodies' slots are free again";
  ASSERT_NO_THROW(world.step(kDt));
  EXPECT_LT(world.transform(ball).position.y, 2.0f);
}

}  // namespace
}  // namespace collide
