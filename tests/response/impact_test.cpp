// The lecture's interpolated impact (slides 21-34) against its closed-form answers, and the
// conservation laws on random rigid-body impacts. The world's Newton restitution (the contact
// solver's) is checked in the world: tests/world/newton_impact_test.cpp.
#include <gtest/gtest.h>

#include <collide/error.h>
#include <collide/settings.h>

#include <cmath>
#include <limits>
#include <random>

#include "response/impact.h"
#include "support/collide_error.h"
#include "support/response_test_helpers.h"
#include "support/test_assertions.h"

using namespace collide;
using namespace collide::detail;
using namespace collide::test;

namespace {

constexpr float kTight = 1e-5f;  // closed-form answers in float, velocities of size ~1

using test::expectVecNear;

// Runs the model on copies.
struct Outcome {
  ImpactBody a;
  ImpactBody b;
};
Outcome run(ImpactBody a, ImpactBody b, const Vec3& point, const Vec3& normal, float e) {
  resolveImpactInterpolated(a, b, point, normal, e);
  return {a, b};
}

// Two random boxes, a contact point near them and a normal along which they approach.
struct RandomImpact {
  BodyCase a;
  BodyCase b;
  Vec3 point{0.0f};
  Vec3 normal{0.0f};
};
RandomImpact randomImpact(std::mt19937& rng) {
  for (;;) {
    RandomImpact c{randomBox(rng), randomBox(rng), Vec3(0.0f), Vec3(0.0f)};
    c.point = 0.5f * (c.a.body.centerOfMass + c.b.body.centerOfMass) + 1.5f * randomInUnitBall(rng);
    c.normal = randomUnitVector(rng);
    float approach = normalApproach(c.a.body, c.b.body, c.point, c.normal);
    if (approach > 0.0f) {
      c.normal = -c.normal;
      approach = -approach;
    }
    if (approach < -1e-2f) return c;
  }
}

}  // namespace

TEST(Impact, EqualMassesElastic1DVelocitiesSwap) {
  // Slide 32: equal masses, fully elastic, 1D: the two velocities swap.
  const BodyCase a = makeParticle(2.0f, Vec3(0, 0, 0), Vec3(3, 0, 0));
  const BodyCase b = makeParticle(2.0f, Vec3(1, 0, 0), Vec3(-1, 0, 0));
  const Outcome out = run(a.body, b.body, Vec3(0.5f, 0, 0), Vec3(1, 0, 0), 1.0f);
  expectVecNear(out.a.linearVelocity, Vec3(-1, 0, 0), kTight);
  expectVecNear(out.b.linearVelocity, Vec3(3, 0, 0), kTight);
}

TEST(Impact, EqualMassesElastic3DNormalComponentsSwapTangentialKept) {
  // Slide 32: the components orthogonal to the impact plane swap; the tangential ones stay.
  const Vec3 n = glm::normalize(Vec3(1, 2, -1));
  Vec3 t, s;
  orthonormalBasis(n, t, s);
  const Vec3 va = 2.0f * n + 0.7f * t - 0.3f * s;
  const Vec3 vb = -1.5f * n - 0.4f * t + 1.1f * s;
  const BodyCase a = makeParticle(0.5f, Vec3(0.0f), va);
  const BodyCase b = makeParticle(0.5f, n, vb);
  {
    const Outcome out = run(a.body, b.body, 0.5f * n, n, 1.0f);
    expectVecNear(out.a.linearVelocity, -1.5f * n + 0.7f * t - 0.3f * s, kTight);
    expectVecNear(out.b.linearVelocity, 2.0f * n - 0.4f * t + 1.1f * s, kTight);
  }
}

TEST(Impact, StaticWallElasticFlipsNormalComponent) {
  // Slide 33: A static (mA -> infinity, vA = 0): the normal component of vB flips.
  const BodyCase wall = makeStatic(Vec3(0.0f));
  const BodyCase ball = makeParticle(3.0f, Vec3(0, 1, 0), Vec3(2, -3, 1));
  {
    const Outcome out = run(wall.body, ball.body, Vec3(0, 0.5f, 0), Vec3(0, 1, 0), 1.0f);
    expectVecNear(out.b.linearVelocity, Vec3(2, 3, 1), kTight);
    expectVecNear(out.a.linearVelocity, Vec3(0.0f), 0.0f);
    expectVecNear(out.a.angularVelocity, Vec3(0.0f), 0.0f);
  }
  // Same with the wall as B: the normal from A to B now points into the wall.
  {
    const Outcome out = run(ball.body, wall.body, Vec3(0, 0.5f, 0), Vec3(0, -1, 0), 1.0f);
    expectVecNear(out.a.linearVelocity, Vec3(2, 3, 1), kTight);
  }
}

TEST(Impact, KinematicWallElasticReflectsTheRelativeVelocity) {
  // In the wall's frame it is the static case: a wall rising at 1 hit by a ball falling at 3 meets it
  // at -4 and sends it off at +4 relative, i.e. 5 upwards; the wall's motion is not changed.
  BodyCase wall = makeStatic(Vec3(0.0f));
  wall.body.linearVelocity = Vec3(0, 1, 0);
  const BodyCase ball = makeParticle(1.0f, Vec3(0, 1, 0), Vec3(0.5f, -3, 0));
  const Outcome out = run(wall.body, ball.body, Vec3(0, 0.5f, 0), Vec3(0, 1, 0), 1.0f);
  expectVecNear(out.b.linearVelocity, Vec3(0.5f, 5, 0), kTight);
  expectVecNear(out.a.linearVelocity, Vec3(0, 1, 0), 0.0f);
}

TEST(Impact, InelasticEqualMassesTakeTheAverage) {
  // Slide 32: fully inelastic, equal masses: both leave with the average velocity (3D).
  const BodyCase a = makeParticle(1.5f, Vec3(0.0f), Vec3(3, 1, -2));
  const BodyCase b = makeParticle(1.5f, Vec3(1, 0, 0), Vec3(-1, 2, 4));
  const Outcome out = run(a.body, b.body, Vec3(0.5f, 0, 0), Vec3(1, 0, 0), 0.0f);
  expectVecNear(out.a.linearVelocity, Vec3(1, 1.5f, 1), kTight);
  expectVecNear(out.b.linearVelocity, Vec3(1, 1.5f, 1), kTight);
}

TEST(Impact, InelasticUnequalMassesShareTheMomentumVelocity) {
  // Slide 21: (mA + mB) v = mA vA + mB vB.
  const BodyCase a = makeParticle(1.0f, Vec3(0.0f), Vec3(4, 0, 1));
  const BodyCase b = makeParticle(3.0f, Vec3(1, 0, 0), Vec3(0, 0, -3));
  const Outcome out = run(a.body, b.body, Vec3(0.5f, 0, 0), Vec3(1, 0, 0), 0.0f);
  expectVecNear(out.a.linearVelocity, Vec3(1, 0, -2), kTight);
  expectVecNear(out.b.linearVelocity, Vec3(1, 0, -2), kTight);
}

TEST(Impact, InelasticAgainstStaticStopsDead) {
  // Slide 33: "B stops dead" (v'B = 0); a rigid body glued to a static one stops spinning as well.
  const BodyCase wall = makeStatic(Vec3(0, -1, 0));
  const BodyCase particle = makeParticle(2.0f, Vec3(0, 1, 0), Vec3(1, -2, 0.5f));
  Outcome out = run(wall.body, particle.body, Vec3(0, 0.5f, 0), Vec3(0, 1, 0), 0.0f);
  expectVecNear(out.b.linearVelocity, Vec3(0.0f), 0.0f);
  const BodyCase box = makeBox(2.0f, Vec3(0.5f, 1, 0.3f), Quat(glm::vec3(0.3f, 0.2f, 0.1f)), Vec3(0, 1, 0),
                               Vec3(1, -2, 0.5f), Vec3(0.4f, 2, -1));
  out = run(box.body, wall.body, Vec3(0.2f, 0.1f, 0), Vec3(0, -1, 0), 0.0f);
  expectVecNear(out.a.linearVelocity, Vec3(0.0f), 0.0f);
  expectVecNear(out.a.angularVelocity, Vec3(0.0f), 0.0f);
}

TEST(Impact, InelasticAgainstKinematicTakesItsVelocityField) {
  // An infinite mass that moves (kinematic): the glued mover follows v + w x (c - cK) and spins with w.
  BodyCase platform = makeStatic(Vec3(0, -1, 0));
  platform.body.linearVelocity = Vec3(1, 0.5f, 0);
  platform.body.angularVelocity = Vec3(0, 0, 2);
  const BodyCase box =
      makeBox(1.0f, Vec3(0.5f), Quat(1, 0, 0, 0), Vec3(1, 0, 0), Vec3(0, -3, 0), Vec3(1, 1, 1));
  const Outcome out = run(platform.body, box.body, Vec3(1, -0.5f, 0), Vec3(0, 1, 0), 0.0f);
  // v = (1, 0.5, 0) + (0, 0, 2) x (1, 1, 0) = (1, 0.5, 0) + (-2, 2, 0).
  expectVecNear(out.b.linearVelocity, Vec3(-1, 2.5f, 0), kTight);
  expectVecNear(out.b.angularVelocity, Vec3(0, 0, 2), kTight);
  expectVecNear(out.a.linearVelocity, platform.body.linearVelocity, 0.0f);
  expectVecNear(out.a.angularVelocity, platform.body.angularVelocity, 0.0f);
}

TEST(Impact, UnequalMassesElasticMatchesSlide27Impulse) {
  // Slide 27: iA = -iB = 2 mA mB / (mA + mB) (vB - vA), 1D along the normal.
  const float massA = 1.0f, massB = 3.0f, va = 5.0f, vb = -1.0f;
  const float expectedImpulseA = 2.0f * massA * massB / (massA + massB) * (vb - va);  // -9
  const BodyCase a = makeParticle(massA, Vec3(0.0f), Vec3(va, 0.5f, 0));
  const BodyCase b = makeParticle(massB, Vec3(1, 0, 0), Vec3(vb, 0, -0.25f));
  ImpactBody na = a.body, nb = b.body;
  const Vec3 impulseOnB = resolveImpactInterpolated(na, nb, Vec3(0.5f, 0, 0), Vec3(1, 0, 0), 1.0f);
  expectVecNear(impulseOnB, Vec3(-expectedImpulseA, 0, 0), 1e-5f);
  const Outcome out = run(a.body, b.body, Vec3(0.5f, 0, 0), Vec3(1, 0, 0), 1.0f);
  expectVecNear(out.a.linearVelocity, Vec3(va + expectedImpulseA / massA, 0.5f, 0), kTight);
  expectVecNear(out.b.linearVelocity, Vec3(vb - expectedImpulseA / massB, 0, -0.25f), kTight);
}

TEST(Impact, HalfBouncinessIsHalfwayBetweenElasticAndInelastic) {
  // Slide 20: mixed cases interpolate the two pure outcomes. Equal masses, vA = (3, 1, 0),
  // vB = (-1, 0, 0), normal x: elastic A (-1, 1, 0), B (3, 0, 0); inelastic both (1, 0.5, 0).
  const BodyCase a = makeParticle(1.0f, Vec3(0.0f), Vec3(3, 1, 0));
  const BodyCase b = makeParticle(1.0f, Vec3(1, 0, 0), Vec3(-1, 0, 0));
  const Outcome out = run(a.body, b.body, Vec3(0.5f, 0, 0), Vec3(1, 0, 0), 0.5f);
  expectVecNear(out.a.linearVelocity, Vec3(0, 0.75f, 0), kTight);
  expectVecNear(out.b.linearVelocity, Vec3(2, 0.25f, 0), kTight);
}

TEST(Impact, MixedBouncinessInterpolatesRigidOutcomesLinearly) {
  // For rigid bodies too, linear and angular velocities after bounciness e are the e-weighted mix of
  // the e = 1 and e = 0 outcomes; checked at e = 0.5 and 0.25 on random pairs.
  std::mt19937 rng(11);
  for (int i = 0; i < 100; ++i) {
    const RandomImpact c = randomImpact(rng);
    const Outcome elastic = run(c.a.body, c.b.body, c.point, c.normal, 1.0f);
    const Outcome inelastic = run(c.a.body, c.b.body, c.point, c.normal, 0.0f);
    for (float e : {0.5f, 0.25f}) {
      const Outcome mixed = run(c.a.body, c.b.body, c.point, c.normal, e);
      const float tolerance =
          1e-4f * (1.0f + glm::length(elastic.a.linearVelocity) + glm::length(inelastic.a.linearVelocity) +
                   glm::length(elastic.b.linearVelocity) + glm::length(inelastic.b.linearVelocity));
      expectVecNear(mixed.a.linearVelocity, glm::mix(inelastic.a.linearVelocity, elastic.a.linearVelocity, e),
                    tolerance);
      expectVecNear(mixed.b.angularVelocity,
                    glm::mix(inelastic.b.angularVelocity, elastic.b.angularVelocity, e), tolerance * 10.0f);
    }
  }
}

TEST(Impact, CombineRules) {
  // Slide 17: avg, min, max (and the product, a common engine choice). Values out of range never get
  // here: a body's bounciness and friction are refused at creation (World.BadBodyDefsNameTheField).
  EXPECT_FLOAT_EQ(combine(CombineRule::Average, 0.2f, 0.8f), 0.5f);
  EXPECT_FLOAT_EQ(combine(CombineRule::Min, 0.2f, 0.8f), 0.2f);
  EXPECT_FLOAT_EQ(combine(CombineRule::Max, 0.2f, 0.8f), 0.8f);
  EXPECT_FLOAT_EQ(combine(CombineRule::Multiply, 0.2f, 0.8f), 0.16f);
  EXPECT_FLOAT_EQ(combine(CombineRule::Min, 0.7f, 0.3f), 0.3f);  // symmetric
  EXPECT_FLOAT_EQ(combine(CombineRule::Max, 0.7f, 0.3f), 0.7f);
}

TEST(Impact, RandomRigidImpactsConserveMomentumAndBoundEnergy) {
  // 1000 random two-way impacts of rotated boxes. Every bounciness keeps the total linear
  // momentum and the angular momentum about a fixed world point; bounciness 1 keeps the kinetic
  // energy (linear + rotational), bounciness < 1 never adds any. Tolerances are relative to the
  // sizes of the quantities (float state, double measurement).
  std::mt19937 rng(2024);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const glm::dvec3 origin(1.0, -2.0, 0.5);
  for (int i = 0; i < 1000; ++i) {
    const RandomImpact c = randomImpact(rng);
    const float partial = unit(rng) * 0.999f;
    const glm::dvec3 momentum = linearMomentum(c.a, c.b);
    const glm::dvec3 angular = angularMomentum(c.a, c.b, origin);
    const double energy = kineticEnergy(c.a, c.b);
    const double momentumScale = linearMomentumScale(c.a, c.b);
    const double angularScale = angularMomentumScale(c.a, origin) + angularMomentumScale(c.b, origin);
    for (float e : {1.0f, partial}) {
      BodyCase a = c.a, b = c.b;
      resolveImpactInterpolated(a.body, b.body, c.point, c.normal, e);
      const double momentumAfterScale = std::max(momentumScale, linearMomentumScale(a, b));
      const double angularAfterScale =
          std::max(angularScale, angularMomentumScale(a, origin) + angularMomentumScale(b, origin));
      EXPECT_LE(glm::length(linearMomentum(a, b) - momentum), 2e-6 * momentumAfterScale) << "config " << i;
      EXPECT_LE(glm::length(angularMomentum(a, b, origin) - angular), 2e-5 * angularAfterScale)
          << "config " << i << " e " << e;
      const double energyAfter = kineticEnergy(a, b);
      if (e == 1.0f) {
        EXPECT_NEAR(energyAfter, energy, 2e-5 * energy) << "config " << i;
      } else {
        EXPECT_LE(energyAfter, energy * (1.0 + 2e-5)) << "config " << i << " e " << e;
      }
      // The normal relative velocity at the point leaves at -e times its value before: -1 elastic,
      // 0 glued, and the mix is linear.
      const float before = normalApproach(c.a.body, c.b.body, c.point, c.normal);
      const float after = normalApproach(a.body, b.body, c.point, c.normal);
      const float velocityScale =
          glm::length(a.body.linearVelocity) + glm::length(b.body.linearVelocity) +
          10.0f * (glm::length(a.body.angularVelocity) + glm::length(b.body.angularVelocity));
      EXPECT_NEAR(after, -e * before, 1e-4f * (velocityScale + std::abs(before))) << "config " << i;
    }
  }
}

TEST(Impact, InelasticRigidBodiesShareOneVelocityField) {
  // Fully inelastic (slide 34: "post-impact angular velocities must also match"): afterwards the two
  // bodies move as one rigid body, so their velocity fields agree at every point; checked at 5 random
  // points for 300 random box pairs and for a particle glued to a box.
  std::mt19937 rng(77);
  for (int i = 0; i < 300; ++i) {
    RandomImpact c = randomImpact(rng);
    if (i % 3 == 0)
      c.a = makeParticle(1.0f / c.a.body.inverseMass, c.a.body.centerOfMass, c.a.body.linearVelocity);
    const glm::dvec3 origin(0.0);
    const glm::dvec3 momentum = linearMomentum(c.a, c.b);
    const glm::dvec3 angular = angularMomentum(c.a, c.b, origin);
    BodyCase a = c.a, b = c.b;
    // The particle changes the approach at the point, so glue it directly (the e = 0 outcome).
    if (isParticle(a.body)) {
      glueVelocities(a.body, b.body);
    } else {
      resolveImpactInterpolated(a.body, b.body, c.point, c.normal, 0.0f);
    }
    if (!isParticle(a.body)) expectVecNear(a.body.angularVelocity, b.body.angularVelocity, 1e-4f);
    // A particle has no rotation: only its own centre is a material point of it.
    const int points = isParticle(a.body) ? 1 : 5;
    for (int k = 0; k < points; ++k) {
      const Vec3 q = isParticle(a.body) ? a.body.centerOfMass : randomPoint(rng, -6.0f, 6.0f);
      const Vec3 va = velocityAt(a.body, q), vb = velocityAt(b.body, q);
      EXPECT_LE(glm::length(va - vb), 1e-4f * (1.0f + glm::length(va))) << "config " << i;
    }
    EXPECT_LE(glm::length(linearMomentum(a, b) - momentum), 2e-6 * linearMomentumScale(c.a, c.b));
    EXPECT_LE(glm::length(angularMomentum(a, b, origin) - angular),
              2e-5 * (angularMomentumScale(c.a, origin) + angularMomentumScale(c.b, origin)));
  }
}

TEST(Impact, TwoParticlesGluedShareTheMomentumVelocityWithoutSpin) {
  // Particles carry no angular velocity: gluing them gives P / M to both even off the line of centres.
  ImpactBody a = makeParticle(2.0f, Vec3(0.0f), Vec3(1, 2, 3)).body;
  ImpactBody b = makeParticle(1.0f, Vec3(1, 1, 0), Vec3(-2, 0, 0)).body;
  glueVelocities(a, b);
  expectVecNear(a.linearVelocity, Vec3(0, 4.0f / 3.0f, 2), kTight);
  expectVecNear(b.linearVelocity, Vec3(0, 4.0f / 3.0f, 2), kTight);
  expectVecNear(a.angularVelocity, Vec3(0.0f), 0.0f);
}

TEST(Impact, NothingHappensUnlessTheBodiesApproach) {
  const BodyCase a = makeParticle(1.0f, Vec3(0.0f), Vec3(-1, 0.5f, 0));
  const BodyCase b = makeParticle(1.0f, Vec3(1, 0, 0), Vec3(1, 0, 0));
  {
    for (float e : {0.0f, 0.5f, 1.0f}) {
      const Outcome out = run(a.body, b.body, Vec3(0.5f, 0, 0), Vec3(1, 0, 0), e);
      expectVecNear(out.a.linearVelocity, a.body.linearVelocity, 0.0f);
      expectVecNear(out.b.linearVelocity, b.body.linearVelocity, 0.0f);
    }
  }
  // Two infinite masses (static against kinematic) never respond.
  BodyCase kinematic = makeStatic(Vec3(1, 0, 0));
  kinematic.body.linearVelocity = Vec3(-5, 0, 0);
  {
    const Outcome out =
        run(makeStatic(Vec3(0.0f)).body, kinematic.body, Vec3(0.5f, 0, 0), Vec3(1, 0, 0), 0.0f);
    expectVecNear(out.b.linearVelocity, Vec3(-5, 0, 0), 0.0f);
  }
}

TEST(Impact, BadInputThrows) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const BodyCase a = makeParticle(1.0f, Vec3(0.0f), Vec3(1, 0, 0));
  const BodyCase b = makeParticle(1.0f, Vec3(1, 0, 0), Vec3(-1, 0, 0));
  const Vec3 p(0.5f, 0, 0), n(1, 0, 0);
  {
    ImpactBody x = a.body, y = b.body;
    EXPECT_COLLIDE_ERROR(resolveImpactInterpolated(x, y, p, n, -0.1f));  // bounciness out of [0, 1]
    EXPECT_COLLIDE_ERROR(resolveImpactInterpolated(x, y, p, n, 1.5f));
    EXPECT_COLLIDE_ERROR(resolveImpactInterpolated(x, y, p, n, nan));
    EXPECT_COLLIDE_ERROR(resolveImpactInterpolated(x, y, p, Vec3(2, 0, 0), 0.5f));  // normal not unit
    EXPECT_COLLIDE_ERROR(resolveImpactInterpolated(x, y, p, Vec3(0.0f), 0.5f));
    EXPECT_COLLIDE_ERROR(resolveImpactInterpolated(x, y, Vec3(nan, 0, 0), n, 0.5f));  // point
    ImpactBody negative = a.body;
    negative.inverseMass = -1.0f;
    EXPECT_COLLIDE_ERROR(resolveImpactInterpolated(negative, y, p, n, 0.5f));
    ImpactBody infiniteSpinning = makeStatic(Vec3(0.0f)).body;
    infiniteSpinning.inverseInertia = Mat3(1.0f);  // infinite mass but finite inertia
    EXPECT_COLLIDE_ERROR(resolveImpactInterpolated(infiniteSpinning, y, p, n, 0.5f));
    ImpactBody badVelocity = b.body;
    badVelocity.linearVelocity.y = nan;
    EXPECT_COLLIDE_ERROR(resolveImpactInterpolated(x, badVelocity, p, n, 0.5f));
    badVelocity = b.body;
    badVelocity.angularVelocity.z = std::numeric_limits<float>::infinity();
    EXPECT_COLLIDE_ERROR(resolveImpactInterpolated(x, badVelocity, p, n, 0.5f));
    ImpactBody badInertia = b.body;
    badInertia.inverseInertia[1][1] = nan;
    EXPECT_COLLIDE_ERROR(resolveImpactInterpolated(x, badInertia, p, n, 0.5f));
    // The bodies are left untouched when the input is rejected.
    expectVecNear(x.linearVelocity, a.body.linearVelocity, 0.0f);
  }
  // The glued model needs the inertia itself: a non-zero but singular inverse inertia is rejected.
  ImpactBody x = a.body, singular = b.body;
  singular.inverseInertia = Mat3(1.0f);
  singular.inverseInertia[2][2] = 0.0f;
  EXPECT_COLLIDE_ERROR(resolveImpactInterpolated(x, singular, p, n, 0.5f));
}
