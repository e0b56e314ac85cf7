// Analytic pairs with a sphere (lecture, slide 62 exercise): the sphere is a point with a radius, so
// each test is the nearest point of the other shape to the centre, compared with the radius.
#include <cmath>

#include "geometry/closest_points.h"
#include "narrowphase/pair_functions.h"

namespace collide::detail {

namespace {

// Contact between a ball around `centerA` and a ball around `centerB`, given their squared
// distance is within reach. The direction is arbitrary (+y) for concentric centres.
void ballContact(const Vec3& centerA, float radiusA, const Vec3& centerB, float radiusB,
                 float distanceSquared, std::uint32_t featureId, Manifold& out) {
  const float distance = std::sqrt(distanceSquared);
  const Vec3 normal = distance > 1e-12f ? (centerB - centerA) / distance : Vec3(0.0f, 1.0f, 0.0f);
  out.normal = normal;
  ContactPoint& point = out.points[0];
  point.pointOnA = centerA + radiusA * normal;
  point.pointOnB = centerB - radiusB * normal;
  point.depth = radiusA + radiusB - distance;
  point.featureId = featureId;
  out.count = 1;
}

}  // namespace

bool collideSphereSphere(const Shape& shapeA, const Transform& transformA, const Shape& shapeB,
                         const Transform& transformB, float margin, Manifold& out) {
  const float radiusA = shapeA.sphere().radius * transformA.scale;
  const float radiusB = shapeB.sphere().radius * transformB.scale;
  const Vec3 d = transformB.position - transformA.position;
  const float distanceSquared = glm::dot(d, d);
  const float reach = radiusA + radiusB + margin;
  if (distanceSquared > reach * reach) {
    out.count = 0;
    return false;
  }
  ballContact(transformA.position, radiusA, transformB.position, radiusB, distanceSquared, 0, out);
  return true;
}

bool collideSphereCapsule(const Shape& shapeA, const Transform& transformA, const Shape& shapeB,
                          const Transform& transformB, float margin, Manifold& out) {
  const float radiusA = shapeA.sphere().radius * transformA.scale;
  const Capsule& capsule = shapeB.capsule();
  const float radiusB = capsule.radius * transformB.scale;
  const Vec3 end0 = transformB.applyToPoint(Vec3(0.0f, -capsule.halfHeight, 0.0f));
  const Vec3 end1 = transformB.applyToPoint(Vec3(0.0f, capsule.halfHeight, 0.0f));
  const Vec3 center = transformA.position;
  const float t = closestParameterOnSegment(center, end0, end1);
  const Vec3 onAxis = end0 + t * (end1 - end0);
  const Vec3 d = onAxis - center;
  const float distanceSquared = glm::dot(d, d);
  const float reach = radiusA + radiusB + margin;
  if (distanceSquared > reach * reach) {
    out.count = 0;
    return false;
  }
  const std::uint32_t featureB = t <= 0.0f ? kCapsuleEnd0 : (t >= 1.0f ? kCapsuleEnd1 : kCapsuleSide);
  ballContact(center, radiusA, onAxis, radiusB, distanceSquared, featurePair(0, featureB), out);
  return true;
}

bool collideSphereBox(const Shape& shapeA, const Transform& transformA, const Shape& shapeB,
                      const Transform& transformB, float margin, Manifold& out) {
  // In the box's frame the box is [-h, h]; the nearest box point to the centre is the clamp.
  const float radiusA = shapeA.sphere().radius * transformA.scale;
  const Vec3 h = shapeB.box().halfExtents;
  const Vec3 center = transformA.position;
  const Vec3 local = transformB.inverseApplyToPoint(center);
  const Vec3 clamped = glm::clamp(local, -h, h);
  int digits[3];
  for (int i = 0; i < 3; ++i) digits[i] = local[i] < -h[i] ? 0 : (local[i] > h[i] ? 2 : 1);

  if (clamped != local) {
    const Vec3 onBox = transformB.applyToPoint(clamped);
    const Vec3 towardsBox = onBox - center;
    const float distance = glm::length(towardsBox);
    if (distance > radiusA + margin) {
      out.count = 0;
      return false;
    }
    // A centre a rounding error outside the box has no usable direction: treat it as inside.
    if (distance > 1e-6f * transformB.scale * glm::length(h)) {
      const Vec3 normal = towardsBox / distance;  // from the centre towards the box: A to B
      out.normal = normal;
      ContactPoint& point = out.points[0];
      point.pointOnA = center + radiusA * normal;
      point.pointOnB = onBox;
      point.depth = radiusA - distance;
      point.featureId = featurePair(0, boxFeature(digits[0], digits[1], digits[2]));
      out.count = 1;
      return true;
    }
    for (int& digit : digits) digit = 1;
  }
  // The centre is inside: it leaves the box through the nearest face.
  int axis = 0;
  float gap = h.x - std::abs(local.x);  // may be a rounding error below 0 (see above)
  for (int i = 1; i < 3; ++i) {
    const float g = h[i] - std::abs(local[i]);
    if (g < gap) {
      gap = g;
      axis = i;
    }
  }
  const float sign = local[axis] >= 0.0f ? 1.0f : -1.0f;
  Vec3 faceNormalLocal(0.0f);
  faceNormalLocal[axis] = sign;
  Vec3 onFace = local;
  onFace[axis] = sign * h[axis];
  digits[axis] = sign > 0.0f ? 2 : 0;
  const Vec3 normal = -transformB.applyToDirection(faceNormalLocal);
  out.normal = normal;
  ContactPoint& point = out.points[0];
  point.pointOnA = center + radiusA * normal;
  point.pointOnB = transformB.applyToPoint(onFace);
  point.depth = radiusA + gap * transformB.scale;
  point.featureId = featurePair(0, boxFeature(digits[0], digits[1], digits[2]));
  out.count = 1;
  return true;
}

}  // namespace collide::detail
