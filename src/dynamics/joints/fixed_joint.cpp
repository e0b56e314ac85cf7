// The fixed (weld) joint: the rotation block (frame B's rotation relative to frame A held at zero)
// and the point block, each with its own softness (Box2D v3's weld joint: angular first).
#include "dynamics/joints/joint_rows.h"

namespace collide::detail {

void warmStartFixed(const JointSolverView& view, Joint& joint) {
  const JointFrame f = jointFrame(view, joint);
  applyAngularImpulse(f.a, f.b, joint.angularImpulse);
  applyImpulse(f.a, f.b, f.rA, f.rB, joint.linearImpulse);
}

void solveFixed(const JointSolverView& view, Joint& joint, float h, float rigidHertz, bool useBias) {
  const JointFrame f = jointFrame(view, joint);
  solveRotation(f, rowSoftness(joint.angularSoftness, rigidHertz, h, useBias), joint.angularImpulse);
  solvePoint(f, rowSoftness(joint.softness, rigidHertz, h, useBias), joint.linearImpulse);
}

}  // namespace collide::detail
