// The first stage of the step: every movable body's world box, and its broad-phase proxy (lecture:
// bounding volumes, the conservative early reject). A proxy's box is the body's box grown by the
// speculative distance and by what the body can move within the step, so that the broad phase
// finds a pair before its bodies meet (speculative contacts need the pair in advance).
#pragma once

#include <collide/broadphase.h>
#include <collide/math.h>

#include "base/task_runner.h"
#include "bodies/body_storage.h"

#include <cstdint>
#include <vector>

namespace collide::detail {

// How far any point of the body can have moved between two poses: the centre's move plus the turn
// angle times the body's bounding radius about its centre of mass.
float pointMotionBound(const BodyRecord& record, const Vec3& com0, const Quat& q0, const Vec3& com1,
                       const Quat& q1);

// A box with both sides kept within +-1e30, the planes' "infinite" extent (NaN to the far side):
// what the broad phase takes and is asked about, whatever a finite state overflowed to.
Aabb withinFloatRange(Aabb box);

// The body's world box computed anew from its shape and pose, and kept with that pose.
Aabb recomputeBounds(BodyStorage& bodies, std::uint32_t index);
// The body's world box: its last computed box grown by how far it can have moved since, while that
// is small (a resting hull need not transform all its vertices again), else computed anew.
Aabb currentBounds(BodyStorage& bodies, std::uint32_t index);
// The box the body's proxy gets: currentBounds grown by the speculative distance and by the motion
// of a step of dt at the body's velocities (dt 0 between steps).
Aabb proxyBounds(BodyStorage& bodies, std::uint32_t index, float dt, float speculativeDistance);

// The stage: the proxy of every awake movable body takes its box for the step of dt. The boxes are
// computed in parallel, in ranges of bodies (each body's reads and writes are its own); the broad
// phase is then told of them one body after another in body order, as its structure changes with
// each move, so the result is the same at every worker count.
class ProxyUpdate {
 public:
  void run(BodyStorage& bodies, BroadPhase& broadPhase, float dt, float speculativeDistance,
           TaskRunner& tasks);

  // After the solve: a body that an impulse (a hit, a constraint) carried out of the box the step
  // predicted for it gets a box where it is now, since the queries between steps (castRay) read
  // these boxes. The next step updates every awake body's box anyway, so no pair depends on this.
  // Parallel and then in body order, as run.
  void refreshEscaped(BodyStorage& bodies, BroadPhase& broadPhase, float speculativeDistance,
                      TaskRunner& tasks);

  std::size_t memoryBytes() const;  // the scratch (World::memoryUse)
  void reserve(std::size_t bodies) {  // World::reserveBodies
    boxes_.reserve(bodies);
    updated_.reserve(bodies);
  }

 private:
  // Resizes the scratch, has fillRange(begin, end) set updated_ and boxes_ for parallel ranges of
  // bodies, then tells the broad phase of every updated proxy in body order.
  template <typename FillRange>
  void updateInBodyOrder(BodyStorage& bodies, BroadPhase& broadPhase, TaskRunner& tasks,
                         std::uint32_t bodiesPerRange, FillRange&& fillRange);

  Array<Aabb> boxes_;            // per body, the proxy's box for the step where updated_
  Array<std::uint8_t> updated_;  // per body: 1 if its proxy is updated this step
};

}  // namespace collide::detail
