// The lecture's impact (slides 13-34, ImpactModel::Interpolated): the sudden velocity change when two
// bodies meet with an approaching normal velocity. Solve the fully elastic impact (impulse along the
// normal, kinetic energy kept, linear and rotational) and the fully inelastic one (the bodies leave
// with one velocity field, as if glued together), then interpolate the resulting linear and angular
// velocities with the bounciness as weight (1 = elastic). It conserves total linear and angular
// momentum in a two-way impact; see docs/response.md. (ImpactModel::Newton, restitution on the
// normal relative velocity, is the contact solver's: src/dynamics/contact_solver.h.)
#pragma once

#include <collide/math.h>

#include <cstdint>

#include "response/impact_body.h"

namespace collide::detail {

// The lecture's model. Against an infinite mass the inelastic result is the mover glued to it: it
// takes the other body's velocity field (v + omega x r), so it stops dead against a static body.
// Between two particles the inelastic result is their shared velocity P / M (slide 21); if at least
// one of two finite bodies can rotate, it is the rigid motion of the glued pair that keeps the total
// linear and angular momentum. Returns the linear impulse given to B (A gets its opposite).
Vec3 resolveImpactInterpolated(ImpactBody& a, ImpactBody& b, const Vec3& point, const Vec3& normalAToB,
                               float bounciness);

// The fully inelastic outcome alone (the "glued" velocities), for both bodies; used by the
// interpolated model and exposed for tests. Needs at least one finite mass.
void glueVelocities(ImpactBody& a, ImpactBody& b);

}  // namespace collide::detail
