// The bodies of the body storage as the response models see them (ImpactBody), and back, and the
// point of a manifold where an impact acts.
#pragma once

#include <collide/narrowphase.h>

#include "bodies/body_storage.h"
#include "response/impact_body.h"

#include <algorithm>

namespace collide::detail {

// Static and kinematic bodies already carry zero inverse mass and inertia in the body storage.
inline ImpactBody impactBodyOf(const BodyState& s) {
  ImpactBody body;
  body.inverseMass = s.inverseMass;
  body.inverseInertia = s.inverseMass == 0.0f ? Mat3(0.0f) : s.inverseInertiaWorld;
  body.linearVelocity = s.linearVelocity;
  body.angularVelocity = s.angularVelocity;
  body.centerOfMass = s.centerOfMass;
  return body;
}

// Only dynamic bodies take the result: a kinematic partner keeps its prescribed motion.
inline void writeBack(const BodyRecord& record, BodyState& s, const ImpactBody& body) {
  if (record.type != BodyType::Dynamic) return;
  s.linearVelocity = body.linearVelocity;
  s.angularVelocity = body.angularVelocity;
}

// The average of the manifold's points at least minDepth deep.
inline Vec3 averagePoint(const Manifold& m, float minDepth) {
  Vec3 sum(0.0f);
  int n = 0;
  for (int i = 0; i < m.count; ++i) {
    if (m.points[i].depth < minDepth) continue;
    sum += m.points[i].midpoint();
    ++n;
  }
  return sum / static_cast<float>(std::max(n, 1));
}

}  // namespace collide::detail
