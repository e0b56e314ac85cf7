// The gyroscopic term: torque-free tumbling conserves angular momentum and energy, and a box
// spun about its intermediate axis flips (the Dzhanibekov effect) when Euler's equations say so.
#include "support/world_helpers.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>

namespace collide {
namespace {

using test::kDt;

using Vec3d = std::array<double, 3>;

// Euler's equations for a principal-axis inertia I: I w' = -w x I w.
Vec3d eulerRate(const Vec3d& inertia, const Vec3d& w) {
  return {(inertia[1] - inertia[2]) * w[1] * w[2] / inertia[0],
          (inertia[2] - inertia[0]) * w[2] * w[0] / inertia[1],
          (inertia[0] - inertia[1]) * w[0] * w[1] / inertia[2]};
}

// Reference: RK4 in double with a 1e-4 s step; the first time the body-frame w_y changes sign.
double referenceFlipTime(const Vec3d& inertia, Vec3d w) {
  const double h = 1e-4;
  for (int i = 0; i < 100000; ++i) {
    const auto add = [](const Vec3d& a, const Vec3d& b, double s) {
      return Vec3d{a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2]};
    };
    const Vec3d k1 = eulerRate(inertia, w);
    const Vec3d k2 = eulerRate(inertia, add(w, k1, h / 2));
    const Vec3d k3 = eulerRate(inertia, add(w, k2, h / 2));
    const Vec3d k4 = eulerRate(inertia, add(w, k3, h));
    const Vec3d next{w[0] + h / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0]),
                     w[1] + h / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1]),
                     w[2] + h / 6 * (k1[2] + 2 * k2[2] + 2 * k3[2] + k4[2])};
    if (w[1] > 0.0 && next[1] <= 0.0) return (i + w[1] / (w[1] - next[1])) * h;
    w = next;
  }
  return -1.0;
}

// A 0.2 x 0.6 x 1.2 box: I_x = 0.15, I_y = 0.1233, I_z = 0.0333 per kg, so y is the intermediate
// axis. Spun at 10 rad/s about y with a 0.1% perturbation, it flips within about a second.
TEST(Gyroscopic, BoxSpunAboutTheIntermediateAxisFlipsWhileMomentumIsKept) {
  World world(test::zeroGravityWorld());
  const Vec3 half(0.1f, 0.3f, 0.6f);
  BodyDef def = test::boxBody(Vec3(0.0f), half, 1.0f);
  const Vec3 omega0(0.01f, 10.0f, 0.01f);
  def.angularVelocity = omega0;
  const BodyId box = world.createBody(def);
  const Vec3d inertia{(half.y * half.y + half.z * half.z) / 3.0, (half.x * half.x + half.z * half.z) / 3.0,
                      (half.x * half.x + half.y * half.y) / 3.0};
  const auto momentum = [&] {
    const Quat q = world.transform(box).rotation;
    const Vec3 w = glm::conjugate(q) * world.angularVelocity(box);
    const Vec3 lBody(static_cast<float>(inertia[0]) * w.x, static_cast<float>(inertia[1]) * w.y,
                     static_cast<float>(inertia[2]) * w.z);
    return q * lBody;
  };
  const Vec3 l0 = momentum();
  const float e0 = world.kineticEnergy();
  float worstMagnitude = 0.0f;
  float worstVector = 0.0f;
  float worstEnergy = 0.0f;
  float lowestAlignment = 1.0f;  // body y axis . L direction
  double flipTime = -1.0;
  float previousY = omega0.y;
  for (int step = 1; step <= 180; ++step) {
    world.step(kDt);
    const Vec3 l = momentum();
    worstMagnitude = std::max(worstMagnitude, std::abs(glm::length(l) - glm::length(l0)) / glm::length(l0));
    worstVector = std::max(worstVector, glm::length(l - l0) / glm::length(l0));
    worstEnergy = std::max(worstEnergy, std::abs(world.kineticEnergy() - e0) / e0);
    const Quat q = world.transform(box).rotation;
    lowestAlignment = std::min(lowestAlignment, glm::dot(q * Vec3(0.0f, 1.0f, 0.0f), glm::normalize(l0)));
    const float y = (glm::conjugate(q) * world.angularVelocity(box)).y;
    if (flipTime < 0.0 && previousY > 0.0f && y <= 0.0f)
      flipTime = (step - 1 + previousY / (previousY - y)) * kDt;
    previousY = y;
  }
  EXPECT_LT(lowestAlignment, -0.9f);  // the box turned its intermediate axis over
  EXPECT_LT(worstMagnitude, 0.01f);   // |L| within 1%
  EXPECT_LT(worstVector, 0.02f);      // and the vector L (world frame) within 2% of |L|
  EXPECT_LT(worstEnergy, 0.01f);      // kinetic energy within 1%
  const double expected = referenceFlipTime(inertia, {omega0.x, omega0.y, omega0.z});
  ASSERT_GT(expected, 0.0);
  EXPECT_NEAR(flipTime, expected, 0.05 * expected);
}

// A body spinning about a principal axis is in steady rotation: the gyroscopic term must not
// disturb it (w x I w = 0).
TEST(Gyroscopic, SpinAboutAPrincipalAxisIsSteady) {
  World world(test::zeroGravityWorld());
  BodyDef def = test::boxBody(Vec3(0.0f), Vec3(0.1f, 0.3f, 0.6f), 1.0f);
  def.angularVelocity = Vec3(0.0f, 0.0f, 7.0f);  // the axis of least inertia: stable
  const BodyId box = world.createBody(def);
  for (int step = 0; step < 120; ++step) world.step(kDt);
  const Vec3 w = world.angularVelocity(box);
  EXPECT_NEAR(w.x, 0.0f, 1e-5f);
  EXPECT_NEAR(w.y, 0.0f, 1e-5f);
  EXPECT_NEAR(w.z, 7.0f, 1e-4f);
}

// A body spun faster than a quarter turn per substep is slowed to that bound (the solver's anchors
// are carried with the rotation and mean nothing past it; Box2D v3's b2_maxRotation), about the same
// axis; below the bound nothing changes.
TEST(Gyroscopic, AngularSpeedIsBoundedByAQuarterTurnPerSubstep) {
  World world(WorldDef{.gravity = Vec3(0.0f)});
  BodyDef def;
  def.shape = Sphere{0.5f};
  def.angularVelocity = Vec3(3000.0f, 4000.0f, 0.0f);  // 5000 rad/s
  const BodyId fast = world.createBody(def);
  def.position = Vec3(5.0f, 0.0f, 0.0f);
  def.angularVelocity = Vec3(0.0f, 0.0f, 200.0f);
  const BodyId slow = world.createBody(def);
  world.step(kDt);
  const float bound = 0.25f * kPi * float(world.def().substeps) / kDt;
  const Vec3 w = world.angularVelocity(fast);
  EXPECT_NEAR(glm::length(w), bound, 1e-3f * bound);
  EXPECT_NEAR(w.x / w.y, 0.75f, 1e-5f);
  EXPECT_EQ(world.angularVelocity(slow), Vec3(0.0f, 0.0f, 200.0f));
}

}  // namespace
}  // namespace collide
