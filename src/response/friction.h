// Contact friction (lecture, slide 12): applied on a prolonged contact, i.e. from the second
// consecutive step in which the two objects touch (the first step is the impact), and only to the
// velocity component parallel to the contact plane. The two ways the lecture lists:
// (1) an explicit force against the tangential velocity, proportional to the speed (viscous), and
// (2) velocity damping, a "tax" on the tangential component of the velocity.
// Both act on the relative velocity at the contact point, by equal and opposite tangential impulses
// on the two bodies, so linear and angular momentum are conserved and the normal component of each
// body's linear velocity is untouched. Neither ever gains kinetic energy.
#pragma once

#include <collide/math.h>

#include "response/impact_body.h"

namespace collide::detail {

// Viscous friction: force F = -k u_t on B (and -F on A), u_t the tangential relative velocity of B
// with respect to A at the point, applied for dt as the impulse F dt along -u_t. Clamped so that the
// component of u_t along its own direction stops at zero rather than reversing (an explicit force
// over a long step would overshoot). coefficient k >= 0 (N s / m), dt > 0. Returns the impulse given
// to B.
Vec3 applyViscousFriction(ImpactBody& a, ImpactBody& b, const Vec3& point, const Vec3& normalAToB,
                          float coefficient, float dt);

// Damping friction: removes the fraction `tax` (in [0, 1]) of the tangential relative velocity at the
// point, u_t -> (1 - tax) u_t exactly, by the tangential impulse that achieves it (solving the 2x2
// tangent block of the contact's inverse mass matrix). Between particles this is the mass-weighted
// split: B loses tax * mA / (mA + mB) of u_t, A gains tax * mB / (mA + mB). Returns the impulse given
// to B.
Vec3 applyDampingFriction(ImpactBody& a, ImpactBody& b, const Vec3& point, const Vec3& normalAToB, float tax);

}  // namespace collide::detail
