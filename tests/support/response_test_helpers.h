// Bodies and measurements for the response tests: random rigid bodies whose inertia is that of a
// random box under a random rotation, and the conserved quantities (momentum, angular momentum about a
// fixed point, kinetic energy) measured in double so the measurement adds no error of its own.
#pragma once

#include <glm/gtc/matrix_transform.hpp>

#include <random>

#include "response/impact_body.h"
#include "support/test_random.h"

namespace collide::test {

// A body and its inertia tensor (the body stores only the inverse).
struct BodyCase {
  detail::ImpactBody body;
  Mat3 inertia{0.0f};  // world frame; zero for a particle or an infinite mass
};

inline BodyCase makeParticle(float mass, const Vec3& position, const Vec3& velocity) {
  BodyCase t;
  t.body.inverseMass = 1.0f / mass;
  t.body.centerOfMass = position;
  t.body.linearVelocity = velocity;
  return t;
}

inline BodyCase makeStatic(const Vec3& position) {
  BodyCase t;
  t.body.centerOfMass = position;
  return t;
}

// A solid box of the given mass and half extents, rotated: I_local = m/3 diag(hy^2 + hz^2, ...).
inline BodyCase makeBox(float mass, const Vec3& halfExtents, const Quat& rotation, const Vec3& position,
                        const Vec3& velocity, const Vec3& angularVelocity) {
  const Vec3 h2 = halfExtents * halfExtents;
  const Vec3 principal = (mass / 3.0f) * Vec3(h2.y + h2.z, h2.x + h2.z, h2.x + h2.y);
  const Mat3 r = glm::mat3_cast(rotation);
  BodyCase t;
  t.inertia = r * Mat3(principal.x, 0, 0, 0, principal.y, 0, 0, 0, principal.z) * glm::transpose(r);
  t.body.inverseInertia = r *
                          Mat3(1.0f / principal.x, 0, 0, 0, 1.0f / principal.y, 0, 0, 0, 1.0f / principal.z) *
                          glm::transpose(r);
  t.body.inverseMass = 1.0f / mass;
  t.body.centerOfMass = position;
  t.body.linearVelocity = velocity;
  t.body.angularVelocity = angularVelocity;
  return t;
}

// Mass in [0.2, 10], half extents in [0.1, 2], position in [-5, 5]^3, velocity in [-4, 4]^3, angular
// velocity in [-3, 3]^3.
inline BodyCase randomBox(std::mt19937& rng) {
  std::uniform_real_distribution<float> mass(0.2f, 10.0f);
  std::uniform_real_distribution<float> half(0.1f, 2.0f);
  const float m = mass(rng);
  const Vec3 h(half(rng), half(rng), half(rng));
  const Quat rotation = randomRotation(rng);
  const Vec3 position = randomPoint(rng, -5.0f, 5.0f);
  const Vec3 velocity = randomPoint(rng, -4.0f, 4.0f);
  const Vec3 angular = randomPoint(rng, -3.0f, 3.0f);
  return makeBox(m, h, rotation, position, velocity, angular);
}

inline double massOf(const BodyCase& t) { return t.body.inverseMass > 0.0f ? 1.0 / t.body.inverseMass : 0.0; }

inline glm::dvec3 linearMomentum(const BodyCase& a, const BodyCase& b) {
  return massOf(a) * glm::dvec3(a.body.linearVelocity) + massOf(b) * glm::dvec3(b.body.linearVelocity);
}

// Spin I w plus orbital (x - origin) x m v, about a fixed world point.
inline glm::dvec3 angularMomentum(const BodyCase& t, const glm::dvec3& origin) {
  return glm::dmat3(t.inertia) * glm::dvec3(t.body.angularVelocity) +
         glm::cross(glm::dvec3(t.body.centerOfMass) - origin, massOf(t) * glm::dvec3(t.body.linearVelocity));
}

inline glm::dvec3 angularMomentum(const BodyCase& a, const BodyCase& b, const glm::dvec3& origin) {
  return angularMomentum(a, origin) + angularMomentum(b, origin);
}

inline double kineticEnergy(const BodyCase& t) {
  const glm::dvec3 v(t.body.linearVelocity), w(t.body.angularVelocity);
  return 0.5 * massOf(t) * glm::dot(v, v) + 0.5 * glm::dot(w, glm::dmat3(t.inertia) * w);
}

inline double kineticEnergy(const BodyCase& a, const BodyCase& b) {
  return kineticEnergy(a) + kineticEnergy(b);
}

// Sizes of the momenta, for relative tolerances.
inline double linearMomentumScale(const BodyCase& a, const BodyCase& b) {
  return massOf(a) * glm::length(glm::dvec3(a.body.linearVelocity)) +
         massOf(b) * glm::length(glm::dvec3(b.body.linearVelocity));
}

inline double angularMomentumScale(const BodyCase& t, const glm::dvec3& origin) {
  return glm::length(glm::dmat3(t.inertia) * glm::dvec3(t.body.angularVelocity)) +
         glm::length(glm::dvec3(t.body.centerOfMass) - origin) * massOf(t) *
             glm::length(glm::dvec3(t.body.linearVelocity));
}

// Normal relative velocity of B with respect to A at the point (negative: approaching).
inline float normalApproach(const detail::ImpactBody& a, const detail::ImpactBody& b, const Vec3& point,
                            const Vec3& normal) {
  return glm::dot(detail::velocityAt(b, point) - detail::velocityAt(a, point), normal);
}

}  // namespace collide::test
