// Rolling resistance (BodyDef::rollingResistance): a rolling ball slows at the rate a resisting
// torque of that lever times the normal force gives, and a rocking ellipsoid comes to rest.
#include "support/collide_error.h"
#include "support/world_helpers.h"

#include <collide/world.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace collide {
namespace {

using test::kDt;

// A solid ball of radius r rolling without slipping, resisted by a torque d N (N = m g): m a = -f and
// I alpha = f r - d m g with a = alpha r and I = 2/5 m r^2 give a = -(5/7) d g / r.
TEST(RollingResistance, ARollingBallSlowsAtTheRateTheTorqueGives) {
  const float r = 0.5f, d = 0.01f, v0 = 2.0f, g = 9.81f;
  for (const float resistance : {0.0f, d}) {
    SCOPED_TRACE(resistance);
    World world;
    BodyDef ground = test::groundBox();
    ground.rollingResistance = resistance;
    world.createBody(ground);
    BodyDef ball = test::sphereBody(Vec3(0.0f, r, 0.0f), r, 1.0f, Vec3(v0, 0.0f, 0.0f));
    ball.angularVelocity = Vec3(0.0f, 0.0f, -v0 / r);  // rolling, not sliding
    const BodyId id = world.createBody(ball);
    for (int i = 0; i < 300; ++i) world.step(kDt);  // 5 s
    const float expected = v0 - 5.0f / 7.0f * resistance * g / r * 5.0f;
    EXPECT_NEAR(world.linearVelocity(id).x, expected, 0.03f * v0);
    EXPECT_NEAR(world.angularVelocity(id).z, -world.linearVelocity(id).x / r,
                0.02f * v0 / r);  // still rolling
  }
}

// An ellipsoid dropped tilted onto a box rocks on its single contact point; without rolling
// resistance it still rocks after 5 s, as an ideal one would, with 5 cm of it it rests on its
// flattest side by then. Either way its mechanical energy never exceeds what it was dropped with.
TEST(RollingResistance, ARockingEllipsoidComesToRest) {
  for (const float resistance : {0.0f, 0.05f}) {
    SCOPED_TRACE(resistance);
    World world;
    world.createBody(test::groundBox());
    BodyDef def;
    def.shape = Shape(Ellipsoid{Vec3(0.6f, 0.3f, 0.4f)});
    def.position = Vec3(0.0f, 0.5f, 0.0f);
    def.rotation = glm::angleAxis(0.2f, glm::normalize(Vec3(1.0f, 0.0f, 1.0f)));
    def.rollingResistance = resistance;
    const BodyId id = world.createBody(def);
    const float g = 9.81f;
    const auto energy = [&] { return world.kineticEnergy() + world.mass(id) * g * world.centerOfMass(id).y; };
    const float dropped = energy();
    float most = dropped;
    for (int i = 0; i < 300; ++i) {
      world.step(kDt);
      most = std::max(most, energy());
    }
    EXPECT_LE(most, dropped + 1e-3f * std::abs(dropped));
    const float speed = glm::length(world.linearVelocity(id)) + glm::length(world.angularVelocity(id));
    if (resistance > 0.0f) {
      EXPECT_LT(speed, 0.01f);
      EXPECT_NEAR(world.transform(id).position.y, 0.3f, 0.005f);  // the short axis vertical
    } else {
      EXPECT_GT(speed, 0.1f);  // still rocking: the resistance is what stops it
    }
  }
}

TEST(RollingResistance, NegativeOrNonFiniteIsRefused) {
  World world;
  BodyDef def = test::sphereBody(Vec3(0.0f), 0.5f, 1.0f);
  def.rollingResistance = -0.1f;
  EXPECT_COLLIDE_ERROR(world.createBody(def));
  def.rollingResistance = std::nanf("");
  EXPECT_COLLIDE_ERROR(world.createBody(def));
}

}  // namespace
}  // namespace collide
