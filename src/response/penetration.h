// Non-penetration by projection (lecture, slide 11: "strategy 2, project to the closest valid
// position"): displace the two bodies apart along the contact normal, minimising the summed squared
// displacements times the masses; in a one-way collision only the movable body moves, by the whole
// depth (the same formula with the static mass going to infinity).
#pragma once

#include <collide/math.h>

namespace collide::detail {

struct Displacements {
  Vec3 a{0.0f};
  Vec3 b{0.0f};
};

// Minimises mA |dA|^2 + mB |dB|^2 subject to (dB - dA) . n = depth: dA = -depth * wA * n and
// dB = depth * wB * n with wX = (1/mX) / (1/mA + 1/mB), so the mass-weighted centre stays put. The
// normal points from A to B; depth >= 0. Two infinite masses (static against static, which the lecture
// never handles) give no displacement. Throws collide::Error on a negative or non-finite inverse mass
// or depth, or a normal that is not unit length.
Displacements projectApart(float inverseMassA, float inverseMassB, const Vec3& normalAToB, float depth);
// The same without the checks, for the solver, whose inputs are valid by construction (a step must
// not throw half-way).
Displacements projectApartUnchecked(float inverseMassA, float inverseMassB, const Vec3& normalAToB,
                                    float depth);

}  // namespace collide::detail
