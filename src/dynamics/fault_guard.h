// The fault guard: a body whose state stops being finite is frozen where it was at the start of the
// step and reported, so one bad body (an accumulated force that overflowed, a NaN from a degenerate
// contact) cannot turn its neighbours' states into NaN through the solver. Checked where a bad value
// would first reach other bodies: after each substep's velocity integration (forces) and after each
// substep's solve, and once more at the end of the step (impacts, friction, CCD, revert).
#pragma once

#include "dynamics/body_storage.h"

#include <collide/world.h>

#include <cstdint>
#include <vector>

namespace collide::detail {

// FaultEvent bits of the state's non-finite parts (0: all finite).
std::uint8_t nonFiniteFields(const BodyState& state);

// Every moving body (awake dynamic, kinematic) with a non-finite part is frozen (freezeBody) and
// reported once in `faults`.
void guardFiniteStates(BodyStorage& bodies, std::vector<FaultEvent>& faults);

// Back to the pose at the start of the step, stopped, forces cleared. A dynamic body also loses its
// inverse mass and inertia and sleeps: the solver then treats it as an immovable obstacle, and
// nothing integrates or wakes it (faulted) until unfreezeBody.
void freezeBody(BodyRecord& record, BodyState& state);
// A dynamic body's inverse mass and inertia back, awake again (the user gave it a new state).
void unfreezeBody(BodyRecord& record, BodyState& state);

}  // namespace collide::detail
