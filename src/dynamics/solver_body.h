// What the solver reads and writes for one moving body during a step (Box2D v3's b2BodyState, in
// 3D): velocities and the change of pose since the step began, 64 bytes that the contact solver
// gathers four at a time. Positions are not needed: a contact's current separation follows from its
// anchors and the pose change. Static bodies have no solver body (they read as zero: at rest, not
// moved), and sleeping bodies are not in the step.
#pragma once

#include <collide/math.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace collide::detail {

struct alignas(16) SolverBody {
  Vec3 linearVelocity{0.0f};
  float pad0 = 0.0f;
  Vec3 angularVelocity{0.0f};
  float pad1 = 0.0f;
  Vec3 deltaPosition{0.0f};  // centre of mass now minus at the step start
  float pad2 = 0.0f;
  Quat deltaRotation{1.0f, 0.0f, 0.0f, 0.0f};  // rotation now = deltaRotation * rotation at the start
};
static_assert(sizeof(SolverBody) == 64, "four rows of four floats, for the 4x4 transposes");
static_assert(offsetof(SolverBody, deltaRotation) == 48);

// The rest of what the step needs per solver body, walked by integration and the joints, not by
// the contact solver (which keeps its own copies of the masses per constraint).
struct SolverBodyInfo {
  std::uint32_t body = 0;  // index in the body storage
  float inverseMass = 0.0f;
  Mat3 inverseInertiaWorld{0.0f};  // at the step start: the solver holds inertia fixed over a step
  // The velocity change per second from gravity and the body's force and torque, constant over the
  // step: integration then reads no body record until a body spins fast enough for the gyroscopic
  // term.
  Vec3 linearAcceleration{0.0f};
  Vec3 angularAcceleration{0.0f};
  // Velocity damping (BodyDef::linearDamping, angularDamping, 1/s); 0 for none, the common case.
  float linearDamping = 0.0f;
  float angularDamping = 0.0f;
  bool gyroscopic = false;  // a rigid body whose inertia is not isotropic
  bool dynamic = false;     // false: kinematic (moves by its velocity, infinite mass)
  bool particle = false;
  bool faulted = false;  // the fault guard stopped it during this step
};

// A moving body's pose at the step start, beside its solver body: the joints rebuild their frames
// from it several times a substep, and the body's whole state is two cache lines of other fields.
struct alignas(32) SolverBodyStart {
  Vec3 centerOfMass{0.0f};
  Quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
};

// Static bodies, and bodies not in the step, map to this index.
inline constexpr std::int32_t kNoSolverBody = -1;

}  // namespace collide::detail
