#include "dynamics/contact_solver.h"

#include <algorithm>
#include <cmath>

namespace collide::detail {

Softness makeSoftness(float hertz, float dampingRatio, float h) {
  if (hertz == 0.0f) return {0.0f, 1.0f, 0.0f};
  const float omega = 2.0f * kPi * hertz;
  const float a1 = 2.0f * dampingRatio + h * omega;
  const float a2 = h * omega * a1;
  const float a3 = 1.0f / (1.0f + a2);
  return {omega / a1, a2 * a3, a3};
}

namespace {

float effectiveMass(const BodyState& a, const BodyState& b, const Vec3& rA, const Vec3& rB,
                    const Vec3& direction) {
  const Vec3 rnA = glm::cross(rA, direction);
  const Vec3 rnB = glm::cross(rB, direction);
  const float k = a.inverseMass + b.inverseMass + glm::dot(rnA, a.inverseInertiaWorld * rnA) +
                  glm::dot(rnB, b.inverseInertiaWorld * rnB);
  return k > 0.0f ? 1.0f / k : 0.0f;
}

Vec3 relativeVelocity(const BodyState& a, const BodyState& b, const Vec3& rA, const Vec3& rB) {
  return b.linearVelocity + glm::cross(b.angularVelocity, rB) - a.linearVelocity -
         glm::cross(a.angularVelocity, rA);
}

// Applies +impulse to B and -impulse to A at their anchors. Bodies with zero inverse mass and
// inertia (static, kinematic) are unchanged, which is the one-way pair of the lecture.
void applyImpulse(BodyState& a, BodyState& b, const Vec3& rA, const Vec3& rB, const Vec3& impulse) {
  a.linearVelocity -= a.inverseMass * impulse;
  a.angularVelocity -= a.inverseInertiaWorld * glm::cross(rA, impulse);
  b.linearVelocity += b.inverseMass * impulse;
  b.angularVelocity += b.inverseInertiaWorld * glm::cross(rB, impulse);
}

// Adds `impulse` to the point's accumulated normal impulse, clamped so the total never pulls
// (contacts only push), records it, and applies the change to both bodies.
void applyNormalImpulse(BodyState& a, BodyState& b, const ConstraintPoint& p, const Vec3& normal,
                        float impulse, ContactPointState& state) {
  const float newImpulse = std::max(state.normalImpulse + impulse, 0.0f);
  impulse = newImpulse - state.normalImpulse;
  state.normalImpulse = newImpulse;
  state.maxNormalImpulse = std::max(state.maxNormalImpulse, impulse);
  state.totalNormalImpulse += impulse;
  applyImpulse(a, b, p.anchorA, p.anchorB, impulse * normal);
}

}  // namespace

void prepareContacts(BodyStorage& bodies, std::vector<Contact>& contacts,
                     std::vector<ContactConstraint>& constraints, const SolverSettings& settings, float h) {
  // Stiffness is capped at a quarter of the substep rate so the spring stays resolvable (Box2D v3).
  const float hertz = std::min(settings.tuning.hertz, 0.25f / h);
  const Softness soft = makeSoftness(hertz, settings.tuning.dampingRatio, h);
  // A one-way pair has half the effective mass to move: a stiffer spring gives the same response.
  const Softness staticSoft = makeSoftness(2.0f * hertz, settings.tuning.dampingRatio, h);

  constraints.clear();
  for (std::uint32_t ci = 0; ci < contacts.size(); ++ci) {
    Contact& contact = contacts[ci];
    if (contact.sensor || !contact.enabled || contact.asleep || contact.manifold.count == 0) continue;
    const BodyState& a = bodies.states[contact.bodyA];
    const BodyState& b = bodies.states[contact.bodyB];
    ContactConstraint& c = constraints.emplace_back();
    c.contactIndex = ci;
    c.bodyA = contact.bodyA;
    c.bodyB = contact.bodyB;
    c.normal = contact.manifold.normal;
    orthonormalBasis(c.normal, c.tangents[0], c.tangents[1]);
    c.friction = settings.friction ? contact.friction : 0.0f;
    c.restitution = contact.restitution;
    c.softness = (a.inverseMass == 0.0f || b.inverseMass == 0.0f) ? staticSoft : soft;
    c.pointCount = contact.manifold.count;
    for (int i = 0; i < c.pointCount; ++i) {
      const ContactPoint& mp = contact.manifold.points[i];
      ConstraintPoint& p = c.points[i];
      const Vec3 point = mp.midpoint();
      p.anchorA = point - a.centerOfMass;
      p.anchorB = point - b.centerOfMass;
      p.adjustedSeparation = -mp.depth - glm::dot(p.anchorB - p.anchorA, c.normal);
      p.normalMass = effectiveMass(a, b, p.anchorA, p.anchorB, c.normal);
      p.tangentMass[0] = effectiveMass(a, b, p.anchorA, p.anchorB, c.tangents[0]);
      p.tangentMass[1] = effectiveMass(a, b, p.anchorA, p.anchorB, c.tangents[1]);
      ContactPointState& state = contact.points[i];
      state.relativeVelocity = glm::dot(c.normal, relativeVelocity(a, b, p.anchorA, p.anchorB));
      state.totalNormalImpulse = 0.0f;
      state.maxNormalImpulse = 0.0f;
      if (c.friction == 0.0f) state.tangentImpulse = {0.0f, 0.0f};
    }
  }
}

void warmStartContacts(BodyStorage& bodies, std::vector<Contact>& contacts,
                       const std::vector<ContactConstraint>& constraints) {
  for (const ContactConstraint& c : constraints) {
    BodyState& a = bodies.states[c.bodyA];
    BodyState& b = bodies.states[c.bodyB];
    Contact& contact = contacts[c.contactIndex];
    for (int i = 0; i < c.pointCount; ++i) {
      ContactPointState& state = contact.points[i];
      const Vec3 impulse = state.normalImpulse * c.normal + state.tangentImpulse[0] * c.tangents[0] +
                           state.tangentImpulse[1] * c.tangents[1];
      state.totalNormalImpulse += state.normalImpulse;
      applyImpulse(a, b, c.points[i].anchorA, c.points[i].anchorB, impulse);
    }
  }
}

void solveContacts(BodyStorage& bodies, std::vector<Contact>& contacts,
                   const std::vector<ContactConstraint>& constraints, float h, float pushOutSpeed,
                   bool useBias) {
  const float inverseH = 1.0f / h;
  for (const ContactConstraint& c : constraints) {
    BodyState& a = bodies.states[c.bodyA];
    BodyState& b = bodies.states[c.bodyB];
    Contact& contact = contacts[c.contactIndex];
    // How far the bodies moved and turned since the step started: the current separation follows
    // from the anchors carried along, without a new narrow-phase query (Box2D v3).
    const Vec3 dpA = a.centerOfMass - a.centerOfMass0;
    const Vec3 dpB = b.centerOfMass - b.centerOfMass0;
    const Quat dqA = a.rotation * glm::conjugate(a.rotation0);
    const Quat dqB = b.rotation * glm::conjugate(b.rotation0);

    for (int i = 0; i < c.pointCount; ++i) {
      const ConstraintPoint& p = c.points[i];
      ContactPointState& state = contact.points[i];
      const Vec3 d = (dpB - dpA) + (dqB * p.anchorB - dqA * p.anchorA);
      const float separation = glm::dot(d, c.normal) + p.adjustedSeparation;

      float bias = 0.0f;
      float massScale = 1.0f;
      float impulseScale = 0.0f;
      if (separation > 0.0f) {
        // Speculative: allow closing exactly the gap within this substep (Catto, GDC 2013).
        bias = separation * inverseH;
      } else if (useBias) {
        bias = std::max(c.softness.biasRate * separation, -pushOutSpeed);
        massScale = c.softness.massScale;
        impulseScale = c.softness.impulseScale;
      }
      const float vn = glm::dot(relativeVelocity(a, b, p.anchorA, p.anchorB), c.normal);
      float impulse = -p.normalMass * massScale * (vn + bias) - impulseScale * state.normalImpulse;
      applyNormalImpulse(a, b, p, c.normal, impulse, state);
    }

    if (c.friction == 0.0f) continue;
    // Coulomb: the tangential impulse stays inside the disc of radius mu * normal impulse (the
    // friction cone of each point), solved after the normal so it sees this substep's bound.
    for (int i = 0; i < c.pointCount; ++i) {
      const ConstraintPoint& p = c.points[i];
      ContactPointState& state = contact.points[i];
      const Vec3 dv = relativeVelocity(a, b, p.anchorA, p.anchorB);
      std::array<float, 2> next{state.tangentImpulse[0] - p.tangentMass[0] * glm::dot(dv, c.tangents[0]),
                                state.tangentImpulse[1] - p.tangentMass[1] * glm::dot(dv, c.tangents[1])};
      const float limit = c.friction * state.normalImpulse;
      const float length = std::sqrt(next[0] * next[0] + next[1] * next[1]);
      if (length > limit) {
        const float s = length > 0.0f ? limit / length : 0.0f;
        next[0] *= s;
        next[1] *= s;
      }
      const Vec3 impulse = (next[0] - state.tangentImpulse[0]) * c.tangents[0] +
                           (next[1] - state.tangentImpulse[1]) * c.tangents[1];
      state.tangentImpulse = next;
      applyImpulse(a, b, p.anchorA, p.anchorB, impulse);
    }
  }
}

// Newton's restitution on the approach velocity measured before the solve: the soft contact has
// absorbed the impact by now, so the bounce is added at the end (Box2D v3's b2ApplyRestitution).
void applyRestitution(BodyStorage& bodies, std::vector<Contact>& contacts,
                      const std::vector<ContactConstraint>& constraints, float threshold) {
  for (const ContactConstraint& c : constraints) {
    if (c.restitution == 0.0f) continue;
    BodyState& a = bodies.states[c.bodyA];
    BodyState& b = bodies.states[c.bodyB];
    Contact& contact = contacts[c.contactIndex];
    for (int i = 0; i < c.pointCount; ++i) {
      const ConstraintPoint& p = c.points[i];
      ContactPointState& state = contact.points[i];
      if (state.relativeVelocity > -threshold || state.maxNormalImpulse == 0.0f) continue;
      const float vn = glm::dot(relativeVelocity(a, b, p.anchorA, p.anchorB), c.normal);
      float impulse = -p.normalMass * (vn + c.restitution * state.relativeVelocity);
      applyNormalImpulse(a, b, p, c.normal, impulse, state);
    }
  }
}

}  // namespace collide::detail
