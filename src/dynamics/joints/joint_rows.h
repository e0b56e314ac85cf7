// The rows every joint type is made of (joint_solver.h): the bodies at their current pose, the
// point block, the rotation blocks, and the single rows that carry springs, motors and limits.
// A joint type's file (ball_joint.cpp, hinge_joint.cpp, ...) builds its rows from these each
// substep and keeps their accumulated impulses in its Joint record.
#pragma once

#include "dynamics/contact_solver.h"
#include "dynamics/joint_solver.h"
#include "memory/prefetch.h"

#include <array>
#include <optional>

namespace collide::detail {

// One end of a joint: the body's current pose, velocities and masses (zero for a body the solver
// does not move). `moving` reads a kinematic body's velocity; `solver` is set for a dynamic one,
// which the joint's impulses change.
struct JointBody {
  Vec3 centerOfMass{0.0f};
  Quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
  const SolverBody* moving = nullptr;
  SolverBody* solver = nullptr;
  float inverseMass = 0.0f;
  Mat3 inverseInertia{0.0f};

  Vec3 linearVelocity() const { return moving ? moving->linearVelocity : Vec3(0.0f); }
  Vec3 angularVelocity() const { return moving ? moving->angularVelocity : Vec3(0.0f); }
  Vec3 velocityAt(const Vec3& r) const { return linearVelocity() + glm::cross(angularVelocity(), r); }
};

JointBody jointBody(const JointSolverView& view, std::uint32_t body);

// Whether asking for joints' bodies ahead pays: only when their solver records outgrow a core's
// L2 cache (1 MiB on the machines measured). Below that they are in cache, and the prefetches
// are work for nothing: 100 ragdolls' 1,100 bodies are 0.2 MB, the 10,000-sphere joint grid's 1.9.
inline bool jointBodiesOutgrowCache(const JointSolverView& view) {
  constexpr std::size_t kCacheBytes = std::size_t{1} << 20;
  constexpr std::size_t kBodyBytes = sizeof(SolverBody) + sizeof(SolverBodyInfo) + sizeof(SolverBodyStart);
  return view.bodies.size() * kBodyBytes > kCacheBytes;
}

// How many joints ahead a pass asks for a joint's bodies (prefetchJointBodies); the waves ask for
// the joint's own record twice as far.
inline constexpr std::uint32_t kJointBodiesAhead = 4;

// Asks for what jointBody reads of a body, ahead of the pass that reads it.
inline void prefetchBody(const JointSolverView& view, std::uint32_t body) {
  const std::int32_t j = view.solverOf[body];
  if (j == kNoSolverBody) {
    prefetchRecord(view.storage.states[body]);
    return;
  }
  const auto index = static_cast<std::size_t>(j);
  prefetchRecord(view.bodies[index]);
  prefetchRecord(view.infos[index]);
  prefetchRecord(view.starts[index]);
}
// The same for both of a joint's bodies.
inline void prefetchJointBodies(const JointSolverView& view, const Joint& joint) {
  prefetchBody(view, joint.bodyA);
  prefetchBody(view, joint.bodyB);
}

// A joint's two bodies and its frame at their current pose.
struct JointFrame {
  JointBody a;
  JointBody b;
  Vec3 rA{0.0f};  // world offsets from the centres of mass to the anchors
  Vec3 rB{0.0f};
  Vec3 d{0.0f};                         // anchor B minus anchor A
  Quat frameA{1.0f, 0.0f, 0.0f, 0.0f};  // the joint frame in the world, as each body carries it
  Quat frameB{1.0f, 0.0f, 0.0f, 0.0f};
};
// The frame at the bodies' current pose: the joint tree's, where its tree built its rows at this
// pose (the same values), else computed into scratch (buildJointFrame), which is left empty
// otherwise (a frame is some 250 bytes to construct for nothing).
const JointFrame& jointFrame(const JointSolverView& view, const Joint& joint,
                             std::optional<JointFrame>& scratch);
JointFrame buildJointFrame(const JointSolverView& view, const Joint& joint);

// The softness of a joint's rows in one pass: the joint's own spring (hertz > 0) in both passes;
// a rigid row's stiff soft constraint in the biased pass; in the relax pass, no bias.
Softness rowSoftness(const JointSoftness& softness, float rigidHertz, float h, bool useBias);

// Impulses: p on B at its anchor (rB from its centre), -p on A at rA; the angular impulse L on B,
// -L on A.
void applyImpulse(const JointBody& a, const JointBody& b, const Vec3& rA, const Vec3& rB, const Vec3& p);
void applyAngularImpulse(const JointBody& a, const JointBody& b, const Vec3& l);
// The positional impulse p (kg m) on B at its anchor, -p on A: each body moved and turned by it as
// its masses say (non-linear Gauss-Seidel on positions).
void applyPositionImpulse(const JointBody& a, const JointBody& b, const Vec3& rA, const Vec3& rB,
                          const Vec3& p);

// The cross-product matrix: skew(r) v = r x v.
Mat3 skew(const Vec3& r);

// The point block: anchor B's velocity relative to anchor A driven to zero, its gap C = d closed by
// the softness's bias. K = (mA^-1 + mB^-1) I - [rA]x IA^-1 [rA]x - [rB]x IB^-1 [rB]x, symmetric and
// positive definite while one body moves; solved as a block, so the anchor does not slide round
// the curve one row after another would trace (Box2D v3's revolute point constraint, Jolt's
// PointConstraintPart).
Mat3 pointInverseMass(const JointBody& a, const JointBody& b, const Vec3& rA, const Vec3& rB);
void solvePoint(const JointFrame& f, const Softness& soft, Vec3& accumulated);

// The rotation block: frame B's rotation relative to frame A (in the world, as a rotation vector e
// of qB qA^-1) driven back to zero, K = IA^-1 + IB^-1 (the fixed and the slider joint).
Vec3 rotationError(const Quat& frameA, const Quat& frameB);
void solveRotation(const JointFrame& f, const Softness& soft, Vec3& accumulated);

// One row: C' = n . (vB - vA) + wB . omegaB - wA . omegaA; an impulse lambda adds n lambda to B's
// momentum and -n lambda to A's, wB lambda to B's angular momentum and -wA lambda to A's.
struct JointRow {
  Vec3 linear{0.0f};
  Vec3 angularA{0.0f};
  Vec3 angularB{0.0f};
  float mass = 0.0f;  // 1 / (the row's inverse effective mass); 0 when nothing can move it
};
JointRow makeRow(const JointBody& a, const JointBody& b, const Vec3& linear, const Vec3& angularA,
                 const Vec3& angularB);
// A row along an axis through the anchors: linear along it, levers rA and rB.
JointRow linearRow(const JointFrame& f, const Vec3& axis, const Vec3& leverA);
// A row of relative rotation about an axis.
JointRow angularRow(const JointBody& a, const JointBody& b, const Vec3& axis);
// The same rows without their mass (0): the equality rows of a joint tree, which solves them with
// the tree's coupled mass instead.
JointRow linearTreeRow(const JointFrame& f, const Vec3& axis, const Vec3& leverA);
JointRow angularTreeRow(const Vec3& axis);
float rowSpeed(const JointBody& a, const JointBody& b, const JointRow& row);
void applyRow(const JointBody& a, const JointBody& b, const JointRow& row, float lambda);
// A solver body turned by a small rotation vector (world): its pose's first-order step (the trees'
// projection turns each body once by the sum of its rows' turns).
void turnSolverBody(SolverBody& body, const Vec3& turn);

// The free coordinate's rows, in Box2D v3's order (spring, motor, limits), given its position.
// The spring pulls position towards spring.target in both passes; the motor's accumulated impulse
// is clamped to h maxForce; the limits are one-sided rows, speculative while inside (a row that
// only acts once the coordinate would cross the limit within the substep), soft or rigid outside.
void solveSpring(const JointFrame& f, const JointRow& row, float position, const JointSpring& spring, float h,
                 float& accumulated);
void solveMotor(const JointFrame& f, const JointRow& row, const JointMotor& motor, float h,
                float& accumulated);
// Friction: the row's speed driven to zero with at most h friction of impulse (a motor at rest), or
// for a ball or cone joint the whole relative angular velocity, its impulse clamped in length.
void solveRowFriction(const JointFrame& f, const JointRow& row, float friction, float h, float& accumulated);
void solveAngularFriction(const JointFrame& f, float friction, float h, Vec3& accumulated);
void solveLowerLimit(const JointFrame& f, const JointRow& row, float position, float lower,
                     const Softness& soft, float h, float& accumulated);
void solveUpperLimit(const JointFrame& f, const JointRow& row, float position, float upper,
                     const Softness& soft, float h, float& accumulated);

// The impulse along the free coordinate of a hinge or slider (spring, motor, friction and limits),
// and the part of it the joint's own warm start applies: without the limits its tree applies.
float axialImpulse(const Joint& joint);
float ownAxialImpulse(const Joint& joint);

// A joint's rigid equality rows, for the direct solve of joint trees (joint_tree.h): each row's
// Jacobian, its position error C and the accumulated impulse it adds to (the same component the
// type's own Gauss-Seidel rows keep and its warm start applies). At most six (the fixed joint).
struct EqualityRow {
  JointRow row;
  float error = 0.0f;
  float* accumulated = nullptr;
  // A limit's row (Joint::treeLimits bit): one-sided, error its distance to the limit (>= 0
  // allowed), row oriented so that a positive impulse pushes away from the limit.
  std::uint8_t limitBit = 0;
};
inline constexpr int kMaxJointTreeRows = 8;  // a hinge's five and its two limits; a cone's three and three
struct EqualityRows {
  std::array<EqualityRow, kMaxJointTreeRows> rows{};
  int count = 0;
  void add(const JointRow& row, float error, float* accumulated, std::uint8_t limitBit = 0) {
    rows[static_cast<std::size_t>(count++)] = {row, error, accumulated, limitBit};
  }
};
// A joint's angles at a pose, which its tree's limit rows and its Gauss-Seidel rows both read: a
// cone's swing about swingAxis and twist about twistAxis (zero axes: no such row), a hinge's angle
// as its twist. Two arc tangents each time they are measured: the tree keeps those it measured at
// the bodies' current pose for the Gauss-Seidel pass at the same pose (anglesAtPose).
struct JointAngles {
  Vec3 swingAxis{0.0f};
  float swing = 0.0f;
  Vec3 twistAxis{0.0f};
  float twist = 0.0f;
};
// The angles the joint's tree measured at the bodies' current pose, or null (not in a tree, no
// limits, or the bodies moved since).
const JointAngles* anglesAtPose(const JointSolverView& view, const Joint& joint);

// Joint::treeLimits bits.
inline constexpr std::uint8_t kLowerLimitBit = 1, kUpperLimitBit = 2, kSwingLimitBit = 4;
// The row of a one-sided limit in the direction its impulse pushes (the upper limit's is the
// coordinate's row negated).
JointRow negatedRow(const JointRow& row);

// The point block's three rows along the world axes (accumulating joint.linearImpulse), and the
// rotation block's (accumulating joint.angularImpulse).
void addPointRows(const JointFrame& f, Joint& joint, EqualityRows& rows);
void addRotationRows(const JointFrame& f, Joint& joint, EqualityRows& rows);

// The per-type pieces, one file each. A joint in a tree (Joint::inTree) leaves its equality rows
// to the tree solve and solves only its springs, motors and limits here.
void warmStartDistance(const JointSolverView& view, Joint& joint);
void solveDistance(const JointSolverView& view, Joint& joint, float h, float rigidHertz, bool useBias);
bool projectDistance(const JointSolverView& view, Joint& joint);

void warmStartBall(const JointSolverView& view, Joint& joint);
void solveBall(const JointSolverView& view, Joint& joint, float h, float rigidHertz, bool useBias);
// Four ball joints at once in SIMD lanes, bit for bit what warmStartBall and solveBall give each:
// four joints of one wave (no moving body shared), each one ballInLanes takes (a ball joint in no
// tree and without friction), gathered into a BallLaneGroup (joint_solver.h) and its impulses
// stored back after the step's passes.
bool ballInLanes(const Joint& joint);
void loadBallGroup(const Array<Joint>& joints, const std::uint32_t (&which)[kBallLanes],
                   BallLaneGroup& group);
void storeBallGroup(const BallLaneGroup& group, Array<Joint>& joints);
void warmStartBalls(const JointSolverView& view, const BallLaneGroup& group);
void solveBalls(const JointSolverView& view, BallLaneGroup& group, float h, float rigidHertz, bool useBias);
void equalityRowsBall(const JointFrame& f, Joint& joint, EqualityRows& rows);

void warmStartHinge(const JointSolverView& view, Joint& joint);
void solveHinge(const JointSolverView& view, Joint& joint, float h, float rigidHertz, bool useBias);
void equalityRowsHinge(const JointFrame& f, Joint& joint, EqualityRows& rows);
void limitRowsHinge(const JointFrame& f, Joint& joint, EqualityRows& rows, JointAngles& angles);

void warmStartSlider(const JointSolverView& view, Joint& joint);
void solveSlider(const JointSolverView& view, Joint& joint, float h, float rigidHertz, bool useBias);
void equalityRowsSlider(const JointFrame& f, Joint& joint, EqualityRows& rows);
void limitRowsSlider(const JointFrame& f, Joint& joint, EqualityRows& rows, JointAngles& angles);

void warmStartFixed(const JointSolverView& view, Joint& joint);
void solveFixed(const JointSolverView& view, Joint& joint, float h, float rigidHertz, bool useBias);
void equalityRowsFixed(const JointFrame& f, Joint& joint, EqualityRows& rows);

void warmStartCone(const JointSolverView& view, Joint& joint);
void solveCone(const JointSolverView& view, Joint& joint, float h, float rigidHertz, bool useBias);
void equalityRowsCone(const JointFrame& f, Joint& joint, EqualityRows& rows);
void limitRowsCone(const JointFrame& f, Joint& joint, EqualityRows& rows, JointAngles& angles);

}  // namespace collide::detail
