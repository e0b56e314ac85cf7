// Revert to the last valid pose (revert.h).
#include "response/revert.h"

#include <collide/narrowphase.h>

#include "bodies/body_parts.h"
#include "memory/heap_bytes.h"

#include <algorithm>

namespace collide::detail {

namespace {

bool canGoBack(const BodyRecord& r) { return r.alive && r.type == BodyType::Dynamic && !r.faulted; }

void backToValidPose(const BodyRecord& r, BodyState& s) {
  s.centerOfMass = r.validCenterOfMass;
  s.rotation = r.validRotation;
  s.inverseInertiaWorld = worldInverseInertia(r.inverseInertiaLocal, s.rotation);
}

}  // namespace

bool RevertResponse::pass(BodyStorage& bodies, float linearSlop) {
  std::fill(penetrating_.begin(), penetrating_.end(), 0);
  bool wentBack = false;
  for (const Candidate& pair : candidates_) {
    const BodyRecord& ra = bodies.records[pair.a];
    const BodyRecord& rb = bodies.records[pair.b];
    BodyState& sa = bodies.states[pair.a];
    BodyState& sb = bodies.states[pair.b];
    if (!hasValidPose(sa) || !hasValidPose(sb)) continue;  // the fault guard, next, freezes it
    Manifold now;
    const auto disabled = [&](std::uint32_t partA, std::uint32_t partB) {
      if (!hasParts(ra) && !hasParts(rb)) return false;  // ruled out before the passes
      const Contact* contact = findContact(contacts_, pair.key, partA, partB);
      return contact && contact->manifold.count > 0 && !contact->enabled;
    };
    if (!collideSolidParts(ra, bodyTransform(ra, sa), rb, bodyTransform(rb, sb), 0.0f, now, disabled))
      continue;
    if (now.maxDepth() <= linearSlop) continue;
    penetrating_[pair.a] = penetrating_[pair.b] = 1;
    const Vec3 n = now.normal;  // from A to B
    if (canGoBack(ra) && !reverted_[pair.a]) {
      backToValidPose(ra, sa);
      sa.linearVelocity -= std::max(0.0f, glm::dot(sa.linearVelocity, n)) * n;  // A moving into B
      reverted_[pair.a] = 1;
      wentBack = true;
    }
    if (canGoBack(rb) && !reverted_[pair.b]) {
      backToValidPose(rb, sb);
      sb.linearVelocity -= std::min(0.0f, glm::dot(sb.linearVelocity, n)) * n;  // B moving into A
      reverted_[pair.b] = 1;
      wentBack = true;
    }
  }
  return wentBack;
}

void RevertResponse::apply(BodyStorage& bodies, const BroadPhase& broadPhase,
                           std::span<const ProxyPair> pairs, std::span<const Contact> contacts,
                           const PairFilters& filters, float linearSlop) {
  // The pairs that respond: a dynamic body, no sensor, the layers agree, not both asleep, and not a
  // contact the pre-solve callback disabled (a one-way platform lets bodies through).
  candidates_.clear();
  for (const ProxyPair& pair : pairs) {
    const auto a = static_cast<std::uint32_t>(broadPhase.userValue(pair.a));
    const auto b = static_cast<std::uint32_t>(broadPhase.userValue(pair.b));
    const BodyRecord& ra = bodies.records[a];
    const BodyRecord& rb = bodies.records[b];
    if (!ra.alive || !rb.alive || ra.sensor || rb.sensor) continue;
    if (ra.type != BodyType::Dynamic && rb.type != BodyType::Dynamic) continue;
    if (!pairAllowed(bodies, filters, a, b)) continue;
    if (!bodies.isAwakeDynamic(a) && !bodies.isAwakeDynamic(b)) continue;
    const std::uint64_t key = pairKey(pair.a.index, pair.b.index);
    if (!hasParts(ra) && !hasParts(rb)) {  // bodies made of parts: per pair of parts, in the pass
      const Contact* contact = findContact(contacts, key);
      if (contact && contact->manifold.count > 0 && !contact->enabled) continue;
    }
    candidates_.push_back({a, b, key});
  }
  contacts_ = contacts;
  reverted_.assign(bodies.records.size(), 0);
  penetrating_.assign(bodies.records.size(), 0);
  while (pass(bodies, linearSlop)) {
  }
  // The last pass moved nothing: it saw the final poses. A body that penetrates nothing there is
  // valid where it is.
  for (std::uint32_t i = 0; i < bodies.records.size(); ++i) {
    BodyRecord& r = bodies.records[i];
    if (!canGoBack(r) || penetrating_[i]) continue;
    r.validCenterOfMass = bodies.states[i].centerOfMass;
    r.validRotation = bodies.states[i].rotation;
  }
}

void takeCurrentPosesAsValid(BodyStorage& bodies) {
  for (std::uint32_t i = 0; i < bodies.records.size(); ++i) {
    bodies.records[i].validCenterOfMass = bodies.states[i].centerOfMass;
    bodies.records[i].validRotation = bodies.states[i].rotation;
  }
}

std::size_t RevertResponse::memoryBytes() const {
  return heapBytes(candidates_) + heapBytes(reverted_) + heapBytes(penetrating_);
}

}  // namespace collide::detail
