// Capsule pairs. Capsule–capsule is the lecture's test (slide 61): the closest points of the two
// segments, compared with the sum of the radii; parallel capsules lying on each other get two
// points, the ends of their overlap, so that they rest without rocking (as Box2D v3's
// b2CollideCapsules does). Capsule–box runs GJK on the core segment and clips the segment to the
// box face it lies on.
#include <algorithm>
#include <cmath>

#include "geometry/closest_points.h"
#include "narrowphase/convex_distance.h"
#include "narrowphase/pair_functions.h"

namespace collide::detail {

namespace {

// Below this sine of the angle between the axes (about 1.1 degrees) capsules count as parallel.
constexpr float kParallelSine = 0.02f;

std::uint32_t capsuleFeature(float t) {
  return t <= 0.0f ? kCapsuleEnd0 : (t >= 1.0f ? kCapsuleEnd1 : kCapsuleSide);
}

// A unit vector perpendicular to `axis` (any, deterministic).
Vec3 perpendicular(const Vec3& axis) {
  const float length = glm::length(axis);
  Vec3 t1, t2;
  orthonormalBasis(length > 0.0f ? axis / length : Vec3(0.0f, 1.0f, 0.0f), t1, t2);
  return t1;
}

// A capsule lying on the box face (axis, sign): its segment, e0 + t segment in the box's frame (h:
// the box's half extents), clipped to the face's rectangle, both ends kept, so that the capsule
// rests on two points rather than rocking on one. False when little of the segment is over the face
// or both ends are beyond the margin: the one point from GJK/EPA answers then.
bool lyingOnFaceContact(const Vec3& e0, const Vec3& segment, const Vec3& h, int axis, float sign,
                        float radius, const Transform& transformB, float margin, Manifold& out) {
  float t0 = 0.0f, t1 = 1.0f;
  bool inside = true;
  for (int i = 0; i < 3 && inside; ++i) {
    if (i == axis) continue;
    if (std::abs(segment[i]) < 1e-12f) {
      inside = std::abs(e0[i]) <= h[i];
      continue;
    }
    float enter = (-h[i] - e0[i]) / segment[i];
    float leave = (h[i] - e0[i]) / segment[i];
    if (enter > leave) std::swap(enter, leave);
    t0 = std::max(t0, enter);
    t1 = std::min(t1, leave);
    inside = t0 <= t1;
  }
  if (!inside || !(t1 - t0 > 1e-3f)) return false;
  Vec3 faceNormalLocal(0.0f);
  faceNormalLocal[axis] = sign;
  const Vec3 faceNormal = transformB.applyToDirection(faceNormalLocal);
  int digits[3] = {1, 1, 1};
  digits[axis] = sign > 0.0f ? 2 : 0;
  const std::uint32_t featureB = boxFeature(digits[0], digits[1], digits[2]);
  int count = 0;
  for (const float t : {t0, t1}) {
    const Vec3 local = e0 + t * segment;
    const float height = (sign * local[axis] - h[axis]) * transformB.scale;
    Vec3 onFace = local;
    onFace[axis] = sign * h[axis];
    ContactPoint& point = out.points[count];
    point.pointOnB = transformB.applyToPoint(onFace);
    point.pointOnA = transformB.applyToPoint(local) - radius * faceNormal;
    point.depth = radius - height;
    if (point.depth < -margin) continue;
    point.featureId = featurePair(capsuleFeature(t), featureB);
    ++count;
  }
  if (count == 0) return false;
  out.normal = -faceNormal;
  out.count = count;
  return true;
}

}  // namespace

bool collideCapsuleCapsule(const Shape& shapeA, const Transform& transformA, const Shape& shapeB,
                           const Transform& transformB, float margin, Manifold& out) {
  const Capsule& capsuleA = shapeA.capsule();
  const Capsule& capsuleB = shapeB.capsule();
  const float radiusA = capsuleA.radius * transformA.scale;
  const float radiusB = capsuleB.radius * transformB.scale;
  const Vec3 a0 = transformA.applyToPoint(Vec3(0.0f, -capsuleA.halfHeight, 0.0f));
  const Vec3 a1 = transformA.applyToPoint(Vec3(0.0f, capsuleA.halfHeight, 0.0f));
  const Vec3 b0 = transformB.applyToPoint(Vec3(0.0f, -capsuleB.halfHeight, 0.0f));
  const Vec3 b1 = transformB.applyToPoint(Vec3(0.0f, capsuleB.halfHeight, 0.0f));

  const SegmentPair closest = closestPointsSegmentSegment(a0, a1, b0, b1);
  const float reach = radiusA + radiusB + margin;
  if (closest.distanceSquared > reach * reach) {
    out.count = 0;
    return false;
  }
  const Vec3 axisA = a1 - a0;
  const Vec3 axisB = b1 - b0;
  const float distance = std::sqrt(closest.distanceSquared);
  Vec3 normal;
  if (distance > 1e-6f * (radiusA + radiusB)) {
    normal = (closest.pointOnSecond - closest.pointOnFirst) / distance;
  } else {
    // The axes cross: the normal is perpendicular to both (either sign is as deep).
    const Vec3 cross = glm::cross(axisA, axisB);
    const float length = glm::length(cross);
    normal = length > 1e-6f * glm::length(axisA) * glm::length(axisB) ? cross / length : perpendicular(axisA);
  }
  out.normal = normal;
  out.count = 0;

  // Parallel and overlapping along the axis: the two ends of the overlap.
  const float lengthA = glm::length(axisA);
  const float lengthB = glm::length(axisB);
  const Vec3 unitA = axisA / lengthA;
  const Vec3 unitB = axisB / lengthB;
  if (glm::length(glm::cross(unitA, unitB)) < kParallelSine) {
    const float s0 = glm::dot(b0 - a0, unitA) / lengthA;
    const float s1 = glm::dot(b1 - a0, unitA) / lengthA;
    const float low = std::max(0.0f, std::min(s0, s1));
    const float high = std::min(1.0f, std::max(s0, s1));
    if (high - low > 1e-3f) {
      for (const float s : {low, high}) {
        const Vec3 onA = a0 + s * axisA;
        const float t = closestParameterOnSegment(onA, b0, b1);
        const Vec3 onB = b0 + t * axisB;
        ContactPoint point;
        point.pointOnA = onA + radiusA * normal;
        point.pointOnB = onB - radiusB * normal;
        point.depth = glm::dot(point.pointOnA - point.pointOnB, normal);
        if (point.depth < -margin) continue;
        point.featureId = featurePair(capsuleFeature(s), capsuleFeature(t));
        out.points[out.count++] = point;
      }
      if (out.count > 0) return true;
    }
  }

  ContactPoint& point = out.points[0];
  point.pointOnA = closest.pointOnFirst + radiusA * normal;
  point.pointOnB = closest.pointOnSecond - radiusB * normal;
  point.depth = radiusA + radiusB - distance;
  point.featureId = featurePair(capsuleFeature(closest.s), capsuleFeature(closest.t));
  out.count = 1;
  return true;
}

bool collideCapsuleBox(const Shape& shapeA, const Transform& transformA, const Shape& shapeB,
                       const Transform& transformB, float margin, Manifold& out) {
  const ConvexSupport a = makeConvexSupport(shapeA, transformA);
  const ConvexSupport b = makeConvexSupport(shapeB, transformB);
  DistanceResult distance;
  if (!convexSignedDistance(a, b, margin, distance)) {
    out.count = 0;
    return false;
  }
  const Capsule& capsule = shapeA.capsule();
  const Vec3 h = shapeB.box().halfExtents;
  const float radius = a.radius;

  // The box face facing the capsule: its outward normal is closest to -normal.
  const Vec3 towardsA = transformB.inverseApplyToDirection(-distance.normal);
  int axis = 0;
  for (int i = 1; i < 3; ++i) {
    if (std::abs(towardsA[i]) > std::abs(towardsA[axis])) axis = i;
  }
  const float sign = towardsA[axis] >= 0.0f ? 1.0f : -1.0f;
  const Vec3 e0 =
      transformB.inverseApplyToPoint(transformA.applyToPoint(Vec3(0.0f, -capsule.halfHeight, 0.0f)));
  const Vec3 e1 =
      transformB.inverseApplyToPoint(transformA.applyToPoint(Vec3(0.0f, capsule.halfHeight, 0.0f)));
  const Vec3 segment = e1 - e0;
  const float segmentLength = glm::length(segment);

  // Lying on that face (normal within ~2.6 degrees of the face's, axis within ~1.1 degrees of the
  // face's plane): clip the segment to the face's rectangle and keep both ends.
  if (std::abs(towardsA[axis]) > 0.999f && std::abs(segment[axis]) < kParallelSine * segmentLength &&
      lyingOnFaceContact(e0, segment, h, axis, sign, radius, transformB, margin, out)) {
    return true;
  }

  // One point. Name the features from where the points lie: the capsule end nearest the contact,
  // the box's vertex, edge or face under it.
  const Vec3 onAxis = transformB.inverseApplyToPoint(distance.pointOnA - radius * distance.normal);
  const float t =
      segmentLength > 0.0f
          ? std::clamp(glm::dot(onAxis - e0, segment) / (segmentLength * segmentLength), 0.0f, 1.0f)
          : 0.0f;
  const Vec3 onBox = transformB.inverseApplyToPoint(distance.pointOnB);
  int digits[3];
  for (int i = 0; i < 3; ++i) {
    const float tolerance = 1e-4f * h[i];
    digits[i] = onBox[i] <= -h[i] + tolerance ? 0 : (onBox[i] >= h[i] - tolerance ? 2 : 1);
  }
  const float tEnd = t <= 1e-4f ? 0.0f : (t >= 1.0f - 1e-4f ? 1.0f : t);
  return manifoldFromDistance(
      distance, featurePair(capsuleFeature(tEnd), boxFeature(digits[0], digits[1], digits[2])), margin, out);
}

}  // namespace collide::detail
