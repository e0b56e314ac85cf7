// The hinge (revolute) joint: the point block, two rotation rows that keep b's hinge axis on a's,
// and the angle about the axis with its spring, motor and limits (Box2D v3's revolute joint, in 3D).
//
// The axis rows: a is the hinge axis as body a carries it, b as body b does, p1 and p2 span the
// plane across a. For a small misalignment, a x b is the rotation from a to b, and its rate is the
// bodies' relative angular velocity across the axis, so C = (p1 . (a x b), p2 . (a x b)) with
// Jacobian rows p1 and p2 on the relative angular velocity, solved as a 2x2 block.
#include "dynamics/joints/joint_rows.h"

namespace collide::detail {

namespace {

struct HingeAxes {
  Vec3 axis{0.0f};
  Vec3 across1{0.0f};
  Vec3 across2{0.0f};
  Vec3 axisB{0.0f};
};

HingeAxes hingeAxes(const JointFrame& f) {
  return {f.frameA * Vec3(1.0f, 0.0f, 0.0f), f.frameA * Vec3(0.0f, 1.0f, 0.0f),
          f.frameA * Vec3(0.0f, 0.0f, 1.0f), f.frameB * Vec3(1.0f, 0.0f, 0.0f)};
}

void solveAxisRows(const JointFrame& f, const HingeAxes& axes, const Softness& soft, Vec3& accumulated) {
  const Mat3 m = f.a.inverseInertia + f.b.inverseInertia;
  const Vec3 m1 = m * axes.across1;
  const Vec3 m2 = m * axes.across2;
  const float k11 = glm::dot(axes.across1, m1);
  const float k12 = glm::dot(axes.across1, m2);
  const float k22 = glm::dot(axes.across2, m2);
  const float det = k11 * k22 - k12 * k12;
  if (!(det > 0.0f)) return;
  const Vec3 w = f.b.angularVelocity() - f.a.angularVelocity();
  const Vec3 misalignment = glm::cross(axes.axis, axes.axisB);
  const float r1 = glm::dot(axes.across1, w) + soft.biasRate * glm::dot(axes.across1, misalignment);
  const float r2 = glm::dot(axes.across2, w) + soft.biasRate * glm::dot(axes.across2, misalignment);
  const float l1 = -soft.massScale * (k22 * r1 - k12 * r2) / det - soft.impulseScale * accumulated.y;
  const float l2 = -soft.massScale * (k11 * r2 - k12 * r1) / det - soft.impulseScale * accumulated.z;
  accumulated.y += l1;
  accumulated.z += l2;
  applyAngularImpulse(f.a, f.b, l1 * axes.across1 + l2 * axes.across2);
}

}  // namespace

void warmStartHinge(const JointSolverView& view, Joint& joint) {
  std::optional<JointFrame> scratch;
  const JointFrame& f = jointFrame(view, joint, scratch);
  const HingeAxes axes = hingeAxes(f);
  if (joint.inTree) {
    applyAngularImpulse(f.a, f.b, ownAxialImpulse(joint) * axes.axis);
    return;
  }
  applyAngularImpulse(f.a, f.b,
                      joint.angularImpulse.y * axes.across1 + joint.angularImpulse.z * axes.across2 +
                          axialImpulse(joint) * axes.axis);
  applyImpulse(f.a, f.b, f.rA, f.rB, joint.linearImpulse);
}

void solveHinge(const JointSolverView& view, Joint& joint, float h, float rigidHertz, bool useBias) {
  std::optional<JointFrame> scratch;
  const JointFrame& f = jointFrame(view, joint, scratch);
  const HingeAxes axes = hingeAxes(f);
  const Softness soft = rowSoftness(joint.softness, rigidHertz, h, useBias);
  const JointRow turn = angularRow(f.a, f.b, axes.axis);
  const JointAngles* measured = anglesAtPose(view, joint);
  const float angle = measured != nullptr ? measured->twist : twistAngle(glm::conjugate(f.frameA) * f.frameB);
  solveSpring(f, turn, angle, joint.spring, h, joint.springImpulse);
  solveMotor(f, turn, joint.motor, h, joint.motorImpulse);
  solveRowFriction(f, turn, joint.friction, h, joint.frictionImpulse.x);
  if (joint.limits.enabled) {
    if (!(joint.treeLimits & kLowerLimitBit))
      solveLowerLimit(f, turn, angle, joint.limits.lower, soft, h, joint.lowerImpulse);
    if (!(joint.treeLimits & kUpperLimitBit))
      solveUpperLimit(f, turn, angle, joint.limits.upper, soft, h, joint.upperImpulse);
  }
  if (joint.inTree) return;
  solveAxisRows(f, axes, soft, joint.angularImpulse);
  solvePoint(f, soft, joint.linearImpulse);
}

void equalityRowsHinge(const JointFrame& f, Joint& joint, EqualityRows& rows) {
  const HingeAxes axes = hingeAxes(f);
  const Vec3 misalignment = glm::cross(axes.axis, axes.axisB);
  rows.add(angularTreeRow(axes.across1), glm::dot(axes.across1, misalignment), &joint.angularImpulse.y);
  rows.add(angularTreeRow(axes.across2), glm::dot(axes.across2, misalignment), &joint.angularImpulse.z);
  addPointRows(f, joint, rows);
}

void limitRowsHinge(const JointFrame& f, Joint& joint, EqualityRows& rows, JointAngles& angles) {
  // Measured with or without limits: the Gauss-Seidel pass's spring and motor read it too.
  angles.twist = twistAngle(glm::conjugate(f.frameA) * f.frameB);
  if (!joint.limits.enabled) return;
  const JointRow turn = angularRow(f.a, f.b, hingeAxes(f).axis);
  const float angle = angles.twist;
  rows.add(turn, angle - joint.limits.lower, &joint.lowerImpulse, kLowerLimitBit);
  rows.add(negatedRow(turn), joint.limits.upper - angle, &joint.upperImpulse, kUpperLimitBit);
}

}  // namespace collide::detail
