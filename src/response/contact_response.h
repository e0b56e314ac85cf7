// The world's use of the lecture's response models (src/response/impact.h, friction.h): run after
// the soft contact solver (src/dynamics/solver.h) has solved the step's velocities, on the
// contacts that the contact cache marks as new impacts or prolonged contacts. See docs/response.md
// ("In the world").
#pragma once

#include "bodies/body_storage.h"
#include "contacts/contact_cache.h"

#include <collide/settings.h>

#include <cstdint>
#include <vector>

namespace collide::detail {

// ImpactModel::Interpolated. For each solved contact that was not touching last step, that the
// solver acted on this step and whose normal approach speed before the solve exceeds `threshold`:
// undo the solver's normal impulses of this contact (the world gives these contacts no restitution
// and no Coulomb friction, so those are all it applied), then apply the lecture's interpolated impact
// with contact.impactBounciness at the impact point (the average of the manifold points within
// `slop` of the deepest). Other contacts' impulses on the same bodies are kept.
void applyInterpolatedImpacts(BodyStorage& bodies, std::vector<Contact>& contacts,
                              const std::vector<std::uint32_t>& solved, float threshold, float slop);

// FrictionModel::Viscous / Damping, once per step per prolonged contact (touching last step and
// active this step), at the average of the manifold points: viscous with k = contact.friction per
// second over dt, damping with tax = contact.friction clamped to [0, 1]. Other models: nothing.
void applyProlongedFriction(BodyStorage& bodies, std::vector<Contact>& contacts,
                            const std::vector<std::uint32_t>& solved, FrictionModel model, float dt);

// The stage after the solve: both of the above, as the world's impact and friction models ask.
void applyResponseModels(BodyStorage& bodies, std::vector<Contact>& contacts,
                         const std::vector<std::uint32_t>& solved, ImpactModel impactModel,
                         FrictionModel frictionModel, const ContactTuning& tuning, float dt);

}  // namespace collide::detail
