// The contact solver's kernels, written once over a lane type F (simd.h): FloatW, four lanes, in
// contact_solver.cpp; FloatW8, eight AVX2 lanes, in contact_solver_avx2.cpp. What the kernels solve
// is described in contact_solver.h; this file is how.
#pragma once

#include "dynamics/contact_solver.h"
#include "memory/heap_bytes.h"
#include "memory/prefetch.h"
#include "memory/scratch.h"
#include "simd/simd.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <vector>

namespace collide::detail {

// One normal point of a batch, in two records in two arrays of the same slots: what the warm start
// reads as well (PointImpulse), and what only the solve passes read (BatchPoint). A large island's
// batches stream from memory each pass, and the warm start then streams four cache lines a point
// slot instead of eight and a half.
template <typename F>
struct PointImpulse {
  Vec3T<F> turnA, turnB;  // I^-1 (anchor x normal): the spin one unit of normal impulse gives
  F normalImpulse;        // accumulated per substep (warm start)
  F totalNormalImpulse;
};
template <typename F>
struct BatchPoint {
  Vec3T<F> anchorA, anchorB;  // from each centre of mass to the contact point, world, at the step start
  F baseSeparation;           // separation at the step start minus normal . (anchorB - anchorA)
  F normalMass;
  F maxNormalImpulse;
};

// kLaneCount<F> manifolds, solved together (Box2D v3's b2ContactConstraintSIMD): what every pass
// reads. The solver streams each batch several times a substep, so what only the biased pass reads
// (BatchBias) and what only the step's end reads (BatchEnd) lie in arrays of their own.
template <typename F>
struct ContactBatch {
  static constexpr int kWidth = kLaneCount<F>;
  std::array<std::int32_t, kWidth> bodyA;  // solver body, or kNoSolverBody
  std::array<std::int32_t, kWidth> bodyB;
  std::array<bool, kWidth> writeA;  // a dynamic body takes the result (not kinematic)
  std::array<bool, kWidth> writeB;
  int pointCount;  // the most points of the manifolds
  // Its pointCount points, in the solver's point array: a batch of spheres holds one point slot,
  // not kMaxPoints (the slots of the batches of one build stay where they are until the next).
  BatchPoint<F>* points;
  F inverseMassA, inverseMassB;
  Vec3T<F> normal, tangent1, tangent2;
  F friction;
  // Friction patch.
  Vec3T<F> patchA, patchB;  // from each centre of mass to the centroid, world, at the step start
  Vec3T<F> tangent1TurnA, tangent2TurnA, tangent1TurnB, tangent2TurnB;  // I^-1 of those
  F tangentMass11, tangentMass12, tangentMass22;                        // inverse of the 2x2 block
  F tangentImpulse1, tangentImpulse2;
  F surfaceSpeed1, surfaceSpeed2;   // the sliding friction drives towards (a conveyor belt)
  Vec3T<F> twistTurnA, twistTurnB;  // I^-1 normal
  F twistMass, twistRadius, twistImpulse;
};

// What the biased pass alone reads of a batch: the softness and the static-friction anchor.
template <typename F>
struct BatchBias {
  F biasRate, massScale, impulseScale;
  // Static-friction anchor: offsets of the anchored points from the centres at the step start, and
  // their tangential gap B - A then.
  Vec3T<F> stickA, stickB;
  F stickGap1, stickGap2;
  F stickRate;  // the softness's bias rate, or 0 where the patch has no anchor (a belt)
  F sliding;    // lane mask: the patch reached the friction bound in a biased pass
};

// What the restitution and the store read of a batch at the step's end.
template <typename F>
struct BatchEnd {
  std::array<std::int32_t, kLaneCount<F>> contact;  // index in the contact array, -1 for an empty lane
  F restitution;
};

template <typename F>
class LaneContactSolver final : public ContactLanes {
 public:
  static constexpr int kWidth = kLaneCount<F>;
  using Batch = ContactBatch<F>;
  using Vec = Vec3T<F>;

  int width() const override { return kWidth; }

  void build(const ContactBatchInput& in, TaskRunner& tasks) override {
    pushOutSpeed_ = in.pushOutSpeed;
    restitutionThreshold_ = in.restitutionThreshold;
    // Each segment's (block's colour's) contacts fill its batches in order, kWidth a batch (the
    // overflow one a batch).
    const std::uint32_t segments = in.blockCount * kColorSegments;
    batchStart_.resize(segments + 1);
    batchStart_[0] = 0;
    for (std::uint32_t s = 0; s < segments; ++s) {
      const std::uint32_t perBatch = lanesOf(s);
      const std::uint32_t count = in.segmentStart(s + 1) - in.segmentStart(s);
      batchStart_[s + 1] = batchStart_[s] + (count + perBatch - 1) / perBatch;
    }
    resizeScratch(batches_, batchStart_[segments]);
    resizeScratch(biases_, batches_.size());
    resizeScratch(ends_, batches_.size());
    // Each batch's point slots: as many as its first contact's points, which has the most.
    resizeScratch(batchPoints_, batches_.size() + 1);
    batchPoints_[0] = 0;
    for (std::uint32_t s = 0, countBucket = 0; s < segments; ++s) {
      const std::uint32_t perBatch = lanesOf(s);
      for (std::uint32_t b = batchStart_[s]; b < batchStart_[s + 1]; ++b) {
        const std::uint32_t first = in.segmentStart(s) + (b - batchStart_[s]) * perBatch;
        int count;
        if (perBatch == 1) {
          count = in.contacts[in.order[first]].manifold.count;
        } else {
          countBucket = std::max(countBucket, s * Manifold::kMaxPoints);
          while (in.countStart[countBucket + 1] <= first) ++countBucket;
          count = Manifold::kMaxPoints - static_cast<int>(countBucket - s * Manifold::kMaxPoints);
        }
        batchPoints_[b + 1] = batchPoints_[b] + static_cast<std::uint32_t>(count);
      }
    }
    resizeScratch(points_, batchPoints_.back());
    resizeScratch(impulses_, points_.size());
    resizeScratch(approach_, points_.size());
    tasks.parallelFor(
        static_cast<std::uint32_t>(batches_.size()), kBatchesPerRange,
        [&](std::uint32_t begin, std::uint32_t end, std::uint32_t) { fillBatches(in, begin, end); });
  }

  // Lanes of a batch of segment s: the overflow colour's batches hold one contact.
  static std::uint32_t lanesOf(std::uint32_t segment) {
    return segment % kColorSegments == kOverflowColor ? 1 : static_cast<std::uint32_t>(kWidth);
  }

  // Batches [begin, end): each batch's lanes are independent of every other batch's, so ranges of
  // batches fill in parallel.
  void fillBatches(const ContactBatchInput& in, std::uint32_t begin, std::uint32_t end) {
    // The segment of batch `begin`, and the contacts of the range: order[firstOrder, lastOrder).
    std::uint32_t segment = static_cast<std::uint32_t>(
        std::upper_bound(batchStart_.begin(), batchStart_.end(), begin) - batchStart_.begin() - 1);
    const auto firstOrderOf = [&](std::uint32_t b, std::uint32_t s) {
      return in.segmentStart(s) + (b - batchStart_[s]) * lanesOf(s);
    };
    const std::size_t firstOrder = firstOrderOf(begin, segment);
    std::size_t lastOrder = in.order.size();
    if (end < batches_.size()) {
      const std::uint32_t endSegment = static_cast<std::uint32_t>(
          std::upper_bound(batchStart_.begin(), batchStart_.end(), end) - batchStart_.begin() - 1);
      lastOrder = firstOrderOf(end, endSegment);
    }
    // Filled batch by batch, each cleared just before its first lane (its lines stay in cache while
    // its lanes are written). The contacts lie anywhere in the contact array, and their bodies
    // anywhere in the body arrays, so both are asked for ahead, in two stages: a contact's lines
    // 2 * kAhead places ahead, then kAhead places ahead, its body indices now at hand, its bodies'
    // state, solver body and info. (Reading the indices of a contact not yet in cache would wait
    // for it, and the prefetch would be no better than the load it replaces.)
    constexpr std::size_t kAhead = 4;
    const auto prefetchContact = [&](std::size_t i) {
      if (i >= lastOrder) return;
      prefetchBytes(&in.contacts[in.order[i]], offsetof(Contact, cache));
    };
    const auto prefetchBody = [&](std::uint32_t body) {
      prefetchRecord(in.storage.states[body]);
      const std::int32_t solver = in.solverOf[body];
      if (solver < 0) return;
      prefetchRecord(in.bodies[solver]);
      prefetchRecord(in.infos[solver]);
    };
    const auto prefetchBodies = [&](std::size_t i) {
      if (i >= lastOrder) return;
      const Contact& ahead = in.contacts[in.order[i]];
      prefetchBody(ahead.bodyA);
      prefetchBody(ahead.bodyB);
    };
    for (std::size_t i = firstOrder; i < firstOrder + 2 * kAhead; ++i) prefetchContact(i);
    for (std::size_t i = firstOrder; i < firstOrder + kAhead; ++i) prefetchBodies(i);
    for (std::uint32_t b = begin; b < end; ++b) {
      while (batchStart_[segment + 1] <= b) ++segment;
      const std::uint32_t first = firstOrderOf(b, segment);
      const std::uint32_t last = std::min(first + lanesOf(segment), in.segmentStart(segment + 1));
      Batch* batch = batches_.data() + b;
      BatchBias<F>* bias = biases_.data() + b;
      BatchEnd<F>* batchEnd = ends_.data() + b;
      std::memset(static_cast<void*>(batch), 0, sizeof(Batch));
      std::memset(static_cast<void*>(bias), 0, sizeof(BatchBias<F>));
      std::memset(static_cast<void*>(batchEnd), 0, sizeof(BatchEnd<F>));
      batch->pointCount = static_cast<int>(batchPoints_[b + 1] - batchPoints_[b]);
      batch->points = points_.data() + batchPoints_[b];
      PointImpulse<F>* impulses = impulses_.data() + batchPoints_[b];
      std::memset(static_cast<void*>(batch->points), 0, sizeof(BatchPoint<F>) * batch->pointCount);
      std::memset(static_cast<void*>(impulses), 0, sizeof(PointImpulse<F>) * batch->pointCount);
      batch->bodyA.fill(kNoSolverBody);
      batch->bodyB.fill(kNoSolverBody);
      batchEnd->contact.fill(-1);
      LaneInputs inputs;
      std::memset(static_cast<void*>(&inputs), 0, sizeof(LaneInputs));
      for (std::uint32_t i = first; i < last; ++i) {
        prefetchContact(i + 2 * kAhead);
        prefetchBodies(i + kAhead);
        fillLane(in, *batch, impulses, *bias, *batchEnd, inputs, static_cast<int>(i - first), in.order[i]);
      }
      finishBatch(*batch, impulses, approach_.data() + batchPoints_[b], inputs);
    }
  }

  // f(batch) for every batch of a block, colour after colour (the last colour first if
  // `backwards`). A colour's batches share no body the solver writes, so their ranges run in
  // parallel and give what one pass in order gives, bit for bit; the overflow's batches may share
  // bodies and run in order (reversed if `backwards`), on the calling thread. For the same reason
  // the order within a colour changes nothing, and it is ascending either way: batches that
  // outgrow the cache stream from memory faster forwards than backwards.
  template <typename Body>
  void forEachBatch(TaskRunner& tasks, std::uint32_t block, bool backwards, Body&& body) {
    forEachBatchOfColors(tasks, block, backwards, 0, kGraphColors, body);
  }
  // The same over the colours [lowest, highest] alone.
  template <typename Body>
  void forEachBatchOfColors(TaskRunner& tasks, std::uint32_t block, bool backwards, int lowest, int highest,
                            Body&& body) {
    for (int k = 0; k <= highest - lowest; ++k) {
      const int color = backwards ? highest - k : lowest + k;
      const std::uint32_t segment = block * kColorSegments + static_cast<std::uint32_t>(color);
      const std::uint32_t first = batchStart_[segment];
      const std::uint32_t last = batchStart_[segment + 1];
      if (first == last) continue;
      if (color == kOverflowColor) {
        if (backwards) {
          for (std::uint32_t i = last; i-- > first;) body(batches_[i]);
        } else {
          for (std::uint32_t i = first; i < last; ++i) body(batches_[i]);
        }
        continue;
      }
      tasks.parallelFor(last - first, kBatchesPerRange,
                        [&](std::uint32_t begin, std::uint32_t end, std::uint32_t) {
                          for (std::uint32_t i = begin; i < end; ++i) body(batches_[first + i]);
                        });
    }
  }

  void warmStart(Array<SolverBody>& bodies, std::uint32_t block, TaskRunner& tasks) override {
    // The colours backwards: it starts with the colour the last pass (the previous substep's
    // relax) ended with, still in the cache, and ends with the one the solve pass starts with.
    forEachBatch(tasks, block, true, [&](Batch& c) { warmStartBatch(bodies, c); });
  }

  // The warm start and the biased pass, with the warm start's last colour and the biased pass's
  // first (the lowest colour with batches) taken together, batch by batch: a colour's batches share
  // no moving body, so each body meets the same impulses in the same order as in the two passes
  // one after the other, bit for bit, with one parallel loop fewer and the colour's batches read
  // once while they are in the cache. The contacts' passes must follow each other with nothing
  // between (no joints' passes).
  void warmStartAndSolve(Array<SolverBody>& bodies, float h, std::uint32_t block,
                         TaskRunner& tasks) override {
    int together = -1;
    for (int color = 0; color < kGraphColors && together < 0; ++color) {
      const std::uint32_t segment = block * kColorSegments + static_cast<std::uint32_t>(color);
      if (batchStart_[segment] != batchStart_[segment + 1]) together = color;
    }
    if (together < 0) {  // the overflow alone, whose batches may share bodies
      warmStart(bodies, block, tasks);
      solvePass<true>(bodies, h, block, tasks);
      return;
    }
    const F inverseH = splatT<F>(1.0f / h);
    const F maxPushOut = splatT<F>(-pushOutSpeed_);
    forEachBatchOfColors(tasks, block, true, together + 1, kGraphColors,
                         [&](Batch& c) { warmStartBatch(bodies, c); });
    forEachBatchOfColors(tasks, block, false, together, together, [&](Batch& c) {
      warmStartBatch(bodies, c);
      solveBatch<true>(bodies, c, inverseH, maxPushOut);
    });
    forEachBatchOfColors(tasks, block, false, together + 1, kGraphColors,
                         [&](Batch& c) { solveBatch<true>(bodies, c, inverseH, maxPushOut); });
  }

  COLLIDE_INLINE void warmStartBatch(Array<SolverBody>& bodies, Batch& c) {
    {
      PointImpulse<F>* impulses = impulsesOf(c);
      Velocities a = gatherVelocities(bodies, c.bodyA);
      Velocities b = gatherVelocities(bodies, c.bodyB);
      for (int k = 0; k < c.pointCount; ++k) {
        PointImpulse<F>& p = impulses[k];
        // The events' impulse counts every substep's warm start as well as the solve's increments.
        p.totalNormalImpulse = p.totalNormalImpulse + p.normalImpulse;
        applyLinear(a, b, c, p.normalImpulse, c.normal);
        addScaled(a.w, -p.normalImpulse, p.turnA);
        addScaled(b.w, p.normalImpulse, p.turnB);
      }
      applyLinear(a, b, c, c.tangentImpulse1, c.tangent1);
      applyLinear(a, b, c, c.tangentImpulse2, c.tangent2);
      addScaled(a.w, -c.tangentImpulse1, c.tangent1TurnA);
      addScaled(a.w, -c.tangentImpulse2, c.tangent2TurnA);
      addScaled(b.w, c.tangentImpulse1, c.tangent1TurnB);
      addScaled(b.w, c.tangentImpulse2, c.tangent2TurnB);
      addScaled(a.w, -c.twistImpulse, c.twistTurnA);
      addScaled(b.w, c.twistImpulse, c.twistTurnB);
      scatter(bodies, c.bodyA, c.writeA, a);
      scatter(bodies, c.bodyB, c.writeB, b);
    }
  }

  void solve(Array<SolverBody>& bodies, float h, bool useBias, std::uint32_t block,
             TaskRunner& tasks) override {
    if (useBias) {
      solvePass<true>(bodies, h, block, tasks);
    } else {
      solvePass<false>(bodies, h, block, tasks);
    }
  }

  // Newton's restitution on the approach velocity measured before the solve: the soft contact has
  // absorbed the impact by now, so the bounce is added at the end (Box2D v3's b2ApplyRestitution).
  void applyRestitution(Array<SolverBody>& bodies, std::uint32_t block, TaskRunner& tasks) override {
    const F zero = zeroT<F>();
    const F threshold = splatT<F>(-restitutionThreshold_);
    forEachBatch(tasks, block, false, [&](Batch& c) {
      const std::size_t index = static_cast<std::size_t>(&c - batches_.data());
      const F restitution = ends_[index].restitution;
      if (!anyW(greaterW(restitution, zero))) return;
      const F* approach = approach_.data() + batchPoints_[index];
      PointImpulse<F>* impulses = impulses_.data() + batchPoints_[index];
      Velocities a = gatherVelocities(bodies, c.bodyA);
      Velocities b = gatherVelocities(bodies, c.bodyB);
      for (int k = 0; k < c.pointCount; ++k) {
        BatchPoint<F>& p = c.points[k];
        PointImpulse<F>& q = impulses[k];
        const F bounce = andW(andW(greaterW(threshold, approach[k]), greaterW(p.maxNormalImpulse, zero)),
                              greaterW(restitution, zero));
        if (!anyW(bounce)) continue;
        // w . (r x n) = r . (n x w): the anchors' crosses are not stored, to keep the batch small
        // (the solver streams every batch several times a substep).
        const F vn = dot(b.v - a.v, c.normal) + dot(p.anchorB, cross(c.normal, b.w)) -
                     dot(p.anchorA, cross(c.normal, a.w));
        F impulse = -(p.normalMass * (vn + restitution * approach[k]));
        const F total = maxW(q.normalImpulse + impulse, zero);
        impulse = selectW(bounce, total - q.normalImpulse, zero);
        q.normalImpulse = q.normalImpulse + impulse;
        p.maxNormalImpulse = maxW(p.maxNormalImpulse, impulse);
        q.totalNormalImpulse = q.totalNormalImpulse + impulse;
        applyLinear(a, b, c, impulse, c.normal);
        addScaled(a.w, -impulse, q.turnA);
        addScaled(b.w, impulse, q.turnB);
      }
      scatter(bodies, c.bodyA, c.writeA, a);
      scatter(bodies, c.bodyB, c.writeB, b);
    });
  }

  // Each batch writes its own contacts: ranges of batches in parallel.
  std::size_t memoryBytes() const override {
    return heapBytes(batches_) + heapBytes(biases_) + heapBytes(ends_) + heapBytes(points_) +
           heapBytes(impulses_) + heapBytes(approach_) + heapBytes(batchPoints_) + heapBytes(batchStart_);
  }

  void store(Array<Contact>& contacts, TaskRunner& tasks) const override {
    tasks.parallelFor(
        static_cast<std::uint32_t>(batches_.size()), kBatchesPerRange,
        [&](std::uint32_t begin, std::uint32_t end, std::uint32_t) { storeBatches(contacts, begin, end); });
  }

  void storeBatches(Array<Contact>& contacts, std::size_t begin, std::size_t end) const {
    // The contacts of a batch two places on, asked for ahead: they lie anywhere in the array. Only
    // the part written here (from the manifold's point count to the friction patch's impulses),
    // not the whole record: a large world's contacts come from memory.
    constexpr std::size_t kAhead = 2;
    constexpr std::size_t kStoredFrom = offsetof(Contact, manifold) + offsetof(Manifold, count);
    constexpr std::size_t kStoredTo = offsetof(Contact, twistImpulse) + sizeof(float);
    static_assert(offsetof(Contact, points) > kStoredFrom && offsetof(Contact, sliding) < kStoredTo &&
                  offsetof(Contact, frictionImpulse) < kStoredTo);
    const auto prefetchContacts = [&](std::size_t batch) {
      if (batch >= end) return;
      for (const std::int32_t index : ends_[batch].contact) {
        if (index < 0) continue;
        const char* record = reinterpret_cast<const char*>(&contacts[static_cast<std::size_t>(index)]);
        prefetchBytes(record + kStoredFrom, kStoredTo - kStoredFrom);
      }
    };
    for (std::size_t i = begin; i < begin + kAhead; ++i) prefetchContacts(i);
    for (std::size_t i = begin; i < end; ++i) {
      prefetchContacts(i + kAhead);
      const Batch& c = batches_[i];
      const BatchEnd<F>& batchEnd = ends_[i];
      const F* approach = approach_.data() + batchPoints_[i];
      const PointImpulse<F>* impulses = impulses_.data() + batchPoints_[i];
      for (int lane = 0; lane < kWidth; ++lane) {
        if (batchEnd.contact[lane] < 0) continue;
        Contact& contact = contacts[static_cast<std::size_t>(batchEnd.contact[lane])];
        for (int k = 0; k < contact.manifold.count; ++k) {
          const BatchPoint<F>& p = c.points[k];
          const PointImpulse<F>& q = impulses[k];
          ContactPointState& state = contact.points[k];
          state.normalImpulse = laneOf(q.normalImpulse, lane);
          state.maxNormalImpulse = laneOf(p.maxNormalImpulse, lane);
          state.totalNormalImpulse = laneOf(q.totalNormalImpulse, lane);
          state.relativeVelocity = laneOf(approach[k], lane);
        }
        contact.frictionImpulse = laneOf(c.tangentImpulse1, lane) * laneOf(c.tangent1, lane) +
                                  laneOf(c.tangentImpulse2, lane) * laneOf(c.tangent2, lane);
        contact.twistImpulse = laneOf(c.twistImpulse, lane);
        contact.sliding = laneSet(biases_[i].sliding, lane);
      }
    }
  }

 private:
  // A batch's point slots in impulses_ (those of its points in points_).
  PointImpulse<F>* impulsesOf(const Batch& c) { return impulses_.data() + (c.points - points_.data()); }

  // The lanes' solver bodies: their velocities (what the solver changes) and their change of pose
  // since the step began (read once per batch for the current separations, then dropped, so that
  // the velocities keep the registers). A lane without a body (static, or an empty lane) reads a
  // body at rest that has not moved.
  struct Velocities {
    Vec v, w;
  };
  struct Poses {
    Vec dp;
    F qx, qy, qz, qw;
  };

  static COLLIDE_INLINE void records(const Array<SolverBody>& bodies,
                                     const std::array<std::int32_t, kWidth>& index,
                                     const float* (&out)[kWidth]) {
    static const SolverBody kRestingBody{};
    for (int i = 0; i < kWidth; ++i)
      out[i] = reinterpret_cast<const float*>(index[i] >= 0 ? &bodies[index[i]] : &kRestingBody);
  }

  static COLLIDE_INLINE Velocities gatherVelocities(const Array<SolverBody>& bodies,
                                                    const std::array<std::int32_t, kWidth>& index) {
    const float* b[kWidth];
    records(bodies, index, b);
    Velocities out;
    F pad;
    gatherRows(b, 0, out.v.x, out.v.y, out.v.z, pad);
    gatherRows(b, 4, out.w.x, out.w.y, out.w.z, pad);
    return out;
  }

  static COLLIDE_INLINE Poses gatherPoses(const Array<SolverBody>& bodies,
                                          const std::array<std::int32_t, kWidth>& index) {
    const float* b[kWidth];
    records(bodies, index, b);
    Poses out;
    F pad;
    gatherRows(b, 8, out.dp.x, out.dp.y, out.dp.z, pad);
    gatherRows(b, 12, out.qx, out.qy, out.qz, out.qw);
    return out;
  }

  // The contact solver changes velocities only; lanes of bodies it must not write are skipped.
  static COLLIDE_INLINE void scatter(Array<SolverBody>& bodies, const std::array<std::int32_t, kWidth>& index,
                                     const std::array<bool, kWidth>& write, const Velocities& body) {
    FloatW vRows[kWidth];  // one row of four floats per lane
    FloatW wRows[kWidth];
    scatterRows(body.v.x, body.v.y, body.v.z, zeroT<F>(), vRows);
    scatterRows(body.w.x, body.w.y, body.w.z, zeroT<F>(), wRows);
    for (int i = 0; i < kWidth; ++i) {
      if (!write[i]) continue;
      float* target = reinterpret_cast<float*>(&bodies[index[i]]);
      storeW(target, vRows[i]);
      storeW(target + 4, wRows[i]);
    }
  }

  // conj(q) v q for unit q: v seen in the frame before the rotation q.
  static COLLIDE_INLINE Vec rotateInverse(const Poses& q, const Vec& v) {
    const Vec u{-q.qx, -q.qy, -q.qz};
    const Vec t = splatT<F>(2.0f) * cross(u, v);
    return v + q.qw * t + cross(u, t);
  }

  // The small-angle rotation vector of q (2 x its vector part, on the shortest arc): the static
  // anchors are kept only while the bodies barely turn, where this is exact to second order.
  static COLLIDE_INLINE Vec smallRotation(const Poses& q) {
    const F negative = greaterW(zeroT<F>(), q.qw);
    const F two = selectW(negative, splatT<F>(-2.0f), splatT<F>(2.0f));
    return {two * q.qx, two * q.qy, two * q.qz};
  }

  static COLLIDE_INLINE void applyLinear(Velocities& a, Velocities& b, const Batch& c, F impulse,
                                         const Vec& direction) {
    addScaled(a.v, -(impulse * c.inverseMassA), direction);
    addScaled(b.v, impulse * c.inverseMassB, direction);
  }

  // What a batch's points need of its bodies' change of pose since the step began: the normal seen
  // from each body's frame at the step start, how far B moved from A along it, and in the biased pass
  // how far the static anchors drifted apart along the tangents.
  struct PoseChange {
    Vec normalA, normalB;
    F moved, drift1, drift2;
  };

  // The current separation from the anchors carried along with each body's change of pose,
  // without a new narrow-phase query (Box2D v3): n . (dq r) = (conj(dq) n) . r. Its own function so
  // that the poses are dropped before the velocities are read, which then keep the registers.
  template <bool useBias>
  static COLLIDE_INLINE PoseChange poseChange(const Array<SolverBody>& bodies, const Batch& c,
                                              const BatchBias<F>& bias) {
    const F zero = zeroT<F>();
    PoseChange out;
    out.drift1 = zero;
    out.drift2 = zero;
    const Poses pa = gatherPoses(bodies, c.bodyA);
    const Poses pb = gatherPoses(bodies, c.bodyB);
    out.normalA = rotateInverse(pa, c.normal);
    out.normalB = rotateInverse(pb, c.normal);
    const Vec dp = pb.dp - pa.dp;
    out.moved = dot(dp, c.normal);
    if constexpr (useBias) {
      const Vec drift = dp + cross(smallRotation(pb), bias.stickB) - cross(smallRotation(pa), bias.stickA);
      out.drift1 = bias.stickGap1 + dot(drift, c.tangent1);
      out.drift2 = bias.stickGap2 + dot(drift, c.tangent2);
    }
    return out;
  }

  // The batch's normal points, in order; returns the sum of their accumulated impulses, which bounds
  // the friction patch and the twist that follow.
  template <bool useBias>
  static COLLIDE_INLINE F solveNormalPoints(Batch& c, PointImpulse<F>* impulses, const BatchBias<F>& soft,
                                            Velocities& a, Velocities& b, const PoseChange& pose, F inverseH,
                                            F maxPushOut) {
    const F zero = zeroT<F>();
    const F one = splatT<F>(1.0f);
    F normalSum = zero;
    for (int k = 0; k < c.pointCount; ++k) {
      BatchPoint<F>& p = c.points[k];
      PointImpulse<F>& q = impulses[k];
      const F separation =
          pose.moved + dot(pose.normalB, p.anchorB) - dot(pose.normalA, p.anchorA) + p.baseSeparation;
      // Speculative: a point still apart may close exactly its gap within the substep.
      const F apart = greaterW(separation, zero);
      F bias = separation * inverseH;
      F massScale = one;
      F impulseScale = zero;
      if constexpr (useBias) {
        bias = selectW(apart, bias, maxW(soft.biasRate * separation, maxPushOut));
        massScale = selectW(apart, one, soft.massScale);
        impulseScale = selectW(apart, zero, soft.impulseScale);
      } else {
        bias = selectW(apart, bias, zero);
      }
      // w . (r x n) = r . (n x w): the anchors' crosses are not stored, to keep the batch small
      // (the solver streams every batch several times a substep).
      const F vn = dot(b.v - a.v, c.normal) + dot(p.anchorB, cross(c.normal, b.w)) -
                   dot(p.anchorA, cross(c.normal, a.w));
      F impulse = -(p.normalMass * massScale * (vn + bias)) - impulseScale * q.normalImpulse;
      // Contacts only push: the accumulated impulse stays >= 0.
      const F total = maxW(q.normalImpulse + impulse, zero);
      impulse = total - q.normalImpulse;
      q.normalImpulse = total;
      p.maxNormalImpulse = maxW(p.maxNormalImpulse, impulse);
      q.totalNormalImpulse = q.totalNormalImpulse + impulse;
      normalSum = normalSum + total;
      applyLinear(a, b, c, impulse, c.normal);
      addScaled(a.w, -impulse, q.turnA);
      addScaled(b.w, impulse, q.turnB);
    }
    return normalSum;
  }

  // Friction patch: the tangential velocity at the centroid (relative to the surface velocity),
  // plus in the biased pass the gap of the static anchors, driven to zero inside the Coulomb disc
  // whose radius the normal impulses set.
  template <bool useBias>
  static COLLIDE_INLINE void solveFriction(Batch& c, BatchBias<F>& soft, Velocities& a, Velocities& b,
                                           F normalSum, const PoseChange& pose) {
    const F zero = zeroT<F>();
    const F one = splatT<F>(1.0f);
    const Vec dv = b.v - a.v;
    const Vec atCentroid = dv + cross(b.w, c.patchB) - cross(a.w, c.patchA);
    F v1 = dot(atCentroid, c.tangent1) - c.surfaceSpeed1;
    F v2 = dot(atCentroid, c.tangent2) - c.surfaceSpeed2;
    F massScale = one;
    F impulseScale = zero;
    if constexpr (useBias) {
      v1 = v1 + soft.stickRate * pose.drift1;
      v2 = v2 + soft.stickRate * pose.drift2;
      massScale = soft.massScale;
      impulseScale = soft.impulseScale;
    }
    F next1 = c.tangentImpulse1 - massScale * (c.tangentMass11 * v1 + c.tangentMass12 * v2) -
              impulseScale * c.tangentImpulse1;
    F next2 = c.tangentImpulse2 - massScale * (c.tangentMass12 * v1 + c.tangentMass22 * v2) -
              impulseScale * c.tangentImpulse2;
    const F limit = c.friction * normalSum;
    const F length = sqrtW(next1 * next1 + next2 * next2);
    const F beyond = greaterW(length, limit);
    const F scale = selectW(beyond, limit / maxW(length, splatT<F>(1e-30f)), one);
    next1 = next1 * scale;
    next2 = next2 * scale;
    if constexpr (useBias) soft.sliding = orW(soft.sliding, beyond);
    const F d1 = next1 - c.tangentImpulse1;
    const F d2 = next2 - c.tangentImpulse2;
    c.tangentImpulse1 = next1;
    c.tangentImpulse2 = next2;
    applyLinear(a, b, c, d1, c.tangent1);
    applyLinear(a, b, c, d2, c.tangent2);
    addScaled(a.w, -d1, c.tangent1TurnA);
    addScaled(a.w, -d2, c.tangent2TurnA);
    addScaled(b.w, d1, c.tangent1TurnB);
    addScaled(b.w, d2, c.tangent2TurnB);
  }

  // Twist about the normal, bounded like the friction by the normal impulses.
  static COLLIDE_INLINE void solveTwist(Batch& c, Velocities& a, Velocities& b, F normalSum) {
    const F spin = dot(b.w - a.w, c.normal);
    const F twistLimit = c.friction * c.twistRadius * normalSum;
    const F twist = maxW(minW(c.twistImpulse - c.twistMass * spin, twistLimit), -twistLimit);
    const F dt = twist - c.twistImpulse;
    c.twistImpulse = twist;
    addScaled(a.w, -dt, c.twistTurnA);
    addScaled(b.w, dt, c.twistTurnB);
  }

  // One pass; the biased and the relax pass are two instantiations, so neither tests the flag inside.
  // Each batch: the pose change, then the normal points, the friction patch and the twist, in that
  // order, on the same gathered velocities.
  template <bool useBias>
  void solvePass(Array<SolverBody>& bodies, float h, std::uint32_t block, TaskRunner& tasks) {
    const F inverseH = splatT<F>(1.0f / h);
    const F maxPushOut = splatT<F>(-pushOutSpeed_);
    forEachBatch(tasks, block, false,
                 [&](Batch& c) { solveBatch<useBias>(bodies, c, inverseH, maxPushOut); });
  }

  template <bool useBias>
  COLLIDE_INLINE void solveBatch(Array<SolverBody>& bodies, Batch& c, F inverseH, F maxPushOut) {
    // The biased pass's part of the batch; the relax pass never reads it.
    BatchBias<F>& soft = biases_[static_cast<std::size_t>(&c - batches_.data())];
    const PoseChange pose = poseChange<useBias>(bodies, c, soft);
    Velocities a = gatherVelocities(bodies, c.bodyA);
    Velocities b = gatherVelocities(bodies, c.bodyB);
    const F normalSum = solveNormalPoints<useBias>(c, impulsesOf(c), soft, a, b, pose, inverseH, maxPushOut);
    solveFriction<useBias>(c, soft, a, b, normalSum, pose);
    solveTwist(c, a, b, normalSum);
    scatter(bodies, c.bodyA, c.writeA, a);
    scatter(bodies, c.bodyB, c.writeB, b);
  }

  // What a batch's vectorised part (finishBatch) reads, gathered lane by lane by fillLane. Lanes
  // and points without a contact stay zero.
  struct LaneInputs {
    std::array<Vec, Manifold::kMaxPoints> points;  // the manifold's midpoints
    std::array<F, Manifold::kMaxPoints> depths;
    F count;  // the manifold's points, as a float
    Vec centroid;
    Vec centerA, centerB;
    Vec linearA, angularA, linearB, angularB;  // velocities before the solve
    // The columns of each side's world inverse inertia; zero for a side the solver does not move.
    std::array<Vec, 3> inertiaA, inertiaB;
  };

  static COLLIDE_INLINE Vec times(const std::array<Vec, 3>& m, const Vec& v) {
    // glm's order (column 0 by x, plus column 1 by y, plus column 2 by z), so a lane computes what
    // glm computes for it.
    return {m[0].x * v.x + m[1].x * v.y + m[2].x * v.z, m[0].y * v.x + m[1].y * v.y + m[2].y * v.z,
            m[0].z * v.x + m[1].z * v.y + m[2].z * v.z};
  }

  static COLLIDE_INLINE Vec select(F mask, const Vec& a) {
    const F zero = zeroT<F>();
    return {selectW(mask, a.x, zero), selectW(mask, a.y, zero), selectW(mask, a.z, zero)};
  }

  // The inverse masses the solver uses for a lane's two bodies: zero for a side it does not move.
  struct LaneMasses {
    float a, b;
  };

  // One lane's bodies: which of them the batch writes back, their masses, inertias, velocities and
  // centres. Apart from the rest of fillLane because it reads the body arrays, the rest the contact.
  static COLLIDE_INLINE LaneMasses fillBodies(const ContactBatchInput& in, Batch& c, LaneInputs& inputs,
                                              int lane, std::uint32_t contactIndex, const Contact& contact,
                                              const BodyState& stateA, const BodyState& stateB) {
    const std::int32_t ia = in.solverOf[contact.bodyA];
    const std::int32_t ib = in.solverOf[contact.bodyB];
    c.bodyA[lane] = ia;
    c.bodyB[lane] = ib;
    c.writeA[lane] = ia >= 0 && in.infos[ia].dynamic;
    c.writeB[lane] = ib >= 0 && in.infos[ib].dynamic;
    // In a stack with a heavier body on a lighter one, each body appears to the contacts that carry
    // weight as heavy as its load (support_masses.h), along the normal and the friction patch alike:
    // one mass per body and contact keeps Gauss-Seidel's iteration that of one consistent system.
    const float scaleA = in.supportMasses != nullptr ? in.supportMasses->scaleA(contactIndex) : 1.0f;
    const float scaleB = in.supportMasses != nullptr ? in.supportMasses->scaleB(contactIndex) : 1.0f;
    const float mA = c.writeA[lane] ? scaleA * in.infos[ia].inverseMass : 0.0f;
    const float mB = c.writeB[lane] ? scaleB * in.infos[ib].inverseMass : 0.0f;
    // A side the solver does not move (static, kinematic) keeps the zeros of the cleared inputs.
    for (int column = 0; column < 3; ++column) {
      if (c.writeA[lane])
        setLane(inputs.inertiaA[column], lane, scaleA * in.infos[ia].inverseInertiaWorld[column]);
      if (c.writeB[lane])
        setLane(inputs.inertiaB[column], lane, scaleB * in.infos[ib].inverseInertiaWorld[column]);
    }
    if (ia >= 0) {
      setLane(inputs.linearA, lane, in.bodies[ia].linearVelocity);
      setLane(inputs.angularA, lane, in.bodies[ia].angularVelocity);
    }
    if (ib >= 0) {
      setLane(inputs.linearB, lane, in.bodies[ib].linearVelocity);
      setLane(inputs.angularB, lane, in.bodies[ib].angularVelocity);
    }
    setLane(inputs.centerA, lane, stateA.centerOfMass);
    setLane(inputs.centerB, lane, stateB.centerOfMass);
    laneOf(c.inverseMassA, lane) = mA;
    laneOf(c.inverseMassB, lane) = mB;
    return {mA, mB};
  }

  // One contact into one lane, the scalar part: bodies, masses, basis, settings and the friction
  // patch's warm start and static anchor; the rest (anchors, effective masses, approach velocity)
  // is finishBatch's, for all lanes at once.
  static void fillLane(const ContactBatchInput& in, Batch& c, PointImpulse<F>* impulses, BatchBias<F>& bias,
                       BatchEnd<F>& end, LaneInputs& inputs, int lane, std::uint32_t contactIndex) {
    Contact& contact = in.contacts[contactIndex];
    const BodyState& stateA = in.storage.states[contact.bodyA];
    const BodyState& stateB = in.storage.states[contact.bodyB];
    end.contact[lane] = static_cast<std::int32_t>(contactIndex);
    const LaneMasses masses = fillBodies(in, c, inputs, lane, contactIndex, contact, stateA, stateB);
    const float mA = masses.a, mB = masses.b;

    const Vec3 n = contact.manifold.normal;
    Vec3 t1, t2;
    orthonormalBasis(n, t1, t2);
    setLane(c.normal, lane, n);
    setLane(c.tangent1, lane, t1);
    setLane(c.tangent2, lane, t2);
    const float friction = in.friction ? contact.friction : 0.0f;
    laneOf(c.friction, lane) = friction;
    laneOf(end.restitution, lane) = contact.restitution;
    const Softness& s = (mA == 0.0f || mB == 0.0f) ? in.oneWaySoftness : in.softness;
    laneOf(bias.biasRate, lane) = s.biasRate;
    laneOf(bias.massScale, lane) = s.massScale;
    laneOf(bias.impulseScale, lane) = s.impulseScale;

    const int count = contact.manifold.count;
    laneOf(inputs.count, lane) = static_cast<float>(count);
    Vec3 centroid(0.0f);
    for (int k = 0; k < count; ++k) {
      const Vec3 point = contact.manifold.points[k].midpoint();
      centroid += point;
      setLane(inputs.points[k], lane, point);
      laneOf(inputs.depths[k], lane) = contact.manifold.points[k].depth;
      laneOf(impulses[k].normalImpulse, lane) = contact.points[k].normalImpulse;
    }
    centroid /= static_cast<float>(count);
    setLane(inputs.centroid, lane, centroid);

    // The friction patch at the centroid.
    const Vec3 rA = centroid - stateA.centerOfMass;
    const Vec3 rB = centroid - stateB.centerOfMass;
    setLane(c.patchA, lane, rA);
    setLane(c.patchB, lane, rB);
    if (friction == 0.0f) {
      contact.frictionImpulse = Vec3(0.0f);
      contact.twistImpulse = 0.0f;
    }
    // Warm start: last step's friction impulse, on this step's tangents (the tangent basis of a
    // normal can turn by 180 degrees between steps, so coefficients would not carry over).
    laneOf(c.tangentImpulse1, lane) = glm::dot(contact.frictionImpulse, t1);
    laneOf(c.tangentImpulse2, lane) = glm::dot(contact.frictionImpulse, t2);
    laneOf(c.twistImpulse, lane) = contact.twistImpulse;

    laneOf(c.surfaceSpeed1, lane) = glm::dot(contact.surfaceVelocity, t1);
    laneOf(c.surfaceSpeed2, lane) = glm::dot(contact.surfaceVelocity, t2);

    // The static anchor: a point in each body, B's the gap the patch has slipped since it stuck
    // away from A's. Each step both are taken again at the patch with the gap they have come to
    // (their slip over the last step added), so that the anchor follows the patch as a wheel or a
    // ball rolls: kept as points fixed in the bodies, a rolling body's point went round with it and
    // its gap grew as r (theta - sin theta) without any slip, the friction pulling it back until
    // the patch slid (a driven wheel's speed swung by 3 % every few steps). Let go, the anchor is
    // taken where the patch is, gap 0: when the patch slid last step, is new, or has slipped
    // beyond the reach.
    const bool anchored = friction > 0.0f && contact.surfaceVelocity == Vec3(0.0f);
    laneOf(bias.stickRate, lane) = anchored ? s.biasRate : 0.0f;
    Vec3 gap(0.0f);
    if (contact.stuck && !contact.sliding && anchored) {
      const Vec3 anchorA = stateA.centerOfMass + stateA.rotation * contact.stickLocalA;
      const Vec3 anchorB = stateB.centerOfMass + stateB.rotation * contact.stickLocalB;
      gap = anchorB - anchorA;
      gap -= glm::dot(gap, n) * n;
      if (glm::dot(gap, gap) > in.anchorReach * in.anchorReach) gap = Vec3(0.0f);
    }
    const Vec3 stickA = rA;
    const Vec3 stickB = rB + gap;
    contact.stickLocalA = glm::conjugate(stateA.rotation) * stickA;
    contact.stickLocalB = glm::conjugate(stateB.rotation) * stickB;
    contact.stuck = anchored;
    contact.sliding = false;
    setLane(bias.stickA, lane, stickA);
    setLane(bias.stickB, lane, stickB);
    laneOf(bias.stickGap1, lane) = glm::dot(gap, t1);
    laneOf(bias.stickGap2, lane) = glm::dot(gap, t2);
  }

  // The batch's vectorised part, all lanes at once: each point's anchors, turns, effective mass,
  // base separation and approach velocity; the patch's tangent turns and 2x2 mass; the twist. Each
  // lane computes what the scalar formulas give for its contact, operation for operation.
  static void finishBatch(Batch& c, PointImpulse<F>* impulses, F* approach, const LaneInputs& in) {
    const F zero = zeroT<F>();
    const F one = splatT<F>(1.0f);
    const Vec& n = c.normal;
    const F masses = c.inverseMassA + c.inverseMassB;
    F radius = zero;
    for (int k = 0; k < c.pointCount; ++k) {
      const F present = greaterW(in.count, splatT<F>(static_cast<float>(k)));
      BatchPoint<F>& p = c.points[k];
      const Vec rA = in.points[k] - in.centerA;
      const Vec rB = in.points[k] - in.centerB;
      const Vec crossA = cross(rA, n);
      const Vec crossB = cross(rB, n);
      const Vec turnA = times(in.inertiaA, crossA);
      const Vec turnB = times(in.inertiaB, crossB);
      p.anchorA = select(present, rA);
      p.anchorB = select(present, rB);
      impulses[k].turnA = select(present, turnA);
      impulses[k].turnB = select(present, turnB);
      p.baseSeparation = selectW(present, -in.depths[k] - dot(rB - rA, n), zero);
      const F kn = masses + dot(crossA, turnA) + dot(crossB, turnB);
      const F positive = andW(present, greaterW(kn, zero));
      p.normalMass = selectW(positive, one / selectW(positive, kn, one), zero);
      const Vec dv = in.linearB + cross(in.angularB, rB) - in.linearA - cross(in.angularA, rA);
      approach[k] = selectW(present, dot(dv, n), zero);
      const Vec offset = in.points[k] - in.centroid;
      radius = radius + selectW(present, sqrtW(dot(offset, offset)), zero);
    }

    const Vec& rA = c.patchA;
    const Vec& rB = c.patchB;
    const Vec t1A = cross(rA, c.tangent1), t2A = cross(rA, c.tangent2);
    const Vec t1B = cross(rB, c.tangent1), t2B = cross(rB, c.tangent2);
    c.tangent1TurnA = times(in.inertiaA, t1A);
    c.tangent2TurnA = times(in.inertiaA, t2A);
    c.tangent1TurnB = times(in.inertiaB, t1B);
    c.tangent2TurnB = times(in.inertiaB, t2B);
    // The tangents are orthonormal, so the linear part of the off-diagonal term vanishes.
    const F k11 = masses + dot(t1A, c.tangent1TurnA) + dot(t1B, c.tangent1TurnB);
    const F k12 = dot(t1A, c.tangent2TurnA) + dot(t1B, c.tangent2TurnB);
    const F k22 = masses + dot(t2A, c.tangent2TurnA) + dot(t2B, c.tangent2TurnB);
    const F det = k11 * k22 - k12 * k12;
    const F invertible = greaterW(det, zero);
    const F safeDet = selectW(invertible, det, one);
    c.tangentMass11 = selectW(invertible, k22 / safeDet, zero);
    c.tangentMass12 = selectW(invertible, -k12 / safeDet, zero);
    c.tangentMass22 = selectW(invertible, k11 / safeDet, zero);
    c.twistTurnA = times(in.inertiaA, n);
    c.twistTurnB = times(in.inertiaB, n);
    const F kt = dot(n, c.twistTurnA) + dot(n, c.twistTurnB);
    const F twistable = greaterW(kt, zero);
    c.twistMass = selectW(twistable, one / selectW(twistable, kt, one), zero);
    const F filled = greaterW(in.count, zero);
    c.twistRadius =
        selectW(filled, splatT<F>(kTwistRadiusScale) * radius / selectW(filled, in.count, one), zero);
  }

  // The fewest batches a parallel range takes; the pool makes ranges longer to give each worker a
  // few. A colour of no more batches than this runs on the calling thread.
  static constexpr std::uint32_t kBatchesPerRange = 4;
  Array<Batch> batches_;
  Array<BatchBias<F>> biases_;        // batch b's biased-pass part
  Array<BatchEnd<F>> ends_;           // batch b's contacts and restitution
  Array<BatchPoint<F>> points_;       // the batches' point slots
  Array<PointImpulse<F>> impulses_;   // the same slots' turns and impulses
  Array<F> approach_;                 // per point slot: the normal relative velocity before the solve
  Array<std::uint32_t> batchPoints_;  // batch b's slots: [batchPoints_[b], [b + 1])
  Array<std::uint32_t> batchStart_;   // segment s's batches: [batchStart_[s], batchStart_[s + 1])
  float pushOutSpeed_ = 3.0f;
  float restitutionThreshold_ = 1.0f;
};

}  // namespace collide::detail
