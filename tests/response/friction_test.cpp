// The lecture's two friction models (slide 12): viscous force and velocity "tax", on particles with
// closed-form answers and on random rigid pairs for the conservation laws.
#include <gtest/gtest.h>

#include <collide/error.h>

#include <limits>
#include <random>

#include "response/friction.h"
#include "support/collide_error.h"
#include "support/response_test_helpers.h"
#include "support/test_assertions.h"

using namespace collide;
using namespace collide::detail;
using namespace collide::test;

namespace {

using test::expectVecNear;

Vec3 relativeAt(const ImpactBody& a, const ImpactBody& b, const Vec3& point) {
  return velocityAt(b, point) - velocityAt(a, point);
}

Vec3 tangentialPart(const Vec3& v, const Vec3& n) { return v - glm::dot(v, n) * n; }

// A particle A at rest-ish and a particle B sliding over it along the contact plane y = 0.
const Vec3 kNormal(0, 1, 0);
const Vec3 kPoint(0, 0, 0);

}  // namespace

TEST(Friction, ViscousForceOnParticlesIsProportionalToTheSlip) {
  // F = -k u_t for dt: B loses k dt u_t / mB, A gains k dt u_t / mA, so the slip shrinks by the
  // factor 1 - k dt (1/mA + 1/mB). mA = 2, mB = 4, k = 3, dt = 0.1: factor 1 - 0.3 * 0.75 = 0.775.
  ImpactBody a = makeParticle(2.0f, Vec3(0, -1, 0), Vec3(0.5f, 0.2f, 0)).body;
  ImpactBody b = makeParticle(4.0f, Vec3(0, 1, 0), Vec3(2.5f, -0.3f, 1)).body;
  const Vec3 slip(2, 0, 1);  // tangential part of vB - vA
  const Vec3 impulse = applyViscousFriction(a, b, kPoint, kNormal, 3.0f, 0.1f);
  expectVecNear(impulse, -0.3f * slip, 1e-6f);
  expectVecNear(b.linearVelocity, Vec3(2.5f, -0.3f, 1) - 0.3f * slip / 4.0f, 1e-6f);
  expectVecNear(a.linearVelocity, Vec3(0.5f, 0.2f, 0) + 0.3f * slip / 2.0f, 1e-6f);
  expectVecNear(tangentialPart(relativeAt(a, b, kPoint), kNormal), 0.775f * slip, 1e-6f);
  EXPECT_FLOAT_EQ(a.linearVelocity.y, 0.2f);  // normal components untouched
  EXPECT_FLOAT_EQ(b.linearVelocity.y, -0.3f);
}

TEST(Friction, ViscousForceNeverReversesTheSlip) {
  // A force that would overshoot over a long step (k dt / m >> 1) stops the slip instead.
  ImpactBody wall = makeStatic(Vec3(0, -1, 0)).body;
  ImpactBody b = makeParticle(1.0f, Vec3(0, 1, 0), Vec3(3, -0.5f, -4)).body;
  applyViscousFriction(wall, b, kPoint, kNormal, 1000.0f, 0.1f);
  expectVecNear(b.linearVelocity, Vec3(0, -0.5f, 0), 1e-6f);
  expectVecNear(wall.linearVelocity, Vec3(0.0f), 0.0f);
}

TEST(Friction, DampingTaxIsMassWeightedOnParticles) {
  // Tax 0.25 on the slip u_t = (2, 0, 1): B loses 0.25 u_t mA / (mA + mB), A gains 0.25 u_t mB / M.
  ImpactBody a = makeParticle(1.0f, Vec3(0, -1, 0), Vec3(0.5f, 0.2f, 0)).body;
  ImpactBody b = makeParticle(3.0f, Vec3(0, 1, 0), Vec3(2.5f, -0.3f, 1)).body;
  const Vec3 slip(2, 0, 1);
  applyDampingFriction(a, b, kPoint, kNormal, 0.25f);
  expectVecNear(b.linearVelocity, Vec3(2.5f, -0.3f, 1) - 0.25f * slip * 0.25f, 1e-6f);
  expectVecNear(a.linearVelocity, Vec3(0.5f, 0.2f, 0) + 0.25f * slip * 0.75f, 1e-6f);
  expectVecNear(tangentialPart(relativeAt(a, b, kPoint), kNormal), 0.75f * slip, 1e-6f);
  // Against a static body the mover pays the whole tax; a tax of 1 stops the sliding.
  ImpactBody wall = makeStatic(Vec3(0, -1, 0)).body;
  ImpactBody c = makeParticle(2.0f, Vec3(0, 1, 0), Vec3(3, -0.5f, -4)).body;
  applyDampingFriction(wall, c, kPoint, kNormal, 0.5f);
  expectVecNear(c.linearVelocity, Vec3(1.5f, -0.5f, -2), 1e-6f);
  applyDampingFriction(wall, c, kPoint, kNormal, 1.0f);
  expectVecNear(c.linearVelocity, Vec3(0, -0.5f, 0), 1e-6f);
}

TEST(Friction, RandomRigidContactsLoseSlipKeepMomentum) {
  // 500 random rotated-box pairs at a random contact. Both models: total linear momentum and angular
  // momentum about a fixed point kept, each body's linear velocity keeps its normal component, kinetic
  // energy never grows. Viscous: the slip's component along its own direction shrinks and stays >= 0.
  // Damping: the tangential slip becomes exactly (1 - tax) times itself.
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const glm::dvec3 origin(-1.0, 0.5, 2.0);
  for (int i = 0; i < 500; ++i) {
    const BodyCase a0 = randomBox(rng), b0 = randomBox(rng);
    const Vec3 point = 0.5f * (a0.body.centerOfMass + b0.body.centerOfMass) + randomInUnitBall(rng);
    const Vec3 normal = randomUnitVector(rng);
    const Vec3 slip = tangentialPart(relativeAt(a0.body, b0.body, point), normal);
    const float speed = glm::length(slip);
    if (speed < 1e-2f) continue;
    const Vec3 direction = slip / speed;
    const double energy = kineticEnergy(a0, b0);
    const double momentumScale = linearMomentumScale(a0, b0);
    const double angularScale = angularMomentumScale(a0, origin) + angularMomentumScale(b0, origin);
    for (int model = 0; model < 2; ++model) {
      BodyCase a = a0, b = b0;
      const float tax = unit(rng);
      if (model == 0) {
        applyViscousFriction(a.body, b.body, point, normal, 20.0f * unit(rng), 1.0f / 60.0f);
      } else {
        applyDampingFriction(a.body, b.body, point, normal, tax);
      }
      EXPECT_LE(glm::length(linearMomentum(a, b) - linearMomentum(a0, b0)), 2e-6 * momentumScale) << i;
      EXPECT_LE(glm::length(angularMomentum(a, b, origin) - angularMomentum(a0, b0, origin)),
                2e-5 * angularScale)
          << i;
      EXPECT_NEAR(glm::dot(a.body.linearVelocity, normal), glm::dot(a0.body.linearVelocity, normal), 1e-5f);
      EXPECT_NEAR(glm::dot(b.body.linearVelocity, normal), glm::dot(b0.body.linearVelocity, normal), 1e-5f);
      EXPECT_LE(kineticEnergy(a, b), energy * (1.0 + 1e-5)) << i;
      const Vec3 slipAfter = tangentialPart(relativeAt(a.body, b.body, point), normal);
      const float alongAfter = glm::dot(slipAfter, direction);
      EXPECT_LE(alongAfter, speed * (1.0f + 1e-5f)) << i;
      EXPECT_GE(alongAfter, -1e-4f * speed) << i;
      if (model == 1) expectVecNear(slipAfter, (1.0f - tax) * slip, 1e-4f * (1.0f + speed));
    }
  }
}

TEST(Friction, NoSlipOrTwoInfiniteMassesDoNothing) {
  ImpactBody a = makeParticle(1.0f, Vec3(0, -1, 0), Vec3(1, 2, 0)).body;
  ImpactBody b = makeParticle(1.0f, Vec3(0, 1, 0), Vec3(1, -1, 0)).body;  // same tangential velocity
  EXPECT_EQ(applyViscousFriction(a, b, kPoint, kNormal, 5.0f, 0.1f), Vec3(0.0f));
  EXPECT_EQ(applyDampingFriction(a, b, kPoint, kNormal, 0.5f), Vec3(0.0f));
  ImpactBody s = makeStatic(Vec3(0, -1, 0)).body;
  ImpactBody k = makeStatic(Vec3(0, 1, 0)).body;
  k.linearVelocity = Vec3(3, 0, 0);
  applyDampingFriction(s, k, kPoint, kNormal, 1.0f);
  EXPECT_EQ(k.linearVelocity, Vec3(3, 0, 0));
}

TEST(Friction, BadInputThrows) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  ImpactBody a = makeParticle(1.0f, Vec3(0, -1, 0), Vec3(0.0f)).body;
  ImpactBody b = makeParticle(1.0f, Vec3(0, 1, 0), Vec3(1, 0, 0)).body;
  EXPECT_COLLIDE_ERROR(applyViscousFriction(a, b, kPoint, kNormal, -1.0f, 0.1f));
  EXPECT_COLLIDE_ERROR(applyViscousFriction(a, b, kPoint, kNormal, nan, 0.1f));
  EXPECT_COLLIDE_ERROR(applyViscousFriction(a, b, kPoint, kNormal, 1.0f, 0.0f));
  EXPECT_COLLIDE_ERROR(applyViscousFriction(a, b, kPoint, kNormal, 1.0f, -0.1f));
  EXPECT_COLLIDE_ERROR(applyViscousFriction(a, b, kPoint, Vec3(0, 3, 0), 1.0f, 0.1f));
  EXPECT_COLLIDE_ERROR(applyDampingFriction(a, b, kPoint, kNormal, 1.5f));
  EXPECT_COLLIDE_ERROR(applyDampingFriction(a, b, kPoint, kNormal, -0.5f));
  EXPECT_COLLIDE_ERROR(applyDampingFriction(a, b, kPoint, kNormal, nan));
  EXPECT_COLLIDE_ERROR(applyDampingFriction(a, b, Vec3(nan), kNormal, 0.5f));
  ImpactBody bad = b;
  bad.inverseMass = nan;
  EXPECT_COLLIDE_ERROR(applyDampingFriction(a, bad, kPoint, kNormal, 0.5f));
  EXPECT_EQ(b.linearVelocity, Vec3(1, 0, 0));
}
