// Sensors that a body crossed within one step. A sensor's contact is tested at the poses the step
// starts from, so a body fast enough to enter and leave a thin sensor between two steps would never
// be seen inside it. After the solve, each sensor pair that was not overlapping at the step's start
// is swept over the step (the time of impact of the two bodies' motions); a body that touched the
// sensor and is out of it again at the step's end gives a begin and an end event in the same step.
// (One that ends inside gets its begin from the next step's contact, as any sensor overlap does.)
#pragma once

#include <collide/broadphase.h>

#include "bodies/body_storage.h"
#include "contacts/contact_cache.h"
#include "contacts/contact_events.h"
#include "contacts/pair_filter.h"

#include <span>

namespace collide::detail {

void reportSensorCrossings(const BodyStorage& bodies, const BroadPhase& broadPhase,
                           std::span<const ProxyPair> pairs, std::span<const Contact> contacts,
                           const PairFilters& filters, StepEvents& events);

}  // namespace collide::detail
