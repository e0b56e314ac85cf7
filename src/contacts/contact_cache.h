// Contacts kept across steps (lecture: new vs prolonged contacts; Box2D v3's contact array and
// Jolt's contact cache). One Contact per broad-phase pair that the narrow phase tested, keyed by the
// two proxy indices (a << 32 | b), in key order: the broad phase hands pairs sorted, so matching last
// step's contacts is a merge of two sorted arrays — no hash map, no allocation after warm-up, and a
// deterministic order for the solver and the events.
//
// Each point of a new manifold is matched with last step's point of the same featureId (ties:
// the nearest one); a point whose id finds no partner takes the nearest old point left within the
// match distance (the world passes its linear slop), because the same physical contact can be renamed
// while it stays in place: two equal boxes face to face trade the reference face between steps.
// A matched point is "prolonged" and inherits its accumulated impulses for warm starting; an
// unmatched one is new and starts from zero.
#pragma once

#include <collide/narrowphase.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace collide::detail {

struct ContactPointState {
  float normalImpulse = 0.0f;       // per substep, accumulated (warm start)
  float totalNormalImpulse = 0.0f;  // everything applied this step (events)
  float maxNormalImpulse = 0.0f;    // did the point act this step (restitution)
  float relativeVelocity = 0.0f;    // normal relative velocity before the solve (restitution, events)
};

// A manifold as it was computed, in the bodies' own frames, with B's pose in A's frame then (Jolt's
// body pair cache). While the two bodies keep that relative pose within the world's tolerance, the
// manifold can be placed again at their new poses instead of being computed: the points are the
// same material points, the depths follow from where they are now.
struct ManifoldCache {
  Vec3 normal{0.0f};                                   // in A's frame
  std::array<Vec3, Manifold::kMaxPoints> pointsOnA{};  // in A's frame
  std::array<Vec3, Manifold::kMaxPoints> pointsOnB{};  // in B's frame
  Vec3 relativePosition{0.0f};                         // B's origin in A's frame
  Quat relativeRotation{1.0f, 0.0f, 0.0f, 0.0f};       // conj(qA) qB
  // A pair found apart: a direction (A's frame, unit) along which they were apart by more than the
  // margin, which the world tests first next time (Gregorius, GDC 2013: temporal coherence of the
  // separating axis).
  Vec3 separatingAxis{0.0f};
  bool valid = false;
  bool hasAxis = false;
};

// Fills the cache from a manifold just computed at these transforms (an empty one too: the pair is
// then known to be apart by more than the speculative margin).
void storeManifold(const Manifold& manifold, const Transform& a, const Transform& b, ManifoldCache& cache);
// If no point of either body moved by more than `distance` (m) relative to the other since the cache
// was filled, writes the cached manifold placed at these transforms (same points and ids, depths
// measured anew) and returns true. radiusA, radiusB bound the bodies about their origins: a body's
// points move by at most |its origin's move| + (turn angle) x radius relative to the other body.
// scaledRotationA, scaledRotationB: each transform's rotation as a matrix times its scale (taken once
// per body and step by the world, not once per pair).
bool reuseManifold(const ManifoldCache& cache, const Manifold& cached, const Transform& a, const Transform& b,
                   const Mat3& scaledRotationA, const Mat3& scaledRotationB, float radiusA, float radiusB,
                   float distance, Manifold& out);

struct Contact {
  std::uint64_t key = 0;  // proxy a index << 32 | proxy b index
  std::uint32_t bodyA = 0;
  std::uint32_t bodyB = 0;
  // The parts in contact (bodies made of parts have a contact per pair of parts that touch, in the
  // order of their indices; bodies of one shape, part 0).
  std::uint32_t partA = 0;
  std::uint32_t partB = 0;
  std::uint32_t generationA = 0;
  std::uint32_t generationB = 0;
  Manifold manifold;
  std::array<ContactPointState, Manifold::kMaxPoints> points{};
  float friction = 0.0f;
  float rollingResistance = 0.0f;  // m: the larger of the two bodies' (contact_response.h)
  float restitution = 0.0f;        // what the solver applies (Newton); 0 under the interpolated model
  float impactBounciness = 0.0f;   // the combined bounciness, for the lecture's interpolated impact
  Vec3 surfaceVelocity{0.0f};      // of B relative to A in the contact plane (pre-solve: a belt)
  bool sensor = false;             // overlap only, no response
  bool enabled = true;             // the pre-solve callback may disable it for this step
  bool asleep = false;             // no awake dynamic body: kept as it was, not solved (sleeping)
  bool touching = false;           // after this step's narrow phase
  bool wasTouching = false;        // after last step's
  // The friction patch's static anchor is set / the patch reached the friction bound last step
  // (re-anchor); see frictionImpulse below. Kept with the other flags: a contact is long.
  bool stuck = false;
  bool sliding = false;
  // Bit i: point i matched a point of last step's manifold (prolonged, not new).
  std::uint8_t prolongedPoints = 0;
  int consecutiveSteps = 0;    // steps in a row with points (lecture: friction from the second step)
  float impactSpeed = 0.0f;    // the approach speed the impact stage resolved this step (events)
  float impactImpulse = 0.0f;  // the normal impulse it gave (events, and the contact touched)
  // The friction patch (dynamics/contact_solver.h), kept across steps: its impulse as a world vector
  // (the tangent basis is rebuilt every step), the twist about the normal, and the static anchor in
  // each body's frame (from the centre of mass) with whether it holds.
  Vec3 frictionImpulse{0.0f};
  float twistImpulse = 0.0f;
  Vec3 stickLocalA{0.0f};
  Vec3 stickLocalB{0.0f};
  // Last: the solver reads everything above and nothing of this (dynamics/contact_lanes.h).
  ManifoldCache cache;

  bool prolonged(int point) const { return (prolongedPoints >> point) & 1u; }
};

// What a pair found apart keeps of its ManifoldCache: all of it but the points, which an empty
// manifold has none of (56 bytes of the cache's 152).
struct ApartCache {
  Vec3 normal{0.0f};
  Vec3 relativePosition{0.0f};
  Quat relativeRotation{1.0f, 0.0f, 0.0f, 0.0f};
  Vec3 separatingAxis{0.0f};
  bool valid = false;
  bool hasAxis = false;
};

inline ApartCache apartCacheOf(const ManifoldCache& cache) {
  return {cache.normal, cache.relativePosition, cache.relativeRotation, cache.separatingAxis,
          cache.valid,  cache.hasAxis};
}

// The cache of an empty manifold again, into `out` (whose points it leaves as they are: an empty
// manifold reads none).
inline void restoreCache(const ApartCache& apart, ManifoldCache& out) {
  out.normal = apart.normal;
  out.relativePosition = apart.relativePosition;
  out.relativeRotation = apart.relativeRotation;
  out.separatingAxis = apart.separatingAxis;
  out.valid = apart.valid;
  out.hasAxis = apart.hasAxis;
}

// A pair the narrow phase found apart, kept for its cache alone: while the pair does not move,
// the next step takes the same "apart" from it (the empty manifold placed again, or the separating
// axis) instead of a collider test. A Contact with no points would hold the same and 400 bytes of
// defaults more; a heap of spheres keeps about as many pairs apart as touching. Kept in key order
// beside the contacts, out of every stage after the narrow phase.
struct ApartPair {
  std::uint64_t key = 0;  // as Contact::key
  std::uint32_t bodyA = 0;
  std::uint32_t bodyB = 0;
  std::uint32_t generationA = 0;
  std::uint32_t generationB = 0;
  ApartCache cache;
};

// Copies the accumulated impulses of `previous`'s points onto `current`'s matching points and marks
// them prolonged. current.manifold must already hold the new points. A point whose id finds no
// partner takes the nearest unmatched old point within matchDistance (m), if any.
void matchContactPoints(const Contact& previous, Contact& current, float matchDistance = 0.0f);
// The same from last step's manifold and point states alone (a contact renewed where it lies).
void matchContactPoints(const Manifold& previous,
                        const std::array<ContactPointState, Manifold::kMaxPoints>& previousPoints,
                        Contact& current, float matchDistance);

// The whole contact carried over from last step: the points matched as above, and the friction
// patch's impulses and static anchor. A manifold placed again from the cache (reuseManifold) is
// the previous one point for point: `reused` says so, and point i then takes point i's state
// without a search.
void inheritContact(const Contact& previous, Contact& current, float matchDistance, bool reused = false);

inline std::uint64_t pairKey(std::uint32_t proxyA, std::uint32_t proxyB) {
  return (static_cast<std::uint64_t>(proxyA) << 32) | proxyB;
}

// A contact's place in the contacts' order after its key: its two parts.
inline std::uint64_t partsKey(std::uint32_t partA, std::uint32_t partB) {
  return (static_cast<std::uint64_t>(partA) << 32) | partB;
}
inline std::uint64_t partsKey(const Contact& c) { return partsKey(c.partA, c.partB); }

// The contact of the pair with this key and these parts, if the step kept one (contacts are in key
// order, then parts order).
inline const Contact* findContact(std::span<const Contact> contacts, std::uint64_t key,
                                  std::uint32_t partA = 0, std::uint32_t partB = 0) {
  const std::uint64_t parts = partsKey(partA, partB);
  const auto it = std::lower_bound(
      contacts.begin(), contacts.end(), key,
      [&](const Contact& c, std::uint64_t k) { return c.key < k || (c.key == k && partsKey(c) < parts); });
  return it != contacts.end() && it->key == key && partsKey(*it) == parts ? &*it : nullptr;
}

}  // namespace collide::detail
