// The lecture's interpolated impact at one contact (impact.h).
#include "response/impact.h"
#include "base/fail.h"

#include <collide/error.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace collide::detail {

namespace {

using DVec3 = glm::dvec3;
using DMat3 = glm::dmat3;

bool validateBounciness(float bounciness, const char* context) {
  if (!std::isfinite(bounciness) || bounciness < 0.0f || bounciness > 1.0f) {
    COLLIDE_FAIL(std::string(context) + ": bounciness must be in [0, 1], got " + std::to_string(bounciness),
                 false);
  }
  return true;
}

bool validateImpact(const ImpactBody& a, const ImpactBody& b, const Vec3& point, const Vec3& normal,
                    float bounciness, const char* context) {
  return validateImpactBody(a, context, "A") && validateImpactBody(b, context, "B") &&
         validateContact(point, normal, context) && validateBounciness(bounciness, context);
}

// The inertia tensor from the inverse one, in double: the glued body needs inertias, which add,
// while the bodies store inverses, which do not. A particle has no rotational inertia of its own.
DMat3 inertiaOf(const ImpactBody& body, const char* name) {
  if (isParticle(body)) return DMat3(0.0);
  const DMat3 inverseInertia(body.inverseInertia);
  const double det = glm::determinant(inverseInertia);
  const DMat3 inertia = glm::inverse(inverseInertia);
  if (det == 0.0 || !std::isfinite(det) || !isFinite(Vec3(inertia[0])) || !isFinite(Vec3(inertia[1])) ||
      !isFinite(Vec3(inertia[2]))) {
    COLLIDE_FAIL(std::string("impact: body ") + name +
                     " inverse inertia must be zero (a particle) or invertible, got determinant " +
                     std::to_string(det),
                 DMat3(0.0));
  }
  return inertia;
}

// Parallel-axis theorem: inertia about a point at `offset` from the centre of mass.
DMat3 shifted(const DMat3& inertiaAtCom, double mass, const DVec3& offset) {
  return inertiaAtCom + mass * (glm::dot(offset, offset) * DMat3(1.0) - glm::outerProduct(offset, offset));
}

// The mover glued to an infinite mass follows that body's velocity field (slide 33: against a static
// body it "stops dead"; against a kinematic one it is carried along).
void glueToInfiniteMass(ImpactBody& mover, const ImpactBody& anchor) {
  mover.linearVelocity = velocityAt(anchor, mover.centerOfMass);
  if (!isParticle(mover)) mover.angularVelocity = anchor.angularVelocity;
}

void glueTwoWay(ImpactBody& a, ImpactBody& b) {
  const double massA = 1.0 / a.inverseMass;
  const double massB = 1.0 / b.inverseMass;
  const double mass = massA + massB;
  const DVec3 centre = (massA * DVec3(a.centerOfMass) + massB * DVec3(b.centerOfMass)) / mass;
  const DVec3 momentum = massA * DVec3(a.linearVelocity) + massB * DVec3(b.linearVelocity);
  const DVec3 velocity = momentum / mass;
  if (isParticle(a) && isParticle(b)) {
    // Slide 21: two particles glued together share one velocity; the total momentum fixes it.
    a.linearVelocity = Vec3(velocity);
    b.linearVelocity = Vec3(velocity);
    return;
  }
  // One rigid body made of the two: total angular momentum about the common centre (each body's
  // spin I w plus the orbital r x m v) over the combined inertia about that centre.
  const DVec3 ra = DVec3(a.centerOfMass) - centre;
  const DVec3 rb = DVec3(b.centerOfMass) - centre;
  const DMat3 inertiaA = inertiaOf(a, "A");
  const DMat3 inertiaB = inertiaOf(b, "B");
  COLLIDE_RETURN_IF_FAILED();
  const DVec3 angularMomentum =
      inertiaA * DVec3(a.angularVelocity) + glm::cross(ra, massA * DVec3(a.linearVelocity)) +
      inertiaB * DVec3(b.angularVelocity) + glm::cross(rb, massB * DVec3(b.linearVelocity));
  const DMat3 inertia = shifted(inertiaA, massA, ra) + shifted(inertiaB, massB, rb);
  // Invertible: at least one body has an invertible inertia, the shifts are semidefinite.
  const DVec3 omega = glm::inverse(inertia) * angularMomentum;
  a.linearVelocity = Vec3(velocity + glm::cross(omega, ra));
  b.linearVelocity = Vec3(velocity + glm::cross(omega, rb));
  if (!isParticle(a)) a.angularVelocity = Vec3(omega);
  if (!isParticle(b)) b.angularVelocity = Vec3(omega);
}

void glueUnchecked(ImpactBody& a, ImpactBody& b) {
  if (hasInfiniteMass(a) && hasInfiniteMass(b)) return;
  if (hasInfiniteMass(a)) {
    glueToInfiniteMass(b, a);
  } else if (hasInfiniteMass(b)) {
    glueToInfiniteMass(a, b);
  } else {
    glueTwoWay(a, b);
  }
}

// The fully elastic impact (slides 26-29): the normal impulse j that turns the normal relative
// velocity u at the point into -u, K_nn j = -2 u; for particles K_nn = 1/mA + 1/mB, and this is the
// slide-27 formula.
void elasticUnchecked(ImpactBody& a, ImpactBody& b, const Vec3& point, const Vec3& normal) {
  if (hasInfiniteMass(a) && hasInfiniteMass(b)) return;
  const float approach = glm::dot(velocityAt(b, point) - velocityAt(a, point), normal);
  if (!(approach < 0.0f)) return;
  const float inverseEffectiveMass = glm::dot(normal, contactInverseMassMatrix(a, b, point) * normal);
  const float impulse = -2.0f * approach / inverseEffectiveMass;
  applyImpulseAt(b, impulse * normal, point);
  applyImpulseAt(a, -impulse * normal, point);
}

}  // namespace

Vec3 resolveImpactInterpolated(ImpactBody& a, ImpactBody& b, const Vec3& point, const Vec3& normalAToB,
                               float bounciness) {
  const ErrorScope scope;
  if (!validateImpact(a, b, point, normalAToB, bounciness, "resolveImpactInterpolated")) return Vec3(0.0f);
  if (hasInfiniteMass(a) && hasInfiniteMass(b)) return Vec3(0.0f);
  if (!(glm::dot(velocityAt(b, point) - velocityAt(a, point), normalAToB) < 0.0f)) return Vec3(0.0f);

  // Slide 20: "solve for both cases, interpolate resulting velocities; the weight of the
  // interpolation = the bounciness". Slide 34: the angular velocities too. Both pure outcomes keep
  // linear and angular momentum, and these are linear in the velocities, so the mix keeps them as
  // well; kinetic energy is convex in the velocities, so the mix never gains energy.
  ImpactBody elasticA = a, elasticB = b;
  elasticUnchecked(elasticA, elasticB, point, normalAToB);
  ImpactBody inelasticA = a, inelasticB = b;
  glueUnchecked(inelasticA, inelasticB);
  COLLIDE_RETURN_IF_FAILED(Vec3(0.0f));

  const Vec3 oldVelocityA = a.linearVelocity;
  const Vec3 oldVelocityB = b.linearVelocity;
  const float e = bounciness;
  a.linearVelocity = glm::mix(inelasticA.linearVelocity, elasticA.linearVelocity, e);
  a.angularVelocity = glm::mix(inelasticA.angularVelocity, elasticA.angularVelocity, e);
  b.linearVelocity = glm::mix(inelasticB.linearVelocity, elasticB.linearVelocity, e);
  b.angularVelocity = glm::mix(inelasticB.angularVelocity, elasticB.angularVelocity, e);
  if (!hasInfiniteMass(b)) return (b.linearVelocity - oldVelocityB) / b.inverseMass;
  return -(a.linearVelocity - oldVelocityA) / a.inverseMass;
}

void glueVelocities(ImpactBody& a, ImpactBody& b) {
  const ErrorScope scope;
  if (!validateImpactBody(a, "glueVelocities", "A") || !validateImpactBody(b, "glueVelocities", "B")) return;
  glueUnchecked(a, b);
}

}  // namespace collide::detail
