// Viscous and damping friction at one contact (friction.h).
#include "response/friction.h"
#include "base/fail.h"

#include <collide/error.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace collide::detail {

namespace {

struct Tangential {
  Vec3 direction{0.0f};  // unit, along the tangential relative velocity
  float speed = 0.0f;
};

// The tangential relative velocity of B with respect to A at the point (lecture, slide 30:
// v_p = v - (v . n) n).
Tangential tangentialRelativeVelocity(const ImpactBody& a, const ImpactBody& b, const Vec3& point,
                                      const Vec3& normal) {
  const Vec3 relative = velocityAt(b, point) - velocityAt(a, point);
  const Vec3 tangential = relative - glm::dot(relative, normal) * normal;
  const float speed = glm::length(tangential);
  if (!(speed > 0.0f)) return {};
  return {tangential / speed, speed};
}

bool validateFrictionContact(const ImpactBody& a, const ImpactBody& b, const Vec3& point, const Vec3& normal,
                             const char* context) {
  return validateImpactBody(a, context, "A") && validateImpactBody(b, context, "B") &&
         validateContact(point, normal, context);
}

void applyPair(ImpactBody& a, ImpactBody& b, const Vec3& impulseOnB, const Vec3& point) {
  applyImpulseAt(b, impulseOnB, point);
  applyImpulseAt(a, -impulseOnB, point);
}

}  // namespace

Vec3 applyViscousFriction(ImpactBody& a, ImpactBody& b, const Vec3& point, const Vec3& normalAToB,
                          float coefficient, float dt) {
  const char* context = "applyViscousFriction";
  if (!validateFrictionContact(a, b, point, normalAToB, context)) return Vec3(0.0f);
  if (!std::isfinite(coefficient) || coefficient < 0.0f) {
    COLLIDE_FAIL(
        std::string(context) + ": coefficient must be finite and >= 0, got " + std::to_string(coefficient),
        Vec3(0.0f));
  }
  if (!std::isfinite(dt) || dt <= 0.0f) {
    COLLIDE_FAIL(std::string(context) + ": dt must be finite and > 0, got " + std::to_string(dt), Vec3(0.0f));
  }
  if (hasInfiniteMass(a) && hasInfiniteMass(b)) return Vec3(0.0f);
  const Tangential slip = tangentialRelativeVelocity(a, b, point, normalAToB);
  if (slip.speed == 0.0f) return Vec3(0.0f);
  // The impulse j along -t changes the slip along t by -K_tt j; j = speed / K_tt stops it, and an
  // impulse between 0 and that bound cannot add kinetic energy (dE = -j (speed - K_tt j / 2)).
  const float inverseEffectiveMass =
      glm::dot(slip.direction, contactInverseMassMatrix(a, b, point) * slip.direction);
  const float impulse = std::min(coefficient * slip.speed * dt, slip.speed / inverseEffectiveMass);
  const Vec3 impulseOnB = -impulse * slip.direction;
  applyPair(a, b, impulseOnB, point);
  return impulseOnB;
}

Vec3 applyDampingFriction(ImpactBody& a, ImpactBody& b, const Vec3& point, const Vec3& normalAToB,
                          float tax) {
  const char* context = "applyDampingFriction";
  if (!validateFrictionContact(a, b, point, normalAToB, context)) return Vec3(0.0f);
  if (!std::isfinite(tax) || tax < 0.0f || tax > 1.0f) {
    COLLIDE_FAIL(std::string(context) + ": tax must be in [0, 1], got " + std::to_string(tax), Vec3(0.0f));
  }
  if (hasInfiniteMass(a) && hasInfiniteMass(b)) return Vec3(0.0f);
  const Tangential slip = tangentialRelativeVelocity(a, b, point, normalAToB);
  if (slip.speed == 0.0f) return Vec3(0.0f);
  // A tangential impulse P = p1 t + p2 s (s = n x t) changes the tangential slip by the tangent block
  // of K times (p1, p2); solve that 2x2 system for the change -tax * speed * t. For particles K is
  // (1/mA + 1/mB) times the identity and P = -tax * u_t * mA mB / (mA + mB).
  const Vec3 t = slip.direction;
  const Vec3 s = glm::cross(normalAToB, t);
  const Mat3 k = contactInverseMassMatrix(a, b, point);
  const float ktt = glm::dot(t, k * t);
  const float kts = glm::dot(t, k * s);
  const float kss = glm::dot(s, k * s);
  const float det = ktt * kss - kts * kts;  // >= (1/mA + 1/mB)^2 > 0
  const float change = -tax * slip.speed;
  const float pt = kss * change / det;
  const float ps = -kts * change / det;
  const Vec3 impulseOnB = pt * t + ps * s;
  applyPair(a, b, impulseOnB, point);
  return impulseOnB;
}

}  // namespace collide::detail
