// The narrow-phase stage of the step (lecture: collision detection, then collision data): for each
// pair the broad phase kept, the contact of last step is found by merging two sorted arrays, the
// pair's manifold is computed or reused, and the contact is carried over (new vs prolonged points,
// warm starting) or ended, then shown to the pre-solve callback.
//
// A manifold costs nothing when it can be avoided exactly: a pair whose bodies did not move relative
// to each other gets its manifold placed again (Jolt's body pair cache, contact_cache.h); bounding
// spheres apart by more than the margin reject the pair (the lecture's cheapest bounding volume); a
// polyhedron pair found apart last time is tested first along the axis that separated it
// (Gregorius, GDC 2013). Contacts are speculative: created up to a margin apart, the margin being
// what the pair can close within the step (Catto, GDC 2013 "Continuous Collision").
#pragma once

#include <collide/broadphase.h>
#include <collide/events.h>
#include <collide/settings.h>

#include "bodies/body_storage.h"
#include "contacts/contact_cache.h"
#include "contacts/contact_events.h"
#include "contacts/pair_filter.h"

#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

namespace collide::detail {

// How fast the body's farthest point turns about its centre of mass (|angular velocity| x radius).
inline float spinReach(const BodyRecord& record, const BodyState& state) {
  return glm::length(state.angularVelocity) * record.boundingRadius;
}

// The speculative margin of a pair: the speculative distance plus the gap the pair can close within
// the step, from the bodies' linear velocities and spin reaches.
inline float speculativeMargin(const Vec3& velocityA, const Vec3& velocityB, float spinA, float spinB,
                               float dt, float speculativeDistance) {
  const float approach = glm::length(velocityB - velocityA) + spinA + spinB;
  const float margin = speculativeDistance + dt * approach;
  // A finite velocity can still have an infinite length (beyond 1.8e19 m/s the square overflows):
  // capped at the largest float (NaN too), so that collide() takes the margin and the step goes
  // on; the fault guard contains what such a body then does.
  constexpr float kMaxMargin = std::numeric_limits<float>::max();
  return margin < kMaxMargin ? margin : kMaxMargin;
}

struct ContactUpdateSettings {
  ContactTuning tuning;
  CombineRule frictionCombine = CombineRule::Average;
  CombineRule bouncinessCombine = CombineRule::Max;
  ImpactModel impactModel = ImpactModel::Newton;
};

struct ContactUpdateCounts {
  std::uint64_t filteredPairs = 0;  // kept by the broad phase, ruled out by the filters
  std::uint64_t narrowPhaseTests = 0;
  std::uint64_t reusedManifolds = 0;  // of those, manifolds placed again rather than computed
};

// The stage, with the per-body snapshots it takes once per step rather than once per pair (kept
// between steps so that a step allocates nothing once they have grown).
class ContactUpdate {
 public:
  // `contacts` holds last step's contacts on entry and this step's on return, in pair order;
  // `previous` is scratch. End events of contacts whose pair vanished go to `events`. Settings the
  // pre-solve callback gets wrong are refused, and the first such refusal is described in
  // `callbackError`.
  ContactUpdateCounts run(const BodyStorage& bodies, const BroadPhase& broadPhase,
                          std::span<const ProxyPair> pairs, std::vector<Contact>& contacts,
                          std::vector<Contact>& previous, const ContactUpdateSettings& settings, float dt,
                          const PreSolveCallback& preSolve, const PairFilters& filters, StepEvents& events,
                          std::string& callbackError);

 private:
  friend class PairPass;
  void snapshotBodies(const BodyStorage& bodies, const BroadPhase& broadPhase, float dt, float cacheDistance);

  std::vector<Transform> poses_;
  std::vector<Mat3> scaledRotations_;  // mat3_cast(rotation) * scale
  std::vector<float> spinReaches_;
  std::vector<Vec3> velocities_;            // linear, for the speculative margins
  std::vector<std::uint8_t> likelyPlaced_;  // moves beyond the manifold cache's tolerance this step
  std::vector<std::uint32_t> proxyBodies_;  // the body of each broad-phase proxy slot (its user value)
};

}  // namespace collide::detail
