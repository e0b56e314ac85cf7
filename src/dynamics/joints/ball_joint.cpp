// The ball (spherical) joint: the point block alone, C = pB - pA.
#include "dynamics/joints/joint_rows.h"

namespace collide::detail {

void warmStartBall(const JointSolverView& view, Joint& joint) {
  const JointFrame f = jointFrame(view, joint);
  applyImpulse(f.a, f.b, f.rA, f.rB, joint.linearImpulse);
}

void solveBall(const JointSolverView& view, Joint& joint, float h, float rigidHertz, bool useBias) {
  const JointFrame f = jointFrame(view, joint);
  solvePoint(f, rowSoftness(joint.softness, rigidHertz, h, useBias), joint.linearImpulse);
}

}  // namespace collide::detail
