#include "response/revert.h"

#include <collide/narrowphase.h>

#include <algorithm>

namespace collide::detail {

namespace {

void backToStepStart(const BodyRecord& r, BodyState& s) {
  s.centerOfMass = s.centerOfMass0;
  s.rotation = s.rotation0;
  s.inverseInertiaWorld = worldInverseInertia(r.inverseInertiaLocal, s.rotation);
}

}  // namespace

void revertPenetrating(BodyStorage& bodies, std::span<const Contact> contacts,
                       std::span<const std::uint32_t> solvedContacts, float linearSlop) {
  for (const std::uint32_t index : solvedContacts) {
    const Contact& c = contacts[index];
    const BodyRecord& ra = bodies.records[c.bodyA];
    const BodyRecord& rb = bodies.records[c.bodyB];
    BodyState& sa = bodies.states[c.bodyA];
    BodyState& sb = bodies.states[c.bodyB];
    Manifold now;
    if (!collide::collide(ra.shape, bodyTransform(ra, sa), rb.shape, bodyTransform(rb, sb), now)) continue;
    if (now.maxDepth() <= linearSlop) continue;
    const Vec3 n = now.normal;  // from A to B
    if (ra.type == BodyType::Dynamic && !ra.faulted) {
      backToStepStart(ra, sa);
      sa.linearVelocity -= std::max(0.0f, glm::dot(sa.linearVelocity, n)) * n;  // A moving into B
    }
    if (rb.type == BodyType::Dynamic && !rb.faulted) {
      backToStepStart(rb, sb);
      sb.linearVelocity -= std::min(0.0f, glm::dot(sb.linearVelocity, n)) * n;  // B moving into A
    }
  }
}

}  // namespace collide::detail
