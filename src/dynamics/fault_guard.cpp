// See fault_guard.h. Jolt and Box2D v3 assert on non-finite states in debug builds only; a game in
// release still needs the world to survive one bad input, so the check is always on (a few compares
// per body per substep, small next to the contact solve).
#include "dynamics/fault_guard.h"

#include <algorithm>
#include <atomic>
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
  // A finite rotation can still be no rotation: an overflowing angular velocity integrates into a
  // quaternion that normalises to zero. The same tolerance as isValid(Transform), which every query
  // on the body's shape would apply.
  if (!finite(s.rotation) || !(std::abs(glm::dot(s.rotation, s.rotation) - 1.0f) < 1e-3f))
    fields |= FaultEvent::kRotation;
  if (!finite(s.linearVelocity)) fields |= FaultEvent::kLinearVelocity;
  if (!finite(s.angularVelocity)) fields |= FaultEvent::kAngularVelocity;
  return fields;
}

void guardFiniteStates(BodyStorage& bodies, Array<FaultEvent>& faults, TaskRunner& tasks) {
  const std::size_t n = bodies.states.size();
  // Faults are rare: the look at every body runs in parallel and only says whether one was found
  // (a flag any range may set, whichever sets it); the walk below then freezes and reports. It
  // reads the dense states first and a body's record (a few hundred bytes on) only for a state
  // that failed: a large world's records are not streamed for nothing.
  constexpr std::uint32_t kBodiesPerRange = 2048;
  std::atomic<bool> found{false};
  tasks.parallelFor(static_cast<std::uint32_t>(n), kBodiesPerRange,
                    [&](std::uint32_t begin, std::uint32_t end, std::uint32_t) {
                      for (std::uint32_t i = begin; i < end; ++i) {
                        if (nonFiniteFields(bodies.states[i]) != 0 && bodies.records[i].alive) {
                          found.store(true, std::memory_order_relaxed);
                          return;
                        }
                      }
                    });
  if (!found.load(std::memory_order_relaxed)) return;
  for (std::size_t i = 0; i < n; ++i) {
    BodyRecord& r = bodies.records[i];
    // Every body, not only the awake moving ones: frozen, sleeping and static bodies have zero
    // inverse mass, but a NaN impulse from a contact still reaches their velocity (0 * NaN is NaN),
    // and a static body's NaN velocity would reach everything that touches it in the next step.
    if (!r.alive) continue;
    const std::uint8_t fields = nonFiniteFields(bodies.states[i]);
    if (fields == 0) continue;
    freezeBody(r, bodies.states[i]);
    const BodyId id{static_cast<std::uint32_t>(i), r.generation};
    const auto same = [&](const FaultEvent& f) { return f.body == id; };
    const auto reported = std::find_if(faults.begin(), faults.end(), same);
    if (reported == faults.end()) {
      faults.push_back({id, fields});
    } else {
      reported->fields |= fields;  // one event per body per step, with every part that failed
    }
  }
}

void dropFaultedContacts(std::span<const FaultEvent> faults, Array<Contact>& contacts,
                         Array<ApartPair>& apartPairs, Array<Joint>& joints) {
  const auto faulted = [&](std::uint32_t body) {
    return std::any_of(faults.begin(), faults.end(),
                       [&](const FaultEvent& f) { return f.body.index == body; });
  };
  for (Contact& c : contacts) {
    if (c.sensor || (!faulted(c.bodyA) && !faulted(c.bodyB))) continue;  // sensor events carry no numbers
    c.manifold = Manifold{};
    c.cache.valid = false;  // computed anew by the next narrow phase, at the frozen pose
    c.points = {};
    c.prolongedPoints = 0;
    c.frictionImpulse = Vec3(0.0f);
    c.twistImpulse = 0.0f;
    c.stuck = false;
    c.touching = false;
  }
  for (ApartPair& p : apartPairs) {
    if (faulted(p.bodyA) || faulted(p.bodyB)) p.cache.valid = false;
  }
  for (Joint& joint : joints) {
    if (!joint.alive || (!faulted(joint.bodyA) && !faulted(joint.bodyB))) continue;
    joint.resetImpulses();
    if (!finite(joint.axis)) joint.axis = Vec3(1.0f, 0.0f, 0.0f);
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
  if (r.type != BodyType::Dynamic) return;  // static, kinematic: already immovable, stay as they are
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
  r.awake = r.enabled;
}

}  // namespace collide::detail
