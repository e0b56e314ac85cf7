// The joints of the soft step (Catto, "Solver2D" 2024 and GDC 2011 "Soft Constraints"), solved in
// the same substep loop as the contacts (StepSolver::solve in src/dynamics/solver.cpp). One record
// per joint with a type tag; warm start, solve and projection switch on it (Box2D v3's joint.c).
//
// Distance: C = |pB - pA| - length, along the unit axis n from anchor A to anchor B. A rigid
// constraint (compliance 0) is a velocity constraint in the relax pass and, in the biased pass, a
// stiff soft constraint (Box2D v3's joint softness: twice the contact hertz, damping ratio 2).
// A compliant one is a spring of stiffness 1/compliance (N/m), the XPBD compliance of Macklin et
// al. 2016: with effective mass m the spring has omega^2 = 1 / (compliance m) and is integrated
// implicitly as a soft constraint in both passes (it is a physical force, not an error correction).
//
// Ball (spherical): C = pB - pA, three rows solved together through the 3x3 effective mass
// K = (mA + mB) I - [rA]x IA^-1 [rA]x - [rB]x IB^-1 [rB]x, soft as a rigid distance joint.
#pragma once

#include "bodies/body_storage.h"
#include "dynamics/solver_body.h"

#include <collide/body.h>

#include <cstdint>
#include <vector>

namespace collide::detail {

struct Joint {
  JointType type = JointType::Distance;
  std::uint32_t bodyA = 0;
  std::uint32_t bodyB = 0;
  Vec3 localAnchorA{0.0f};  // from the centre of mass, body frame, scaled
  Vec3 localAnchorB{0.0f};
  bool collideConnected = true;  // false: its bodies are kept apart in the pair filters
  bool alive = false;
  bool active = false;  // this step: at least one awake dynamic body
  std::uint32_t generation = 1;

  // Distance.
  float length = 0.0f;
  float compliance = 0.0f;  // m/N; 0 = rigid
  float dampingRatio = 0.0f;
  float impulse = 0.0f;         // accumulated along the axis (warm start), N s
  Vec3 axis{1.0f, 0.0f, 0.0f};  // the last axis, kept for coincident anchors

  // Ball.
  Vec3 pointImpulse{0.0f};  // accumulated on B at the anchor (warm start), N s
};

// The step's bodies as the joints see them: the solver bodies of moving bodies, the body storage
// for the start-of-step poses and for static bodies.
struct JointSolverView {
  std::vector<SolverBody>& bodies;
  const std::vector<SolverBodyInfo>& infos;
  const std::vector<std::int32_t>& solverOf;
  const BodyStorage& storage;
};

// Once per step: which joints take part (at least one awake dynamic body).
void prepareJoints(const JointSolverView& view, std::vector<Joint>& joints);
// Per substep, over the active joints: apply the accumulated impulse along the current axis.
void warmStartJoints(const JointSolverView& view, std::vector<Joint>& joints);
// Per substep: one pass; useBias = false is the relax pass (rigid joints without position bias).
// rigidHertz: the stiffness of the rigid joints' position correction (twice the contact hertz).
void solveJoints(const JointSolverView& view, std::vector<Joint>& joints, float h, float rigidHertz,
                 bool useBias);

// Per substep, after the position update: the length a rigid distance joint lost or gained beyond
// kJointLengthSlop, and the gap a ball joint's anchors opened beyond kBallJointGapSlop, are removed
// by moving its bodies (non-linear Gauss-Seidel on positions, Box2D
// v2's and Jolt's position iterations), over the joints in order, pass after pass while one is
// still off, at most kJointProjectionPasses times. The soft joint holds a link within the slop on
// its own; under the load of a whipping chain it gives, and the passes take the give back. Below
// the slop nothing moves: a projection there would only cost a spinning pair its angular momentum
// (positions moved without turning the velocities).
inline constexpr float kJointLengthSlop = 0.005f;   // of the joint's length
inline constexpr float kBallJointGapSlop = 0.001f;  // m
inline constexpr int kJointProjectionPasses = 128;
void projectJoints(const JointSolverView& view, std::vector<Joint>& joints);

}  // namespace collide::detail
