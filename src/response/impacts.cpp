// Impacts by impulses, the stage before the solve (impacts.h).
#include "response/impacts.h"

#include "memory/heap_bytes.h"
#include "response/impact.h"
#include "response/stored_bodies.h"

#include <collide/error.h>

#include <algorithm>
#include <cmath>

namespace collide::detail {

namespace {

float normalVelocity(const ImpactBody& a, const ImpactBody& b, const Vec3& point, const Vec3& normal) {
  return glm::dot(velocityAt(b, point) - velocityAt(a, point), normal);
}

// Newton's impact law with Coulomb friction: the normal impulse that turns the approach u_n into
// -e u_n, then the tangential impulse that stops the sliding at the point, bounded by mu times the
// normal one. Returns the normal impulse.
float newtonImpact(ImpactBody& a, ImpactBody& b, const Vec3& point, const Vec3& n, float e, float mu) {
  const float approach = normalVelocity(a, b, point, n);
  const Mat3 k = contactInverseMassMatrix(a, b, point);
  const float normalImpulse = -(1.0f + e) * approach / glm::dot(n, k * n);
  applyImpulseAt(b, normalImpulse * n, point);
  applyImpulseAt(a, -normalImpulse * n, point);
  const Vec3 u = velocityAt(b, point) - velocityAt(a, point);
  const Vec3 sliding = u - glm::dot(u, n) * n;
  const float speed = glm::length(sliding);
  if (speed > 0.0f && mu > 0.0f) {
    const Vec3 t = sliding / speed;
    const float tangentMass = glm::dot(t, k * t);
    const float stop = std::min(speed / tangentMass, mu * normalImpulse);
    applyImpulseAt(b, -stop * t, point);
    applyImpulseAt(a, stop * t, point);
  }
  return normalImpulse;
}

// Whether a contact whose deepest point is at `depth` (negative: a gap) closes it within the step at
// the approach speed, with the slop a contact may keep.
bool meetsThisStep(float depth, float approach, const ContactTuning& tuning, float dt) {
  return -depth <= tuning.linearSlop - approach * dt;
}

}  // namespace

// Every contact that can act this step is an entry, for an impact elsewhere may set its bodies
// approaching; those that meet this step at their present velocities, fast enough, start the queue.
void ImpactStage::collect(const BodyStorage& bodies, const Array<Contact>& contacts, ImpactModel model,
                          const ContactTuning& tuning, float dt) {
  entries_.clear();
  queue_.clear();
  for (std::uint32_t i = 0; i < contacts.size(); ++i) {
    const Contact& c = contacts[i];
    if (c.sensor || !c.enabled || c.asleep || c.manifold.count == 0) continue;
    if (model == ImpactModel::Newton && !(c.restitution > 0.0f)) continue;
    const float deepest = c.manifold.maxDepth();
    Entry entry;
    entry.contact = i;
    entry.point = averagePoint(c.manifold, deepest - tuning.linearSlop);
    const ImpactBody a = impactBodyOf(bodies.states[c.bodyA]);
    const ImpactBody b = impactBodyOf(bodies.states[c.bodyB]);
    const float approach = normalVelocity(a, b, entry.point, c.manifold.normal);
    if (approach < -tuning.restitutionThreshold && meetsThisStep(deepest, approach, tuning, dt)) {
      entry.queued = true;
      queue_.push_back(static_cast<std::uint32_t>(entries_.size()));
    }
    entries_.push_back(entry);
  }
}

// Each body's entries, so that a body hit by an impact has its other contacts looked at again.
void ImpactStage::linkBodies(const Array<Contact>& contacts, std::size_t bodyCount) {
  firstOfBody_.assign(bodyCount + 1, 0);
  for (const Entry& e : entries_) {
    ++firstOfBody_[contacts[e.contact].bodyA + 1];
    ++firstOfBody_[contacts[e.contact].bodyB + 1];
  }
  for (std::size_t b = 0; b < bodyCount; ++b) firstOfBody_[b + 1] += firstOfBody_[b];
  entryOfBody_.resize(firstOfBody_[bodyCount]);
  Array<std::uint32_t> next(firstOfBody_.begin(), firstOfBody_.end() - 1);
  for (std::uint32_t i = 0; i < entries_.size(); ++i) {
    entryOfBody_[next[contacts[entries_[i].contact].bodyA]++] = i;
    entryOfBody_[next[contacts[entries_[i].contact].bodyB]++] = i;
  }
}

void ImpactStage::enqueueContactsOf(std::uint32_t body) {
  for (std::uint32_t k = firstOfBody_[body]; k < firstOfBody_[body + 1]; ++k) {
    Entry& e = entries_[entryOfBody_[k]];
    if (e.queued || e.visits >= kImpactVisits) continue;
    e.queued = true;
    queue_.push_back(entryOfBody_[k]);
  }
}

// One contact's impact, if its bodies still approach faster than the threshold. Returns whether it
// changed their velocities.
bool ImpactStage::resolve(BodyStorage& bodies, Contact& c, const Entry& entry, ImpactModel model,
                          const ContactTuning& tuning, const Vec3& gravity, float dt) {
  BodyState& sa = bodies.states[c.bodyA];
  BodyState& sb = bodies.states[c.bodyB];
  ImpactBody a = impactBodyOf(sa);
  ImpactBody b = impactBodyOf(sb);
  const Vec3& n = c.manifold.normal;
  const float approach = normalVelocity(a, b, entry.point, n);
  if (!(approach < -tuning.restitutionThreshold)) return false;
  // Apart all step even at the speed an impact elsewhere gave them: the solver's speculative contact
  // keeps them from closing more than the gap, and the impact, if any, is a later step's.
  if (!meetsThisStep(c.manifold.maxDepth(), approach, tuning, dt)) return false;
  // When in the step: once the gap closes at the approach speed, and not before either body's last
  // impact (an impact passed on through bodies at rest happens when it arrives).
  const float gap = std::max(0.0f, -c.manifold.maxDepth());
  const float t =
      std::clamp(std::max({gap / -approach, impactTime_[c.bodyA], impactTime_[c.bodyB]}), 0.0f, dt);
  // The impact acts on the velocities at that time: gravity has acted on the dynamic bodies until
  // then, and acts on for the rest of the step (the solver integrates it over the whole step).
  const bool dynamicA = bodies.records[c.bodyA].type == BodyType::Dynamic;
  const bool dynamicB = bodies.records[c.bodyB].type == BodyType::Dynamic;
  const Vec3 gravityA = bodies.records[c.bodyA].gravityScale * gravity;
  const Vec3 gravityB = bodies.records[c.bodyB].gravityScale * gravity;
  if (dynamicA) a.linearVelocity += t * gravityA;
  if (dynamicB) b.linearVelocity += t * gravityB;
  // A body left non-finite by a fault earlier in the step takes no impact (the fault guard stops it
  // at the step's end); the step goes on.
  if (!canApplyImpact(a, b, entry.point, n)) return false;
  const float impulse =
      model == ImpactModel::Newton
          ? newtonImpact(a, b, entry.point, n, c.restitution, c.friction)
          : glm::dot(resolveImpactInterpolated(a, b, entry.point, n, c.impactBounciness), n);
  if (!std::isfinite(impulse)) return false;
  if (dynamicA) a.linearVelocity -= t * gravityA;
  if (dynamicB) b.linearVelocity -= t * gravityB;
  // Integration over the step moves a body by its velocity after the stage; one whose velocity
  // changed at time t should have moved by the old velocity until then: the difference, the change
  // times t, is taken back once the step has moved it (applyTimeShifts), so that an impact found a
  // few centimetres early (its gap closes within the step) happens where the bodies meet, and a ball
  // that leaves the end of a row leaves from where it rested.
  const auto apply = [&](std::uint32_t body, BodyState& s, const ImpactBody& after) {
    linearShift_[body] -= t * (after.linearVelocity - s.linearVelocity);
    angularShift_[body] -= t * (after.angularVelocity - s.angularVelocity);
    shifted_ = true;
    writeBack(bodies.records[body], s, after);
    impactTime_[body] = t;
  };
  if (dynamicA) apply(c.bodyA, sa, a);
  if (dynamicB) apply(c.bodyB, sb, b);
  c.impactSpeed = std::max(c.impactSpeed, -approach);
  c.impactImpulse += impulse;
  return true;
}

void ImpactStage::applyTimeShifts(BodyStorage& bodies) {
  if (!shifted_) return;
  shifted_ = false;
  for (std::uint32_t i = 0; i < bodies.records.size() && i < linearShift_.size(); ++i) {
    const BodyRecord& r = bodies.records[i];
    if (!r.alive || r.type != BodyType::Dynamic || r.faulted) continue;
    BodyState& s = bodies.states[i];
    s.centerOfMass += linearShift_[i];
    if (!r.particle && angularShift_[i] != Vec3(0.0f)) {
      s.rotation = glm::normalize(s.rotation + 0.5f * Quat(0.0f, angularShift_[i]) * s.rotation);
      s.inverseInertiaWorld = worldInverseInertia(r.inverseInertiaLocal, s.rotation);
    }
  }
}

void ImpactStage::run(BodyStorage& bodies, Array<Contact>& contacts, ImpactModel model,
                      const ContactTuning& tuning, const Vec3& gravity, float dt) {
  collect(bodies, contacts, model, tuning, dt);
  if (queue_.empty()) return;  // nothing meets fast enough this step: the common case
  linkBodies(contacts, bodies.records.size());
  impactTime_.assign(bodies.records.size(), 0.0f);
  linearShift_.assign(bodies.records.size(), Vec3(0.0f));
  angularShift_.assign(bodies.records.size(), Vec3(0.0f));
  for (std::size_t head = 0; head < queue_.size(); ++head) {
    Entry& entry = entries_[queue_[head]];
    entry.queued = false;
    ++entry.visits;
    Contact& c = contacts[entry.contact];
    if (!resolve(bodies, c, entry, model, tuning, gravity, dt)) continue;
    // Only a dynamic body's velocity changed: its other contacts may now approach.
    if (bodies.records[c.bodyA].type == BodyType::Dynamic) enqueueContactsOf(c.bodyA);
    if (bodies.records[c.bodyB].type == BodyType::Dynamic) enqueueContactsOf(c.bodyB);
  }
}

std::size_t ImpactStage::memoryBytes() const {
  return heapBytes(entries_) + heapBytes(queue_) + heapBytes(firstOfBody_) + heapBytes(entryOfBody_) +
         heapBytes(impactTime_) + heapBytes(linearShift_) + heapBytes(angularShift_);
}

}  // namespace collide::detail
