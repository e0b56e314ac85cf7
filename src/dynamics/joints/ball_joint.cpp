// The ball (spherical) joint: the point block, C = pB - pA, and its friction against turning.
#include "dynamics/joints/joint_rows.h"

namespace collide::detail {

void warmStartBall(const JointSolverView& view, Joint& joint) {
  // In a tree with no friction impulse there is nothing to apply here (a net of 10,000 of them).
  if (joint.inTree && joint.frictionImpulse == Vec3(0.0f)) return;
  const JointFrame f = jointFrame(view, joint);
  applyAngularImpulse(f.a, f.b, joint.frictionImpulse);
  if (!joint.inTree) applyImpulse(f.a, f.b, f.rA, f.rB, joint.linearImpulse);
}

void solveBall(const JointSolverView& view, Joint& joint, float h, float rigidHertz, bool useBias) {
  if (joint.inTree && !(joint.friction > 0.0f)) return;
  const JointFrame f = jointFrame(view, joint);
  solveAngularFriction(f, joint.friction, h, joint.frictionImpulse);
  if (joint.inTree) return;
  solvePoint(f, rowSoftness(joint.softness, rigidHertz, h, useBias), joint.linearImpulse);
}

void equalityRowsBall(const JointFrame& f, Joint& joint, EqualityRows& rows) { addPointRows(f, joint, rows); }

}  // namespace collide::detail
