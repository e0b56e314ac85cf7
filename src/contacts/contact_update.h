// The narrow-phase stage of the step (lecture: collision detection, then collision data): for each
// pair the broad phase kept, the contact of last step is found by a merge in key order (one array,
// rewritten in place: in_place_merge.h), the pair's manifold is computed or reused, and the contact
// is carried over (new vs prolonged points, warm starting) or ended, then shown to the pre-solve
// callback. A contact whose manifold is placed again is updated where it lies.
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
#include <collide/narrowphase.h>
#include <collide/settings.h>

#include "base/task_runner.h"
#include "bodies/body_storage.h"
#include "contacts/contact_cache.h"
#include "contacts/contact_events.h"
#include "contacts/in_place_merge.h"
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
  // `contacts` holds last step's contacts on entry and this step's on return, in pair order, and
  // `apart` likewise the pairs found apart (ApartPair), each rewritten in place (InPlaceMerge). End
  // events of contacts whose pair vanished go to `events`. Settings the pre-solve callback gets wrong
  // are refused, and the first such refusal is described in `callbackError`. With more than one
  // worker, the pairs' full collider tests run first, in parallel ranges (each pair's test reads
  // only the step's snapshot), when last step tested many; then the walk takes their results, in
  // blocks of pairs on the workers (each block rewrites its own part of the arrays, and the parts
  // are joined in order) unless a pre-solve callback or a pair filter must be called in pair order
  // from the calling thread. The contacts, the events and the callbacks are those of one worker, in
  // the same order.
  ContactUpdateCounts run(const BodyStorage& bodies, const BroadPhase& broadPhase,
                          std::span<const ProxyPair> pairs, Array<Contact>& contacts, Array<ApartPair>& apart,
                          const ContactUpdateSettings& settings, float dt, const PreSolveCallback& preSolve,
                          const PairFilters& filters, StepEvents& events, std::string& callbackError,
                          TaskRunner& tasks);

  // A pair's collider test, run ahead: the manifold, and the distance when it came out empty
  // between polyhedra (for the separating-axis cache).
  struct StagedTest {
    Manifold manifold;
    DistanceResult apart;
    bool hasApart = false;
    bool reused = false;  // last step's manifold placed again, not a test
  };
  // Pairs not tested ahead: the walk finds their route itself, or takes the one found apart.
  static constexpr std::uint32_t kNotStaged = 0xFFFFFFFFu;
  static constexpr std::uint32_t kSpheresApart = 0xFFFFFFFEu;
  static constexpr std::uint32_t kAxisApart = 0xFFFFFFFDu;
  static constexpr std::uint32_t kPairsPerRange = 64;

  std::size_t memoryBytes() const;  // the snapshots, the staged tests, the walk's scratch (World::memoryUse)

 private:
  friend class PairPass;
  void snapshotBodies(const BodyStorage& bodies, const BroadPhase& broadPhase, float dt, float cacheDistance,
                      TaskRunner& tasks);
  void snapshotRange(const BodyStorage& bodies, float dt, float cacheDistance, std::uint32_t begin,
                     std::uint32_t end);
  // The tests of the pairs whose walk will reach collide(), in parallel ranges.
  void stageTests(const BodyStorage& bodies, std::span<const ProxyPair> pairs, const Array<Contact>& previous,
                  const Array<ApartPair>& previousApart, const ContactUpdateSettings& settings, float dt,
                  TaskRunner& tasks);
  // Whether the stage found the pair apart this way (PairPass::ManifoldRoute).
  template <typename Route>
  bool stagedRoute(std::size_t pair, Route route) const {
    if (pair >= stagedIndex_.size()) return false;
    return stagedIndex_[pair] == (route == Route::SpheresApart ? kSpheresApart : kAxisApart);
  }
  const StagedTest* stagedTest(std::size_t pair) const {
    if (pair >= stagedIndex_.size() || stagedIndex_[pair] >= kAxisApart) return nullptr;
    const std::uint32_t index = stagedIndex_[pair];
    return &staged_[index >> 26].tests[index & ((1u << 26) - 1)];
  }

  Array<Transform> poses_;
  Array<Mat3> scaledRotations_;  // mat3_cast(rotation) * scale
  Array<float> spinReaches_;
  Array<Vec3> velocities_;            // linear, for the speculative margins
  Array<std::uint8_t> likelyPlaced_;  // moves beyond the manifold cache's tolerance this step
  Array<std::uint32_t> proxyBodies_;  // the body of each broad-phase proxy slot (its user value)
  // Per pair, its staged test (worker << 26 | index in that worker's array) or kNotStaged; empty
  // with one worker.
  Array<std::uint32_t> stagedIndex_;
  // Per worker, apart by a cache line: each worker's push_back writes its own vector's end.
  struct alignas(64) WorkerTests {
    Array<StagedTest> tests;
  };
  Array<WorkerTests> staged_;
  // The walk's scratch: last step's records moved aside while this step's are written over them
  // (InPlaceMerge), and the walked pair's last contacts.
  Array<Contact> contactSpill_;
  Array<ApartPair> apartSpill_;
  Array<Contact> pairPrevious_;

  // The walk in blocks on several workers (walkInBlocks): each block's pairs, its own scratch,
  // events and counts, and its part of the contacts and of the pairs apart (contactBlocks_ and
  // apartBlocks_, as compactBlocks joins them), kept from step to step.
  static constexpr std::size_t kMinPairsPerBlock = 256;
  static constexpr std::size_t kBlocksPerWorker = 4;
  static constexpr std::size_t kKeptOverflow = 256;  // records a block's overflow keeps room for
  struct WalkBlock {
    std::size_t firstPair = 0;
    std::size_t endPair = 0;
    Array<Contact> pairPrevious;
    StepEvents events;
    std::string callbackError;
    ContactUpdateCounts counts;
  };
  ContactUpdateCounts walkInBlocks(const BodyStorage& bodies, std::span<const ProxyPair> pairs,
                                   Array<Contact>& contacts, Array<ApartPair>& apart,
                                   const ContactUpdateSettings& settings, float dt,
                                   const PairFilters& filters, StepEvents& events, TaskRunner& tasks);
  Array<WalkBlock> blocks_;
  Array<MergeBlock<Contact>> contactBlocks_;
  Array<MergeBlock<ApartPair>> apartBlocks_;
  // Last step's pairs that reached the narrow phase, and of those the ones not reused: the stage
  // runs ahead when at least one in kStageWhenTestedOneIn was tested.
  static constexpr std::uint64_t kStageWhenTestedOneIn = 4;
  std::uint64_t lastTests_ = 0;
  std::uint64_t lastPairs_ = 0;
};

}  // namespace collide::detail
