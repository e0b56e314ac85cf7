// The definitions of the joints a World ties bodies with (World::createDistanceConstraint,
// createBallJoint, createHingeJoint, createSliderJoint, createFixedJoint, createConeJoint), and the
// settings every joint shares: softness, limits, a motor, a spring, a break force. docs/joints.md
// explains the model; each field can be read and changed after creation (World::setJointLimits, ...).
//
// Points and axes are given in the world frame at creation: each body keeps them at its own local
// point and direction from then on. Angles are in radians, lengths in metres.
#pragma once

#include <collide/body.h>
#include <collide/math.h>

#include <limits>
#include <optional>

namespace collide {

inline constexpr float kUnbreakable = std::numeric_limits<float>::infinity();

// The stiffness of a joint's rows as a spring: hertz 0 is rigid (the solver's own stiff setting),
// otherwise a spring of that natural frequency (on the joint's effective mass) and damping ratio,
// Catto's soft step. A soft joint gives under load and springs back; a soft limit is a cushion.
struct JointSoftness {
  float hertz = 0.0f;         // >= 0; 0 = rigid
  float dampingRatio = 1.0f;  // >= 0; 1 is critical
  friend bool operator==(const JointSoftness&, const JointSoftness&) = default;
};

// The range of a joint's free coordinate: a hinge's angle, a slider's offset, a distance joint's
// length, a cone joint's twist. lower <= upper.
struct JointLimits {
  bool enabled = false;
  float lower = 0.0f;
  float upper = 0.0f;
  friend bool operator==(const JointLimits&, const JointLimits&) = default;
};

// Drives the free coordinate's speed (rad/s for a hinge, m/s for a slider) towards `speed` with at
// most `maxForce` (N m for a hinge, N for a slider). A motor of speed 0 is a brake or friction.
struct JointMotor {
  bool enabled = false;
  float speed = 0.0f;
  float maxForce = 0.0f;  // >= 0
  friend bool operator==(const JointMotor&, const JointMotor&) = default;
};

// Pulls the free coordinate towards `target` (a hinge's angle, a slider's offset, a distance
// joint's length) as a spring of `hertz` and `dampingRatio` on the joint's effective mass.
struct JointSpring {
  bool enabled = false;
  float hertz = 0.0f;  // > 0 when enabled
  float dampingRatio = 0.0f;
  float target = 0.0f;
  friend bool operator==(const JointSpring&, const JointSpring&) = default;
};

// Keeps an anchor on body a at `length` from an anchor on body b (a rope that also pushes: a rod).
// Any two bodies, at least one dynamic. Anchors are points in each body's local frame (scaled with
// the body, like its shape); unset, they are the centres of mass. A particle's anchor must be its
// centre (it cannot turn, so an offset anchor would have no lever).
struct DistanceConstraintDef {
  BodyId a{};
  BodyId b{};
  std::optional<Vec3> localAnchorA{};
  std::optional<Vec3> localAnchorB{};
  std::optional<float> length{};  // >= 0; unset: the anchors' distance at creation
  // m/N, >= 0. 0 is rigid; otherwise a spring of stiffness 1/compliance (XPBD's compliance), see
  // docs/joints.md. A spring in hertz is `spring`; a joint has one or the other.
  float compliance = 0.0f;
  float dampingRatio = 0.0f;  // of the compliance spring, >= 0; 1 is critical
  JointSpring spring{};       // target unused: the spring pulls towards `length`
  // [lower, upper] of the length, rigid: with a spring, a rope's slack and its end stop.
  JointLimits limits{};
  // false: the two bodies do not collide with each other while the constraint exists (a ragdoll's
  // neighbouring limbs, a chain's links that overlap at the joints).
  bool collideConnected = true;
  float breakForce = kUnbreakable;  // N
};

// A ball (spherical) joint: the two bodies share the anchor point and turn freely about it (a
// chain's links, a ragdoll's shoulder without limits).
struct BallJointDef {
  BodyId a{};
  BodyId b{};
  Vec3 anchor{0.0f};
  // false (the default): the two bodies do not collide with each other while the joint exists.
  bool collideConnected = false;
  JointSoftness softness{};
  float breakForce = kUnbreakable;  // N
  // The joint's friction: the most torque it spends against the bodies' relative turning (N m,
  // >= 0; 0 = none). A ragdoll's joints or a stiff pin come to rest with it.
  float frictionTorque = 0.0f;
};

// A hinge (revolute) joint: the bodies share the anchor and turn about `axis` only (doors, wheels,
// a bridge's planks, elbows and knees). Its angle is b's turn relative to a about the axis (right
// hand), 0 at creation.
struct HingeJointDef {
  BodyId a{};
  BodyId b{};
  Vec3 anchor{0.0f};
  Vec3 axis{0.0f, 0.0f, 1.0f};  // non-zero; normalised
  JointLimits limits{};         // of the angle, within [-pi, pi]
  JointMotor motor{};           // rad/s, N m
  JointSpring spring{};         // about the angle `target`
  bool collideConnected = false;
  JointSoftness softness{};          // of the point and axis rows, and of the limits
  float breakForce = kUnbreakable;   // N
  float breakTorque = kUnbreakable;  // N m
  float frictionTorque = 0.0f;       // N m, >= 0: the most torque spent against turning about the axis
};

// A slider (prismatic) joint: b keeps its rotation relative to a and moves along `axis` (fixed in a)
// only (pistons, lifts, drawers). Its offset is the anchors' separation along the axis, 0 at
// creation.
struct SliderJointDef {
  BodyId a{};
  BodyId b{};
  Vec3 anchor{0.0f};
  Vec3 axis{1.0f, 0.0f, 0.0f};  // non-zero; normalised
  JointLimits limits{};         // of the offset, m
  JointMotor motor{};           // m/s, N
  JointSpring spring{};         // about the offset `target`
  bool collideConnected = false;
  JointSoftness softness{};
  float breakForce = kUnbreakable;
  float breakTorque = kUnbreakable;
  float frictionForce = 0.0f;  // N, >= 0: the most force spent against sliding along the axis
};

// A fixed (weld) joint: the bodies keep their relative pose, as if one rigid body (breakable
// structures, parts glued at run time). Unset, the anchor is b's centre of mass; it matters for a
// soft joint (where it bends) and for the break force's lever.
struct FixedJointDef {
  BodyId a{};
  BodyId b{};
  std::optional<Vec3> anchor{};
  bool collideConnected = false;
  JointSoftness linearSoftness{};   // of the point rows
  JointSoftness angularSoftness{};  // of the rotation rows
  float breakForce = kUnbreakable;
  float breakTorque = kUnbreakable;
};

// A cone (swing-twist) joint: a ball joint whose `axis`, carried by b, stays within `swingLimit` of
// its creation direction in a, and whose twist about it stays within `twistLimits` (a ragdoll's
// shoulders, hips and neck).
struct ConeJointDef {
  BodyId a{};
  BodyId b{};
  Vec3 anchor{0.0f};
  Vec3 axis{1.0f, 0.0f, 0.0f};  // non-zero; normalised
  float swingLimit = kPi;       // half-angle of the cone, [0, pi]; pi: free
  JointLimits twistLimits{};    // within [-pi, pi]
  bool collideConnected = false;
  JointSoftness softness{};  // of the point rows and of the limits
  float breakForce = kUnbreakable;
  float breakTorque = kUnbreakable;
  float frictionTorque = 0.0f;  // N m, >= 0: the most torque spent against the relative turning
};

}  // namespace collide
