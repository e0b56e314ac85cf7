// The lecture's projection of two bodies apart, mass-weighted (penetration.h).
#include "response/penetration.h"
#include "base/fail.h"

#include <collide/error.h>

#include <cmath>
#include <string>

namespace collide::detail {

Displacements projectApart(float inverseMassA, float inverseMassB, const Vec3& normalAToB, float depth) {
  if (!std::isfinite(inverseMassA) || inverseMassA < 0.0f) {
    COLLIDE_FAIL("projectApart: inverse mass A must be finite and >= 0, got " + std::to_string(inverseMassA),
                 {});
  }
  if (!std::isfinite(inverseMassB) || inverseMassB < 0.0f) {
    COLLIDE_FAIL("projectApart: inverse mass B must be finite and >= 0, got " + std::to_string(inverseMassB),
                 {});
  }
  if (!isFinite(normalAToB) || std::abs(glm::length(normalAToB) - 1.0f) > 1e-3f) {
    COLLIDE_FAIL(
        "projectApart: normal must be unit length, got length " + std::to_string(glm::length(normalAToB)),
        {});
  }
  if (!std::isfinite(depth) || depth < 0.0f) {
    COLLIDE_FAIL("projectApart: depth must be finite and >= 0, got " + std::to_string(depth), {});
  }
  return projectApartUnchecked(inverseMassA, inverseMassB, normalAToB, depth);
}

Displacements projectApartUnchecked(float inverseMassA, float inverseMassB, const Vec3& normalAToB,
                                    float depth) {
  const float total = inverseMassA + inverseMassB;
  if (total == 0.0f) return {};
  // Lagrange condition: each displacement is parallel to n and proportional to the inverse mass.
  return {-depth * (inverseMassA / total) * normalAToB, depth * (inverseMassB / total) * normalAToB};
}

}  // namespace collide::detail
