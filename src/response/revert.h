// Non-penetration by reverting (lecture, slide 10: "strategy 1: revert to last valid position"):
// after the solve, a dynamic body that penetrates another by more than the linear slop goes back to
// its last valid pose — the last pose at which it penetrated nothing, kept at the end of every step
// (BodyRecord::validCenterOfMass, validRotation) — and loses the component of its velocity into the
// other body. A body put back can now overlap a neighbour that moved into the place it left, so the
// test repeats until no body that can still go back penetrates; each body goes back at most once a
// step, so this ends. Only pairs whose bodies were both created or placed inside each other are left
// penetrating (they have no valid pose apart), for the solver's push-out.
//
// Every pair the broad phase kept is tested, not only the contacts the solver took: a contact found
// apart at the step's start can still close within the step when the solve stops one of its bodies
// (a box landing while the ball above it keeps falling).
#pragma once

#include <collide/broadphase.h>

#include "bodies/body_storage.h"
#include "contacts/contact_cache.h"
#include "contacts/pair_filter.h"

#include <cstdint>
#include <span>
#include <vector>

namespace collide::detail {

class RevertResponse {
 public:
  void apply(BodyStorage& bodies, const BroadPhase& broadPhase, std::span<const ProxyPair> pairs,
             std::span<const Contact> contacts, const PairFilters& filters, float linearSlop);

  std::size_t memoryBytes() const;  // World::memoryUse

 private:
  // One pass over the pairs: marks the bodies that penetrate, and puts back those that can still go
  // back. Returns whether a body went back.
  bool pass(BodyStorage& bodies, float linearSlop);

  struct Candidate {
    std::uint32_t a;
    std::uint32_t b;
    std::uint64_t key;  // the contacts' pair key
  };
  std::span<const Contact> contacts_;  // this step's, during apply
  Array<Candidate> candidates_;        // the pairs that can respond this step
  Array<std::uint8_t> reverted_;       // per body: went back this step
  Array<std::uint8_t> penetrating_;    // per body: penetrates something (last pass)
};

// Every body's current pose becomes its valid one (the world switched to the revert response).
void takeCurrentPosesAsValid(BodyStorage& bodies);

}  // namespace collide::detail
