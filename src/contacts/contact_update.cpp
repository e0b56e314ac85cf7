// The contacts stage: the narrow phase over the broad phase's pairs, manifold reuse, the
// separating-axis cache and the pre-solve callback (contact_update.h).
#include "contacts/contact_update.h"

#include <collide/narrowphase.h>

#include "base/format.h"
#include "bodies/body_parts.h"
#include "contacts/in_place_merge.h"
#include "memory/heap_bytes.h"
#include "memory/prefetch.h"
#include "memory/scratch.h"
#include "shapes/shape_functions.h"

#include <algorithm>
#include <memory>
#include <utility>

namespace collide::detail {

namespace {

// A separating axis is kept for pairs apart where the collider test is costly: polyhedra (k-DOP,
// hull) against any convex shape. Two support points decide whether the pair is still apart.
bool separatingAxisPays(const Shape& a, const Shape& b) {
  const auto polyhedron = [](const Shape& s) {
    return s.type() == ShapeType::ConvexHull || s.type() == ShapeType::Kdop;
  };
  return a.isConvex() && b.isConvex() && (polyhedron(a) || polyhedron(b));
}

// How far B lies beyond A along the unit world direction: B's farthest point against it minus A's
// farthest point along it; > 0 is apart.
float separationAlong(const Shape& a, const Transform& ta, const Shape& b, const Transform& tb,
                      const Vec3& axis) {
  const Vec3 pa = ta.applyToPoint(support(a, ta.inverseApplyToDirection(axis)));
  const Vec3 pb = tb.applyToPoint(support(b, tb.inverseApplyToDirection(-axis)));
  return glm::dot(pb - pa, axis);
}

// Whether last step's record of a pair (a Contact or an ApartPair) was between these very bodies,
// not bodies that took a freed slot since.
template <typename Record>
bool sameBodies(const Record& old, const BodyStorage& bodies, std::uint32_t ia, std::uint32_t ib) {
  return old.bodyA == ia && old.bodyB == ib && old.generationA == bodies.records[ia].generation &&
         old.generationB == bodies.records[ib].generation;
}

// Whether a pair keeps its manifold in the cache (ManifoldCache), to place it again while the pair
// holds still. Not a sphere against a sphere or a plane: their test (a distance and a normal) costs
// less than checking the cache, and it is exact where the cached points drift by up to the cache's
// tolerance as the sphere rolls. Their manifold is computed every step, and when they are apart
// they keep no record.
bool cachesManifold(const Shape& a, const Shape& b) {
  const ShapeType ta = a.type(), tb = b.type();
  if (ta == ShapeType::Sphere) return tb != ShapeType::Sphere && tb != ShapeType::Plane;
  return !(tb == ShapeType::Sphere && ta == ShapeType::Plane);
}

// Last step's record of a pair found apart, as the walk reads a previous contact: one with no
// points, its cache (every other field of it was the default). `view` starts as Contact{}.
const Contact* viewOf(const ApartPair& apart, Contact& view) {
  view.key = apart.key;
  view.bodyA = apart.bodyA;
  view.bodyB = apart.bodyB;
  view.generationA = apart.generationA;
  view.generationB = apart.generationB;
  view.enabled = false;
  restoreCache(apart.cache, view.cache);
  return &view;
}

// The walk in blocks runs without a pre-solve callback (ContactUpdate::run).
const PreSolveCallback kNoPreSolve{};

bool settingsInRange(const ContactSettings& s) {
  return isFinite(s.friction) && s.friction >= 0.0f && isFinite(s.bounciness) && s.bounciness >= 0.0f &&
         s.bounciness <= 1.0f && isFinite(s.surfaceVelocity);
}

}  // namespace

// One run of the stage over the pairs: the walk through them, merged with last step's contacts.
class PairPass {
 public:
  PairPass(const ContactUpdate& scratch, const BodyStorage& bodies, std::span<const ProxyPair> pairs,
           InPlaceMerge<Contact>& contacts, InPlaceMerge<ApartPair>& apart, Array<Contact>& pairPrevious,
           const ContactUpdateSettings& settings, float dt, const PreSolveCallback& preSolve,
           const PairFilters& filters, StepEvents& events, std::string& callbackError)
      : s_(scratch),
        bodies_(bodies),
        pairs_(pairs),
        contacts_(contacts),
        apart_(apart),
        pairPrevious_(pairPrevious),
        settings_(settings),
        dt_(dt),
        preSolve_(preSolve),
        filters_(filters),
        events_(events),
        callbackError_(callbackError) {}

  // Last step's manifold of the pair placed again at this step's poses, into `out`, if neither
  // body moved beyond the cache's tolerance relative to the other (reuseManifold).
  static bool placeAgain(const ContactUpdate& s, const BodyStorage& bodies, std::uint32_t ia,
                         std::uint32_t ib, const Contact& previous, const ContactTuning& tuning,
                         Manifold& out) {
    return reuseManifold(previous.cache, previous.manifold, s.poses_[ia], s.poses_[ib],
                         s.scaledRotations_[ia], s.scaledRotations_[ib], bodies.records[ia].originRadius,
                         bodies.records[ib].originRadius, tuning.manifoldCacheDistance, out);
  }

  // How a pair's manifold is found, the cheapest exact way first: last step's placed again
  // (Reused, written to `out`; not tried again when `reuseTried`), the bounding spheres apart by
  // more than the margin, still apart along last step's separating axis, or the proxies' collider
  // test.
  enum class ManifoldRoute { Reused, SpheresApart, AxisApart, Test };
  static ManifoldRoute manifoldRoute(const ContactUpdate& s, const BodyStorage& bodies, std::uint32_t ia,
                                     std::uint32_t ib, const Contact* previous, float margin,
                                     const ContactTuning& tuning, bool reuseTried, Manifold& out) {
    const BodyRecord& ra = bodies.records[ia];
    const BodyRecord& rb = bodies.records[ib];
    const Transform& ta = s.poses_[ia];
    const Transform& tb = s.poses_[ib];
    const bool sensor = ra.sensor || rb.sensor;
    if (previous && !sensor && !reuseTried && placeAgain(s, bodies, ia, ib, *previous, tuning, out))
      return ManifoldRoute::Reused;
    // The lecture's early reject with the cheapest bounding volume, before the collider test.
    if (glm::length(tb.position - ta.position) > ra.originRadius + rb.originRadius + margin)
      return ManifoldRoute::SpheresApart;
    // Two support points instead of the separating-axis test (the broad phase's fat boxes keep
    // many such pairs, e.g. neighbours in a heap of hulls).
    if (previous && !sensor && previous->cache.hasAxis && previous->manifold.count == 0 &&
        separationAlong(ra.shape, ta, rb.shape, tb, ta.applyToDirection(previous->cache.separatingAxis)) >
            margin)
      return ManifoldRoute::AxisApart;
    return ManifoldRoute::Test;
  }

  // The speculative margin of a pair (none for a sensor's).
  static float pairMargin(const ContactUpdate& s, const BodyRecord& ra, const BodyRecord& rb,
                          std::uint32_t ia, std::uint32_t ib, float dt, const ContactTuning& tuning) {
    if (ra.sensor || rb.sensor) return 0.0f;
    return speculativeMargin(s.velocities_[ia], s.velocities_[ib], s.spinReaches_[ia], s.spinReaches_[ib], dt,
                             tuning.speculativeDistance);
  }

  // The proxies' collider test, and for polyhedra found apart their distance (the next step tests
  // the separating axis first).
  static ContactUpdate::StagedTest runTest(const BodyRecord& ra, const Transform& ta, const BodyRecord& rb,
                                           const Transform& tb, float margin) {
    ContactUpdate::StagedTest test;
    collide::collide(ra.shape, ta, rb.shape, tb, test.manifold, margin);
    const bool sensor = ra.sensor || rb.sensor;
    if (!sensor && test.manifold.count == 0 && separatingAxisPays(ra.shape, rb.shape)) {
      test.apart = collide::distance(ra.shape, ta, rb.shape, tb);
      test.hasApart = true;
    }
    return test;
  }

  // Whether the walk takes this pair to manifoldRoute (not skipped, filtered aside, asleep or made
  // of parts), and last step's contact of it: what stageTests needs to know ahead of the walk.
  // The pair filters are not asked (a user's filter is called once, by the walk): a filtered pair
  // may be tested for nothing.
  static bool walkTests(const BodyStorage& bodies, std::uint32_t ia, std::uint32_t ib) {
    const BodyRecord& ra = bodies.records[ia];
    const BodyRecord& rb = bodies.records[ib];
    if (ra.type != BodyType::Dynamic && rb.type != BodyType::Dynamic) return false;
    if (ra.sensor && rb.sensor) return false;
    if (!bodies.isAwakeDynamic(ia) && !bodies.isAwakeDynamic(ib)) return false;
    return !hasParts(ra) && !hasParts(rb);
  }

  // The pairs [begin, end), and last step's contacts after the last of them (in the merges) ended.
  ContactUpdateCounts run(std::size_t begin, std::size_t end) {
    for (std::size_t p = begin; p < end; ++p) {
      prefetchAhead(p);
      updatePair(pairs_[p], p);
    }
    for (; contacts_.hasNext(); contacts_.pop()) events_.endVanished(bodies_, contacts_.next());
    return counts_;
  }

 private:
  // Last step's contacts are read, and this step's written, in order, and a contact is long: both
  // are asked for a few contacts ahead, where the hardware's stride detection would come too late.
  // The shapes of the pairs a few places on that will likely be computed, not reused, are asked for
  // in three stages: the bodies' records (where the shape is), the hulls, their arrays.
  static constexpr std::size_t kContactsAhead = 4;
  static constexpr std::size_t kPairsAhead = 4;

  void prefetchAhead(std::size_t p) const {
    if (const Contact* unread = contacts_.unreadAhead(kContactsAhead)) prefetchBytes(unread, sizeof(Contact));
    if (const Contact* slot = contacts_.slotAhead(kContactsAhead)) prefetchBytes(slot, sizeof(Contact));
    prefetchPairShapes(p + 3 * kPairsAhead, [](const Shape& shape) { prefetchLine(&shape); });
    prefetchPairShapes(p + 2 * kPairsAhead, prefetchShapeHeader);
    prefetchPairShapes(p + kPairsAhead, prefetchShapeArrays);
  }
  template <typename Prefetch>
  void prefetchPairShapes(std::size_t p, Prefetch prefetch) const {
    if (p >= pairs_.size()) return;
    const std::uint32_t a = bodyOf(pairs_[p].a), b = bodyOf(pairs_[p].b);
    if (!s_.likelyPlaced_[a] && !s_.likelyPlaced_[b]) return;
    prefetch(bodies_.records[a].shape);
    prefetch(bodies_.records[b].shape);
  }

  std::uint32_t bodyOf(ProxyId proxy) const { return s_.proxyBodies_[proxy.index]; }

  // Last step's contacts of pairs before this one in key order are of pairs that are gone: they end.
  void endVanishedBefore(std::uint64_t key) {
    for (; contacts_.hasNext() && contacts_.next().key < key; contacts_.pop())
      events_.endVanished(bodies_, contacts_.next());
  }

  // Whether last step's contacts of this pair (one, or one per pair of parts for bodies made of
  // parts), next in the merge, were between these very bodies (not bodies that took a freed slot).
  bool previousIsOurs(std::uint64_t key, std::uint32_t ia, std::uint32_t ib) const {
    return contacts_.hasNext() && contacts_.next().key == key &&
           sameBodies(contacts_.next(), bodies_, ia, ib);
  }

  // Goes past last step's contacts of this pair; `visit` sees each that was ours (previousIsOurs).
  // A contact is visited where it lies: `visit` may emplace (the slot emplace() gives is never an
  // unread contact's), and a reference to it holds until the next emplace().
  template <typename Visit>
  void passPrevious(std::uint64_t key, std::uint32_t ia, std::uint32_t ib, Visit&& visit) {
    const bool ours = previousIsOurs(key, ia, ib);
    for (; contacts_.hasNext() && contacts_.next().key == key; contacts_.pop())
      if (ours) visit(contacts_.next());
  }

  // Last step's contacts of this pair, copied out (for pairs of parts, which write several contacts
  // while they read several).
  std::span<const Contact> copyPrevious(std::uint64_t key, std::uint32_t ia, std::uint32_t ib) {
    pairPrevious_.clear();
    passPrevious(key, ia, ib, [&](const Contact& old) { pairPrevious_.push_back(old); });
    return pairPrevious_;
  }

  // Last step's record of this pair found apart, if it was between these very bodies (a pair has
  // a contact or an apart record, not both). It lies in the merge: valid until the next record apart
  // is emplaced.
  const ApartPair* takePreviousApart(std::uint64_t key, std::uint32_t ia, std::uint32_t ib) {
    for (; apart_.hasNext() && apart_.next().key < key; apart_.pop()) {
    }
    if (!apart_.hasNext() || apart_.next().key != key) return nullptr;
    const ApartPair* old = &apart_.next();
    apart_.pop();
    return sameBodies(*old, bodies_, ia, ib) ? old : nullptr;
  }

  void updatePair(const ProxyPair& pair, std::size_t pairIndex) {
    const std::uint64_t key = pairKey(pair.a.index, pair.b.index);
    const std::uint32_t ia = bodyOf(pair.a);
    const std::uint32_t ib = bodyOf(pair.b);
    endVanishedBefore(key);
    const ApartPair* previousApart = takePreviousApart(key, ia, ib);
    const BodyRecord& ra = bodies_.records[ia];
    const BodyRecord& rb = bodies_.records[ib];
    const auto end = [&](const Contact& old) { events_.endVanished(bodies_, old); };
    // Only a dynamic body responds: kinematic-kinematic and kinematic-static pairs are never tested
    // (static-static never reaches us: the broad phase does not produce them).
    if (ra.type != BodyType::Dynamic && rb.type != BodyType::Dynamic) {
      passPrevious(key, ia, ib, [](const Contact&) {});
      return;
    }
    if (ra.sensor && rb.sensor) {
      passPrevious(key, ia, ib, end);
      return;
    }
    if (!pairAllowed(bodies_, filters_, ia, ib)) {
      ++counts_.filteredPairs;
      passPrevious(key, ia, ib, end);
      return;
    }
    if (!bodies_.isAwakeDynamic(ia) && !bodies_.isAwakeDynamic(ib)) {
      // Sleeping against static, sleeping or still kinematic: nothing moves, so last step's contact
      // is kept as it was (touching state, impulses for the warm start on waking), unsolved.
      passPrevious(key, ia, ib, [&](const Contact& old) {
        Contact& kept = contacts_.emplace(old);
        kept.asleep = true;
        kept.wasTouching = kept.touching;
        kept.impactSpeed = kept.impactImpulse = 0.0f;
      });
      if (previousApart) {
        const ApartPair kept = *previousApart;  // emplace() may spill over where it lies
        apart_.emplace(kept);
      }
      return;
    }
    if (hasParts(ra) || hasParts(rb)) {
      updatePartPairs(key, ia, ib, copyPrevious(key, ia, ib));
      return;
    }
    // Last step's contact is read where it lies, and this step's made beside it (building_): in a
    // steady pile the new one goes into the old one's very slot, so it is copied there at the end.
    const Contact* previous = nullptr;
    passPrevious(key, ia, ib, [&](const Contact& old) {
      if (!previous) previous = &old;
    });
    const bool sensor = ra.sensor || rb.sensor;
    const bool reuseTried = previous && !sensor;
    if (reuseTried && placedAgain(ia, ib, *previous, pairIndex, placed_)) {
      // The common case of a resting pile, updated where it lies without a copy.
      ++counts_.narrowPhaseTests;
      ++counts_.reusedManifolds;
      Contact& c = contacts_.keep(*previous);
      refreshPlaced(key, ia, ib, partMaterial(ra, 0), partMaterial(rb, 0), c);
      finishContact(ia, ib, c);
      return;
    }
    const bool previousIsContact = previous != nullptr;
    if (!previous && previousApart) previous = viewOf(*previousApart, apartView_);
    ++counts_.narrowPhaseTests;
    if (previousIsContact && !sensor && !cachesManifold(ra.shape, rb.shape)) {
      // A sphere that touched last step (a heap): its manifold is computed (no cache), and the
      // contact renewed where it lies rather than made aside and copied over it.
      computeManifold(ia, ib, previous, reuseTried, uncached_, unusedCache_, pairIndex);
      if (uncached_.count == 0) {
        events_.endVanished(bodies_, *previous);
        return;
      }
      Contact& c = contacts_.keep(*previous);
      renewUncached(key, ia, ib, partMaterial(ra, 0), partMaterial(rb, 0), c);
      finishContact(ia, ib, c);
      return;
    }
    Contact& c = *std::construct_at(&building_);
    const bool reused = computeManifold(ia, ib, previous, reuseTried, c.manifold, c.cache, pairIndex);
    if (c.manifold.count == 0) {
      if (previous) events_.endVanished(bodies_, *previous);
      if (c.cache.valid) keepApart(key, ia, ib, c.cache);
      return;
    }
    fillContact(key, ia, ib, partMaterial(ra, 0), partMaterial(rb, 0), sensor, previous, reused, c);
    finishContact(ia, ib, c);
    contacts_.emplace(c);  // last: it may spill over where `previous` lies
  }

  // Last step's contact `c` of a pair that keeps no manifold cache, made this step's from the
  // manifold just computed (uncached_): what fillContact gives a new contact made from it, and a
  // new contact's defaults where fillContact leaves them; what a new contact inherits (the
  // friction patch, its anchor and state) is there already.
  void renewUncached(std::uint64_t key, std::uint32_t ia, std::uint32_t ib, const BodyMaterial& ma,
                     const BodyMaterial& mb, Contact& c) const {
    const Manifold previousManifold = c.manifold;
    const std::array<ContactPointState, Manifold::kMaxPoints> previousPoints = c.points;
    renewPairFields(key, ia, ib, ma, mb, c);
    c.manifold = uncached_;
    if (c.cache.valid || c.cache.hasAxis) c.cache = ManifoldCache{};
    c.points = {};
    matchContactPoints(previousManifold, previousPoints, c, settings_.tuning.linearSlop);
    c.enabled = true;
  }

  // Whether last step's contact's manifold is placed again this step (ManifoldRoute::Reused, as
  // computeManifold would find it, or as the stage run ahead found it), into `out`.
  bool placedAgain(std::uint32_t ia, std::uint32_t ib, const Contact& previous, std::size_t pairIndex,
                   Manifold& out) const {
    if (const ContactUpdate::StagedTest* staged = s_.stagedTest(pairIndex)) {
      if (!staged->reused) return false;
      out = staged->manifold;
      return true;
    }
    if (s_.stagedRoute(pairIndex, ManifoldRoute::SpheresApart) ||
        s_.stagedRoute(pairIndex, ManifoldRoute::AxisApart))
      return false;
    return placeAgain(s_, bodies_, ia, ib, previous, settings_.tuning, out);
  }

  // What a contact renewed in its slot (refreshPlaced, renewUncached) takes as a new contact made
  // from it would: the pair's fields one step on, and the defaults fillContact leaves in place.
  void renewPairFields(std::uint64_t key, std::uint32_t ia, std::uint32_t ib, const BodyMaterial& ma,
                       const BodyMaterial& mb, Contact& c) const {
    setPairFields(key, ia, ib, ma, mb, false, c.consecutiveSteps + 1, c.touching, c);
    c.partA = c.partB = 0;
    c.surfaceVelocity = Vec3(0.0f);
    c.asleep = false;
    c.impactSpeed = c.impactImpulse = 0.0f;
  }

  // Last step's contact `c` turned into this step's, in place, with its manifold placed again
  // (placed_): every field as computeManifold and fillContact give a new contact from it (with
  // reused true), the cache, the friction patch and the anchors kept as they are.
  void refreshPlaced(std::uint64_t key, std::uint32_t ia, std::uint32_t ib, const BodyMaterial& ma,
                     const BodyMaterial& mb, Contact& c) const {
    renewPairFields(key, ia, ib, ma, mb, c);
    const int count = placed_.count;
    c.manifold.count = count;
    c.manifold.normal = placed_.normal;
    for (int i = 0; i < Manifold::kMaxPoints; ++i) {
      const float normalImpulse = c.points[i].normalImpulse;
      c.manifold.points[i] = i < count ? placed_.points[i] : ContactPoint{};
      c.points[i] = ContactPointState{};
      if (i < count) c.points[i].normalImpulse = normalImpulse;
    }
    c.prolongedPoints = static_cast<std::uint8_t>((1u << count) - 1u);
    c.enabled = true;
  }

  // The pre-solve callback, then whether the contact touches.
  void finishContact(std::uint32_t ia, std::uint32_t ib, Contact& c) const {
    if (!c.sensor && preSolve_) applyPreSolve(ia, ib, c);
    const float deepest = c.manifold.maxDepth();
    c.touching = c.enabled && (c.sensor ? deepest >= 0.0f : deepest >= -settings_.tuning.linearSlop);
    if (!c.enabled) {
      c.points = {};
      c.prolongedPoints = 0;
    }
  }

  // A pair with a body made of parts: a contact per pair of parts that the parts' filters allow,
  // not both sensors, whose boxes (grown by the margin) overlap and whose manifold has points, in
  // the order of the parts. Each is computed every step (no manifold cache) and carried over from
  // last step's contact of the same parts.
  void updatePartPairs(std::uint64_t key, std::uint32_t ia, std::uint32_t ib,
                       std::span<const Contact> previous) {
    const BodyRecord& ra = bodies_.records[ia];
    const BodyRecord& rb = bodies_.records[ib];
    const Transform& ta = s_.poses_[ia];
    const Transform& tb = s_.poses_[ib];
    const float speculative =
        speculativeMargin(s_.velocities_[ia], s_.velocities_[ib], s_.spinReaches_[ia], s_.spinReaches_[ib],
                          dt_, settings_.tuning.speculativeDistance);
    std::size_t k = 0;  // last step's contacts before k are matched or ended
    forEachAllowedPartPair(ra, rb, [&](std::uint32_t i, std::uint32_t j) {
      const bool sensor = partIsSensor(ra, i) || partIsSensor(rb, j);
      if (partIsSensor(ra, i) && partIsSensor(rb, j)) return;
      const std::uint64_t parts = partsKey(i, j);
      while (k < previous.size() && partsKey(previous[k]) < parts)
        events_.endVanished(bodies_, previous[k++]);
      const Contact* old = k < previous.size() && partsKey(previous[k]) == parts ? &previous[k++] : nullptr;
      const Shape& shapeA = partShape(ra, i);
      const Shape& shapeB = partShape(rb, j);
      const Transform pa = ta * partLocalPose(ra, i);
      const Transform pb = tb * partLocalPose(rb, j);
      const float margin = sensor ? 0.0f : speculative;
      // A body of one plane against parts: the plane's box is everywhere.
      const bool plane = shapeA.type() == ShapeType::Plane || shapeB.type() == ShapeType::Plane;
      if (!plane && !worldBounds(shapeA, pa).expanded(margin).overlaps(worldBounds(shapeB, pb))) {
        if (old) events_.endVanished(bodies_, *old);
        return;
      }
      ++counts_.narrowPhaseTests;
      Contact& c = contacts_.emplace();
      collide::collide(shapeA, pa, shapeB, pb, c.manifold, margin);
      if (c.manifold.count == 0) {
        if (old) events_.endVanished(bodies_, *old);
        contacts_.dropLast();
        return;
      }
      c.partA = i;
      c.partB = j;
      fillContact(key, ia, ib, partMaterial(ra, i), partMaterial(rb, j), sensor, old, false, c);
      finishContact(ia, ib, c);
    });
    while (k < previous.size()) events_.endVanished(bodies_, previous[k++]);
  }

  // The pair's manifold in c.manifold and what the next step may reuse of it in c.cache, by the
  // cheapest exact way (manifoldRoute); the collider test's result from `staged` if it ran ahead.
  // `reuseTried`: the walk already tried to place last step's manifold again (placedAgain), in vain.
  // Returns whether last step's manifold was placed again.
  bool computeManifold(std::uint32_t ia, std::uint32_t ib, const Contact* previous, bool reuseTried,
                       Manifold& manifold, ManifoldCache& cache, std::size_t pairIndex) {
    const ContactUpdate::StagedTest* staged = s_.stagedTest(pairIndex);
    const BodyRecord& ra = bodies_.records[ia];
    const BodyRecord& rb = bodies_.records[ib];
    const Transform& ta = s_.poses_[ia];
    const Transform& tb = s_.poses_[ib];
    const ContactTuning& tuning = settings_.tuning;
    const bool sensor = ra.sensor || rb.sensor;
    const float margin = pairMargin(s_, ra, rb, ia, ib, dt_, tuning);
    // An empty manifold is cached only if the margin exceeds the cache's tolerance: a pair found
    // apart by more than the margin then cannot touch before it moves beyond the tolerance.
    const bool cacheApart = margin > 2.0f * tuning.manifoldCacheDistance;
    const bool cached = !sensor && cachesManifold(ra.shape, rb.shape);
    // The stage ran ahead found the route of a pair it tested (and of one found apart).
    const ManifoldRoute route =
        staged ? (staged->reused ? ManifoldRoute::Reused : ManifoldRoute::Test)
        : s_.stagedRoute(pairIndex, ManifoldRoute::SpheresApart) ? ManifoldRoute::SpheresApart
        : s_.stagedRoute(pairIndex, ManifoldRoute::AxisApart)
            ? ManifoldRoute::AxisApart
            : manifoldRoute(s_, bodies_, ia, ib, previous, margin, tuning, reuseTried, manifold);
    switch (route) {
      case ManifoldRoute::Reused:
        if (staged) manifold = staged->manifold;
        // A pair that has not moved relative to itself since its manifold was computed (a resting
        // stack, a crate on the terrain).
        cache = previous->cache;
        ++counts_.reusedManifolds;
        return true;
      case ManifoldRoute::SpheresApart:
        manifold.count = 0;
        if (cached && cacheApart) storeManifold(manifold, ta, tb, cache);
        return false;
      case ManifoldRoute::AxisApart:
        manifold.count = 0;
        if (cacheApart) storeManifold(manifold, ta, tb, cache);
        cache.separatingAxis = previous->cache.separatingAxis;
        cache.hasAxis = true;
        return false;
      case ManifoldRoute::Test:
        break;
    }
    const ContactUpdate::StagedTest test = staged ? *staged : runTest(ra, ta, rb, tb, margin);
    manifold = test.manifold;
    if (cached && (manifold.count > 0 || cacheApart)) storeManifold(manifold, ta, tb, cache);
    if (test.hasApart) {
      const DistanceResult& apart = test.apart;
      if (!apart.overlapping && apart.distance > margin) {
        cache.separatingAxis = ta.inverseApplyToDirection(apart.normal);
        cache.hasAxis = true;
      }
    }
    return false;
  }

  // A pair found apart keeps its cache (ApartPair), so that next step can take the same "apart"
  // while the pair does not move.
  void keepApart(std::uint64_t key, std::uint32_t ia, std::uint32_t ib, const ManifoldCache& cache) {
    apart_.emplace(ApartPair{key, ia, ib, bodies_.records[ia].generation, bodies_.records[ib].generation,
                             apartCacheOf(cache)});
  }

  // A touching or speculative contact: the two parts' materials combined, and last step's points and
  // friction patch carried over (new vs prolonged contact).
  void fillContact(std::uint64_t key, std::uint32_t ia, std::uint32_t ib, const BodyMaterial& ma,
                   const BodyMaterial& mb, bool sensor, const Contact* previous, bool reused,
                   Contact& c) const {
    setPairFields(key, ia, ib, ma, mb, sensor, previous ? previous->consecutiveSteps + 1 : 1,
                  previous ? previous->touching : false, c);
    if (previous) {
      inheritContact(*previous, c, settings_.tuning.linearSlop, reused);
    } else {
      c.points = {};
      c.prolongedPoints = 0;
    }
    c.enabled = true;
  }

  // The pair's own fields of a contact: its bodies, the parts' materials combined, and how long it
  // has lasted.
  void setPairFields(std::uint64_t key, std::uint32_t ia, std::uint32_t ib, const BodyMaterial& ma,
                     const BodyMaterial& mb, bool sensor, int consecutiveSteps, bool wasTouching,
                     Contact& c) const {
    c.key = key;
    c.bodyA = ia;
    c.bodyB = ib;
    c.generationA = bodies_.records[ia].generation;
    c.generationB = bodies_.records[ib].generation;
    c.sensor = sensor;
    c.friction = combine(settings_.frictionCombine, ma.friction, mb.friction);
    c.rollingResistance = std::max(ma.rollingResistance, mb.rollingResistance);
    c.restitution = combine(settings_.bouncinessCombine, ma.bounciness, mb.bounciness);
    c.impactBounciness = c.restitution;
    c.consecutiveSteps = consecutiveSteps;
    c.wasTouching = wasTouching;
    if (settings_.impactModel == ImpactModel::Interpolated) {
      // The lecture's impact replaces the solver's restitution, and its glued (inelastic) part
      // already handles the tangent, so the impact step gets no solver bounce and no Coulomb
      // friction (friction is for prolonged contacts, lecture slide 12). See contact_response.h.
      c.restitution = 0.0f;
      if (!c.wasTouching) c.friction = 0.0f;
    }
  }

  // The pre-solve callback may disable the contact for this step or change its settings. A NaN
  // friction would reach every body the contact touches: bad settings are refused (the contact
  // keeps the world's values), the step completes, and then World::step reports them.
  void applyPreSolve(std::uint32_t ia, std::uint32_t ib, Contact& c) const {
    ContactSettings settings{c.friction, c.impactBounciness, Vec3(0.0f), c.partA, c.partB};
    c.enabled = preSolve_(bodies_.idOf(ia), bodies_.idOf(ib), c.manifold, settings);
    if (!settingsInRange(settings)) {
      if (callbackError_.empty()) {
        callbackError_ = "world: step: the pre-solve callback set contact settings out of range for bodies " +
                         std::to_string(ia) + " and " + std::to_string(ib) + " (friction " +
                         formatFloat(settings.friction) + ", bounciness " + formatFloat(settings.bounciness) +
                         ", surfaceVelocity " + formatVec(settings.surfaceVelocity) +
                         "); the contact kept its own values";
      }
      settings = ContactSettings{c.friction, c.impactBounciness, Vec3(0.0f), c.partA, c.partB};
    }
    c.friction = settings.friction;
    c.impactBounciness = settings.bounciness;
    if (settings_.impactModel != ImpactModel::Interpolated) c.restitution = settings.bounciness;
    c.surfaceVelocity =
        settings.surfaceVelocity - glm::dot(settings.surfaceVelocity, c.manifold.normal) * c.manifold.normal;
  }

  const ContactUpdate& s_;
  const BodyStorage& bodies_;
  std::span<const ProxyPair> pairs_;
  InPlaceMerge<Contact>& contacts_;  // last step's contacts read, this step's written over them
  InPlaceMerge<ApartPair>& apart_;   // and the pairs found apart
  Array<Contact>& pairPrevious_;     // the walked pair's last contacts, copied out (copyPrevious)
  const ContactUpdateSettings& settings_;
  float dt_;
  const PreSolveCallback& preSolve_;
  const PairFilters& filters_;
  StepEvents& events_;
  std::string& callbackError_;
  Contact apartView_;          // the previous contact of a pair that was apart (viewOf)
  Manifold uncached_;          // the manifold of a pair that keeps no cache (renewUncached)
  ManifoldCache unusedCache_;  // what computeManifold writes for such a pair: nothing
  Contact building_;           // this step's contact of the walked pair, until it is kept
  Manifold placed_;            // last step's manifold placed again (placedAgain)
  ContactUpdateCounts counts_;
};

void ContactUpdate::snapshotBodies(const BodyStorage& bodies, const BroadPhase& broadPhase, float dt,
                                   float cacheDistance, TaskRunner& tasks) {
  const std::size_t n = bodies.records.size();
  poses_.resize(n);
  scaledRotations_.resize(n);
  spinReaches_.resize(n);
  velocities_.resize(n);
  likelyPlaced_.assign(n, 0);
  // Each body's entries are its own: ranges of bodies in parallel.
  constexpr std::uint32_t kBodiesPerRange = 256;
  tasks.parallelFor(static_cast<std::uint32_t>(n), kBodiesPerRange,
                    [&](std::uint32_t begin, std::uint32_t end, std::uint32_t) {
                      snapshotRange(bodies, dt, cacheDistance, begin, end);
                    });
  // Each proxy's body (its user value), copied into a compact array that the pair loop and its
  // prefetching read twice a pair, instead of the broad phase's larger records.
  const auto& proxies = broadPhase.records();
  proxyBodies_.resize(proxies.size());
  for (std::size_t k = 0; k < proxies.size(); ++k)
    proxyBodies_[k] = static_cast<std::uint32_t>(proxies[k].userValue);
}

void ContactUpdate::snapshotRange(const BodyStorage& bodies, float dt, float cacheDistance,
                                  std::uint32_t begin, std::uint32_t end) {
  for (std::uint32_t i = begin; i < end; ++i) {
    if (!bodies.records[i].alive) continue;
    poses_[i] = bodyTransform(bodies.records[i], bodies.states[i]);
    scaledRotations_[i] = glm::mat3_cast(poses_[i].rotation) * poses_[i].scale;
    spinReaches_[i] = spinReach(bodies.records[i], bodies.states[i]);
    velocities_[i] = bodies.states[i].linearVelocity;
    // A body that moves this step by more than the manifold cache's tolerance will likely have its
    // pairs computed, not reused: the pair loop asks ahead for such bodies' shape data.
    const float motion = dt * (glm::length(velocities_[i]) + spinReaches_[i]);
    likelyPlaced_[i] = motion > cacheDistance;
  }
}

void ContactUpdate::stageTests(const BodyStorage& bodies, std::span<const ProxyPair> pairs,
                               const Array<Contact>& previous, const Array<ApartPair>& previousApart,
                               const ContactUpdateSettings& settings, float dt, TaskRunner& tasks) {
  stagedIndex_.resize(pairs.size());
  staged_.resize(static_cast<std::size_t>(tasks.workerCount()));
  for (WorkerTests& list : staged_) list.tests.clear();
  tasks.parallelFor(
      static_cast<std::uint32_t>(pairs.size()), kPairsPerRange,
      [&](std::uint32_t begin, std::uint32_t end, std::uint32_t worker) {
        Array<StagedTest>& list = staged_[worker].tests;
        Manifold scratch;
        // Last step's contacts, merged in key order as the walk does, from where
        // this range's first pair would find them.
        const std::uint64_t firstKey = pairKey(pairs[begin].a.index, pairs[begin].b.index);
        auto cursor =
            previous.begin() + static_cast<std::ptrdiff_t>(firstAtOrAfter<Contact>(previous, firstKey));
        auto apartCursor = previousApart.begin() +
                           static_cast<std::ptrdiff_t>(firstAtOrAfter<ApartPair>(previousApart, firstKey));
        Contact apartView;
        for (std::uint32_t p = begin; p < end; ++p) {
          stagedIndex_[p] = kNotStaged;
          const std::uint32_t ia = proxyBodies_[pairs[p].a.index];
          const std::uint32_t ib = proxyBodies_[pairs[p].b.index];
          if (!PairPass::walkTests(bodies, ia, ib)) continue;
          // Last step's contact of the pair, as the walk's merge finds it.
          const std::uint64_t key = pairKey(pairs[p].a.index, pairs[p].b.index);
          while (cursor != previous.end() && cursor->key < key) ++cursor;
          while (apartCursor != previousApart.end() && apartCursor->key < key) ++apartCursor;
          const Contact* old = nullptr;
          if (cursor != previous.end() && cursor->key == key && sameBodies(*cursor, bodies, ia, ib))
            old = &*cursor;
          else if (apartCursor != previousApart.end() && apartCursor->key == key &&
                   sameBodies(*apartCursor, bodies, ia, ib))
            old = viewOf(*apartCursor, apartView);
          const BodyRecord& ra = bodies.records[ia];
          const BodyRecord& rb = bodies.records[ib];
          const float margin = PairPass::pairMargin(*this, ra, rb, ia, ib, dt, settings.tuning);
          const PairPass::ManifoldRoute route =
              PairPass::manifoldRoute(*this, bodies, ia, ib, old, margin, settings.tuning, false, scratch);
          if (route == PairPass::ManifoldRoute::SpheresApart) stagedIndex_[p] = kSpheresApart;
          if (route == PairPass::ManifoldRoute::AxisApart) stagedIndex_[p] = kAxisApart;
          if (route == PairPass::ManifoldRoute::Reused) {
            stagedIndex_[p] = worker << 26 | static_cast<std::uint32_t>(list.size());
            ContactUpdate::StagedTest& placed = list.emplace_back();
            placed.manifold = scratch;
            placed.reused = true;
          }
          if (route != PairPass::ManifoldRoute::Test) continue;
          stagedIndex_[p] = worker << 26 | static_cast<std::uint32_t>(list.size());
          list.push_back(PairPass::runTest(ra, poses_[ia], rb, poses_[ib], margin));
        }
      });
}

ContactUpdateCounts ContactUpdate::run(const BodyStorage& bodies, const BroadPhase& broadPhase,
                                       std::span<const ProxyPair> pairs, Array<Contact>& contacts,
                                       Array<ApartPair>& apart, const ContactUpdateSettings& settings,
                                       float dt, const PreSolveCallback& preSolve, const PairFilters& filters,
                                       StepEvents& events, std::string& callbackError, TaskRunner& tasks) {
  snapshotBodies(bodies, broadPhase, dt, settings.tuning.manifoldCacheDistance, tasks);
  // Running ahead pays when many pairs need their collider test; when most reuse last step's
  // manifold (a resting pile) the walk's bookkeeping is the work and staging only adds to it. Last
  // step's share decides (either way the contacts are the same).
  const bool manyTests = lastTests_ * kStageWhenTestedOneIn >= lastPairs_;
  if (tasks.workerCount() > 1 && manyTests) {
    stageTests(bodies, pairs, contacts, apart, settings, dt, tasks);  // before the walk rewrites them
  } else {
    stagedIndex_.clear();
  }
  ContactUpdateCounts counts;
  // The walk in blocks on several workers needs its callbacks free of threads (a user's pre-solve
  // or pair filter is called from the calling thread, in pair order) and enough pairs to share.
  const bool callbacks = preSolve || (filters.callback && *filters.callback);
  if (tasks.workerCount() > 1 && !callbacks && pairs.size() >= 2 * kMinPairsPerBlock) {
    counts = walkInBlocks(bodies, pairs, contacts, apart, settings, dt, filters, events, tasks);
  } else {
    InPlaceMerge<Contact> contactMerge(contacts, contactSpill_);
    InPlaceMerge<ApartPair> apartMerge(apart, apartSpill_);
    counts = PairPass(*this, bodies, pairs, contactMerge, apartMerge, pairPrevious_, settings, dt, preSolve,
                      filters, events, callbackError)
                 .run(0, pairs.size());
    contactMerge.finish();
    apartMerge.finish();
  }
  lastTests_ = counts.narrowPhaseTests - counts.reusedManifolds;
  lastPairs_ = counts.narrowPhaseTests;
  // A landing's staged tests (a manifold a tested pair, per worker) are not kept once the pile
  // rests: this step's lists, or none when nothing ran ahead, are their last use.
  for (WorkerTests& list : staged_)
    releaseOversizedScratch(list.tests, stagedIndex_.empty() ? 0 : list.tests.size());
  return counts;
}

ContactUpdateCounts ContactUpdate::walkInBlocks(const BodyStorage& bodies, std::span<const ProxyPair> pairs,
                                                Array<Contact>& contacts, Array<ApartPair>& apart,
                                                const ContactUpdateSettings& settings, float dt,
                                                const PairFilters& filters, StepEvents& events,
                                                TaskRunner& tasks) {
  // Consecutive blocks of pairs, each with the block of last step's contacts (and pairs apart) whose
  // keys fall between its first pair's and the next block's: what the one walk would read while it
  // walks those pairs. How the pairs are cut does not change what each pair gets, so the result is
  // the one walk's at every worker count.
  // A whole number of blocks per worker, so that the workers finish together.
  const auto workers = static_cast<std::size_t>(tasks.workerCount());
  const std::size_t blockCount =
      workers * std::clamp<std::size_t>(pairs.size() / kMinPairsPerBlock / workers, 1, kBlocksPerWorker);
  blocks_.resize(blockCount);
  contactBlocks_.resize(blockCount);
  apartBlocks_.resize(blockCount);
  const auto firstKey = [&](std::size_t block) {
    const ProxyPair& pair = pairs[pairs.size() * block / blockCount];
    return pairKey(pair.a.index, pair.b.index);
  };
  for (std::size_t b = 0; b < blockCount; ++b) {
    blocks_[b].firstPair = pairs.size() * b / blockCount;
    blocks_[b].endPair = pairs.size() * (b + 1) / blockCount;
    const bool last = b + 1 == blockCount;
    contactBlocks_[b].begin = b == 0 ? 0 : contactBlocks_[b - 1].end;
    contactBlocks_[b].end = last ? contacts.size() : firstAtOrAfter<Contact>(contacts, firstKey(b + 1));
    apartBlocks_[b].begin = b == 0 ? 0 : apartBlocks_[b - 1].end;
    apartBlocks_[b].end = last ? apart.size() : firstAtOrAfter<ApartPair>(apart, firstKey(b + 1));
  }
  tasks.parallelFor(
      static_cast<std::uint32_t>(blockCount), 1, [&](std::uint32_t begin, std::uint32_t end, std::uint32_t) {
        for (std::uint32_t b = begin; b < end; ++b) {
          WalkBlock& block = blocks_[b];
          block.events.contacts.clear();
          block.events.contactOfEvent.clear();
          block.events.sensors.clear();
          InPlaceMerge<Contact> contactMerge(contacts, contactBlocks_[b]);
          InPlaceMerge<ApartPair> apartMerge(apart, apartBlocks_[b]);
          block.counts = PairPass(*this, bodies, pairs, contactMerge, apartMerge, block.pairPrevious,
                                  settings, dt, kNoPreSolve, filters, block.events, block.callbackError)
                             .run(block.firstPair, block.endPair);
          contactMerge.finish();
          apartMerge.finish();
        }
      });
  // The blocks' records made one array each, and their events and counts added, in block order.
  compactBlocks<Contact>(contacts, contactBlocks_);
  compactBlocks<ApartPair>(apart, apartBlocks_);
  ContactUpdateCounts counts;
  for (const WalkBlock& block : blocks_) {
    events.contacts.insert(events.contacts.end(), block.events.contacts.begin(), block.events.contacts.end());
    events.contactOfEvent.insert(events.contactOfEvent.end(), block.events.contactOfEvent.begin(),
                                 block.events.contactOfEvent.end());
    events.sensors.insert(events.sensors.end(), block.events.sensors.begin(), block.events.sensors.end());
    counts.filteredPairs += block.counts.filteredPairs;
    counts.narrowPhaseTests += block.counts.narrowPhaseTests;
    counts.reusedManifolds += block.counts.reusedManifolds;
  }
  // A block's overflow is small once contacts come and go a few at a time; while a pile lands,
  // nearly every contact is new and lands there (the blocks start from last step's fewer ones).
  // Such overflows are freed rather than kept for good beside the array they were copied into.
  for (MergeBlock<Contact>& block : contactBlocks_)
    if (block.overflow.capacity() > kKeptOverflow) Array<Contact>().swap(block.overflow);
  for (MergeBlock<ApartPair>& block : apartBlocks_)
    if (block.overflow.capacity() > kKeptOverflow) Array<ApartPair>().swap(block.overflow);
  return counts;
}

std::size_t ContactUpdate::memoryBytes() const {
  std::size_t bytes = heapBytes(poses_) + heapBytes(scaledRotations_) + heapBytes(spinReaches_) +
                      heapBytes(velocities_) + heapBytes(likelyPlaced_) + heapBytes(proxyBodies_) +
                      heapBytes(stagedIndex_) + heapBytes(staged_) + heapBytes(contactSpill_) +
                      heapBytes(apartSpill_) + heapBytes(pairPrevious_) + heapBytes(blocks_) +
                      heapBytes(contactBlocks_) + heapBytes(apartBlocks_);
  for (const WorkerTests& worker : staged_) bytes += heapBytes(worker.tests);
  for (const WalkBlock& block : blocks_) bytes += heapBytes(block.pairPrevious) + block.events.memoryBytes();
  for (const MergeBlock<Contact>& block : contactBlocks_)
    bytes += heapBytes(block.spill) + heapBytes(block.overflow);
  for (const MergeBlock<ApartPair>& block : apartBlocks_)
    bytes += heapBytes(block.spill) + heapBytes(block.overflow);
  return bytes;
}

}  // namespace collide::detail
