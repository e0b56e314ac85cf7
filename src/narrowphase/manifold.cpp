// Building manifolds: reducing many candidate contacts to four, and one contact from a distance.
#include <algorithm>
#include <cmath>
#include <vector>

#include "narrowphase/pair_functions.h"

namespace collide::detail {

namespace {

// Whether candidate i beats the best so far (index `best`, -1 for none) by `value`: by more than a
// rounding tolerance, or within it and deeper, or as deep and first in a fixed order of positions.
// Near-ties are common (a clipped rectangle's two corners across its diagonal span the same area)
// and must not be decided by the order in which the candidates were made: two routines that find
// the same points (the box–box path and the generic SAT) then keep the same four.
bool beats(std::span<const ContactPoint> candidates, int i, float value, int best, float bestValue) {
  if (best < 0) return true;
  const float tolerance = 1e-4f * std::max(std::abs(value), std::abs(bestValue)) + 1e-12f;
  if (value > bestValue + tolerance) return true;
  if (value < bestValue - tolerance) return false;
  const ContactPoint& a = candidates[i];
  const ContactPoint& b = candidates[best];
  const float depthTolerance = 1e-6f * (1.0f + std::abs(a.depth) + std::abs(b.depth));
  if (a.depth > b.depth + depthTolerance) return true;
  if (a.depth < b.depth - depthTolerance) return false;
  const Vec3 pa = a.midpoint(), pb = b.midpoint();
  if (pa.x != pb.x) return pa.x < pb.x;
  if (pa.y != pb.y) return pa.y < pb.y;
  return pa.z < pb.z;
}

}  // namespace

void reduceContacts(std::span<const ContactPoint> candidates, const Vec3& normal, Manifold& out) {
  const int count = static_cast<int>(candidates.size());
  if (count <= Manifold::kMaxPoints) {
    for (int i = 0; i < count; ++i) out.points[i] = candidates[i];
    out.count = count;
    return;
  }
  // Work on the midpoints projected into the contact plane.
  auto position = [&](int i) {
    const Vec3 p = candidates[i].midpoint();
    return p - glm::dot(p, normal) * normal;
  };
  // 1. The deepest point: the solver needs it most.
  int first = -1;
  for (int i = 0; i < count; ++i) {
    if (beats(candidates, i, candidates[i].depth, first, first < 0 ? 0.0f : candidates[first].depth))
      first = i;
  }
  // 2. The point farthest from it.
  int second = -1;
  float best = -1.0f;
  for (int i = 0; i < count; ++i) {
    if (i == first) continue;
    const Vec3 d = position(i) - position(first);
    const float distance = glm::dot(d, d);
    if (beats(candidates, i, distance, second, best)) {
      best = distance;
      second = i;
    }
  }
  // 3. The point making the largest triangle with them, on either side.
  const Vec3 p0 = position(first), p1 = position(second);
  int third = -1;
  float thirdArea = 0.0f;
  best = -1.0f;
  for (int i = 0; i < count; ++i) {
    if (i == first || i == second) continue;
    const float area = glm::dot(glm::cross(p1 - p0, position(i) - p0), normal);
    if (beats(candidates, i, std::abs(area), third, best)) {
      best = std::abs(area);
      third = i;
      thirdArea = area;
    }
  }
  // 4. The point adding the largest triangle on the other side of the first edge, else the one
  // farthest from the triangle's corners.
  int fourth = -1;
  best = 0.0f;
  for (int i = 0; i < count; ++i) {
    if (i == first || i == second || i == third) continue;
    const float area = glm::dot(glm::cross(p1 - p0, position(i) - p0), normal);
    if (area * thirdArea < 0.0f && std::abs(area) > 0.0f &&
        beats(candidates, i, std::abs(area), fourth, best)) {
      best = std::abs(area);
      fourth = i;
    }
  }
  if (fourth < 0) {
    best = -1.0f;
    const Vec3 p2 = position(third);
    for (int i = 0; i < count; ++i) {
      if (i == first || i == second || i == third) continue;
      const Vec3 q = position(i);
      const float nearest =
          std::min({glm::dot(q - p0, q - p0), glm::dot(q - p1, q - p1), glm::dot(q - p2, q - p2)});
      if (beats(candidates, i, nearest, fourth, best)) {
        best = nearest;
        fourth = i;
      }
    }
  }
  out.points[0] = candidates[first];
  out.points[1] = candidates[second];
  out.points[2] = candidates[third];
  out.points[3] = candidates[fourth];
  out.count = 4;
}

bool manifoldFromDistance(const DistanceResult& distance, std::uint32_t featureId, float margin,
                          Manifold& out) {
  if (distance.distance > margin) {
    out.count = 0;
    return false;
  }
  out.normal = distance.normal;
  out.points[0].pointOnA = distance.pointOnA;
  out.points[0].pointOnB = distance.pointOnB;
  out.points[0].depth = -distance.distance;
  out.points[0].featureId = featureId;
  out.count = 1;
  return true;
}

}  // namespace collide::detail

namespace collide::detail {

bool mergeContacts(std::span<const NormalContact> contacts, float margin, Manifold& out) {
  out.count = 0;
  if (contacts.empty()) return false;
  std::size_t deepest = 0;
  for (std::size_t i = 1; i < contacts.size(); ++i) {
    if (contacts[i].point.depth > contacts[deepest].point.depth) deepest = i;
  }
  const Vec3 normal = contacts[deepest].normal;
  // cos 25°: contacts of nearly coplanar triangles or of children resting on the same surface.
  constexpr float kSameDirection = 0.906f;
  ContactPoint kept[64];
  Array<ContactPoint> overflow;
  std::size_t count = 0;
  for (const NormalContact& contact : contacts) {
    if (glm::dot(contact.normal, normal) < kSameDirection) continue;
    ContactPoint point = contact.point;
    point.depth = glm::dot(point.pointOnA - point.pointOnB, normal);
    // A point apart along its own normal stays apart along the shared one. Its pair of points is
    // not always along its normal (a speculative edge contact's closest points at an edge's end),
    // and measured along another normal such a pair could read as penetrating.
    if (contact.point.depth < 0.0f && point.depth > 0.0f) point.depth = contact.point.depth;
    if (point.depth < -margin) continue;
    // A point on an edge shared by two triangles comes from both, with the same id: keep one.
    const ContactPoint* begin = overflow.empty() ? kept : overflow.data();
    const std::size_t stored = overflow.empty() ? std::min<std::size_t>(count, 64) : overflow.size();
    if (std::any_of(begin, begin + stored, [&](const ContactPoint& other) {
          const Vec3 d = other.pointOnB - point.pointOnB;
          return other.featureId == point.featureId &&
                 glm::dot(d, d) <= 1e-10f * (1.0f + glm::dot(point.pointOnB, point.pointOnB));
        })) {
      continue;
    }
    if (count < 64) {
      kept[count] = point;
    } else {
      if (overflow.empty()) overflow.assign(kept, kept + 64);
      overflow.push_back(point);
    }
    ++count;
  }
  out.normal = normal;
  const std::span<const ContactPoint> candidates =
      overflow.empty() ? std::span<const ContactPoint>(kept, count) : std::span<const ContactPoint>(overflow);
  reduceContacts(candidates, normal, out);
  return out.count > 0;
}

}  // namespace collide::detail
