// Impact resolution (lecture, slides 13-34): the sudden velocity change when two bodies meet with an
// approaching normal velocity. Two models:
// - Newton: restitution on the normal relative velocity at the contact point, impulse along the
//   normal only (what Box2D, Bullet and Jolt do).
// - Interpolated, the lecture's model: solve the fully elastic impact (impulse along the normal,
//   kinetic energy kept, linear and rotational) and the fully inelastic one (the bodies leave with
//   one velocity field, as if glued together), then interpolate the resulting linear and angular
//   velocities with the bounciness as weight (1 = elastic).
// Both conserve total linear and angular momentum in a two-way impact; see docs/response.md.
#pragma once

#include <collide/math.h>

#include <cstdint>

#include "response/impact_body.h"

namespace collide::detail {

// How the bounciness (or friction) of two colliding objects combines (lecture, slide 17: "adopt some
// formula between the values of the two objects, e.g. avg, min, max; a choice of the engine").
enum class CombineRuleKind : std::uint8_t { Average, Min, Max, Multiply };

// Both values must be finite and >= 0; throws collide::Error otherwise.
float combineMaterial(CombineRuleKind rule, float a, float b);

enum class ImpactModel : std::uint8_t { Newton, Interpolated };

// The normal points from A to B. Nothing happens unless the bodies approach at the point
// (normal relative velocity (vB - vA).n < 0) and at least one has finite mass. Bounciness in [0, 1].
// Returns the impulse magnitude applied along the normal to B (and its opposite to A), 0 if none.
float resolveImpactNewton(ImpactBody& a, ImpactBody& b, const Vec3& point, const Vec3& normalAToB,
                          float bounciness);

// The lecture's model. Against an infinite mass the inelastic result is the mover glued to it: it
// takes the other body's velocity field (v + omega x r), so it stops dead against a static body.
// Between two particles the inelastic result is their shared velocity P / M (slide 21); if at least
// one of two finite bodies can rotate, it is the rigid motion of the glued pair that keeps the total
// linear and angular momentum. Returns the linear impulse given to B (A gets its opposite).
Vec3 resolveImpactInterpolated(ImpactBody& a, ImpactBody& b, const Vec3& point, const Vec3& normalAToB,
                               float bounciness);

// Dispatches to one of the two models above.
void resolveImpact(ImpactModel model, ImpactBody& a, ImpactBody& b, const Vec3& point, const Vec3& normalAToB,
                   float bounciness);

// The fully inelastic outcome alone (the "glued" velocities), for both bodies; used by the
// interpolated model and exposed for tests. Needs at least one finite mass.
void glueVelocities(ImpactBody& a, ImpactBody& b);

}  // namespace collide::detail
