// A body as one contact's response sees it: velocities at a point, impulses, validation
// (impact_body.h).
#include "response/impact_body.h"
#include "base/fail.h"

#include <collide/error.h>

#include <cmath>
#include <sstream>
#include <string>

namespace collide::detail {

namespace {

bool isFiniteMatrix(const Mat3& m) { return isFinite(m[0]) && isFinite(m[1]) && isFinite(m[2]); }

bool isZeroMatrix(const Mat3& m) { return m == Mat3(0.0f); }

std::string toText(const Vec3& v) {
  std::ostringstream out;
  out << "(" << v.x << ", " << v.y << ", " << v.z << ")";
  return out.str();
}

// The matrix of r x (.): crossMatrix(r) * x == glm::cross(r, x). glm is column-major.
Mat3 crossMatrix(const Vec3& r) {
  return Mat3(Vec3(0.0f, r.z, -r.y), Vec3(-r.z, 0.0f, r.x), Vec3(r.y, -r.x, 0.0f));
}

}  // namespace

bool hasInfiniteMass(const ImpactBody& body) { return body.inverseMass == 0.0f; }

bool isParticle(const ImpactBody& body) {
  return body.inverseMass > 0.0f && isZeroMatrix(body.inverseInertia);
}

Vec3 velocityAt(const ImpactBody& body, const Vec3& point) {
  return body.linearVelocity + glm::cross(body.angularVelocity, point - body.centerOfMass);
}

void applyImpulseAt(ImpactBody& body, const Vec3& impulse, const Vec3& point) {
  body.linearVelocity += body.inverseMass * impulse;
  body.angularVelocity += body.inverseInertia * glm::cross(point - body.centerOfMass, impulse);
}

Mat3 contactInverseMassMatrix(const ImpactBody& a, const ImpactBody& b, const Vec3& point) {
  // The velocity change at the point from an impulse P at the point is (1/m) P - [r] I^-1 [r] P;
  // -[r] = [r]^T, so each body adds the positive semidefinite [r]^T I^-1 [r].
  const Mat3 ra = crossMatrix(point - a.centerOfMass);
  const Mat3 rb = crossMatrix(point - b.centerOfMass);
  return (a.inverseMass + b.inverseMass) * Mat3(1.0f) + glm::transpose(ra) * a.inverseInertia * ra +
         glm::transpose(rb) * b.inverseInertia * rb;
}

namespace {

bool isValidImpactBody(const ImpactBody& body) {
  return std::isfinite(body.inverseMass) && body.inverseMass >= 0.0f && isFiniteMatrix(body.inverseInertia) &&
         (!hasInfiniteMass(body) || isZeroMatrix(body.inverseInertia)) && isFinite(body.linearVelocity) &&
         isFinite(body.angularVelocity) && isFinite(body.centerOfMass);
}

bool isValidContact(const Vec3& point, const Vec3& normal) {
  return isFinite(point) && isFinite(normal) && std::abs(glm::length(normal) - 1.0f) <= 1e-3f;
}

bool hasUsableInertia(const ImpactBody& body) {
  if (isZeroMatrix(body.inverseInertia)) return true;
  const double det = glm::determinant(glm::dmat3(body.inverseInertia));
  return det != 0.0 && std::isfinite(det);
}

}  // namespace

bool canApplyImpact(const ImpactBody& a, const ImpactBody& b, const Vec3& point, const Vec3& normal) {
  if (!isValidImpactBody(a) || !isValidImpactBody(b) || !isValidContact(point, normal)) return false;
  // Only two finite masses are glued into one body, whose inertia adds theirs.
  return hasInfiniteMass(a) || hasInfiniteMass(b) || (hasUsableInertia(a) && hasUsableInertia(b));
}

bool validateImpactBody(const ImpactBody& body, const char* context, const char* name) {
  const std::string prefix = std::string(context) + ": body " + name + " ";
  if (!std::isfinite(body.inverseMass) || body.inverseMass < 0.0f) {
    COLLIDE_FAIL(prefix + "inverse mass must be finite and >= 0, got " + std::to_string(body.inverseMass),
                 false);
  }
  if (!isFiniteMatrix(body.inverseInertia)) COLLIDE_FAIL(prefix + "inverse inertia must be finite", false);
  if (hasInfiniteMass(body) && !isZeroMatrix(body.inverseInertia)) {
    COLLIDE_FAIL(prefix + "has infinite mass (inverse mass 0) but a non-zero inverse inertia", false);
  }
  if (!isFinite(body.linearVelocity)) {
    COLLIDE_FAIL(prefix + "linear velocity must be finite, got " + toText(body.linearVelocity), false);
  }
  if (!isFinite(body.angularVelocity)) {
    COLLIDE_FAIL(prefix + "angular velocity must be finite, got " + toText(body.angularVelocity), false);
  }
  if (!isFinite(body.centerOfMass)) {
    COLLIDE_FAIL(prefix + "centre of mass must be finite, got " + toText(body.centerOfMass), false);
  }
  return true;
}

bool validateContact(const Vec3& point, const Vec3& normal, const char* context) {
  if (!isFinite(point))
    COLLIDE_FAIL(std::string(context) + ": contact point must be finite, got " + toText(point), false);
  if (!isFinite(normal) || std::abs(glm::length(normal) - 1.0f) > 1e-3f) {
    COLLIDE_FAIL(std::string(context) + ": contact normal must be unit length, got " + toText(normal), false);
  }
  return true;
}

}  // namespace collide::detail
