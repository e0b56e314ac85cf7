// See fault_guard.h. Jolt and Box2D v3 assert on non-finite states in debug builds only; a game in
// release still needs the world to survive one bad input, so the check is always on (a few compares
// per body per substep, small next to the contact solve).
#include "dynamics/fault_guard.h"

#include <cmath>

namespace collide::detail {

namespace {

bool finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool finite(const Quat& q) {
  return std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z) && std::isfinite(q.w);
}

}  // namespace

std::uint8_t nonFiniteFields(const BodyState& s) {
  std::uint8_t fields = 0;
  if (!finite(s.centerOfMass)) fields |= FaultEvent::kPosition;
  if (!finite(s.rotation)) fields |= FaultEvent::kRotation;
  if (!finite(s.linearVelocity)) fields |= FaultEvent::kLinearVelocity;
  if (!finite(s.angularVelocity)) fields |= FaultEvent::kAngularVelocity;
  return fields;
}

void guardFiniteStates(BodyStorage& bodies, std::vector<FaultEvent>& faults) {
  const std::size_t n = bodies.states.size();
  for (std::size_t i = 0; i < n; ++i) {
    BodyRecord& r = bodies.records[i];
    if (!r.alive || r.type == BodyType::Static || !r.awake) continue;
    const std::uint8_t fields = nonFiniteFields(bodies.states[i]);
    if (fields == 0) continue;
    freezeBody(r, bodies.states[i]);
    faults.push_back({BodyId{static_cast<std::uint32_t>(i), r.generation}, fields});
  }
}

void freezeBody(BodyRecord& r, BodyState& s) {
  // The start-of-step pose was finite: the previous step ended through this guard, and the setters
  // refuse non-finite values.
  s.centerOfMass = s.centerOfMass0;
  s.rotation = s.rotation0;
  s.linearVelocity = Vec3(0.0f);
  s.angularVelocity = Vec3(0.0f);
  r.force = Vec3(0.0f);
  r.torque = Vec3(0.0f);
  if (r.type != BodyType::Dynamic) return;  // kinematic: already immovable, stays awake
  s.inverseMass = 0.0f;
  s.inverseInertiaWorld = Mat3(0.0f);
  r.awake = false;
  r.sleepTime = 0.0f;
  r.faulted = true;
}

void unfreezeBody(BodyRecord& r, BodyState& s) {
  if (!r.faulted) return;
  r.faulted = false;
  s.inverseMass = 1.0f / r.mass;
  s.inverseInertiaWorld = worldInverseInertia(r.inverseInertiaLocal, s.rotation);
  r.awake = true;
}

}  // namespace collide::detail
