// The soft-step contact solver (Catto, "Solver2D" 2024 and Box2D v3's contact_solver.c), written for
// 3D and four or eight lanes wide. Per step, prepare() turns the contacts into batches of manifolds
// that share no dynamic body (constraint_graph.h colours them), so a batch is solved in SIMD lanes
// exactly as sequential solves would be (contact_lanes.h has the kernels). Per substep: warm start, solve
// with the soft position bias, (integrate positions), relax without it. At the end: restitution, and the
// impulses go back to the contacts for warm starting and events.
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

#include "base/task_runner.h"
#include "bodies/body_storage.h"
#include "contacts/contact_cache.h"
#include "dynamics/constraint_graph.h"
#include "dynamics/solver_blocks.h"
#include "dynamics/solver_body.h"
#include "dynamics/support_masses.h"

#include <collide/settings.h>

#include <array>
#include <cstdint>
#include <memory>
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

struct ContactSolverSettings {
  ContactTuning tuning;
  bool friction = true;  // Coulomb friction (off under the viscous and damping models)
  Vec3 gravity{0.0f};    // "up" for the support masses
};

// What the lane kernels need to build their batches: the contacts to solve, ordered by block of
// islands (solver_blocks.h), then by colour within a block, and the step's bodies and settings.
// Segment s = block * kColorSegments + colour holds order[segmentStart(s) .. segmentStart(s + 1))
// (the overflow colour last in each block).
inline constexpr int kColorSegments = kGraphColors + 1;
struct ContactBatchInput {
  Array<Contact>& contacts;
  const Array<std::uint32_t>& order;
  std::uint32_t blockCount;
  // Within segment s (but an overflow one), order[countStart[s * kMaxPoints + 4 - n], ... + 1) are
  // the contacts of n points: a batch's first contact has the most points of its lanes.
  const Array<std::uint32_t>& countStart;
  const BodyStorage& storage;
  const Array<SolverBody>& bodies;
  const Array<SolverBodyInfo>& infos;
  const Array<std::int32_t>& solverOf;
  Softness softness;
  Softness oneWaySoftness;
  bool friction = true;
  float anchorReach = 0.0f;
  float pushOutSpeed = 0.0f;
  float restitutionThreshold = 0.0f;
  const SupportMasses* supportMasses = nullptr;  // scales on the bodies' masses, if any (support_masses.h)

  std::uint32_t segmentStart(std::uint32_t segment) const {
    return countStart[segment * Manifold::kMaxPoints];
  }
};

// The kernels of one lane width (contact_lanes.h): batches of that many manifolds, and the passes.
class ContactLanes {
 public:
  virtual ~ContactLanes() = default;
  virtual int width() const = 0;
  // Each takes its batches in parallel ranges, a colour at a time (tasks: the step's workers); the
  // passes take those of one block of islands.
  virtual void build(const ContactBatchInput& input, TaskRunner& tasks) = 0;
  virtual void warmStart(Array<SolverBody>& bodies, std::uint32_t block, TaskRunner& tasks) = 0;
  virtual void solve(Array<SolverBody>& bodies, float h, bool useBias, std::uint32_t block,
                     TaskRunner& tasks) = 0;
  // warmStart then solve with useBias, bit for bit, with nothing between them.
  virtual void warmStartAndSolve(Array<SolverBody>& bodies, float h, std::uint32_t block,
                                 TaskRunner& tasks) = 0;
  virtual void applyRestitution(Array<SolverBody>& bodies, std::uint32_t block, TaskRunner& tasks) = 0;
  virtual void store(Array<Contact>& contacts, TaskRunner& tasks) const = 0;
  virtual std::size_t memoryBytes() const = 0;
};

// The widest lanes this machine runs: 8 where the AVX2 kernel is built and the processor has AVX2,
// else 4. Every width gives the same result, bit for bit.
int widestContactLanes();
// For tests and benchmarks: the width a ContactSolver made with laneWidth 0 takes from now on (0:
// the widest again). Worlds created afterwards use it.
void setDefaultContactLanes(int laneWidth);

// Once per step: the enabled, awake, non-sensor contacts with points, coloured (constraint_graph.h:
// the contacts of a colour share no dynamic body) and handed to the lane kernels in batches; then the
// passes of the substep loop. The vectors are reused across steps: no allocation after warm-up.
class ContactSolver {
 public:
  // laneWidth 4 or 8; 0 for the widest this machine runs. Throws Error for a width it cannot run.
  explicit ContactSolver(int laneWidth = 0);
  ~ContactSolver();
  ContactSolver(ContactSolver&&) noexcept;
  ContactSolver& operator=(ContactSolver&&) noexcept;

  int laneWidth() const { return lanes_->width(); }
  // The contacts in the batches, in solve order (the response models and revert walk them).
  const Array<std::uint32_t>& solvedContacts() const { return solvedContacts_; }

  // blocks: the step's blocks of islands, begun by the caller (its joints joined); the contacts
  // taken join their islands here and the blocks are finished. Null for one block of every contact.
  void prepare(Array<Contact>& contacts, const BodyStorage& storage, const Array<SolverBody>& bodies,
               const Array<SolverBodyInfo>& infos, const Array<std::int32_t>& solverOf,
               const ContactSolverSettings& settings, SolverBlocks* blocks, float h, TaskRunner& tasks);
  // Per substep, the contacts of one block: apply the accumulated impulses.
  void warmStart(Array<SolverBody>& bodies, std::uint32_t block, TaskRunner& tasks) {
    lanes_->warmStart(bodies, block, tasks);
  }
  // Per substep, where no joint's pass comes between them: warmStart and then the biased pass,
  // bit for bit, the warm start's last colour and the pass's first taken together.
  void warmStartAndSolve(Array<SolverBody>& bodies, float h, std::uint32_t block, TaskRunner& tasks) {
    lanes_->warmStartAndSolve(bodies, h, block, tasks);
  }
  // Per substep: one pass; useBias = false is the relax pass.
  void solve(Array<SolverBody>& bodies, float h, bool useBias, std::uint32_t block, TaskRunner& tasks) {
    lanes_->solve(bodies, h, useBias, block, tasks);
  }
  // Once at the end: Newton's restitution from the approach velocity taken in prepare().
  void applyRestitution(Array<SolverBody>& bodies, std::uint32_t block, TaskRunner& tasks) {
    lanes_->applyRestitution(bodies, block, tasks);
  }
  // The impulses back into the contacts (warm starting next step, events, response models).
  void store(Array<Contact>& contacts, TaskRunner& tasks) const { lanes_->store(contacts, tasks); }

  std::size_t memoryBytes() const;  // the batches, the colouring and support scratch (World::memoryUse)

 private:
  std::unique_ptr<ContactLanes> lanes_;
  SupportMasses supportMasses_;
  Array<std::uint32_t> solvedContacts_;
  // Colouring scratch (constraint_graph.h).
  Array<std::array<std::int32_t, 2>> writtenBodies_;
  Array<std::uint64_t> colorBits_;
  Array<std::uint32_t> order_;
  Array<std::uint8_t> colorOf_;
  // Per solved contact its block (its solver body on one side until the blocks are known); per
  // (block, colour, point count) bucket its start in the order.
  Array<std::uint32_t> blockOf_;
  // Per solved contact its manifold's points, read by the scan: the sort below would otherwise
  // read each contact's record again, long out of the cache in a large world.
  Array<std::uint8_t> pointCounts_;
  Array<std::uint32_t> bucketStart_;
  Array<std::uint32_t> countStart_;
};

}  // namespace collide::detail
