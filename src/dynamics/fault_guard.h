// The fault guard: a body whose state stops being finite is frozen where it was at the start of the
// step and reported, so one bad body (an accumulated force that overflowed, a NaN from a degenerate
// contact) cannot turn its neighbours' states into NaN through the solver. Checked where a bad value
// would first reach other bodies: after each substep's velocity integration (forces) and after each
// substep's solve, and once more at the end of the step (impacts, friction, CCD, revert).
#pragma once

#include "base/task_runner.h"
#include "bodies/body_storage.h"
#include "contacts/contact_cache.h"
#include "dynamics/joint_solver.h"

#include <collide/events.h>

#include <cstdint>
#include <span>
#include <vector>

namespace collide::detail {

// FaultEvent bits of the state's non-finite parts (0: all finite), the rotation's also when it is
// no longer a unit quaternion.
std::uint8_t nonFiniteFields(const BodyState& state);

// Every body with a non-finite part (awake, asleep, already frozen, even static: a NaN impulse
// reaches a zero inverse mass's velocity too) is frozen (freezeBody) and reported in `faults`, once
// per step: a body already there gets the new fields added to its event. The bodies are looked at
// in parallel ranges; only when one of them found a fault is the freezing and reporting done, in
// body order on the calling thread.
void guardFiniteStates(BodyStorage& bodies, Array<FaultEvent>& faults, TaskRunner& tasks);

// The bodies in `faults` took part in a solve that produced a non-finite value; so may their
// contacts' manifolds (a degenerate pair is a source of NaN) and accumulated impulses, and their
// joints' impulses (NaN, or what NaN made of them). Their contacts are dropped for this step (not
// touching: no begin event, an end event if they touched before) and the joints' impulses zeroed,
// so that no event reports those numbers and the next step's warm start does not hand them to the
// bodies' neighbours. The next narrow phase finds the contacts again, at the frozen pose, and
// tests their pairs found apart anew (their caches are dropped).
void dropFaultedContacts(std::span<const FaultEvent> faults, Array<Contact>& contacts,
                         Array<ApartPair>& apartPairs, Array<Joint>& joints);

// Back to the pose at the start of the step, stopped, forces cleared. A dynamic body also loses its
// inverse mass and inertia and sleeps: the solver then treats it as an immovable obstacle, and
// nothing integrates or wakes it (faulted) until unfreezeBody.
void freezeBody(BodyRecord& record, BodyState& state);
// A dynamic body's inverse mass and inertia back, awake again (the user gave it a new state).
void unfreezeBody(BodyRecord& record, BodyState& state);

}  // namespace collide::detail
