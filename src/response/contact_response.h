// The lecture's friction models in the world (src/response/friction.h): run after the soft contact
// solver (src/dynamics/solver.h) has solved the step's velocities, on the contacts that the contact
// cache marks as prolonged. Impacts come before the solve (impacts.h). See docs/response.md ("In the
// world").
#pragma once

#include "bodies/body_storage.h"
#include "contacts/contact_cache.h"

#include <collide/settings.h>

#include <cstdint>
#include <vector>

namespace collide::detail {

// FrictionModel::Viscous / Damping, once per step per prolonged contact (touching last step and
// active this step), at the average of the manifold points: viscous with k = contact.friction per
// second over dt, damping with tax = contact.friction clamped to [0, 1]. Other models: nothing.
void applyProlongedFriction(BodyStorage& bodies, Array<Contact>& contacts, const Array<std::uint32_t>& solved,
                            FrictionModel model, float dt);

// Rolling resistance, once per step per solved contact that touched and has a rolling resistance:
// the angular impulse that stops the two bodies' relative turning, rolling and pivoting alike (a
// one-point contact has no twist friction to stop the pivoting), bounded by the contact's rolling
// resistance (a length) times the step's normal impulse. Box3D's rolling resistance, applied once
// after the solve.
void applyRollingResistance(BodyStorage& bodies, Array<Contact>& contacts,
                            const Array<std::uint32_t>& solved);

}  // namespace collide::detail
