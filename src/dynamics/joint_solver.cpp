// The joints of the soft step (joint_solver.h): distance and ball.
#include "dynamics/joint_solver.h"

#include "dynamics/contact_solver.h"

#include <algorithm>
#include <cmath>

namespace collide::detail {

namespace {

// One end of a joint: the body's current pose, velocities and masses (zero for a body the solver
// does not move).
struct JointBody {
  Vec3 centerOfMass{0.0f};
  Quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
  SolverBody* solver = nullptr;
  float inverseMass = 0.0f;
  Mat3 inverseInertia{0.0f};
};

JointBody jointBody(const JointSolverView& view, std::uint32_t body) {
  JointBody out;
  const BodyState& s = view.storage.states[body];
  const std::int32_t j = view.solverOf[body];
  if (j == kNoSolverBody) {
    out.centerOfMass = s.centerOfMass;
    out.rotation = s.rotation;
    return out;
  }
  SolverBody& b = view.bodies[static_cast<std::size_t>(j)];
  const SolverBodyInfo& info = view.infos[static_cast<std::size_t>(j)];
  out.centerOfMass = s.centerOfMass0 + b.deltaPosition;
  out.rotation = b.deltaRotation * s.rotation0;
  if (info.dynamic && !info.faulted) {
    out.solver = &b;
    out.inverseMass = info.inverseMass;
    out.inverseInertia = info.inverseInertiaWorld;
  }
  return out;
}

Vec3 linearVelocity(const JointSolverView& view, std::uint32_t body) {
  const std::int32_t j = view.solverOf[body];
  return j == kNoSolverBody ? Vec3(0.0f) : view.bodies[static_cast<std::size_t>(j)].linearVelocity;
}
Vec3 angularVelocity(const JointSolverView& view, std::uint32_t body) {
  const std::int32_t j = view.solverOf[body];
  return j == kNoSolverBody ? Vec3(0.0f) : view.bodies[static_cast<std::size_t>(j)].angularVelocity;
}

// The velocity of anchor B relative to anchor A (offsets rA, rB from the centres of mass).
Vec3 relativeAnchorVelocity(const JointSolverView& view, const Joint& joint, const Vec3& rA, const Vec3& rB) {
  const Vec3 va = linearVelocity(view, joint.bodyA) + glm::cross(angularVelocity(view, joint.bodyA), rA);
  const Vec3 vb = linearVelocity(view, joint.bodyB) + glm::cross(angularVelocity(view, joint.bodyB), rB);
  return vb - va;
}

struct JointFrame {
  Vec3 rA{0.0f};  // world offsets from the centres of mass to the anchors, at the current pose
  Vec3 rB{0.0f};
  Vec3 axis{0.0f};
  float distance = 0.0f;
};

// The anchors are rotated with each body's current rotation, so a turning body carries its anchor
// exactly (Box2D v3 uses the step-start frames and the delta rotation instead; same result).
JointFrame frameOf(const JointBody& a, const JointBody& b, Joint& joint) {
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

// The impulse p on B at its anchor (rB from its centre), -p on A at its anchor.
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

void applyAxisImpulse(const JointBody& a, const JointBody& b, const JointFrame& f, float impulse) {
  applyImpulse(a, b, f.rA, f.rB, impulse * f.axis);
}

// The positional impulse p (kg m) on B at its anchor, -p on A: each body moved and turned by it as
// its masses say (non-linear Gauss-Seidel on positions).
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

// The cross-product matrix: skew(r) v = r x v.
Mat3 skew(const Vec3& r) { return Mat3(0.0f, r.z, -r.y, -r.z, 0.0f, r.x, r.y, -r.x, 0.0f); }

// The effective mass matrix of a point constraint between the anchors (its inverse, K): an impulse
// P on B at rB and -P on A at rA changes the anchors' relative velocity by K P, with
// K = (mA^-1 + mB^-1) I - [rA]x IA^-1 [rA]x - [rB]x IB^-1 [rB]x (symmetric, positive definite
// while one body moves).
Mat3 pointInverseMass(const JointBody& a, const JointBody& b, const Vec3& rA, const Vec3& rB) {
  const Mat3 sA = skew(rA);
  const Mat3 sB = skew(rB);
  return Mat3(a.inverseMass + b.inverseMass) - sA * a.inverseInertia * sA - sB * b.inverseInertia * sB;
}

struct BallFrame {
  Vec3 rA{0.0f};
  Vec3 rB{0.0f};
  Vec3 gap{0.0f};  // anchor B minus anchor A: C
};

BallFrame ballFrameOf(const JointBody& a, const JointBody& b, const Joint& joint) {
  BallFrame f;
  f.rA = a.rotation * joint.localAnchorA;
  f.rB = b.rotation * joint.localAnchorB;
  f.gap = (b.centerOfMass + f.rB) - (a.centerOfMass + f.rA);
  return f;
}

bool isAwakeDynamic(const BodyRecord& r) { return r.alive && r.type == BodyType::Dynamic && r.awake; }

}  // namespace

void prepareJoints(const JointSolverView& view, std::vector<Joint>& joints) {
  for (Joint& joint : joints) {
    const BodyRecord& a = view.storage.records[joint.bodyA];
    const BodyRecord& b = view.storage.records[joint.bodyB];
    // A disabled body takes no part in the step: its constraints rest with it.
    joint.active = joint.alive && a.enabled && b.enabled && (isAwakeDynamic(a) || isAwakeDynamic(b));
  }
}

void warmStartJoints(const JointSolverView& view, std::vector<Joint>& joints) {
  for (Joint& joint : joints) {
    if (!joint.active) continue;
    const JointBody a = jointBody(view, joint.bodyA);
    const JointBody b = jointBody(view, joint.bodyB);
    switch (joint.type) {
      case JointType::Distance:
        applyAxisImpulse(a, b, frameOf(a, b, joint), joint.impulse);
        break;
      case JointType::Ball: {
        const BallFrame f = ballFrameOf(a, b, joint);
        applyImpulse(a, b, f.rA, f.rB, joint.pointImpulse);
        break;
      }
    }
  }
}

namespace {

void solveDistance(const JointSolverView& view, Joint& joint, float h, float rigidHertz, bool useBias) {
  const JointBody a = jointBody(view, joint.bodyA);
  const JointBody b = jointBody(view, joint.bodyB);
  const JointFrame f = frameOf(a, b, joint);
  const Vec3 rnA = glm::cross(f.rA, f.axis);
  const Vec3 rnB = glm::cross(f.rB, f.axis);
  const float k = a.inverseMass + b.inverseMass + glm::dot(rnA, a.inverseInertia * rnA) +
                  glm::dot(rnB, b.inverseInertia * rnB);
  if (k <= 0.0f) return;
  const float axialMass = 1.0f / k;
  const float c = f.distance - joint.length;
  const float cdot = glm::dot(relativeAnchorVelocity(view, joint, f.rA, f.rB), f.axis);

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

// The three rows at once: a block solve keeps the anchor from sliding round a curve that one row
// after another would trace (Box2D v3's revolute point constraint, Jolt's PointConstraintPart).
void solveBall(const JointSolverView& view, Joint& joint, float h, float rigidHertz, bool useBias) {
  const JointBody a = jointBody(view, joint.bodyA);
  const JointBody b = jointBody(view, joint.bodyB);
  const BallFrame f = ballFrameOf(a, b, joint);
  const Mat3 k = pointInverseMass(a, b, f.rA, f.rB);
  if (!(glm::determinant(k) > 0.0f)) return;
  const Vec3 cdot = relativeAnchorVelocity(view, joint, f.rA, f.rB);
  Softness soft;  // the relax pass: no bias, the whole mass
  if (useBias) soft = makeSoftness(rigidHertz, 2.0f, h);
  const Vec3 impulse = -soft.massScale * (glm::inverse(k) * (cdot + soft.biasRate * f.gap)) -
                       soft.impulseScale * joint.pointImpulse;
  joint.pointImpulse += impulse;
  applyImpulse(a, b, f.rA, f.rB, impulse);
}

}  // namespace

void solveJoints(const JointSolverView& view, std::vector<Joint>& joints, float h, float rigidHertz,
                 bool useBias) {
  for (Joint& joint : joints) {
    if (!joint.active) continue;
    switch (joint.type) {
      case JointType::Distance:
        solveDistance(view, joint, h, rigidHertz, useBias);
        break;
      case JointType::Ball:
        solveBall(view, joint, h, rigidHertz, useBias);
        break;
    }
  }
}

namespace {

// One rigid joint's projection: whether its length was off by more than the tolerance (a fraction
// of the length), which is then removed, split by the effective masses.
bool projectDistance(const JointSolverView& view, Joint& joint, float tolerance) {
  const JointBody a = jointBody(view, joint.bodyA);
  const JointBody b = jointBody(view, joint.bodyB);
  const JointFrame f = frameOf(a, b, joint);
  const float c = f.distance - joint.length;
  const float allowed = tolerance * joint.length;
  if (!(std::abs(c) > allowed)) return false;
  const float excess = c > 0.0f ? c - allowed : c + allowed;
  const Vec3 rnA = glm::cross(f.rA, f.axis);
  const Vec3 rnB = glm::cross(f.rB, f.axis);
  const float k = a.inverseMass + b.inverseMass + glm::dot(rnA, a.inverseInertia * rnA) +
                  glm::dot(rnB, b.inverseInertia * rnB);
  if (k <= 0.0f) return false;
  applyPositionImpulse(a, b, f.rA, f.rB, (-excess / k) * f.axis);
  return true;
}

// A ball joint's gap beyond the slop, removed along the gap through the 3x3 effective mass.
bool projectBall(const JointSolverView& view, Joint& joint) {
  const JointBody a = jointBody(view, joint.bodyA);
  const JointBody b = jointBody(view, joint.bodyB);
  const BallFrame f = ballFrameOf(a, b, joint);
  const float gap = glm::length(f.gap);
  if (!(gap > kBallJointGapSlop)) return false;
  const Mat3 k = pointInverseMass(a, b, f.rA, f.rB);
  if (!(glm::determinant(k) > 0.0f)) return false;
  const Vec3 excess = (1.0f - kBallJointGapSlop / gap) * f.gap;
  applyPositionImpulse(a, b, f.rA, f.rB, -(glm::inverse(k) * excess));
  return true;
}

}  // namespace

void projectJoints(const JointSolverView& view, std::vector<Joint>& joints) {
  for (int pass = 0; pass < kJointProjectionPasses; ++pass) {
    bool projected = false;
    for (Joint& joint : joints) {
      if (!joint.active) continue;
      if (joint.type == JointType::Distance && joint.compliance == 0.0f) {
        projected |= projectDistance(view, joint, kJointLengthSlop);
      } else if (joint.type == JointType::Ball) {
        projected |= projectBall(view, joint);
      }
    }
    if (!projected) break;
  }
}

}  // namespace collide::detail
