// Symplectic Euler per substep on the solver bodies (Box2D v3's b2IntegrateVelocitiesTask /
// b2IntegratePositionsTask): velocities first (gravity, forces, the gyroscopic term), then the
// constraints act on them, then the pose change follows the new velocities.
#pragma once

#include "bodies/body_storage.h"
#include "dynamics/solver_body.h"

#include <cstdint>
#include <span>
#include <vector>

namespace collide::detail {

// One implicit-midpoint step of torque-free rotation in the body frame; returns the new body-frame
// angular velocity.
Vec3 gyroscopicStep(const Mat3& inertia, const Mat3& inverseInertia, const Vec3& bodyOmega, float h);

// Velocity step of one substep for the dynamic solver bodies: gravity, the body's accumulated force
// and torque (SolverBodyInfo's accelerations), and the gyroscopic term; the angular speed is bounded
// (see integrate.cpp). The listed bodies: each body's step reads and writes only its own state.
void integrateVelocities(Array<SolverBody>& bodies, const Array<SolverBodyInfo>& infos,
                         const BodyStorage& storage, float h, std::span<const std::uint32_t> which);

// Position step of one substep for dynamic and kinematic solver bodies: the change of position by
// v h, the change of rotation by dq' = 1/2 (0, w) dq, renormalised; particles never turn. The listed
// bodies.
void integratePositions(Array<SolverBody>& bodies, const Array<SolverBodyInfo>& infos, float h,
                        std::span<const std::uint32_t> which);

}  // namespace collide::detail
