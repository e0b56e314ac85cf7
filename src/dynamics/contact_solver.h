// The soft-step contact solver (Catto, "Solver2D" 2024 and Box2D v3's contact_solver.c), written for
// 3D and four lanes wide. Per step, prepare() turns the contacts into batches of four manifolds
// that share no dynamic body (constraint_graph.h colours them), so a batch is solved in SIMD lanes
// exactly as four sequential solves would be. Per substep: warm start, solve with the soft position
// bias, (integrate positions), relax without it. At the end: restitution, and the impulses go back
// to the contacts for warm starting and events.
//
// Each manifold is solved as
//   - up to four normal points, each a soft constraint (Catto, GDC 2011 "Soft Constraints"): a
//     mass-spring-damper whose stiffness is a physical setting (ContactTuning::hertz), with the
//     speculative gap of a point still apart (Catto, GDC 2013 "Continuous Collision");
//   - one friction patch at the points' centroid: two tangents solved as a 2x2 block inside the
//     Coulomb disc mu * (sum of the normal impulses), and a twist about the normal bounded by
//     mu * r * (sum) (kTwistRadiusScale gives r). Per-point friction, solved point after
//     point, couples the points through the body's rotation and made resting boxes rock and stacks
//     walk (docs/architecture.md, "Stacking"); one block per patch does not;
//   - a static-friction anchor: where a patch first sticks, a point fixed in each body is kept, and
//     the biased pass pulls the two back together with the contact's softness. Velocity-level
//     friction stops sliding but forgets where it started, so the solver's small errors walked tall
//     stacks sideways by centimetres in ten seconds; the anchor remembers. It moves with the
//     contact when the patch slides (the friction bound is reached) or drifts beyond the reach.
#pragma once

#include "contacts/contact_cache.h"
#include "dynamics/body_storage.h"
#include "dynamics/simd.h"
#include "dynamics/solver_body.h"

#include <collide/world.h>

#include <array>
#include <cstdint>
#include <vector>

namespace collide::detail {

// A soft constraint as a mass-spring-damper at substep h (Catto, GDC 2011 "Soft Constraints").
struct Softness {
  float biasRate = 0.0f;
  float massScale = 1.0f;
  float impulseScale = 0.0f;
};
Softness makeSoftness(float hertz, float dampingRatio, float h);

// The stiffest spring the solver uses, as a fraction of the substep rate 1/h: contacts, one-way
// contacts and rigid joints alike (h omega = pi / 2).
inline constexpr float kMaxHertzPerSubstepRate = 0.25f;

// The twist friction's radius as a fraction of the manifold points' mean distance from their
// centroid. A uniformly pressed patch resists twisting with mu N times the mean distance of its
// area from the centre; for a rectangle whose corners are the points that is 0.54 (square) down to
// 0.50 (a long strip, e.g. a capsule lying down) of the corners' distance, for a disc with points on
// its rim 0.67. The square's value, since box faces are the common patch.
inline constexpr float kTwistRadiusScale = 0.54f;

// One normal point of a batch, four lanes.
struct BatchPoint {
  Vec3W anchorA, anchorB;  // from each centre of mass to the contact point, world, at the step start
  Vec3W crossA, crossB;    // anchor x normal
  Vec3W turnA, turnB;      // I^-1 (anchor x normal): the spin one unit of normal impulse gives
  FloatW baseSeparation;   // separation at the step start minus normal . (anchorB - anchorA)
  FloatW normalMass;
  FloatW normalImpulse;  // accumulated per substep (warm start)
  FloatW maxNormalImpulse;
  FloatW totalNormalImpulse;
  FloatW approachVelocity;  // normal relative velocity before the solve (restitution, events)
};

// Four manifolds, solved together (Box2D v3's b2ContactConstraintSIMD).
struct ContactBatch {
  std::array<std::int32_t, kLanes> bodyA{};  // solver body, or kNoSolverBody
  std::array<std::int32_t, kLanes> bodyB{};
  std::array<std::int32_t, kLanes> contact{};  // index in the contact array, -1 for an empty lane
  std::array<bool, kLanes> writeA{};           // a dynamic body takes the result (not kinematic)
  std::array<bool, kLanes> writeB{};
  int pointCount = 0;  // the most points of the four manifolds
  FloatW inverseMassA, inverseMassB;
  Vec3W normal, tangent1, tangent2;
  FloatW friction, restitution;
  FloatW biasRate, massScale, impulseScale;
  std::array<BatchPoint, Manifold::kMaxPoints> points;
  // Friction patch.
  Vec3W tangent1CrossA, tangent2CrossA, tangent1CrossB, tangent2CrossB;  // centroid anchor x tangent
  Vec3W tangent1TurnA, tangent2TurnA, tangent1TurnB, tangent2TurnB;      // I^-1 of those
  FloatW tangentMass11, tangentMass12, tangentMass22;                    // inverse of the 2x2 block
  FloatW tangentImpulse1, tangentImpulse2;
  FloatW surfaceSpeed1, surfaceSpeed2;  // the sliding friction drives towards (a conveyor belt)
  Vec3W twistTurnA, twistTurnB;  // I^-1 normal
  FloatW twistMass, twistRadius, twistImpulse;
  // Static-friction anchor: offsets of the anchored points from the centres at the step start, and
  // their tangential gap B - A then.
  Vec3W stickA, stickB;
  FloatW stickGap1, stickGap2;
  FloatW stickRate;  // the softness's bias rate, or 0 where the patch has no anchor (a belt)
  FloatW sliding;  // lane mask: the patch reached the friction bound in a biased pass
};

struct ContactSolverSettings {
  ContactTuning tuning;
  bool friction = true;  // Coulomb friction (off under the viscous and damping models)
};

// Once per step: batches for the enabled, awake, non-sensor contacts with points, in colours of
// the constraint graph (batches of one colour share no dynamic body) and then the overflow (one
// contact per batch, solved one after another). Approach velocities are taken here, before the
// solve. The vectors are reused across steps: no allocation after warm-up.
struct ContactSolver {
  std::vector<ContactBatch> batches;
  std::vector<std::uint32_t> solvedContacts;  // the contacts in the batches, in solve order

  void prepare(std::vector<Contact>& contacts, const BodyStorage& storage,
               const std::vector<SolverBody>& bodies, const std::vector<SolverBodyInfo>& infos,
               const std::vector<std::int32_t>& solverOf, const ContactSolverSettings& settings, float h);
  // Per substep: apply the accumulated impulses.
  void warmStart(std::vector<SolverBody>& bodies);
  // Per substep: one pass; useBias = false is the relax pass.
  void solve(std::vector<SolverBody>& bodies, float h, bool useBias);
  // Once at the end: Newton's restitution from the approach velocity taken in prepare().
  void applyRestitution(std::vector<SolverBody>& bodies);
  // The impulses back into the contacts (warm starting next step, events, response models).
  void store(std::vector<Contact>& contacts) const;

 private:
  template <bool useBias>
  void solvePass(std::vector<SolverBody>& bodies, float h);

  float pushOutSpeed_ = 3.0f;
  float restitutionThreshold_ = 1.0f;
  float anchorReach_ = 0.02f;
  // Colouring scratch (constraint_graph.h).
  std::vector<std::array<std::int32_t, 2>> writtenBodies_;
  std::vector<std::uint64_t> colorBits_;
  std::vector<std::uint32_t> order_;
  std::vector<std::uint8_t> colorOf_;
};

}  // namespace collide::detail
