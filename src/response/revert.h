// Non-penetration by reverting (lecture, slide 10: "strategy 1: revert to last valid position"), a
// simple version: after the solve, each solved pair is tested again at the new poses, and a dynamic
// body still penetrating its partner by more than the linear slop goes back to its pose at the start
// of the step, with the component of its velocity into the partner removed.
#pragma once

#include "bodies/body_storage.h"
#include "contacts/contact_cache.h"

#include <cstdint>
#include <span>

namespace collide::detail {

void revertPenetrating(BodyStorage& bodies, std::span<const Contact> contacts,
                       std::span<const std::uint32_t> solvedContacts, float linearSlop);

}  // namespace collide::detail
