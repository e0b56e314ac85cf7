// One step's solve (Box2D v3's solver.c), between the narrow phase and the response models:
//   1. solver bodies for the awake dynamic and the kinematic bodies (solver_body.h), the contact
//      batches (contact_solver.h) and the joints' frames;
//   2. per substep (h = dt / substeps): integrate velocities (gravity, forces, the gyroscopic term)
//      -> fault guard -> warm start joints and contacts -> solve both with the soft position bias ->
//      integrate positions -> relax both without it -> fault guard;
//   3. restitution, the impulses back into the contacts, the new poses and velocities back into the
//      body storage (inertia refreshed), and bodies the guard stopped frozen and reported.
// Each block of islands (solver_blocks.h) runs step 2 and the restitution on its own: the blocks
// of a few hundred contacts in parallel, a worker each; a larger island, and the islands with
// joints, on every worker, colour by colour. The result is the same as one loop over the world,
// which the projection response (a pass over the whole world of its own) still takes.
// Joints go before contacts in each pass, so contacts (the stiffer, one-sided constraints) have the
// last word on penetration: first the joints' Gauss-Seidel rows (springs, motors, limits, and the
// joints no tree takes; in waves, joint_solver.h), then the rigid rows of joint trees, solved
// directly (joint_tree.h).
#pragma once

#include "base/task_runner.h"
#include "bodies/body_storage.h"
#include "contacts/contact_cache.h"
#include "dynamics/contact_projection.h"
#include "dynamics/contact_solver.h"
#include "dynamics/joint_solver.h"
#include "dynamics/joint_tree.h"
#include "dynamics/solver_blocks.h"
#include "dynamics/solver_body.h"

#include <collide/events.h>
#include <collide/settings.h>

#include <atomic>
#include <cstdint>
#include <span>
#include <vector>

namespace collide::detail {

struct StepSettings {
  Vec3 gravity{0.0f};
  int substeps = 4;
  int relaxPasses = 1;
  ContactTuning tuning;
  bool friction = true;     // Coulomb friction in the solver (off under the viscous and damping models)
  bool projection = false;  // PenetrationResponse::Project (contact_projection.h)
};

// For tests and benchmarks: whether worlds solve in blocks of islands where they can (the default)
// or always as one block, which gives the same result; and how many blocks the last solve of any
// world ran.
void setSolveInBlocks(bool enabled);
std::uint32_t lastSolveBlockCount();

// Solver bodies a parallel range takes at least (integration, the fault guard, the write-back); the
// pool lengthens ranges to about two per worker. 256 lets two workers share the 466 bodies of the
// pyramid (R3), whose integration ran on one worker in ranges of 1,024; a range's hand-over (a few
// hundred ns) stays small beside 256 bodies' work.
inline constexpr std::uint32_t kBodiesPerRange = 256;

class StepSolver {
 public:
  void solve(BodyStorage& storage, Array<Contact>& contacts, Array<Joint>& joints,
             const StepSettings& settings, float dt, Array<FaultEvent>& faults, TaskRunner& tasks);

  // The contacts the last solve took, in solve order (the response models and revert walk them).
  const Array<std::uint32_t>& solvedContacts() const { return contacts_.solvedContacts(); }

  // World::memoryUse: the solver bodies, contact batches and projection; the joints' waves and trees apart.
  std::size_t memoryBytes() const;
  std::size_t jointMemoryBytes() const { return jointWaves_.memoryBytes() + jointTree_.memoryBytes(); }

 private:
  // withStarts: the bodies' start poses too (starts_), which the joints read.
  void gatherBodies(BodyStorage& storage, const Vec3& gravity, bool withStarts, TaskRunner& tasks);
  // What the substep loop of every block reads.
  struct Substeps {
    BodyStorage& storage;
    const JointSolverView& view;
    Array<Joint>& joints;
    const StepSettings& settings;
    float h;
  };
  // Step 2 and the restitution for the bodies and contacts of one block, with the joints' passes
  // where the block holds the joints.
  void substeps(const Substeps& loop, std::uint32_t block, std::span<const std::uint32_t> bodies,
                bool withJoints, TaskRunner& tasks);
  void writeBack(BodyStorage& storage, Array<FaultEvent>& faults, TaskRunner& tasks);
  // Over the listed solver bodies (each body's own state).
  void guard(std::span<const std::uint32_t> which);

  Array<SolverBody> bodies_;
  Array<SolverBodyInfo> infos_;
  Array<SolverBodyStart> starts_;    // with joints only
  Array<std::int32_t> solverOf_;     // body index -> solver body, kNoSolverBody if none
  Array<std::uint32_t> chunkStart_;  // gatherBodies: chunk c's first solver body
  Array<std::uint8_t> faultFields_;
  // The guard stopped a body this step (its pose went back to the step's start).
  std::atomic<bool> stoppedABody_{false};
  SolverBlocks blocks_;
  Array<std::uint32_t> allBodies_;  // 0, 1, ... every solver body (the solve as one block)
  TaskRunner inline_;               // runs a block on the worker that took it
  ContactSolver contacts_;
  ContactProjection projection_;
  JointWaves jointWaves_;
  JointTree jointTree_;
};

}  // namespace collide::detail
