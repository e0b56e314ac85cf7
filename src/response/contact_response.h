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
void applyProlongedFriction(BodyStorage& bodies, std::vector<Contact>& contacts,
                            const std::vector<std::uint32_t>& solved, FrictionModel model, float dt);

}  // namespace collide::detail
