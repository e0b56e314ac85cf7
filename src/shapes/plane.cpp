// Half-space proxy (lecture, slide 58): the solid side of the plane normal·x = distance.
#include "shapes/shape_functions.h"

#include <cmath>

namespace collide::detail {

namespace {
constexpr float kInfinite = 1e30f;

// The box of a half-space is unbounded, except on the far side of an axis-aligned normal: a ground
// plane with normal +y has nothing above y = distance, which the broad phase can use. Only an
// exactly aligned normal bounds the solid: with any tilt it rises without limit far enough out (a
// 1 mrad tilt is 1 unit higher 1000 units away), so a near-axis normal gets the infinite box.
Aabb halfSpaceBounds(const Vec3& normal, float distance) {
  Aabb box{Vec3(-kInfinite), Vec3(kInfinite)};
  for (int axis = 0; axis < 3; ++axis) {
    if (normal[(axis + 1) % 3] != 0.0f || normal[(axis + 2) % 3] != 0.0f) continue;
    if (normal[axis] > 0.0f)
      box.max[axis] = distance / normal[axis];
    else
      box.min[axis] = distance / normal[axis];
  }
  return box;
}
}  // namespace

Aabb computeLocalBounds(const Plane& s) { return halfSpaceBounds(s.normal, s.distance); }

Aabb computeWorldBounds(const Plane& s, const Transform& t) {
  const Vec3 normal = t.applyToDirection(s.normal);
  const float distance = s.distance * t.scale + glm::dot(normal, t.position);
  return halfSpaceBounds(normal, distance);
}

bool localContains(const Plane& s, const Vec3& p) { return s.signedDistance(p) <= 0.0f; }

SurfacePoint localClosestPoint(const Plane& s, const Vec3& p) {
  const float d = s.signedDistance(p);
  return {p - d * s.normal, s.normal, d};
}

std::optional<RayHit> localRayCast(const Plane& s, const Ray& ray) {
  const float originDistance = s.signedDistance(ray.origin);
  if (originDistance <= 0.0f) return RayHit{0.0f, ray.origin, -ray.direction, 0};
  const float approach = glm::dot(s.normal, ray.direction);
  if (approach >= 0.0f) return std::nullopt;
  const float t = -originDistance / approach;
  if (t > ray.maxDistance) return std::nullopt;
  return RayHit{t, ray.origin + t * ray.direction, s.normal, 0};
}

}  // namespace collide::detail
