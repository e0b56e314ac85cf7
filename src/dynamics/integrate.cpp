// See integrate.h. Sleeping bodies are not in the step.
#include "dynamics/integrate.h"

#include <algorithm>
#include <cmath>

namespace collide::detail {

namespace {

// skew(a) b = a x b.
Mat3 skew(const Vec3& a) { return Mat3(Vec3(0.0f, a.z, -a.y), Vec3(-a.z, 0.0f, a.x), Vec3(a.y, -a.x, 0.0f)); }

}  // namespace

// Torque-free rotation in the body frame is dL/dt = -w x L with L = I w (Euler's equations). An
// explicit step of it gains energy without bound; Catto (GDC 2015, "Physics for Game Programmers:
// Numerical Methods") solves the implicit (backward Euler) step with one Newton iteration, which is
// stable but loses |L| by (h |w x L| / |L|)^2 / 2 a step (about 1e-4 at 10 rad/s and 240 Hz: a
// quarter of the momentum in five seconds of tumbling). We solve the implicit *midpoint* step
// instead, L2 = L1 - h w(Lm) x Lm with Lm = (L1 + L2) / 2, by Newton iteration from L1: the midpoint
// rule keeps every quadratic invariant (Hairer, Lubich & Wanner, "Geometric Numerical
// Integration", IV.2), here both |L|^2 and the energy L . I^-1 L, up to the solve's residual, and is
// as stable as the backward step.
Vec3 gyroscopicStep(const Mat3& inertia, const Mat3& inverseInertia, const Vec3& bodyOmega, float h) {
  const Vec3 l1 = inertia * bodyOmega;
  // Simplified Newton: the Jacobian of the residual, I + (h/2) (skew(wm) - skew(Lm) I^-1), taken once
  // at L2 = L1 and kept. It changes by O(h |w|) over the iteration, so the iteration still contracts
  // by about h |w| per pass (at most a quarter turn per substep), and one inverse replaces four.
  const Vec3 w1 = inverseInertia * l1;
  const Mat3 inverseJacobian = glm::inverse(Mat3(1.0f) + (0.5f * h) * (skew(w1) - skew(l1) * inverseInertia));
  Vec3 l2 = l1;
  for (int iteration = 0; iteration < 6; ++iteration) {
    const Vec3 lm = 0.5f * (l1 + l2);
    const Vec3 wm = inverseInertia * lm;
    const Vec3 residual = l2 - l1 + h * glm::cross(wm, lm);
    const Vec3 correction = inverseJacobian * residual;
    l2 -= correction;
    if (glm::dot(correction, correction) <= 1e-14f * glm::dot(l1, l1)) break;
  }
  return inverseInertia * l2;
}

// The solver carries contact anchors along with each body's rotation over the step and reads the
// current separation from them; past a quarter turn per substep that reading is meaningless (a
// gap that is not there, or none where there is one) and a spinning body sinks through or is
// flung out. Box2D v3 bounds the turn per substep the same way (b2_maxRotation); Jolt bounds the
// angular speed. 0.25 pi per substep is 283 rad/s at 60 Hz with 6 substeps.
constexpr float kMaxRotationPerSubstep = 0.25f * kPi;

// A rotation slower than this per substep (rad) keeps its angular velocity as it is: the gyroscopic
// change of w per substep is at most about h |w| |w| (times the inertia's anisotropy), so below
// 1e-4 rad per substep it is below 1e-4 of w itself, less than the contact solver's own error. This
// skips the Newton solve for every resting body.
constexpr float kGyroscopicMinTurn = 1e-4f;

void integrateVelocities(Array<SolverBody>& bodies, const Array<SolverBodyInfo>& infos,
                         const BodyStorage& storage, float h, std::span<const std::uint32_t> which) {
  const float maxAngularSpeed = kMaxRotationPerSubstep / h;
  for (const std::uint32_t j : which) {
    const SolverBodyInfo& info = infos[j];
    if (!info.dynamic || info.faulted) continue;
    SolverBody& b = bodies[j];
    // Damping as Box2D applies it, v <- v / (1 + h c) + h a: stable for any c and h.
    if (info.linearDamping > 0.0f) b.linearVelocity *= 1.0f / (1.0f + h * info.linearDamping);
    b.linearVelocity += h * info.linearAcceleration;
    if (info.particle) continue;
    if (info.angularDamping > 0.0f) b.angularVelocity *= 1.0f / (1.0f + h * info.angularDamping);
    b.angularVelocity += h * info.angularAcceleration;
    const float turn2 = h * h * glm::dot(b.angularVelocity, b.angularVelocity);
    if (info.gyroscopic && turn2 > kGyroscopicMinTurn * kGyroscopicMinTurn) {
      const BodyRecord& record = storage.records[info.body];
      const Quat rotation = b.deltaRotation * storage.states[info.body].rotation0;
      const Vec3 bodyOmega = glm::conjugate(rotation) * b.angularVelocity;
      b.angularVelocity =
          rotation * gyroscopicStep(record.inertiaLocal, record.inverseInertiaLocal, bodyOmega, h);
    }
    const float speedSquared = glm::dot(b.angularVelocity, b.angularVelocity);
    if (speedSquared > maxAngularSpeed * maxAngularSpeed) {
      b.angularVelocity *= maxAngularSpeed / std::sqrt(speedSquared);
    }
  }
}

void integratePositions(Array<SolverBody>& bodies, const Array<SolverBodyInfo>& infos, float h,
                        std::span<const std::uint32_t> which) {
  for (const std::uint32_t j : which) {
    const SolverBodyInfo& info = infos[j];
    if (info.faulted) continue;
    SolverBody& b = bodies[j];
    b.deltaPosition += h * b.linearVelocity;
    if (info.particle) continue;  // a point mass keeps its rotation bit for bit
    const Vec3& w = b.angularVelocity;
    const Quat spin(0.0f, w.x, w.y, w.z);
    b.deltaRotation = glm::normalize(b.deltaRotation + (0.5f * h) * (spin * b.deltaRotation));
  }
}

}  // namespace collide::detail
