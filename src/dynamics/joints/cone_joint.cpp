// The cone (swing-twist) joint: the point block, a swing limit that keeps b's axis within a cone
// about a's, and twist limits about the axis (Jolt's SwingTwistConstraint and Box2D v3's 3D
// spherical joint are the models; the rows are our own).
//
// Swing: the angle phi between a's axis a and b's axis b. Turning b about n = (a x b) / |a x b|
// opens it, so the limit's row is the relative rotation about n, C = swingLimit - phi >= 0.
// Twist: the turn of frame B relative to frame A about the axis (the twist of the swing-twist
// split), measured about the mean of the two axes, where a twist rate does not change the swing.
#include "dynamics/joints/joint_rows.h"

#include <cmath>

namespace collide::detail {

namespace {

// The swing axis is zero where the axes coincide or the cone is the whole sphere, the twist axis
// where they are opposite. withAngles false: the axes alone, for the warm start, which applies
// impulses along them and needs no angle (two arc tangents a joint and substep fewer).
JointAngles coneRows(const JointFrame& f, const Joint& joint, bool withAngles = true) {
  JointAngles rows;
  const Vec3 a = f.frameA * Vec3(1.0f, 0.0f, 0.0f);
  const Vec3 b = f.frameB * Vec3(1.0f, 0.0f, 0.0f);
  const Vec3 s = glm::cross(a, b);
  const float sine = glm::length(s);
  if (withAngles) rows.swing = std::atan2(sine, glm::dot(a, b));
  if (joint.swingLimit < kPi && sine > 1e-6f) rows.swingAxis = s / sine;
  const Vec3 mean = a + b;
  const float meanLength = glm::length(mean);
  if (joint.limits.enabled && meanLength > 1e-6f) {
    rows.twistAxis = mean / meanLength;
    if (withAngles) rows.twist = twistAngle(glm::conjugate(f.frameA) * f.frameB);
  }
  return rows;
}

}  // namespace

void warmStartCone(const JointSolverView& view, Joint& joint) {
  std::optional<JointFrame> scratch;
  const JointFrame& f = jointFrame(view, joint, scratch);
  const JointAngles* measured = anglesAtPose(view, joint);
  const JointAngles rows = measured != nullptr ? *measured : coneRows(f, joint, false);
  // The swing limit is an upper limit on phi: its impulse turns b back, about -n.
  const bool treeSwing = joint.treeLimits & kSwingLimitBit;
  const float lower = joint.treeLimits & kLowerLimitBit ? 0.0f : joint.lowerImpulse;
  const float upper = joint.treeLimits & kUpperLimitBit ? 0.0f : joint.upperImpulse;
  applyAngularImpulse(f.a, f.b,
                      -(treeSwing ? 0.0f : joint.swingImpulse) * rows.swingAxis +
                          (lower - upper) * rows.twistAxis + joint.frictionImpulse);
  if (!joint.inTree) applyImpulse(f.a, f.b, f.rA, f.rB, joint.linearImpulse);
}

void solveCone(const JointSolverView& view, Joint& joint, float h, float rigidHertz, bool useBias) {
  std::optional<JointFrame> scratch;
  const JointFrame& f = jointFrame(view, joint, scratch);
  const JointAngles* measured = anglesAtPose(view, joint);
  const JointAngles rows = measured != nullptr ? *measured : coneRows(f, joint);
  const Softness soft = rowSoftness(joint.softness, rigidHertz, h, useBias);
  solveAngularFriction(f, joint.friction, h, joint.frictionImpulse);
  if (rows.swingAxis != Vec3(0.0f)) {
    const JointRow row = angularRow(f.a, f.b, rows.swingAxis);
    if (!(joint.treeLimits & kSwingLimitBit))
      solveUpperLimit(f, row, rows.swing, joint.swingLimit, soft, h, joint.swingImpulse);
  } else {
    joint.swingImpulse = 0.0f;
  }
  if (rows.twistAxis != Vec3(0.0f)) {
    const JointRow row = angularRow(f.a, f.b, rows.twistAxis);
    if (!(joint.treeLimits & kLowerLimitBit))
      solveLowerLimit(f, row, rows.twist, joint.limits.lower, soft, h, joint.lowerImpulse);
    if (!(joint.treeLimits & kUpperLimitBit))
      solveUpperLimit(f, row, rows.twist, joint.limits.upper, soft, h, joint.upperImpulse);
  } else {
    joint.lowerImpulse = joint.upperImpulse = 0.0f;
  }
  if (!joint.inTree) solvePoint(f, soft, joint.linearImpulse);
}

void equalityRowsCone(const JointFrame& f, Joint& joint, EqualityRows& rows) { addPointRows(f, joint, rows); }

void limitRowsCone(const JointFrame& f, Joint& joint, EqualityRows& rows, JointAngles& angles) {
  angles = coneRows(f, joint);
  const JointAngles& cone = angles;
  if (cone.swingAxis != Vec3(0.0f)) {
    const JointRow row = angularRow(f.a, f.b, cone.swingAxis);
    rows.add(negatedRow(row), joint.swingLimit - cone.swing, &joint.swingImpulse, kSwingLimitBit);
  }
  if (cone.twistAxis != Vec3(0.0f)) {
    const JointRow row = angularRow(f.a, f.b, cone.twistAxis);
    rows.add(row, cone.twist - joint.limits.lower, &joint.lowerImpulse, kLowerLimitBit);
    rows.add(negatedRow(row), joint.limits.upper - cone.twist, &joint.upperImpulse, kUpperLimitBit);
  }
}

}  // namespace collide::detail
