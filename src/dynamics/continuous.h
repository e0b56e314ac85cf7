// The continuous pass (docs/ccd.md): after the solve, each fast dynamic body is stopped at its first
// time of impact with the static geometry its swept box reaches, and a body flagged ccd (a bullet)
// also with moving bodies, as Box2D v3's and Box3D's continuous stage does: nothing tunnels through
// static geometry by default. The time of impact itself is the narrow phase's timeOfImpact.
#pragma once

#include <collide/broadphase.h>

#include <cstdint>
#include <span>
#include <vector>

#include "bodies/body_storage.h"
#include "contacts/pair_filter.h"

namespace collide::detail {

struct ContinuousStats {
  std::uint32_t fastBodies = 0;  // bodies that moved more than half their smallest extent
  std::uint32_t candidates = 0;  // time-of-impact queries run
  std::uint32_t stopped = 0;     // bodies moved back to a time of impact
};

// Moves each awake, dynamic, fast body (not a sensor) back along its sweep (centerOfMass0/rotation0
// to the current pose) to the earliest time of impact with another body whose proxy its swept box
// touches — static ones only, unless the body is flagged ccd — leaving linearSlop between them. Velocities
// are kept: the next step's speculative contact, now touching, takes the impact (so no energy is added and no
// contact skipped). Bodies are visited in index order; a partner that was already moved back sweeps to its
// new pose.
//
// Jointed bodies stop together: when one body of a group (jointGroup[body], the bodies its joints
// connect; kNoJointGroup for none) is stopped at a fraction of its sweep, every body of the group is
// moved back to the same fraction of its own sweep. A link stopped alone, its neighbours carried on
// to the step's end, would open its joints by its speed times the rest of the step (a whipping
// chain's tip hitting a post opened them by centimetres). Earlier along its sweep than its own stop,
// each body is where nothing static was in its way.
inline constexpr std::uint32_t kNoJointGroup = 0xffffffffu;
ContinuousStats solveContinuous(BodyStorage& bodies, const BroadPhase& broadPhase, const PairFilters& filters,
                                float linearSlop, std::span<const std::uint32_t> jointGroup = {});

}  // namespace collide::detail
