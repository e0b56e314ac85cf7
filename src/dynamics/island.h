// Islands and sleeping (Box2D's union-find islands): awake dynamic bodies joined by touching contacts
// or joints form an island; when every body of an island has rested long enough, the island sleeps
// as a whole, and a sleeping island wakes as a whole. Static bodies join no island (a floor would join
// every pile on it); a moving kinematic body keeps what it touches awake. See docs/architecture.md,
// "Islands and sleeping".
#pragma once

#include <collide/broadphase.h>
#include <collide/settings.h>

#include "bodies/body_storage.h"
#include "contacts/contact_cache.h"
#include "dynamics/joint_solver.h"

#include <cstdint>
#include <span>
#include <vector>

namespace collide::detail {

// Wakes the island the body fell asleep with, all of it (a stack never has half its boxes frozen),
// and restarts an awake body's rest timer. Returns whether a sleeping body woke (a body frozen by
// the fault guard does not: it only looks asleep).
bool wakeIsland(BodyStorage& bodies, std::uint32_t index);
// The user gave the body a new state: a body frozen by the fault guard comes back, and its island
// wakes.
void wakeByUser(BodyStorage& bodies, std::uint32_t index);

// Before the narrow phase: an awake dynamic or moving kinematic body that may reach a sleeping one
// within this step (its speculative manifold has points) wakes the sleeper's island, so that the
// island takes part in this step's solve instead of being run into.
void wakeTouchedIslands(BodyStorage& bodies, const BroadPhase& broadPhase, std::span<const ProxyPair> pairs,
                        float speculativeDistance, float dt);

// After the events: the islands of the awake dynamic bodies, their bodies' rest timers, and the
// islands that fall asleep. Keeps its union-find arrays between steps.
class Islands {
 public:
  void updateSleep(BodyStorage& bodies, std::span<const Contact> contacts, std::span<const Joint> joints,
                   const SleepTuning& tuning, float dt);

  std::size_t memoryBytes() const;  // World::memoryUse

 private:
  std::uint32_t findRoot(std::uint32_t i);
  void unite(std::uint32_t a, std::uint32_t b);

  Array<std::uint32_t> parent_;
  Array<float> sleepTime_;  // per root: the least rest time of the island's bodies
};

}  // namespace collide::detail
