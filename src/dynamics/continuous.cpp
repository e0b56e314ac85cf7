// The continuous pass (see continuous.h and docs/ccd.md).
#include "dynamics/continuous.h"

#include "bodies/body_bounds.h"
#include "bodies/body_parts.h"

#include <collide/narrowphase.h>

#include <algorithm>
#include <cmath>

namespace collide::detail {

namespace {

// The first time of impact of the two sweeps within the step (1 for none).
float impactTime(const Shape& a, const Sweep& sweepA, const Shape& b, const Sweep& sweepB,
                 const ToiSettings& settings, float linearSlop) {
  ToiResult toi = timeOfImpact(a, sweepA, b, sweepB, settings);
  if (toi.state == ToiResult::State::Overlapping) {
    // Touching at the start: stopping there would freeze a body sliding fast along a floor, so the
    // pair may go on as long as it gets no deeper than the slop below where it started (the solver's
    // contact should hold it; this catches a contact that gave way, e.g. a fast-spinning ball whose
    // turning anchor the solver's linearised separation misreads).
    ToiSettings touching = settings;
    touching.targetSeparation = std::min(toi.separation, linearSlop) - linearSlop;
    // A depth beyond float range (a half-space placed 3e38 m away holds the body infinitely deep),
    // or one a huge slop takes beyond it: no depth to keep, so no stop; the contact pushes out what
    // it can.
    if (!std::isfinite(touching.targetSeparation)) return 1.0f;
    toi = timeOfImpact(a, sweepA, b, sweepB, touching);
  }
  return toi.hit() ? toi.t : 1.0f;
}

}  // namespace

namespace {

void moveToSweepFraction(const BodyRecord& record, BodyState& state, const Sweep& sweep, float fraction) {
  const Transform stop = sweep.at(fraction);
  state.rotation = stop.rotation;
  state.centerOfMass = stop.position + stop.rotation * record.localCenterOfMass;
  state.inverseInertiaWorld = worldInverseInertia(record.inverseInertiaLocal, state.rotation);
}

}  // namespace

ContinuousStats solveContinuous(BodyStorage& bodies, const BroadPhase& broadPhase, const PairFilters& filters,
                                float linearSlop, std::span<const std::uint32_t> jointGroup) {
  ContinuousStats stats;
  // Per joint group (indexed by its id, a body index), the earliest stop of its bodies; and each
  // grouped body's sweep as the solve left it, for the group's stop.
  thread_local Array<float> groupStop;
  thread_local Array<Sweep> groupSweeps;
  const bool grouped = !jointGroup.empty();
  if (grouped) {
    groupStop.assign(bodies.records.size(), 1.0f);
    groupSweeps.resize(bodies.records.size());
    for (std::uint32_t i = 0; i < jointGroup.size(); ++i) {
      if (jointGroup[i] != kNoJointGroup && hasValidPose(bodies.states[i]))
        groupSweeps[i] = bodySweep(bodies.records[i], bodies.states[i]);
    }
  }
  ToiSettings settings;
  settings.targetSeparation = linearSlop;
  settings.tolerance = std::max(0.25f * linearSlop, 1e-4f);
  const auto count = static_cast<std::uint32_t>(bodies.records.size());
  for (std::uint32_t i = 0; i < count; ++i) {
    const BodyRecord& record = bodies.records[i];
    if (!record.alive || !record.awake || record.type != BodyType::Dynamic || record.sensor) continue;
    BodyState& state = bodies.states[i];
    // Most bodies are slow: a bound on their motion, without the sweep's angle, sets them aside.
    if (pointMotionBound(record, state.centerOfMass0, state.rotation0, state.centerOfMass, state.rotation) <
        0.5f * record.minExtent)
      continue;
    const Sweep sweep = bodySweep(record, state);
    const float angle = sweep.angle();
    // Box2D v3's test for a fast body: one that moved less than half its smallest extent cannot
    // have passed through anything its speculative contacts did not see.
    const float turn = angle * record.boundingRadius;
    const float motion = glm::length(sweep.center1 - sweep.center0) + turn;
    if (motion < 0.5f * record.minExtent) continue;
    if (!hasValidPose(state)) continue;  // the fault guard, next, freezes it
    ++stats.fastBodies;

    Aabb swept = worldBounds(record.shape, sweep.at(0.0f));
    swept.grow(worldBounds(record.shape, sweep.at(1.0f)));
    // Between the ends, turning reaches at most this far; a large shape far out can overflow it.
    swept = withinFloatRange(swept.expanded(turn + linearSlop));
    float first = 1.0f;
    // Every layer: a body of the same positive group collides whatever its layer. Every body
    // against static geometry; a body flagged ccd (a bullet) against moving ones too: the others
    // search the static proxies alone (in a pile, the moving bodies around are most of the tree).
    const MotionFilter motions = record.ccd ? MotionFilter::All : MotionFilter::StaticOnly;
    broadPhase.queryAabb(swept, kAllLayers, motions, [&](ProxyId id) {
      const auto j = static_cast<std::uint32_t>(broadPhase.userValue(id));
      if (j == i) return true;
      const BodyRecord& other = bodies.records[j];
      if (other.sensor || !pairAllowed(bodies, filters, i, j)) return true;
      if (!hasValidPose(bodies.states[j])) return true;  // frozen by the fault guard, next
      ++stats.candidates;
      const Sweep otherSweep = bodySweep(other, bodies.states[j]);
      if (!hasParts(record) && !hasParts(other)) {
        first =
            std::min(first, impactTime(record.shape, sweep, other.shape, otherSweep, settings, linearSlop));
      } else {
        // Bodies made of parts: each pair of solid parts the filters allow, each part turning with
        // its body.
        forEachAllowedPartPair(record, other, [&](std::uint32_t a, std::uint32_t b) {
          if (partIsSensor(record, a) || partIsSensor(other, b)) return;
          const Sweep sweepA = partSweep(sweep, partLocalPose(record, a));
          const Sweep sweepB = partSweep(otherSweep, partLocalPose(other, b));
          // A part placed near float's limit from its body's centre has an offset that overflows
          // when turned: no sweep to test; its contact still acts.
          if (!sweepStaysFinite(sweepA) || !sweepStaysFinite(sweepB)) return;
          first = std::min(first, impactTime(partShape(record, a), sweepA, partShape(other, b), sweepB,
                                             settings, linearSlop));
        });
      }
      return true;
    });
    if (first >= 1.0f) continue;
    ++stats.stopped;
    moveToSweepFraction(record, state, sweep, first);
    if (grouped && jointGroup[i] != kNoJointGroup) {
      groupStop[jointGroup[i]] = std::min(groupStop[jointGroup[i]], first);
    }
  }
  if (grouped && stats.stopped > 0) {
    for (std::uint32_t i = 0; i < jointGroup.size(); ++i) {
      if (jointGroup[i] == kNoJointGroup || !(groupStop[jointGroup[i]] < 1.0f)) continue;
      const BodyRecord& record = bodies.records[i];
      if (!record.alive || !record.awake || record.type != BodyType::Dynamic) continue;
      if (!hasValidPose(bodies.states[i])) continue;
      moveToSweepFraction(record, bodies.states[i], groupSweeps[i], groupStop[jointGroup[i]]);
    }
  }
  return stats;
}

}  // namespace collide::detail
