// The fixed (weld) joint: the point block and the rotation block solved together as one 6x6 block.
// Solved one after the other (Box2D v3's weld joint: angular first), the two blocks undo each other
// where the anchor is far from a body's centre: the point rows then turn the body through their
// lever, the rotation rows move the anchor, and a rotor of blades welded to a light hub spun itself
// apart. As one block the six rows are met at once; each keeps its own softness (linear for the
// point rows, angular for the rotation rows).
#include "dynamics/joints/joint_rows.h"

#include <array>
#include <cmath>

namespace collide::detail {

namespace {

using Vector6 = std::array<float, 6>;
using Matrix6 = std::array<std::array<float, 6>, 6>;

// Solves k x = b for the symmetric positive definite k (Cholesky, k = L L^T); false if it is not.
bool solveSymmetric(Matrix6 k, Vector6& x) {
  for (int j = 0; j < 6; ++j) {
    float d = k[j][j];
    for (int p = 0; p < j; ++p) d -= k[j][p] * k[j][p];
    if (!(d > 0.0f)) return false;
    k[j][j] = std::sqrt(d);
    for (int i = j + 1; i < 6; ++i) {
      float s = k[i][j];
      for (int p = 0; p < j; ++p) s -= k[i][p] * k[j][p];
      k[i][j] = s / k[j][j];
    }
  }
  for (int i = 0; i < 6; ++i) {  // L y = b
    for (int p = 0; p < i; ++p) x[i] -= k[i][p] * x[p];
    x[i] /= k[i][i];
  }
  for (int i = 5; i >= 0; --i) {  // L^T x = y
    for (int p = i + 1; p < 6; ++p) x[i] -= k[p][i] * x[p];
    x[i] /= k[i][i];
  }
  return true;
}

// The block's inverse effective mass J M^-1 J^T for the rows (v_anchorB - v_anchorA, wB - wA):
// [[Kpp, Kpr], [Kpr^T, Krr]] with Kpp the point block's, Krr = IA^-1 + IB^-1 and
// Kpr = IA^-1-weighted levers: -[rA]x IA^-1 - [rB]x IB^-1 (an angular impulse L turns each body,
// which moves its anchor by omega x r).
Matrix6 weldInverseMass(const JointFrame& f) {
  const Mat3 kpp = pointInverseMass(f.a, f.b, f.rA, f.rB);
  const Mat3 krr = f.a.inverseInertia + f.b.inverseInertia;
  const Mat3 kpr = -(skew(f.rA) * f.a.inverseInertia) - skew(f.rB) * f.b.inverseInertia;
  Matrix6 k{};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      // glm is column-major: m[column][row].
      k[i][j] = kpp[j][i];
      k[3 + i][3 + j] = krr[j][i];
      k[i][3 + j] = kpr[j][i];
      k[3 + j][i] = kpr[j][i];
    }
  }
  return k;
}

}  // namespace

void warmStartFixed(const JointSolverView& view, Joint& joint) {
  if (joint.inTree) return;
  std::optional<JointFrame> scratch;
  const JointFrame& f = jointFrame(view, joint, scratch);
  applyAngularImpulse(f.a, f.b, joint.angularImpulse);
  applyImpulse(f.a, f.b, f.rA, f.rB, joint.linearImpulse);
}

void solveFixed(const JointSolverView& view, Joint& joint, float h, float rigidHertz, bool useBias) {
  if (joint.inTree) return;
  std::optional<JointFrame> scratch;
  const JointFrame& f = jointFrame(view, joint, scratch);
  const Softness linear = rowSoftness(joint.softness, rigidHertz, h, useBias);
  const Softness angular = rowSoftness(joint.angularSoftness, rigidHertz, h, useBias);
  const Vec3 pointSpeed = f.b.velocityAt(f.rB) - f.a.velocityAt(f.rA);
  const Vec3 turnSpeed = f.b.angularVelocity() - f.a.angularVelocity();
  const Vec3 pointRhs = pointSpeed + linear.biasRate * f.d;
  const Vec3 turnRhs = turnSpeed + angular.biasRate * rotationError(f.frameA, f.frameB);
  Vector6 x{pointRhs.x, pointRhs.y, pointRhs.z, turnRhs.x, turnRhs.y, turnRhs.z};
  if (!solveSymmetric(weldInverseMass(f), x)) return;
  const Vec3 p = -linear.massScale * Vec3(x[0], x[1], x[2]) - linear.impulseScale * joint.linearImpulse;
  const Vec3 l = -angular.massScale * Vec3(x[3], x[4], x[5]) - angular.impulseScale * joint.angularImpulse;
  joint.linearImpulse += p;
  joint.angularImpulse += l;
  applyImpulse(f.a, f.b, f.rA, f.rB, p);
  applyAngularImpulse(f.a, f.b, l);
}

void equalityRowsFixed(const JointFrame& f, Joint& joint, EqualityRows& rows) {
  addPointRows(f, joint, rows);
  addRotationRows(f, joint, rows);
}

}  // namespace collide::detail
