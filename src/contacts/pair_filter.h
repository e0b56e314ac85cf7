// Which pairs of bodies may collide (docs/architecture.md, "Filtering"): the bodies' groups, layers
// and masks, the constraints that keep their bodies apart, and the world's pair filter. One test for
// every stage that pairs bodies: the contacts, the sensors' crossings, continuous collision and revert.
#pragma once

#include <collide/events.h>

#include "bodies/body_parts.h"
#include "bodies/body_storage.h"

#include <cstdint>
#include <unordered_map>

namespace collide::detail {

// What keeps a pair apart besides the bodies' own filters: the constraints that do not let their
// bodies collide (pairs of body indices, bodyPairKey, with how many such constraints join them) and
// the world's pair filter.
struct PairFilters {
  const std::unordered_map<std::uint64_t, std::uint32_t>* jointedApart = nullptr;
  const PairFilter* callback = nullptr;
};

inline std::uint64_t bodyPairKey(std::uint32_t a, std::uint32_t b) {
  return a < b ? (std::uint64_t(a) << 32 | b) : (std::uint64_t(b) << 32 | a);
}

// The whole test for bodies ia and ib: their filters (for bodies made of parts: some pair of their
// parts passes; each stage then tests the pairs of parts, forEachAllowedPartPair), the constraints
// between them, the callback last.
inline bool pairAllowed(const BodyStorage& bodies, const PairFilters& filters, std::uint32_t ia,
                        std::uint32_t ib) {
  if (!anyPartPairAllowed(bodies.records[ia], bodies.records[ib])) return false;
  if (filters.jointedApart != nullptr && !filters.jointedApart->empty() &&
      filters.jointedApart->contains(bodyPairKey(ia, ib)))
    return false;
  return filters.callback == nullptr || !*filters.callback ||
         (*filters.callback)(bodies.idOf(ia), bodies.idOf(ib));
}

}  // namespace collide::detail
