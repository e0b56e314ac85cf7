// Contacts kept across steps: the manifold cache and the matching of new to prolonged points
// (contact_cache.h).
#include "contacts/contact_cache.h"

#include <algorithm>
#include <cmath>

namespace collide::detail {

namespace {

// The nearest untaken point of `previous` that passes `accept`, or -1.
template <typename Accept>
int nearestPrevious(const Manifold& previous, const ContactPoint& point,
                    const std::array<bool, Manifold::kMaxPoints>& taken, Accept accept) {
  int best = -1;
  float bestDistance2 = 0.0f;
  for (int j = 0; j < previous.count; ++j) {
    if (taken[j] || !accept(previous.points[j])) continue;
    const Vec3 d = previous.points[j].midpoint() - point.midpoint();
    const float distance2 = glm::dot(d, d);
    if (best < 0 || distance2 < bestDistance2) {
      best = j;
      bestDistance2 = distance2;
    }
  }
  return best;
}

}  // namespace

void matchContactPoints(const Contact& previous, Contact& current, float matchDistance) {
  matchContactPoints(previous.manifold, previous.points, current, matchDistance);
}

void matchContactPoints(const Manifold& previous,
                        const std::array<ContactPointState, Manifold::kMaxPoints>& previousPoints,
                        Contact& current, float matchDistance) {
  std::array<bool, Manifold::kMaxPoints> taken{};
  std::array<int, Manifold::kMaxPoints> match{};
  match.fill(-1);
  // First by feature id (several old points may share an id, e.g. generic GJK contacts all use 0:
  // the nearest wins).
  for (int i = 0; i < current.manifold.count; ++i) {
    const ContactPoint& point = current.manifold.points[i];
    match[i] = nearestPrevious(previous, point, taken,
                               [&](const ContactPoint& old) { return old.featureId == point.featureId; });
    if (match[i] >= 0) taken[match[i]] = true;
  }
  // Then by position: the same physical contact can change its name while it stays in place, e.g.
  // when two equal faces trade the role of reference face. Losing its impulse would drop the warm
  // start on exactly the resting contacts that need it.
  const float limit2 = matchDistance * matchDistance;
  for (int i = 0; i < current.manifold.count; ++i) {
    if (match[i] >= 0) continue;
    const ContactPoint& point = current.manifold.points[i];
    match[i] = nearestPrevious(previous, point, taken, [&](const ContactPoint& old) {
      const Vec3 d = old.midpoint() - point.midpoint();
      return glm::dot(d, d) < limit2;
    });
    if (match[i] >= 0) taken[match[i]] = true;
  }
  current.prolongedPoints = 0;
  for (int i = 0; i < current.manifold.count; ++i) {
    ContactPointState& state = current.points[i];
    state = ContactPointState{};
    if (match[i] >= 0) {
      state.normalImpulse = previousPoints[match[i]].normalImpulse;
      current.prolongedPoints |= static_cast<std::uint8_t>(1u << i);
    }
  }
}

void storeManifold(const Manifold& manifold, const Transform& a, const Transform& b, ManifoldCache& cache) {
  cache.normal = a.inverseApplyToDirection(manifold.normal);
  for (int i = 0; i < manifold.count; ++i) {
    cache.pointsOnA[i] = a.inverseApplyToPoint(manifold.points[i].pointOnA);
    cache.pointsOnB[i] = b.inverseApplyToPoint(manifold.points[i].pointOnB);
  }
  const Quat inverseA = glm::conjugate(a.rotation);
  cache.relativePosition = inverseA * (b.position - a.position);
  cache.relativeRotation = inverseA * b.rotation;
  cache.valid = true;
}

bool reuseManifold(const ManifoldCache& cache, const Manifold& cached, const Transform& a, const Transform& b,
                   const Mat3& scaledRotationA, const Mat3& scaledRotationB, float radiusA, float radiusB,
                   float distance, Manifold& out) {
  if (!cache.valid) return false;
  const Quat inverseA = glm::conjugate(a.rotation);
  const Quat rotation = inverseA * b.rotation;  // B's rotation in A's frame
  const Vec3 position = inverseA * (b.position - a.position);
  // The turn between the cached and the current relative rotation: 2 asin |vector part of the
  // difference|, at most pi times that |vector part|.
  const Quat turn = rotation * glm::conjugate(cache.relativeRotation);
  const float angle = kPi * glm::length(Vec3(turn.x, turn.y, turn.z));
  // B's points seen from A, and A's points seen from B; either bound holds, the smaller one decides.
  const float movedB = glm::length(position - cache.relativePosition) + angle * radiusB;
  if (movedB > distance) {
    const Vec3 positionA = glm::conjugate(rotation) * position;
    // A's origin in B's frame then, derived here: this bound is needed far less often than stored.
    const Vec3 cachedPositionA = glm::conjugate(cache.relativeRotation) * cache.relativePosition;
    const float movedA = glm::length(positionA - cachedPositionA) + angle * radiusA;
    if (movedA > distance) return false;
  }
  // Placed with the two rotations as matrices, not a quaternion rotation per point.
  const Mat3& rotationA = scaledRotationA;
  const Mat3& rotationB = scaledRotationB;
  out.count = cached.count;
  out.normal = rotationA * cache.normal / a.scale;
  for (int i = 0; i < cached.count; ++i) {
    ContactPoint& p = out.points[i];
    p.pointOnA = a.position + rotationA * cache.pointsOnA[i];
    p.pointOnB = b.position + rotationB * cache.pointsOnB[i];
    p.depth = glm::dot(p.pointOnA - p.pointOnB, out.normal);
    p.featureId = cached.points[i].featureId;
  }
  return true;
}

void inheritContact(const Contact& previous, Contact& current, float matchDistance, bool reused) {
  if (reused) {
    for (int i = 0; i < current.manifold.count; ++i) {
      current.points[i] = ContactPointState{};
      current.points[i].normalImpulse = previous.points[i].normalImpulse;
    }
    current.prolongedPoints = static_cast<std::uint8_t>((1u << current.manifold.count) - 1u);
  } else {
    matchContactPoints(previous, current, matchDistance);
  }
  current.frictionImpulse = previous.frictionImpulse;
  current.twistImpulse = previous.twistImpulse;
  current.stickLocalA = previous.stickLocalA;
  current.stickLocalB = previous.stickLocalB;
  current.stuck = previous.stuck;
  current.sliding = previous.sliding;
}

}  // namespace collide::detail
