// The step's solve: solver bodies, the substep loop, the write-back (solver.h).
#include "dynamics/solver.h"

#include "dynamics/fault_guard.h"
#include "dynamics/integrate.h"
#include "memory/heap_bytes.h"
#include "simd/simd.h"

#include <algorithm>
#include <cmath>

namespace collide::detail {

namespace {

std::atomic<bool> solveInBlocks{true};
std::atomic<std::uint32_t> lastBlockCount{0};

bool finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool finite(const Quat& q) {
  return std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z) && std::isfinite(q.w);
}

}  // namespace

void setSolveInBlocks(bool enabled) { solveInBlocks.store(enabled, std::memory_order_relaxed); }
std::uint32_t lastSolveBlockCount() { return lastBlockCount.load(std::memory_order_relaxed); }

// In two parallel walks over fixed chunks of bodies: the first counts each chunk's moving bodies
// (and keeps every body's pose at the step start), the second writes them from their chunk's
// offset. The solver bodies come out in body order, whatever the split.
void StepSolver::gatherBodies(BodyStorage& storage, const Vec3& gravity, bool withStarts, TaskRunner& tasks) {
  const std::uint32_t n = static_cast<std::uint32_t>(storage.states.size());
  const std::uint32_t chunks = (n + kBodiesPerRange - 1) / kBodiesPerRange;
  const auto moves = [&](std::uint32_t i) {
    const BodyRecord& r = storage.records[i];
    return r.alive && r.type != BodyType::Static && r.awake;
  };
  solverOf_.resize(n);
  chunkStart_.resize(chunks + 1);
  chunkStart_[0] = 0;
  tasks.parallelFor(chunks, 1, [&](std::uint32_t begin, std::uint32_t end, std::uint32_t) {
    for (std::uint32_t c = begin; c < end; ++c) {
      std::uint32_t count = 0;
      for (std::uint32_t i = c * kBodiesPerRange; i < std::min(n, (c + 1) * kBodiesPerRange); ++i) {
        BodyState& s = storage.states[i];
        s.centerOfMass0 = s.centerOfMass;
        s.rotation0 = s.rotation;
        count += moves(i) ? 1 : 0;
      }
      chunkStart_[c + 1] = count;
    }
  });
  for (std::uint32_t c = 0; c < chunks; ++c) chunkStart_[c + 1] += chunkStart_[c];
  const std::uint32_t total = chunkStart_[chunks];
  // Resized, not cleared: the elements of the last step are written over, not constructed first.
  bodies_.resize(total);
  infos_.resize(total);
  starts_.resize(withStarts ? total : 0);
  tasks.parallelFor(chunks, 1, [&](std::uint32_t begin, std::uint32_t end, std::uint32_t) {
    for (std::uint32_t c = begin; c < end; ++c) {
      std::uint32_t j = chunkStart_[c];
      for (std::uint32_t i = c * kBodiesPerRange; i < std::min(n, (c + 1) * kBodiesPerRange); ++i) {
        if (!moves(i)) {
          solverOf_[i] = kNoSolverBody;
          continue;
        }
        const BodyState& s = storage.states[i];
        const BodyRecord& r = storage.records[i];
        solverOf_[i] = static_cast<std::int32_t>(j);
        if (withStarts) starts_[j] = {s.centerOfMass0, s.rotation0};
        SolverBody& body = bodies_[j];
        body = SolverBody{};
        body.linearVelocity = s.linearVelocity;
        body.angularVelocity = s.angularVelocity;
        SolverBodyInfo& info = infos_[j];
        info = SolverBodyInfo{};
        info.body = i;
        info.dynamic = r.type == BodyType::Dynamic;
        info.particle = r.particle;
        if (info.dynamic) {
          info.inverseMass = s.inverseMass;
          info.inverseInertiaWorld = s.inverseInertiaWorld;
          info.linearAcceleration = r.gravityScale * gravity + info.inverseMass * r.force;
          info.linearDamping = r.linearDamping;
          info.angularDamping = r.particle ? 0.0f : r.angularDamping;
          info.angularAcceleration = info.inverseInertiaWorld * r.torque;
          info.gyroscopic = !r.particle && !r.isotropicInertia;
        }
        ++j;
      }
    }
  });
}

// The guard inside the step: a solver body with a non-finite part is stopped where the step began
// (its solver state back to rest, unmoved) before its value reaches another body, and frozen and
// reported at the end of the solve (fault_guard.h).
void StepSolver::guard(std::span<const std::uint32_t> which) {
  for (const std::uint32_t j : which) {
    SolverBodyInfo& info = infos_[j];
    if (info.faulted) continue;
    SolverBody& b = bodies_[j];
    // x * 0 is 0 for every finite x and NaN otherwise: one sum tells whether all sixteen floats
    // (the pads are 0) are finite, and only a bad body pays for the field-by-field look.
    const float* f = reinterpret_cast<const float*>(&b);
    const FloatW zero = zeroW();
    const FloatW sum = (loadW(f) * zero + loadW(f + 4) * zero) + (loadW(f + 8) * zero + loadW(f + 12) * zero);
    if (!anyW(notEqualW(sum, zero))) continue;
    std::uint8_t fields = 0;
    if (!finite(b.deltaPosition)) fields |= FaultEvent::kPosition;
    if (!finite(b.deltaRotation)) fields |= FaultEvent::kRotation;
    if (!finite(b.linearVelocity)) fields |= FaultEvent::kLinearVelocity;
    if (!finite(b.angularVelocity)) fields |= FaultEvent::kAngularVelocity;
    if (fields == 0) continue;
    info.faulted = true;
    faultFields_[j] = fields;
    b = SolverBody{};
    stoppedABody_.store(true, std::memory_order_relaxed);
  }
}

void StepSolver::writeBack(BodyStorage& storage, Array<FaultEvent>& faults, TaskRunner& tasks) {
  tasks.parallelFor(static_cast<std::uint32_t>(bodies_.size()), kBodiesPerRange,
                    [&](std::uint32_t begin, std::uint32_t end, std::uint32_t) {
                      for (std::size_t j = begin; j < end; ++j) {
                        const SolverBodyInfo& info = infos_[j];
                        if (info.faulted) continue;
                        const BodyRecord& r = storage.records[info.body];
                        BodyState& s = storage.states[info.body];
                        const SolverBody& b = bodies_[j];
                        s.centerOfMass = s.centerOfMass0 + b.deltaPosition;
                        if (!info.particle) s.rotation = glm::normalize(b.deltaRotation * s.rotation0);
                        s.linearVelocity = b.linearVelocity;
                        s.angularVelocity = b.angularVelocity;
                        if (info.dynamic)
                          s.inverseInertiaWorld = worldInverseInertia(r.inverseInertiaLocal, s.rotation);
                      }
                    });
  // The bodies the guard stopped, in solver order (one byte each to look at).
  for (std::size_t j = 0; j < bodies_.size(); ++j) {
    if (faultFields_[j] == 0) continue;
    const SolverBodyInfo& info = infos_[j];
    BodyRecord& r = storage.records[info.body];
    freezeBody(r, storage.states[info.body]);
    faults.push_back({BodyId{info.body, r.generation}, faultFields_[j]});
  }
}

void StepSolver::solve(BodyStorage& storage, Array<Contact>& contacts, Array<Joint>& joints,
                       const StepSettings& settings, float dt, Array<FaultEvent>& faults, TaskRunner& tasks) {
  const float h = dt / static_cast<float>(settings.substeps);
  gatherBodies(storage, settings.gravity, !joints.empty(), tasks);
  faultFields_.assign(bodies_.size(), 0);
  stoppedABody_.store(false, std::memory_order_relaxed);
  JointSolverView view{bodies_, infos_, starts_, solverOf_, storage, &jointTree_};
  prepareJoints(view, joints);
  // The projection response has a pass over the whole world of its own: one block then.
  const bool inBlocks = !settings.projection && solveInBlocks.load(std::memory_order_relaxed);
  if (inBlocks) {
    // The joints' islands, which their passes over the world take together (one block).
    blocks_.begin(static_cast<std::uint32_t>(bodies_.size()));
    for (const Joint& joint : joints)
      if (joint.active) blocks_.joinJoint(solverOf_[joint.bodyA], solverOf_[joint.bodyB]);
  }
  ContactSolverSettings contactSettings;
  contactSettings.tuning = settings.tuning;
  contactSettings.friction = settings.friction;
  contactSettings.gravity = settings.gravity;
  jointWaves_.prepare(view, joints);
  jointTree_.prepare(view, joints);
  // The contacts meet a joint tree's bodies with the inertia the tree solves them with.
  jointTree_.buildStartRows(view, joints, h, tasks);
  jointTree_.swapInverseInertia(infos_);
  contacts_.prepare(contacts, storage, bodies_, infos_, solverOf_, contactSettings,
                    inBlocks ? &blocks_ : nullptr, h, tasks);
  jointTree_.swapInverseInertia(infos_);
  if (settings.projection)
    projection_.prepare(contacts, contacts_.solvedContacts(), solverOf_, infos_, storage);
  jointWaves_.plan(joints);
  const Substeps loop{storage, view, joints, settings, h};
  if (inBlocks) {
    // The joints' block and the large islands one after another, each on every worker; the blocks
    // of small islands a worker each. No block reads what another writes, so the order they run in
    // changes nothing.
    const std::uint32_t blockCount = blocks_.count();
    lastBlockCount.store(blockCount, std::memory_order_relaxed);
    const auto ownThread = [&](std::uint32_t b) { return blocks_.large(b) || blocks_.jointed(b); };
    for (std::uint32_t b = 0; b < blockCount; ++b)
      if (ownThread(b)) substeps(loop, b, blocks_.bodies(b), blocks_.jointed(b), tasks);
    tasks.parallelFor(blockCount, 1, [&](std::uint32_t begin, std::uint32_t end, std::uint32_t) {
      for (std::uint32_t b = begin; b < end; ++b)
        if (!ownThread(b)) substeps(loop, b, blocks_.bodies(b), false, inline_);
    });
  } else {
    lastBlockCount.store(1, std::memory_order_relaxed);
    allBodies_.resize(bodies_.size());
    for (std::uint32_t j = 0; j < allBodies_.size(); ++j) allBodies_[j] = j;
    substeps(loop, 0, allBodies_, !joints.empty(), tasks);
  }
  jointWaves_.finish(joints);
  contacts_.store(contacts, tasks);
  writeBack(storage, faults, tasks);
}

// The substep loop and the restitution over the bodies and contacts of one block, with the joints'
// passes where it holds the joints.
void StepSolver::substeps(const Substeps& loop, std::uint32_t block, std::span<const std::uint32_t> bodies,
                          bool withJoints, TaskRunner& tasks) {
  const StepSettings& settings = loop.settings;
  const float h = loop.h;
  const JointSolverView& view = loop.view;
  Array<Joint>& joints = loop.joints;
  const auto overBodies = [&](auto&& f) {
    tasks.parallelFor(static_cast<std::uint32_t>(bodies.size()), kBodiesPerRange,
                      [&](std::uint32_t begin, std::uint32_t end, std::uint32_t) {
                        f(bodies.subspan(begin, end - begin));
                      });
  };
  // Box2D v3: rigid joints correct at twice the contact stiffness, within the solver's cap (a
  // joint past it made a net draped over a ball shiver instead of sleeping).
  const float rigidHertz = std::min(2.0f * settings.tuning.hertz, kMaxHertzPerSubstepRate / h);
  for (int i = 0; i < settings.substeps; ++i) {
    overBodies([&](std::span<const std::uint32_t> which) {
      // The previous substep's closing guard, in the same walk over the bodies: each body's sequence
      // (guard, integrate, guard) is unchanged, and a large world's bodies are read once, not twice.
      if (i > 0) guard(which);
      integrateVelocities(bodies_, infos_, loop.storage, h, which);
      guard(which);  // before a bad velocity reaches a contact
    });
    if (withJoints) {
      // A body the guard stopped went back to the step's start: rows built since are off its pose.
      if (stoppedABody_.load(std::memory_order_relaxed)) jointTree_.posesMoved();
      jointWaves_.warmStart(view, joints, tasks);
      jointTree_.warmStart(view, joints, h, tasks);
    }
    if (withJoints) {
      contacts_.warmStart(bodies_, block, tasks);
      jointWaves_.solve(view, joints, h, rigidHertz, true, tasks);
      jointTree_.solve(view, joints, h, rigidHertz, true, tasks);
      contacts_.solve(bodies_, h, true, block, tasks);
    } else {
      contacts_.warmStartAndSolve(bodies_, h, block, tasks);
    }
    overBodies([&](std::span<const std::uint32_t> which) { integratePositions(bodies_, infos_, h, which); });
    if (settings.projection) projection_.project(bodies_, settings.tuning.linearSlop);
    if (withJoints) {
      jointTree_.posesMoved();
      jointTree_.project(view, joints, tasks);
      if (projectJoints(view, joints, jointWaves_.distanceJoints())) jointTree_.posesMoved();
      jointWaves_.solve(view, joints, h, rigidHertz, false, tasks);
      jointTree_.solve(view, joints, h, rigidHertz, false, tasks);
    }
    for (int pass = 0; pass < settings.relaxPasses; ++pass) contacts_.solve(bodies_, h, false, block, tasks);
  }
  // The last substep's guard (the others' run with the next substep's integration).
  if (settings.substeps > 0) overBodies([&](std::span<const std::uint32_t> which) { guard(which); });
  contacts_.applyRestitution(bodies_, block, tasks);
  overBodies([&](std::span<const std::uint32_t> which) { guard(which); });
}

std::size_t StepSolver::memoryBytes() const {
  return heapBytes(bodies_) + heapBytes(infos_) + heapBytes(starts_) + heapBytes(solverOf_) +
         heapBytes(faultFields_) + heapBytes(allBodies_) + heapBytes(chunkStart_) + blocks_.memoryBytes() +
         contacts_.memoryBytes() + projection_.memoryBytes();
}

}  // namespace collide::detail
