// The joints of the soft step (Catto, "Solver2D" 2024 and GDC 2011 "Soft Constraints"), solved in
// the same substep loop as the contacts (StepSolver::solve in src/dynamics/solver.cpp). One record
// per joint with a type tag; warm start, solve and projection switch on it (Box2D v3's joint.c),
// and each type is one file of src/dynamics/joints/ built from the rows of joints/joint_rows.h.
//
// Every joint is made of the same few rows: a point block (the anchors coincide: three rows solved
// together through their 3x3 effective mass), a rotation block (the bodies keep their relative
// rotation, or all but its turn about one axis), and single rows along a free coordinate (a hinge's
// angle, a slider's offset, a distance joint's length) that carry its spring, motor and limits.
// Rigid rows are soft constraints at twice the contact stiffness in the biased pass and plain
// velocity constraints in the relax pass; a joint given a softness (hertz > 0) is a spring in both.
#pragma once

#include "base/task_runner.h"
#include "bodies/body_storage.h"
#include "dynamics/solver_body.h"

#include <collide/body.h>
#include <collide/events.h>
#include <collide/joints.h>

#include <cstdint>
#include <span>
#include <vector>

namespace collide::detail {

struct Joint {
  JointType type = JointType::Distance;
  std::uint32_t bodyA = 0;
  std::uint32_t bodyB = 0;
  Vec3 localAnchorA{0.0f};  // from the centre of mass, body frame, scaled
  Vec3 localAnchorB{0.0f};
  // The joint frame in each body's frame; its x axis is the joint's axis (hinge, slider, cone).
  // Equal in the world at creation: the relative rotation of the two frames is the joint's turn.
  Quat localFrameA{1.0f, 0.0f, 0.0f, 0.0f};
  Quat localFrameB{1.0f, 0.0f, 0.0f, 0.0f};
  bool collideConnected = true;  // false: its bodies are kept apart in the pair filters
  bool alive = false;
  bool active = false;          // this step: at least one awake dynamic body
  bool inTree = false;          // this pass: its rigid rows are solved directly with its tree (joint_tree.h)
  std::uint8_t treeLimits = 0;  // this pass: the limits its tree solves with them (joints/joint_rows.h bits)
  std::uint32_t generation = 1;

  JointSoftness softness;         // the point rows (and, but for the fixed joint, every row)
  JointSoftness angularSoftness;  // the fixed joint's rotation rows
  JointLimits limits;
  JointMotor motor;
  JointSpring spring;
  float swingLimit = kPi;  // cone
  float friction = 0.0f;   // N m (ball, cone, hinge) or N (slider): the joint's friction
  float breakForce = kUnbreakable;
  float breakTorque = kUnbreakable;

  // Distance.
  float length = 0.0f;
  float compliance = 0.0f;  // m/N; 0 = rigid
  float dampingRatio = 0.0f;
  Vec3 axis{1.0f, 0.0f, 0.0f};  // the last axis, kept for coincident anchors

  // Accumulated impulses of the last substep (the warm start), N s and N m s.
  Vec3 linearImpulse{0.0f};   // point rows, on B at the anchor; the slider's rows across its axis
  Vec3 angularImpulse{0.0f};  // rotation rows, on B; the hinge's two across its axis
  float impulse = 0.0f;       // the distance joint's length row
  float springImpulse = 0.0f;
  float motorImpulse = 0.0f;
  float lowerImpulse = 0.0f;
  float upperImpulse = 0.0f;
  float swingImpulse = 0.0f;
  Vec3 frictionImpulse{0.0f};  // ball and cone: angular, on B; hinge and slider: x along the axis

  void resetImpulses() {
    linearImpulse = angularImpulse = frictionImpulse = Vec3(0.0f);
    impulse = springImpulse = motorImpulse = lowerImpulse = upperImpulse = swingImpulse = 0.0f;
  }
};

// The step's bodies as the joints see them: the solver bodies of moving bodies and their poses at
// the step start, the body storage for static bodies.
class JointTree;
struct JointSolverView {
  Array<SolverBody>& bodies;
  const Array<SolverBodyInfo>& infos;
  const Array<SolverBodyStart>& starts;
  const Array<std::int32_t>& solverOf;
  const BodyStorage& storage;
  // The joint trees, whose frames at the bodies' current pose jointFrame takes where they have them.
  const JointTree* trees = nullptr;
};

// Once per step: which joints take part (at least one awake dynamic body).
void prepareJoints(const JointSolverView& view, Array<Joint>& joints);

// The Gauss-Seidel passes over the active joints in waves: a joint's wave is one past the last wave
// of an earlier joint that writes one of its bodies, so the joints of a wave share no dynamic body
// (a graph colouring, constraint_graph.h) and every body sees its joints in joint order. The step's
// workers take a wave's joints in parallel ranges, and the pass gives exactly what one joint after
// another in joint order gives, at every worker count: a chain built from its anchor keeps the
// order that converges fastest, and many ragdolls or a net make wide waves.
// Ball joints the Gauss-Seidel waves solve at once in SIMD lanes (joints/ball_joint.cpp).
inline constexpr int kBallLanes = 4;
// What the lanes read of their four joints, lane by lane. The waves gather it once a step
// (JointWaves::plan), so that a pass reads one run of these instead of four joint records spread
// over the array, and keep the point block's impulse here until the step's solve is over
// (storeBallGroup writes it back). The friction impulse only warm starts: a joint with friction
// is solved alone.
struct BallLaneGroup {
  std::uint32_t joint[kBallLanes];
  std::uint32_t bodyA[kBallLanes];
  std::uint32_t bodyB[kBallLanes];
  float anchorA[3][kBallLanes];  // x, y and z of the four joints' localAnchorA
  float anchorB[3][kBallLanes];
  float impulse[3][kBallLanes];  // linearImpulse
  float frictionImpulse[3][kBallLanes];
  JointSoftness softness[kBallLanes];
};

class JointWaves {
 public:
  // Once per step, after prepareJoints.
  void prepare(const JointSolverView& view, const Array<Joint>& joints);
  // Once per step, after JointTree::prepare (which says which joints are in trees): each wave's
  // ball joints that the lanes take all step (none in a tree, none with friction) gathered into
  // groups of four, the others left to one at a time.
  void plan(const Array<Joint>& joints);
  // After the step's last pass: the groups' impulses back to their joints.
  void finish(Array<Joint>& joints);
  // The active distance joints, in joint order (plan's; projectJoints takes them).
  std::span<const std::uint32_t> distanceJoints() const { return distance_; }
  // Per substep: apply the accumulated impulses at the current pose.
  void warmStart(const JointSolverView& view, Array<Joint>& joints, TaskRunner& tasks);
  // Per substep: one pass; useBias = false is the relax pass (rigid rows without position bias).
  // rigidHertz: the stiffness of the rigid rows' position correction (twice the contact hertz).
  void solve(const JointSolverView& view, Array<Joint>& joints, float h, float rigidHertz, bool useBias,
             TaskRunner& tasks);
  std::size_t memoryBytes() const;

 private:
  // Joints per parallel range: a joint's pass is some tens of nanoseconds, a range's hand-over a few
  // hundred. A smaller wave runs on the calling thread. The joint grid's waves hold 50 to 67 joints
  // each (a grid's waves are its diagonals), so that two workers share each one.
  static constexpr std::uint32_t kJointsPerRange = 32;
  // Wave by wave: four(group) for each group of ball joints in lanes, one(joint) for each other
  // active joint.
  template <typename One, typename Four>
  void forEachJoint(const JointSolverView& view, Array<Joint>& joints, TaskRunner& tasks, One&& one,
                    Four&& four);

  Array<std::uint32_t> order_;      // the active joints by wave, in joint order within a wave
  Array<std::uint32_t> waveStart_;  // wave w's joints: order_[waveStart_[w] .. waveStart_[w + 1])
  Array<std::uint32_t> waveOf_;     // per active joint, in joint order
  Array<std::uint32_t> lastWave_;   // per solver body: 1 + the wave of its last joint so far
  // plan's: wave w's groups, groups_[groupStart_[w] .. groupStart_[w + 1]), and its other joints,
  // alone_[aloneStart_[w] .. aloneStart_[w + 1]).
  Array<BallLaneGroup> groups_;
  Array<std::uint32_t> groupStart_;
  Array<std::uint32_t> alone_;
  Array<std::uint32_t> aloneStart_;
  Array<std::uint32_t> distance_;
};

// Per substep, after the position update: the length a rigid distance joint lost or gained beyond
// kJointLengthSlop is removed by moving its bodies (non-linear Gauss-Seidel on positions, Box2D
// v2's and Jolt's position iterations), over the joints in order, pass after pass while one is
// still off, at most kJointProjectionPasses times. Below the slop nothing moves: a projection there
// would only cost a spinning pair its angular momentum (positions moved without turning the
// velocities). The other rigid joints of a tree are projected through it (JointTree::project);
// a joint that closes a loop is held by its soft rows alone: projected one by one, it and the tree
// undid each other's moves every substep, and a loaded bridge shook.
inline constexpr float kJointLengthSlop = 0.005f;   // of the joint's length
inline constexpr float kBallJointGapSlop = 0.001f;  // m (or rad): the tree's projection slop
inline constexpr int kJointProjectionPasses = 128;
// `distance`: the active distance joints, in joint order (JointWaves::distanceJoints). True if
// it moved a body.
bool projectJoints(const JointSolverView& view, Array<Joint>& joints,
                   std::span<const std::uint32_t> distance);

// The groups of dynamic bodies the step's active joints connect: groupOf[body] is the lowest body
// index of its group, kNoJointGroup (continuous.h) for a body without such a joint. The continuous
// pass stops a group together.
void jointGroups(const BodyStorage& storage, const Array<Joint>& joints, Array<std::uint32_t>& groupOf);

// The force and torque a joint carried in the last substep (its accumulated impulses over h).
struct JointLoad {
  float force = 0.0f;
  float torque = 0.0f;
};
JointLoad jointLoad(const Joint& joint, float h);

// After the solve: every active joint whose load exceeds its break force or torque, as events (in
// joint order); the caller destroys them.
void findBrokenJoints(const BodyStorage& storage, const Array<Joint>& joints, float h,
                      Array<JointBreakEvent>& broken);

// The free coordinate of a joint at the bodies' current poses: a hinge's angle, a slider's offset,
// a cone joint's twist, a distance joint's length; 0 for a ball or fixed joint. Also the anchors'
// world points and the joint frame's axis in the world, for queries and drawing.
struct JointPose {
  Vec3 anchorA{0.0f};
  Vec3 anchorB{0.0f};
  Vec3 axisA{1.0f, 0.0f, 0.0f};  // the joint frame's x in the world, as body a carries it
  Vec3 axisB{1.0f, 0.0f, 0.0f};
  Quat frameA{1.0f, 0.0f, 0.0f, 0.0f};
  Quat frameB{1.0f, 0.0f, 0.0f, 0.0f};
  float position = 0.0f;
};
JointPose jointPose(const BodyStorage& storage, const Joint& joint);

// The twist of the relative rotation q (frame B in frame A) about frame A's x axis, in (-pi, pi].
float twistAngle(const Quat& q);

}  // namespace collide::detail
