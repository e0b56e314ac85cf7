#include "dynamics/joint_solver.h"

#include "dynamics/contact_solver.h"

#include <algorithm>
#include <cmath>

namespace collide::detail {

namespace {

struct JointFrame {
  Vec3 rA{0.0f};  // world offsets from the centres of mass to the anchors, at the current pose
  Vec3 rB{0.0f};
  Vec3 axis{0.0f};
  float distance = 0.0f;
};

// The anchors are rotated with each body's current rotation, so a turning body carries its anchor
// exactly (Box2D v3 uses the step-start frames and the delta rotation instead; same result).
JointFrame frameOf(const BodyStorage& bodies, DistanceJoint& joint) {
  const BodyState& a = bodies.states[joint.bodyA];
  const BodyState& b = bodies.states[joint.bodyB];
  JointFrame f;
  f.rA = a.rotation * joint.localAnchorA;
  f.rB = b.rotation * joint.localAnchorB;
  const Vec3 d = (b.centerOfMass + f.rB) - (a.centerOfMass + f.rA);
  f.distance = glm::length(d);
  // Coincident anchors have no direction: keep the last one (the constraint is then C = -length).
  if (f.distance > 1e-6f) joint.axis = d / f.distance;
  f.axis = joint.axis;
  return f;
}

void applyAxisImpulse(BodyState& a, BodyState& b, const JointFrame& f, float impulse) {
  const Vec3 p = impulse * f.axis;
  a.linearVelocity -= a.inverseMass * p;
  a.angularVelocity -= a.inverseInertiaWorld * glm::cross(f.rA, p);
  b.linearVelocity += b.inverseMass * p;
  b.angularVelocity += b.inverseInertiaWorld * glm::cross(f.rB, p);
}

}  // namespace

void warmStartJoints(BodyStorage& bodies, std::vector<DistanceJoint>& joints) {
  for (DistanceJoint& joint : joints) {
    if (!joint.active) continue;
    const JointFrame f = frameOf(bodies, joint);
    applyAxisImpulse(bodies.states[joint.bodyA], bodies.states[joint.bodyB], f, joint.impulse);
  }
}

void solveJoints(BodyStorage& bodies, std::vector<DistanceJoint>& joints, float h, float rigidHertz,
                 bool useBias) {
  for (DistanceJoint& joint : joints) {
    if (!joint.active) continue;
    BodyState& a = bodies.states[joint.bodyA];
    BodyState& b = bodies.states[joint.bodyB];
    const JointFrame f = frameOf(bodies, joint);
    const Vec3 rnA = glm::cross(f.rA, f.axis);
    const Vec3 rnB = glm::cross(f.rB, f.axis);
    const float k = a.inverseMass + b.inverseMass + glm::dot(rnA, a.inverseInertiaWorld * rnA) +
                    glm::dot(rnB, b.inverseInertiaWorld * rnB);
    if (k <= 0.0f) continue;
    const float axialMass = 1.0f / k;
    const float c = f.distance - joint.length;
    const Vec3 va = a.linearVelocity + glm::cross(a.angularVelocity, f.rA);
    const Vec3 vb = b.linearVelocity + glm::cross(b.angularVelocity, f.rB);
    const float cdot = glm::dot(vb - va, f.axis);

    float bias = 0.0f;
    float massScale = 1.0f;
    float impulseScale = 0.0f;
    if (joint.compliance > 0.0f) {
      // XPBD compliance as a spring: stiffness 1/compliance on this effective mass gives
      // omega = sqrt(k / compliance) (k = 1 / effective mass); a spring acts in both passes.
      const float hertz = std::sqrt(k / joint.compliance) / (2.0f * kPi);
      const Softness soft = makeSoftness(hertz, joint.dampingRatio, h);
      bias = soft.biasRate * c;
      massScale = soft.massScale;
      impulseScale = soft.impulseScale;
    } else if (useBias) {
      // Box2D v3's rigid joints: a soft constraint at twice the contact stiffness (the contact
      // hertz is capped at a quarter of the substep rate), damping ratio 2. The stiff limit (bias
      // C/h) overshoots in Gauss-Seidel over a chain and pumped energy into a swinging one.
      const Softness soft = makeSoftness(rigidHertz, 2.0f, h);
      bias = soft.biasRate * c;
      massScale = soft.massScale;
      impulseScale = soft.impulseScale;
    }
    const float impulse = -axialMass * massScale * (cdot + bias) - impulseScale * joint.impulse;
    joint.impulse += impulse;
    applyAxisImpulse(a, b, f, impulse);
  }
}

}  // namespace collide::detail
