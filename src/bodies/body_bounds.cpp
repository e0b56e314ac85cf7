// World boxes and broad-phase proxies of the bodies: the step's first stage (body_bounds.h).
#include "bodies/body_bounds.h"

#include "memory/heap_bytes.h"
#include "memory/prefetch.h"
#include "shapes/shape_functions.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace collide::detail {

// A finite state can still give an infinite box (a large shape turning fast, a body at 1e38 m
// moving on), which the broad phase refuses: both sides are kept within the planes' "infinite"
// extent, +-1e30 (NaN goes to the far side). Nothing that far matters to a contact any more; the
// broad phase keeps working, and the fault guard contains the body.
Aabb withinFloatRange(Aabb box) {
  static constexpr float kFar = 1e30f;
  const auto clampFar = [](float v, float ifNaN) {
    return std::isnan(v) ? ifNaN : std::clamp(v, -kFar, kFar);
  };
  for (int axis = 0; axis < 3; ++axis) {
    box.min[axis] = clampFar(box.min[axis], -kFar);
    box.max[axis] = clampFar(box.max[axis], kFar);
  }
  return box;
}

namespace {

// A body's world box is recomputed once any of its points may have moved this far (m) since the box
// was computed; until then the old box grown by the possible motion stands in (conservative).
constexpr float kBoundsReuseDistance = 0.002f;

// Whether the body's last box still serves, grown by `moved` (set then).
bool boundsReusable(const BodyStorage& bodies, std::uint32_t index, float& moved) {
  const BodyRecord& r = bodies.records[index];
  if (!r.boundsValid || r.type == BodyType::Static) return false;
  const BodyState& s = bodies.states[index];
  moved = pointMotionBound(r, r.boundsCenter, r.boundsRotation, s.centerOfMass, s.rotation);
  return moved <= kBoundsReuseDistance;
}

// The body's box as its proxy's: grown by the step's motion and the speculative distance.
Aabb grownForStep(const BodyStorage& bodies, std::uint32_t index, float dt, float speculativeDistance,
                  Aabb box) {
  const BodyRecord& r = bodies.records[index];
  const BodyState& s = bodies.states[index];
  if (r.type == BodyType::Static) return withinFloatRange(box);
  const Vec3 motion = dt * s.linearVelocity;
  box.min = glm::min(box.min, box.min + motion);
  box.max = glm::max(box.max, box.max + motion);
  const float turn = dt * glm::length(s.angularVelocity) * r.boundingRadius;
  return withinFloatRange(box.expanded(speculativeDistance + turn));
}

// What ProxyUpdate decides for a body: is its proxy updated, and is its box grown from the last
// one or computed anew.
struct BoxVerdict {
  bool updated = false;
  bool reusable = false;
  float moved = 0.0f;
};

// A box computed anew reads the body's shape data, which lies anywhere in memory (a hull's header,
// then its vertex arrays). Each body's verdict is taken kAhead places before its turn, where a box
// to compute anew has its shape's header asked for, and its arrays half-way; the verdicts wait in a
// ring until their turn.
class BoxVerdicts {
 public:
  static constexpr std::uint32_t kAhead = 16;

  // For the bodies [begin, end), taken in order.
  BoxVerdicts(const BodyStorage& bodies, std::uint32_t begin, std::uint32_t end)
      : bodies_(bodies), end_(end) {
    for (std::uint32_t i = begin; i < std::min(begin + kAhead, end_); ++i) judge(i);
  }

  // Body i's verdict; judges body i + kAhead and asks for the arrays of body i + kAhead / 2.
  BoxVerdict take(std::uint32_t i) {
    const BoxVerdict v = ring_[i % kAhead];
    if (i + kAhead < end_) judge(i + kAhead);
    if (const std::uint32_t half = i + kAhead / 2; half < end_) {
      const BoxVerdict& w = ring_[half % kAhead];
      if (w.updated && !w.reusable) prefetchShapeArrays(bodies_.records[half].shape);
    }
    return v;
  }

 private:
  void judge(std::uint32_t i) {
    const BodyRecord& r = bodies_.records[i];
    BoxVerdict v;
    v.updated = r.alive && r.type != BodyType::Static && r.awake;
    if (v.updated) v.reusable = boundsReusable(bodies_, i, v.moved);
    if (v.updated && !v.reusable) prefetchShapeHeader(r.shape);
    ring_[i % kAhead] = v;
  }

  const BodyStorage& bodies_;
  std::uint32_t end_;
  std::array<BoxVerdict, kAhead> ring_;
};

}  // namespace

// The turn angle is 2 asin |vector part of the turn|, at most pi times that |vector part|.
float pointMotionBound(const BodyRecord& record, const Vec3& com0, const Quat& q0, const Vec3& com1,
                       const Quat& q1) {
  const Quat turn = q1 * glm::conjugate(q0);
  return glm::length(com1 - com0) + kPi * glm::length(Vec3(turn.x, turn.y, turn.z)) * record.boundingRadius;
}

Aabb recomputeBounds(BodyStorage& bodies, std::uint32_t index) {
  BodyRecord& r = bodies.records[index];
  const BodyState& s = bodies.states[index];
  r.bounds = worldBounds(r.shape, bodyTransform(r, s));
  r.boundsCenter = s.centerOfMass;
  r.boundsRotation = s.rotation;
  r.boundsValid = true;
  return r.bounds;
}

Aabb currentBounds(BodyStorage& bodies, std::uint32_t index) {
  float moved = 0.0f;
  if (boundsReusable(bodies, index, moved)) return bodies.records[index].bounds.expanded(moved);
  return recomputeBounds(bodies, index);
}

Aabb proxyBounds(BodyStorage& bodies, std::uint32_t index, float dt, float speculativeDistance) {
  return grownForStep(bodies, index, dt, speculativeDistance, currentBounds(bodies, index));
}

template <typename FillRange>
void ProxyUpdate::updateInBodyOrder(BodyStorage& bodies, BroadPhase& broadPhase, TaskRunner& tasks,
                                    std::uint32_t bodiesPerRange, FillRange&& fillRange) {
  const auto count = static_cast<std::uint32_t>(bodies.records.size());
  boxes_.resize(count);
  updated_.resize(count);
  tasks.parallelFor(count, bodiesPerRange,
                    [&](std::uint32_t begin, std::uint32_t end, std::uint32_t) { fillRange(begin, end); });
  for (std::uint32_t i = 0; i < count; ++i) {
    if (updated_[i] != 0) broadPhase.update(bodies.records[i].proxy, boxes_[i]);
  }
}

void ProxyUpdate::run(BodyStorage& bodies, BroadPhase& broadPhase, float dt, float speculativeDistance,
                      TaskRunner& tasks) {
  // A range's boxes cost from a few ns (a box grown from the last) to a few hundred (a hull's
  // vertices transformed): ranges of this many bodies keep the task overhead small beside them.
  constexpr std::uint32_t kBodiesPerRange = 256;
  updateInBodyOrder(bodies, broadPhase, tasks, kBodiesPerRange, [&](std::uint32_t begin, std::uint32_t end) {
    BoxVerdicts verdicts(bodies, begin, end);
    for (std::uint32_t i = begin; i < end; ++i) {
      const BoxVerdict v = verdicts.take(i);
      updated_[i] = v.updated ? 1 : 0;
      if (!v.updated) continue;
      const Aabb box = v.reusable ? bodies.records[i].bounds.expanded(v.moved) : recomputeBounds(bodies, i);
      boxes_[i] = grownForStep(bodies, i, dt, speculativeDistance, box);
      // Most boxes stay inside the broad phase's margin: stored here, on the workers; the serial
      // walk after the ranges updates the rest, in body order.
      if (broadPhase.updateInPlace(bodies.records[i].proxy, boxes_[i])) updated_[i] = 0;
    }
  });
}

void ProxyUpdate::refreshEscaped(BodyStorage& bodies, BroadPhase& broadPhase, float speculativeDistance,
                                 TaskRunner& tasks) {
  constexpr std::uint32_t kBodiesPerRange = 1024;
  updateInBodyOrder(bodies, broadPhase, tasks, kBodiesPerRange, [&](std::uint32_t begin, std::uint32_t end) {
    for (std::uint32_t i = begin; i < end; ++i) {
      updated_[i] = 0;
      const BodyRecord& r = bodies.records[i];
      if (!r.alive || r.type == BodyType::Static || !r.awake) continue;
      // The step's box was grown by at least the speculative distance all round: a body whose
      // points moved less than that since the step began is still inside it.
      const BodyState& s = bodies.states[i];
      if (pointMotionBound(r, s.centerOfMass0, s.rotation0, s.centerOfMass, s.rotation) < speculativeDistance)
        continue;
      const Aabb now = currentBounds(bodies, i);
      if (broadPhase.bounds(r.proxy).contains(now)) continue;
      boxes_[i] = proxyBounds(bodies, i, 0.0f, speculativeDistance);
      updated_[i] = 1;
    }
  });
}

std::size_t ProxyUpdate::memoryBytes() const { return heapBytes(boxes_) + heapBytes(updated_); }

}  // namespace collide::detail
