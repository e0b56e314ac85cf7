// The slider (prismatic) joint: the rotation block, two rows across the axis that keep anchor B on
// the line through anchor A along a's axis, and the offset along it with its spring, motor and
// limits (Box2D v3's prismatic joint, in 3D). The rows' lever on body a reaches anchor B (rA + d):
// the line is a's, and b's anchor slides along it.
#include "dynamics/joints/joint_rows.h"

namespace collide::detail {

namespace {

struct SliderRows {
  Vec3 axis{0.0f};
  JointRow along;
  JointRow across1;
  JointRow across2;
};

SliderRows sliderRows(const JointFrame& f) {
  SliderRows rows;
  rows.axis = f.frameA * Vec3(1.0f, 0.0f, 0.0f);
  const Vec3 leverA = f.rA + f.d;
  rows.along = linearRow(f, rows.axis, leverA);
  rows.across1 = linearRow(f, f.frameA * Vec3(0.0f, 1.0f, 0.0f), leverA);
  rows.across2 = linearRow(f, f.frameA * Vec3(0.0f, 0.0f, 1.0f), leverA);
  return rows;
}

// The coupling of two rows through the bodies' masses: row i's impulse changes row j's speed by
// K_ij per unit.
float coupling(const JointFrame& f, const JointRow& i, const JointRow& j) {
  return (f.a.inverseMass + f.b.inverseMass) * glm::dot(i.linear, j.linear) +
         glm::dot(i.angularA, f.a.inverseInertia * j.angularA) +
         glm::dot(i.angularB, f.b.inverseInertia * j.angularB);
}

void solveAcrossRows(const JointFrame& f, const SliderRows& rows, const Softness& soft, Vec3& accumulated) {
  const float k11 = coupling(f, rows.across1, rows.across1);
  const float k12 = coupling(f, rows.across1, rows.across2);
  const float k22 = coupling(f, rows.across2, rows.across2);
  const float det = k11 * k22 - k12 * k12;
  if (!(det > 0.0f)) return;
  const float r1 = rowSpeed(f.a, f.b, rows.across1) + soft.biasRate * glm::dot(rows.across1.linear, f.d);
  const float r2 = rowSpeed(f.a, f.b, rows.across2) + soft.biasRate * glm::dot(rows.across2.linear, f.d);
  const float l1 = -soft.massScale * (k22 * r1 - k12 * r2) / det - soft.impulseScale * accumulated.y;
  const float l2 = -soft.massScale * (k11 * r2 - k12 * r1) / det - soft.impulseScale * accumulated.z;
  accumulated.y += l1;
  accumulated.z += l2;
  applyRow(f.a, f.b, rows.across1, l1);
  applyRow(f.a, f.b, rows.across2, l2);
}

}  // namespace

void warmStartSlider(const JointSolverView& view, Joint& joint) {
  std::optional<JointFrame> scratch;
  const JointFrame& f = jointFrame(view, joint, scratch);
  const SliderRows rows = sliderRows(f);
  applyRow(f.a, f.b, rows.along, joint.inTree ? ownAxialImpulse(joint) : axialImpulse(joint));
  if (joint.inTree) return;
  applyAngularImpulse(f.a, f.b, joint.angularImpulse);
  applyRow(f.a, f.b, rows.across1, joint.linearImpulse.y);
  applyRow(f.a, f.b, rows.across2, joint.linearImpulse.z);
}

void solveSlider(const JointSolverView& view, Joint& joint, float h, float rigidHertz, bool useBias) {
  std::optional<JointFrame> scratch;
  const JointFrame& f = jointFrame(view, joint, scratch);
  const SliderRows rows = sliderRows(f);
  const Softness soft = rowSoftness(joint.softness, rigidHertz, h, useBias);
  const float offset = glm::dot(rows.axis, f.d);
  solveSpring(f, rows.along, offset, joint.spring, h, joint.springImpulse);
  solveMotor(f, rows.along, joint.motor, h, joint.motorImpulse);
  solveRowFriction(f, rows.along, joint.friction, h, joint.frictionImpulse.x);
  if (joint.limits.enabled) {
    if (!(joint.treeLimits & kLowerLimitBit))
      solveLowerLimit(f, rows.along, offset, joint.limits.lower, soft, h, joint.lowerImpulse);
    if (!(joint.treeLimits & kUpperLimitBit))
      solveUpperLimit(f, rows.along, offset, joint.limits.upper, soft, h, joint.upperImpulse);
  }
  if (joint.inTree) return;
  solveRotation(f, soft, joint.angularImpulse);
  solveAcrossRows(f, rows, soft, joint.linearImpulse);
}

void equalityRowsSlider(const JointFrame& f, Joint& joint, EqualityRows& rows) {
  const SliderRows slider = sliderRows(f);
  addRotationRows(f, joint, rows);
  rows.add(slider.across1, glm::dot(slider.across1.linear, f.d), &joint.linearImpulse.y);
  rows.add(slider.across2, glm::dot(slider.across2.linear, f.d), &joint.linearImpulse.z);
}

void limitRowsSlider(const JointFrame& f, Joint& joint, EqualityRows& rows, JointAngles&) {
  if (!joint.limits.enabled) return;
  const SliderRows slider = sliderRows(f);
  const float offset = glm::dot(slider.axis, f.d);
  rows.add(slider.along, offset - joint.limits.lower, &joint.lowerImpulse, kLowerLimitBit);
  rows.add(negatedRow(slider.along), joint.limits.upper - offset, &joint.upperImpulse, kUpperLimitBit);
}

}  // namespace collide::detail
