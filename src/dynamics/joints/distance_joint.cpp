// The distance joint: C = |pB - pA| - length along the unit axis n from anchor A to anchor B.
// Rigid, it is one row (a rod). A spring (hertz, or the XPBD compliance of Macklin et al. 2016:
// stiffness 1/compliance on the row's effective mass m gives omega^2 = 1 / (compliance m)) makes the
// row soft in both passes: a physical force, not an error correction. Limits are one-sided rows at
// [lower, upper] of the length; with limits and no spring the length is free between them (a rope).
#include "dynamics/joints/joint_rows.h"

#include <cmath>

namespace collide::detail {

namespace {

bool hasSpring(const Joint& joint) {
  return joint.compliance > 0.0f || (joint.spring.enabled && joint.spring.hertz > 0.0f);
}
// The length row: a rigid rod, or a spring; a rope (limits, no spring) has none.
bool hasLengthRow(const Joint& joint) { return hasSpring(joint) || !joint.limits.enabled; }

struct Axis {
  Vec3 n{0.0f};
  float distance = 0.0f;
};

// Coincident anchors have no direction: the last one is kept (the constraint is then C = -length).
Axis axisOf(const JointFrame& f, Joint& joint) {
  const float distance = glm::length(f.d);
  if (distance > 1e-6f) joint.axis = f.d / distance;
  return {joint.axis, distance};
}

// The length row's inverse effective mass along the unit axis n.
float axialInverseMass(const JointFrame& f, const Vec3& n) {
  const Vec3 rnA = glm::cross(f.rA, n);
  const Vec3 rnB = glm::cross(f.rB, n);
  return f.a.inverseMass + f.b.inverseMass + glm::dot(rnA, f.a.inverseInertia * rnA) +
         glm::dot(rnB, f.b.inverseInertia * rnB);
}

}  // namespace

void warmStartDistance(const JointSolverView& view, Joint& joint) {
  std::optional<JointFrame> scratch;
  const JointFrame& f = jointFrame(view, joint, scratch);
  const Axis axis = axisOf(f, joint);
  applyImpulse(f.a, f.b, f.rA, f.rB, (joint.impulse + joint.lowerImpulse - joint.upperImpulse) * axis.n);
}

void solveDistance(const JointSolverView& view, Joint& joint, float h, float rigidHertz, bool useBias) {
  std::optional<JointFrame> scratch;
  const JointFrame& f = jointFrame(view, joint, scratch);
  const Axis axis = axisOf(f, joint);
  const float k = axialInverseMass(f, axis.n);
  if (k <= 0.0f) return;
  if (hasLengthRow(joint)) {
    Softness soft;
    if (joint.spring.enabled && joint.spring.hertz > 0.0f) {
      soft = makeSoftness(joint.spring.hertz, joint.spring.dampingRatio, h);
    } else if (joint.compliance > 0.0f) {
      const float hertz = std::sqrt(k / joint.compliance) / (2.0f * kPi);
      soft = makeSoftness(hertz, joint.dampingRatio, h);
    } else {
      soft = rowSoftness(joint.softness, rigidHertz, h, useBias);
    }
    const float c = axis.distance - joint.length;
    const float cdot = glm::dot(f.b.velocityAt(f.rB) - f.a.velocityAt(f.rA), axis.n);
    const float impulse =
        -(1.0f / k) * soft.massScale * (cdot + soft.biasRate * c) - soft.impulseScale * joint.impulse;
    joint.impulse += impulse;
    applyImpulse(f.a, f.b, f.rA, f.rB, impulse * axis.n);
  }
  if (joint.limits.enabled) {
    const JointRow row = linearRow(f, axis.n, f.rA);
    const Softness soft = rowSoftness(joint.softness, rigidHertz, h, useBias);
    solveLowerLimit(f, row, axis.distance, joint.limits.lower, soft, h, joint.lowerImpulse);
    solveUpperLimit(f, row, axis.distance, joint.limits.upper, soft, h, joint.upperImpulse);
  }
}

// A rigid rod's length, or a rigid limit, off by more than kJointLengthSlop of it: the excess
// removed along the axis, split by the effective masses.
bool projectDistance(const JointSolverView& view, Joint& joint) {
  const bool rod = !hasSpring(joint) && !joint.limits.enabled;
  if (joint.softness.hertz > 0.0f || (!rod && !joint.limits.enabled)) return false;
  std::optional<JointFrame> scratch;
  const JointFrame& f = jointFrame(view, joint, scratch);
  const Axis axis = axisOf(f, joint);
  float excess = 0.0f;
  if (rod) {
    const float allowed = kJointLengthSlop * joint.length;
    const float c = axis.distance - joint.length;
    if (!(std::abs(c) > allowed)) return false;
    excess = c > 0.0f ? c - allowed : c + allowed;
  } else {
    const float allowedUpper = kJointLengthSlop * joint.limits.upper;
    const float allowedLower = kJointLengthSlop * joint.limits.lower;
    if (axis.distance > joint.limits.upper + allowedUpper) {
      excess = axis.distance - joint.limits.upper - allowedUpper;
    } else if (axis.distance < joint.limits.lower - allowedLower) {
      excess = axis.distance - joint.limits.lower + allowedLower;
    } else {
      return false;
    }
  }
  const float k = axialInverseMass(f, axis.n);
  if (k <= 0.0f) return false;
  applyPositionImpulse(f.a, f.b, f.rA, f.rB, (-excess / k) * axis.n);
  return true;
}

}  // namespace collide::detail
