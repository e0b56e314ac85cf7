// Out-of-line parts of math.h: validity checks, box transforms, slab tests and culling.
#include <collide/math.h>

#include <algorithm>
#include <cmath>

namespace collide {

bool isFinite(float value) { return std::isfinite(value); }
bool isFinite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool isFinite(const Quat& q) {
  return std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z) && std::isfinite(q.w);
}

bool isValid(const Transform& transform) {
  return isFinite(transform.position) && isFinite(transform.rotation) &&
         std::abs(glm::dot(transform.rotation, transform.rotation) - 1.0f) < 1e-3f &&
         isFinite(transform.scale) && transform.scale > 0.0f;
}

Aabb merge(const Aabb& a, const Aabb& b) { return {glm::min(a.min, b.min), glm::max(a.max, b.max)}; }

Aabb transformAabb(const Aabb& local, const Transform& transform) {
  if (local.isEmpty()) return local;
  // Arvo, "Transforming axis-aligned bounding boxes" (Graphics Gems, 1990), in centre/extent form:
  // the world half extent along axis i is sum_j |R_ij| h_j.
  const Mat3 rotation = glm::mat3_cast(transform.rotation);
  const Vec3 center = transform.applyToPoint(local.center());
  const Vec3 h = transform.scale * local.halfExtents();
  Vec3 extent(0.0f);
  for (int j = 0; j < 3; ++j) extent += glm::abs(rotation[j]) * h[j];
  return {center - extent, center + extent};
}

float rayAabbEntry(const Ray& ray, const Aabb& box) {
  float tMin = 0.0f;
  float tMax = ray.maxDistance;
  for (int i = 0; i < 3; ++i) {
    if (std::abs(ray.direction[i]) < 1e-12f) {
      if (ray.origin[i] < box.min[i] || ray.origin[i] > box.max[i]) return -1.0f;
      continue;
    }
    const float inverse = 1.0f / ray.direction[i];
    float t0 = (box.min[i] - ray.origin[i]) * inverse;
    float t1 = (box.max[i] - ray.origin[i]) * inverse;
    if (t0 > t1) std::swap(t0, t1);
    tMin = std::max(tMin, t0);
    tMax = std::min(tMax, t1);
    if (tMin > tMax) return -1.0f;
  }
  return tMin;
}

Side classify(const Plane& plane, const Aabb& box) {
  // The box's projection radius on the normal (Akenine-Möller et al., Real-Time Rendering).
  const float centerDistance = plane.signedDistance(box.center());
  const float radius = glm::dot(box.halfExtents(), glm::abs(plane.normal));
  if (centerDistance > radius) return Side::Outside;
  if (centerDistance < -radius) return Side::Inside;
  return Side::Straddling;
}

Side classify(const Plane& plane, const BoundingSphere& sphere) {
  const float centerDistance = plane.signedDistance(sphere.center);
  if (centerDistance > sphere.radius) return Side::Outside;
  if (centerDistance < -sphere.radius) return Side::Inside;
  return Side::Straddling;
}

Frustum Frustum::fromViewProjection(const Mat4& m, ClipDepth depth) {
  // Gribb and Hartmann, "Fast extraction of viewing frustum planes from the world-view-projection
  // matrix" (2001). A clip-space point is inside when -w <= x, y <= w and -w <= z <= w (or
  // 0 <= z <= w); each inequality is a plane row4 ± row_i >= 0 (or row_3 >= 0). glm is
  // column-major: row i is (m[0][i], m[1][i], m[2][i], m[3][i]).
  auto row = [&](int i) { return Vec4(m[0][i], m[1][i], m[2][i], m[3][i]); };
  const Vec4 r0 = row(0), r1 = row(1), r2 = row(2), r3 = row(3);
  const Vec4 nearSide = depth == ClipDepth::ZeroToOne ? r2 : r3 + r2;
  const Vec4 inside[6] = {r3 + r0, r3 - r0, r3 + r1, r3 - r1, nearSide, r3 - r2};
  Frustum f;
  for (int i = 0; i < 6; ++i) {
    // inside: a·x + w >= 0. Our planes keep the solid (inside) side at n·x <= d, so n = -a/|a|.
    const Vec3 a(inside[i]);
    const float length = glm::length(a);
    f.planes[i] = Plane{-a / length, inside[i].w / length};
  }
  return f;
}

bool Frustum::intersects(const Aabb& box) const {
  for (const Plane& plane : planes) {
    if (classify(plane, box) == Side::Outside) return false;
  }
  return true;
}

bool Frustum::intersects(const BoundingSphere& sphere) const {
  for (const Plane& plane : planes) {
    if (classify(plane, sphere) == Side::Outside) return false;
  }
  return true;
}

bool Frustum::contains(const Vec3& point) const {
  for (const Plane& plane : planes) {
    if (plane.signedDistance(point) > 0.0f) return false;
  }
  return true;
}

void orthonormalBasis(const Vec3& n, Vec3& outTangent, Vec3& outBitangent) {
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float b = n.x * n.y * a;
  outTangent = Vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
  outBitangent = Vec3(b, sign + n.y * n.y * a, -n.y);
}

}  // namespace collide
