// Islands, sleeping and waking (island.h).
#include "dynamics/island.h"

#include <collide/narrowphase.h>

#include "bodies/body_parts.h"
#include "contacts/contact_update.h"
#include "dynamics/fault_guard.h"
#include "memory/heap_bytes.h"

#include <algorithm>
#include <limits>

namespace collide::detail {

bool wakeIsland(BodyStorage& bodies, std::uint32_t index) {
  BodyRecord& r = bodies.records[index];
  if (!r.alive || !r.enabled || r.type != BodyType::Dynamic || r.faulted) return false;
  r.sleepTime = 0.0f;
  if (r.awake) return false;
  const std::uint32_t root = r.island;
  for (BodyRecord& other : bodies.records) {
    if (other.alive && other.enabled && other.type == BodyType::Dynamic && !other.awake && !other.faulted &&
        other.island == root) {
      other.awake = true;
      other.sleepTime = 0.0f;
    }
  }
  return true;
}

void wakeByUser(BodyStorage& bodies, std::uint32_t index) {
  unfreezeBody(bodies.records[index], bodies.states[index]);
  wakeIsland(bodies, index);
}

// Repeated until no island wakes, because a woken island can reach the next one. Only pairs on the
// border of a sleeping island are tested.
void wakeTouchedIslands(BodyStorage& bodies, const BroadPhase& broadPhase, std::span<const ProxyPair> pairs,
                        float speculativeDistance, float dt) {
  const auto margin = [&](std::uint32_t ia, std::uint32_t ib) {
    const BodyState& sa = bodies.states[ia];
    const BodyState& sb = bodies.states[ib];
    return speculativeMargin(sa.linearVelocity, sb.linearVelocity, spinReach(bodies.records[ia], sa),
                             spinReach(bodies.records[ib], sb), dt, speculativeDistance);
  };
  bool woke = true;
  while (woke) {
    woke = false;
    for (const ProxyPair& pair : pairs) {
      const auto ia = static_cast<std::uint32_t>(broadPhase.records()[pair.a.index].userValue);
      const auto ib = static_cast<std::uint32_t>(broadPhase.records()[pair.b.index].userValue);
      const bool sleepA = bodies.isSleeping(ia);
      const bool sleepB = bodies.isSleeping(ib);
      if (sleepA == sleepB) continue;
      const std::uint32_t mover = sleepA ? ib : ia;
      if (!bodies.isAwakeDynamic(mover) && !bodies.isMovingKinematic(mover)) continue;
      const BodyRecord& ra = bodies.records[ia];
      const BodyRecord& rb = bodies.records[ib];
      if (ra.sensor || rb.sensor || (ra.layer & rb.mask) == 0 || (rb.layer & ra.mask) == 0) continue;
      Manifold manifold;
      if (!collideSolidParts(ra, bodyTransform(ra, bodies.states[ia]), rb,
                             bodyTransform(rb, bodies.states[ib]), margin(ia, ib), manifold,
                             [](std::uint32_t, std::uint32_t) { return false; }))
        continue;
      // Only what actually woke repeats the pass: a frozen body touched by a mover never wakes, and
      // counting it would repeat the pass forever.
      if (wakeIsland(bodies, sleepA ? ia : ib)) woke = true;
    }
  }
}

std::uint32_t Islands::findRoot(std::uint32_t i) {
  while (parent_[i] != i) {
    parent_[i] = parent_[parent_[i]];  // path halving
    i = parent_[i];
  }
  return i;
}

// The smaller index becomes the root: the islands do not depend on the order of the unions.
void Islands::unite(std::uint32_t a, std::uint32_t b) {
  a = findRoot(a);
  b = findRoot(b);
  if (a < b) parent_[b] = a;
  if (b < a) parent_[a] = b;
}

// A body below both sleep speeds accumulates rest time; an island whose every body has rested for
// timeToSleep falls asleep as a whole, velocities zeroed.
void Islands::updateSleep(BodyStorage& bodies, std::span<const Contact> contacts,
                          std::span<const Joint> joints, const SleepTuning& tuning, float dt) {
  const auto n = static_cast<std::uint32_t>(bodies.records.size());
  parent_.resize(n);
  sleepTime_.assign(n, std::numeric_limits<float>::infinity());
  for (std::uint32_t i = 0; i < n; ++i) parent_[i] = i;
  const auto link = [&](std::uint32_t a, std::uint32_t b) {
    if (bodies.isAwakeDynamic(a) && bodies.isAwakeDynamic(b)) unite(a, b);
    // -dt: the timer below then restarts from 0 whatever the body's own speed.
    if (bodies.isAwakeDynamic(a) && bodies.isMovingKinematic(b)) bodies.records[a].sleepTime = -dt;
    if (bodies.isAwakeDynamic(b) && bodies.isMovingKinematic(a)) bodies.records[b].sleepTime = -dt;
  };
  for (const Contact& c : contacts) {
    if (!c.sensor && c.touching && !c.asleep) link(c.bodyA, c.bodyB);
  }
  for (const Joint& joint : joints) {
    if (joint.alive && bodies.records[joint.bodyA].enabled && bodies.records[joint.bodyB].enabled)
      link(joint.bodyA, joint.bodyB);
  }
  for (std::uint32_t i = 0; i < n; ++i) {
    if (!bodies.isAwakeDynamic(i)) continue;
    BodyRecord& r = bodies.records[i];
    const BodyState& s = bodies.states[i];
    const bool resting = glm::length(s.linearVelocity) <= tuning.linearSpeed &&
                         glm::length(s.angularVelocity) <= tuning.angularSpeed;
    r.sleepTime = resting ? r.sleepTime + dt : 0.0f;
    float& islandTime = sleepTime_[findRoot(i)];
    islandTime = std::min(islandTime, r.sleepTime);
  }
  for (std::uint32_t i = 0; i < n; ++i) {
    if (!bodies.isAwakeDynamic(i)) continue;
    const std::uint32_t root = findRoot(i);
    if (sleepTime_[root] < tuning.timeToSleep) continue;
    BodyRecord& r = bodies.records[i];
    BodyState& s = bodies.states[i];
    r.awake = false;
    r.island = root;
    s.linearVelocity = Vec3(0.0f);
    s.angularVelocity = Vec3(0.0f);
  }
}

std::size_t Islands::memoryBytes() const { return heapBytes(parent_) + heapBytes(sleepTime_); }

}  // namespace collide::detail
