// Box proxy: axis-aligned in its local frame, oriented by its transform (lecture, slide 51).
#include "shapes/shape_functions.h"

#include <cmath>

namespace collide::detail {

Aabb computeLocalBounds(const Box& s) { return {-s.halfExtents, s.halfExtents}; }

Aabb computeWorldBounds(const Box& s, const Transform& t) { return transformAabb(computeLocalBounds(s), t); }

Vec3 computeSupport(const Box& s, const Vec3& direction) {
  return {direction.x >= 0.0f ? s.halfExtents.x : -s.halfExtents.x,
          direction.y >= 0.0f ? s.halfExtents.y : -s.halfExtents.y,
          direction.z >= 0.0f ? s.halfExtents.z : -s.halfExtents.z};
}

MassProperties computeMassProperties(const Box& s, float density) {
  const Vec3 h = s.halfExtents;
  MassProperties m;
  m.volume = 8.0f * h.x * h.y * h.z;
  m.mass = density * m.volume;
  // Full side 2h: m (4 hy² + 4 hz²) / 12 about x, and so on.
  m.inertia = Mat3(0.0f);
  m.inertia[0][0] = m.mass / 3.0f * (h.y * h.y + h.z * h.z);
  m.inertia[1][1] = m.mass / 3.0f * (h.x * h.x + h.z * h.z);
  m.inertia[2][2] = m.mass / 3.0f * (h.x * h.x + h.y * h.y);
  return m;
}

bool localContains(const Box& s, const Vec3& p) {
  return std::abs(p.x) <= s.halfExtents.x && std::abs(p.y) <= s.halfExtents.y &&
         std::abs(p.z) <= s.halfExtents.z;
}

SurfacePoint localClosestPoint(const Box& s, const Vec3& p) {
  const Vec3 clamped = glm::clamp(p, -s.halfExtents, s.halfExtents);
  if (clamped != p) {
    const Vec3 d = p - clamped;
    const float distance = glm::length(d);
    return {clamped, d / distance, distance};
  }
  // Inside: the nearest face is the one with the smallest gap.
  int axis = 0;
  float gap = s.halfExtents.x - std::abs(p.x);
  for (int i = 1; i < 3; ++i) {
    const float g = s.halfExtents[i] - std::abs(p[i]);
    if (g < gap) {
      gap = g;
      axis = i;
    }
  }
  Vec3 point = p;
  Vec3 normal(0.0f);
  const float sign = p[axis] >= 0.0f ? 1.0f : -1.0f;
  point[axis] = sign * s.halfExtents[axis];
  normal[axis] = sign;
  return {point, normal, -gap};
}

std::optional<RayHit> localRayCast(const Box& s, const Ray& ray) {
  if (localContains(s, ray.origin)) return RayHit{0.0f, ray.origin, -ray.direction, 0};
  // Slab test, remembering which slab the ray entered last: that face is the one it hits. The
  // origin is outside, so some slab is entered at t >= 0 if the ray hits at all.
  float tEnter = -1e30f;
  float tExit = ray.maxDistance;
  int enterAxis = -1;
  float enterSign = 0.0f;
  for (int i = 0; i < 3; ++i) {
    const float o = ray.origin[i], d = ray.direction[i], h = s.halfExtents[i];
    if (std::abs(d) < 1e-12f) {
      if (o < -h || o > h) return std::nullopt;
      continue;
    }
    const float inverse = 1.0f / d;
    float t0 = (-h - o) * inverse;
    float t1 = (h - o) * inverse;
    float sign = -1.0f;  // moving towards +axis, the ray enters through the -h face
    if (t0 > t1) {
      std::swap(t0, t1);
      sign = 1.0f;
    }
    if (t0 > tEnter) {
      tEnter = t0;
      enterAxis = i;
      enterSign = sign;
    }
    tExit = std::min(tExit, t1);
  }
  if (enterAxis < 0 || tEnter < 0.0f || tEnter > tExit) return std::nullopt;
  Vec3 normal(0.0f);
  normal[enterAxis] = enterSign;
  return RayHit{tEnter, ray.origin + tEnter * ray.direction, normal, 0};
}

}  // namespace collide::detail
