// The rows every joint type is made of (joint_rows.h).
#include "dynamics/joints/joint_rows.h"

#include "dynamics/joint_tree.h"

#include <algorithm>
#include <cmath>

namespace collide::detail {

JointBody jointBody(const JointSolverView& view, std::uint32_t body) {
  JointBody out;
  const std::int32_t j = view.solverOf[body];
  if (j == kNoSolverBody) {
    const BodyState& s = view.storage.states[body];
    out.centerOfMass = s.centerOfMass;
    out.rotation = s.rotation;
    return out;
  }
  SolverBody& b = view.bodies[static_cast<std::size_t>(j)];
  const SolverBodyInfo& info = view.infos[static_cast<std::size_t>(j)];
  const SolverBodyStart& start = view.starts[static_cast<std::size_t>(j)];
  out.centerOfMass = start.centerOfMass + b.deltaPosition;
  out.rotation = b.deltaRotation * start.rotation;
  if (info.faulted) return out;
  out.moving = &b;
  if (info.dynamic) {
    out.solver = &b;
    out.inverseMass = info.inverseMass;
    out.inverseInertia = info.inverseInertiaWorld;
  }
  return out;
}

const JointFrame& jointFrame(const JointSolverView& view, const Joint& joint,
                             std::optional<JointFrame>& scratch) {
  const JointFrame* atPose = view.trees != nullptr ? view.trees->frameAtPose(joint) : nullptr;
  if (atPose != nullptr) return *atPose;
  return scratch.emplace(buildJointFrame(view, joint));
}

const JointAngles* anglesAtPose(const JointSolverView& view, const Joint& joint) {
  return view.trees != nullptr ? view.trees->anglesAtPose(joint) : nullptr;
}

// The anchors are rotated with each body's current rotation, so a turning body carries its anchor
// exactly (Box2D v3 uses the step-start frames and the delta rotation instead; same result).
JointFrame buildJointFrame(const JointSolverView& view, const Joint& joint) {
  JointFrame f;
  f.a = jointBody(view, joint.bodyA);
  f.b = jointBody(view, joint.bodyB);
  f.rA = f.a.rotation * joint.localAnchorA;
  f.rB = f.b.rotation * joint.localAnchorB;
  f.d = (f.b.centerOfMass + f.rB) - (f.a.centerOfMass + f.rA);
  f.frameA = f.a.rotation * joint.localFrameA;
  f.frameB = f.b.rotation * joint.localFrameB;
  return f;
}

Softness rowSoftness(const JointSoftness& softness, float rigidHertz, float h, bool useBias) {
  if (softness.hertz > 0.0f) return makeSoftness(softness.hertz, softness.dampingRatio, h);
  // Box2D v3's rigid joints: a soft constraint at twice the contact stiffness (the contact hertz
  // is capped at a quarter of the substep rate), damping ratio 2. The stiff limit (bias C/h)
  // overshoots in Gauss-Seidel over a chain and pumped energy into a swinging one.
  if (useBias) return makeSoftness(rigidHertz, 2.0f, h);
  return Softness{};  // the relax pass: no bias, the whole mass
}

void applyImpulse(const JointBody& a, const JointBody& b, const Vec3& rA, const Vec3& rB, const Vec3& p) {
  if (a.solver) {
    a.solver->linearVelocity -= a.inverseMass * p;
    a.solver->angularVelocity -= a.inverseInertia * glm::cross(rA, p);
  }
  if (b.solver) {
    b.solver->linearVelocity += b.inverseMass * p;
    b.solver->angularVelocity += b.inverseInertia * glm::cross(rB, p);
  }
}

void applyAngularImpulse(const JointBody& a, const JointBody& b, const Vec3& l) {
  if (a.solver) a.solver->angularVelocity -= a.inverseInertia * l;
  if (b.solver) b.solver->angularVelocity += b.inverseInertia * l;
}

void applyPositionImpulse(const JointBody& a, const JointBody& b, const Vec3& rA, const Vec3& rB,
                          const Vec3& p) {
  if (a.solver) {
    a.solver->deltaPosition -= a.inverseMass * p;
    const Vec3 turn = -(a.inverseInertia * glm::cross(rA, p));
    a.solver->deltaRotation =
        glm::normalize(a.solver->deltaRotation + 0.5f * Quat(0.0f, turn) * a.solver->deltaRotation);
  }
  if (b.solver) {
    b.solver->deltaPosition += b.inverseMass * p;
    const Vec3 turn = b.inverseInertia * glm::cross(rB, p);
    b.solver->deltaRotation =
        glm::normalize(b.solver->deltaRotation + 0.5f * Quat(0.0f, turn) * b.solver->deltaRotation);
  }
}

Mat3 skew(const Vec3& r) { return Mat3(0.0f, r.z, -r.y, -r.z, 0.0f, r.x, r.y, -r.x, 0.0f); }

Mat3 pointInverseMass(const JointBody& a, const JointBody& b, const Vec3& rA, const Vec3& rB) {
  const Mat3 sA = skew(rA);
  const Mat3 sB = skew(rB);
  return Mat3(a.inverseMass + b.inverseMass) - sA * a.inverseInertia * sA - sB * b.inverseInertia * sB;
}

void solvePoint(const JointFrame& f, const Softness& soft, Vec3& accumulated) {
  const Mat3 k = pointInverseMass(f.a, f.b, f.rA, f.rB);
  if (!(glm::determinant(k) > 0.0f)) return;
  const Vec3 cdot = f.b.velocityAt(f.rB) - f.a.velocityAt(f.rA);
  const Vec3 impulse =
      -soft.massScale * (glm::inverse(k) * (cdot + soft.biasRate * f.d)) - soft.impulseScale * accumulated;
  accumulated += impulse;
  applyImpulse(f.a, f.b, f.rA, f.rB, impulse);
}

// qB qA^-1 is the turn from frame A to frame B in the world; its vector part is sin(angle / 2)
// times the axis, so twice it is the rotation vector to first order (the short way round).
Vec3 rotationError(const Quat& frameA, const Quat& frameB) {
  Quat q = frameB * glm::conjugate(frameA);
  if (q.w < 0.0f) q = -q;
  return 2.0f * Vec3(q.x, q.y, q.z);
}

void solveRotation(const JointFrame& f, const Softness& soft, Vec3& accumulated) {
  const Mat3 k = f.a.inverseInertia + f.b.inverseInertia;
  if (!(glm::determinant(k) > 0.0f)) return;
  const Vec3 cdot = f.b.angularVelocity() - f.a.angularVelocity();
  const Vec3 c = rotationError(f.frameA, f.frameB);
  const Vec3 impulse =
      -soft.massScale * (glm::inverse(k) * (cdot + soft.biasRate * c)) - soft.impulseScale * accumulated;
  accumulated += impulse;
  applyAngularImpulse(f.a, f.b, impulse);
}

void addPointRows(const JointFrame& f, Joint& joint, EqualityRows& rows) {
  for (int i = 0; i < 3; ++i) {
    Vec3 axis(0.0f);
    axis[i] = 1.0f;
    rows.add(linearTreeRow(f, axis, f.rA), f.d[i], &joint.linearImpulse[i]);
  }
}

void addRotationRows(const JointFrame& f, Joint& joint, EqualityRows& rows) {
  const Vec3 error = rotationError(f.frameA, f.frameB);
  for (int i = 0; i < 3; ++i) {
    Vec3 axis(0.0f);
    axis[i] = 1.0f;
    rows.add(angularTreeRow(axis), error[i], &joint.angularImpulse[i]);
  }
}

JointRow negatedRow(const JointRow& row) { return {-row.linear, -row.angularA, -row.angularB, row.mass}; }

JointRow makeRow(const JointBody& a, const JointBody& b, const Vec3& linear, const Vec3& angularA,
                 const Vec3& angularB) {
  JointRow row{linear, angularA, angularB, 0.0f};
  const float k = (a.inverseMass + b.inverseMass) * glm::dot(linear, linear) +
                  glm::dot(angularA, a.inverseInertia * angularA) +
                  glm::dot(angularB, b.inverseInertia * angularB);
  row.mass = k > 0.0f ? 1.0f / k : 0.0f;
  return row;
}

JointRow linearRow(const JointFrame& f, const Vec3& axis, const Vec3& leverA) {
  return makeRow(f.a, f.b, axis, glm::cross(leverA, axis), glm::cross(f.rB, axis));
}

JointRow angularRow(const JointBody& a, const JointBody& b, const Vec3& axis) {
  return makeRow(a, b, Vec3(0.0f), axis, axis);
}

JointRow linearTreeRow(const JointFrame& f, const Vec3& axis, const Vec3& leverA) {
  return {axis, glm::cross(leverA, axis), glm::cross(f.rB, axis), 0.0f};
}

JointRow angularTreeRow(const Vec3& axis) { return {Vec3(0.0f), axis, axis, 0.0f}; }

float rowSpeed(const JointBody& a, const JointBody& b, const JointRow& row) {
  return glm::dot(row.linear, b.linearVelocity() - a.linearVelocity()) +
         glm::dot(row.angularB, b.angularVelocity()) - glm::dot(row.angularA, a.angularVelocity());
}

void applyRow(const JointBody& a, const JointBody& b, const JointRow& row, float lambda) {
  if (a.solver) {
    a.solver->linearVelocity -= (a.inverseMass * lambda) * row.linear;
    a.solver->angularVelocity -= a.inverseInertia * (lambda * row.angularA);
  }
  if (b.solver) {
    b.solver->linearVelocity += (b.inverseMass * lambda) * row.linear;
    b.solver->angularVelocity += b.inverseInertia * (lambda * row.angularB);
  }
}

void turnSolverBody(SolverBody& body, const Vec3& turn) {
  body.deltaRotation = glm::normalize(body.deltaRotation + 0.5f * Quat(0.0f, turn) * body.deltaRotation);
}

void solveSpring(const JointFrame& f, const JointRow& row, float position, const JointSpring& spring, float h,
                 float& accumulated) {
  if (!spring.enabled || spring.hertz <= 0.0f || row.mass == 0.0f) return;
  const Softness soft = makeSoftness(spring.hertz, spring.dampingRatio, h);
  const float c = position - spring.target;
  const float impulse = -row.mass * soft.massScale * (rowSpeed(f.a, f.b, row) + soft.biasRate * c) -
                        soft.impulseScale * accumulated;
  accumulated += impulse;
  applyRow(f.a, f.b, row, impulse);
}

void solveMotor(const JointFrame& f, const JointRow& row, const JointMotor& motor, float h,
                float& accumulated) {
  if (!motor.enabled || row.mass == 0.0f) return;
  const float impulse = -row.mass * (rowSpeed(f.a, f.b, row) - motor.speed);
  const float old = accumulated;
  const float most = h * motor.maxForce;
  accumulated = std::clamp(old + impulse, -most, most);
  applyRow(f.a, f.b, row, accumulated - old);
}

void solveRowFriction(const JointFrame& f, const JointRow& row, float friction, float h, float& accumulated) {
  if (!(friction > 0.0f) || row.mass == 0.0f) return;
  solveMotor(f, row, JointMotor{true, 0.0f, friction}, h, accumulated);
}

void solveAngularFriction(const JointFrame& f, float friction, float h, Vec3& accumulated) {
  if (!(friction > 0.0f)) return;
  const Mat3 k = f.a.inverseInertia + f.b.inverseInertia;
  if (!(glm::determinant(k) > 0.0f)) return;
  const Vec3 impulse = -(glm::inverse(k) * (f.b.angularVelocity() - f.a.angularVelocity()));
  const Vec3 old = accumulated;
  accumulated += impulse;
  const float most = h * friction;
  const float length = glm::length(accumulated);
  if (length > most) accumulated *= most / length;
  applyAngularImpulse(f.a, f.b, accumulated - old);
}

namespace {

// One side of a limit: c >= 0 is allowed, c' its rate; returns the impulse to apply along +c.
float limitImpulse(float c, float cdot, float mass, const Softness& soft, float h, float& accumulated) {
  float bias = 0.0f;
  float massScale = 1.0f;
  float impulseScale = 0.0f;
  if (c > 0.0f) {
    bias = c / h;  // speculative: only the approach that would cross the limit this substep
  } else {
    bias = soft.biasRate * c;
    massScale = soft.massScale;
    impulseScale = soft.impulseScale;
  }
  const float impulse = -mass * massScale * (cdot + bias) - impulseScale * accumulated;
  const float updated = std::max(accumulated + impulse, 0.0f);
  const float applied = updated - accumulated;
  accumulated = updated;
  return applied;
}

}  // namespace

void solveLowerLimit(const JointFrame& f, const JointRow& row, float position, float lower,
                     const Softness& soft, float h, float& accumulated) {
  if (row.mass == 0.0f) return;
  const float applied =
      limitImpulse(position - lower, rowSpeed(f.a, f.b, row), row.mass, soft, h, accumulated);
  applyRow(f.a, f.b, row, applied);
}

void solveUpperLimit(const JointFrame& f, const JointRow& row, float position, float upper,
                     const Softness& soft, float h, float& accumulated) {
  if (row.mass == 0.0f) return;
  const float applied =
      limitImpulse(upper - position, -rowSpeed(f.a, f.b, row), row.mass, soft, h, accumulated);
  applyRow(f.a, f.b, row, -applied);
}

float axialImpulse(const Joint& joint) {
  return joint.springImpulse + joint.motorImpulse + joint.frictionImpulse.x + joint.lowerImpulse -
         joint.upperImpulse;
}

// The axial impulse the joint's own warm start applies: without the limits its tree applies.
float ownAxialImpulse(const Joint& joint) {
  float impulse = joint.springImpulse + joint.motorImpulse + joint.frictionImpulse.x;
  if (!(joint.treeLimits & kLowerLimitBit)) impulse += joint.lowerImpulse;
  if (!(joint.treeLimits & kUpperLimitBit)) impulse -= joint.upperImpulse;
  return impulse;
}

}  // namespace collide::detail
