// Cylinder proxy: radius around the local y axis, from -halfHeight to +halfHeight.
#include "shapes/shape_functions.h"

#include <cmath>

namespace collide::detail {

Aabb computeLocalBounds(const Cylinder& s) {
  const Vec3 extent(s.radius, s.halfHeight, s.radius);
  return {-extent, extent};
}

Aabb computeWorldBounds(const Cylinder& s, const Transform& t) {
  // A disc of radius r with unit normal a spans r sqrt(1 - a_i²) along axis i; the axis adds h |a_i|.
  const Vec3 axis = t.applyToDirection(Vec3(0.0f, 1.0f, 0.0f));
  Vec3 extent;
  for (int i = 0; i < 3; ++i) {
    extent[i] =
        s.halfHeight * std::abs(axis[i]) + s.radius * std::sqrt(std::max(0.0f, 1.0f - axis[i] * axis[i]));
  }
  return Aabb::fromCenterHalfExtents(t.position, t.scale * extent);
}

Vec3 computeSupport(const Cylinder& s, const Vec3& direction) {
  const float radial = std::sqrt(direction.x * direction.x + direction.z * direction.z);
  const float y = direction.y >= 0.0f ? s.halfHeight : -s.halfHeight;
  if (radial < 1e-12f) return {0.0f, y, 0.0f};
  return {s.radius * direction.x / radial, y, s.radius * direction.z / radial};
}

MassProperties computeMassProperties(const Cylinder& s, float density) {
  const float r = s.radius, h = s.halfHeight;
  MassProperties m;
  m.volume = kPi * r * r * 2.0f * h;
  m.mass = density * m.volume;
  const float transverse = m.mass * (3.0f * r * r + 4.0f * h * h) / 12.0f;
  m.inertia = Mat3(0.0f);
  m.inertia[0][0] = transverse;
  m.inertia[1][1] = m.mass * r * r / 2.0f;
  m.inertia[2][2] = transverse;
  return m;
}

bool localContains(const Cylinder& s, const Vec3& p) {
  return std::abs(p.y) <= s.halfHeight && p.x * p.x + p.z * p.z <= s.radius * s.radius;
}

SurfacePoint localClosestPoint(const Cylinder& s, const Vec3& p) {
  const float radial = std::sqrt(p.x * p.x + p.z * p.z);
  // The radial direction; on the axis every direction is nearest, pick +x.
  const Vec3 outward = radial > 1e-12f ? Vec3(p.x / radial, 0.0f, p.z / radial) : Vec3(1.0f, 0.0f, 0.0f);
  const float capSign = p.y >= 0.0f ? 1.0f : -1.0f;
  const bool outsideSide = radial > s.radius;
  const bool outsideCap = std::abs(p.y) > s.halfHeight;
  if (outsideSide || outsideCap) {
    const Vec3 point =
        Vec3(0.0f, glm::clamp(p.y, -s.halfHeight, s.halfHeight), 0.0f) + std::min(radial, s.radius) * outward;
    // The offset in the (radial, axial) half-plane, from the scalar gaps rather than p - point: a
    // point a few ulps outside the side would otherwise get a normal made of rounding noise.
    const float radialGap = std::max(radial - s.radius, 0.0f);
    const float capGap = std::max(std::abs(p.y) - s.halfHeight, 0.0f);
    const float distance = std::sqrt(radialGap * radialGap + capGap * capGap);
    const Vec3 normal = (radialGap * outward + Vec3(0.0f, capSign * capGap, 0.0f)) / distance;
    return {point, normal, distance};
  }
  // Inside: leave through the nearer of the side and the caps.
  const float sideGap = s.radius - radial;
  const float capGap = s.halfHeight - std::abs(p.y);
  if (sideGap < capGap) return {Vec3(0.0f, p.y, 0.0f) + s.radius * outward, outward, -sideGap};
  return {Vec3(p.x, capSign * s.halfHeight, p.z), Vec3(0.0f, capSign, 0.0f), -capGap};
}

std::optional<RayHit> localRayCast(const Cylinder& s, const Ray& ray) {
  if (localContains(s, ray.origin)) return RayHit{0.0f, ray.origin, -ray.direction, 0};
  const Vec3& o = ray.origin;
  const Vec3& d = ray.direction;
  float best = ray.maxDistance;
  Vec3 bestNormal(0.0f);
  bool found = false;
  // Side: x² + z² = r² with |y| <= h.
  const float a = d.x * d.x + d.z * d.z;
  if (a > 1e-12f) {
    const float b = o.x * d.x + o.z * d.z;
    const float c = o.x * o.x + o.z * o.z - s.radius * s.radius;
    const float discriminant = b * b - a * c;
    if (discriminant >= 0.0f) {
      const float t = (-b - std::sqrt(discriminant)) / a;
      const Vec3 p = o + t * d;
      if (t >= 0.0f && t <= best && std::abs(p.y) <= s.halfHeight) {
        best = t;
        bestNormal = glm::normalize(Vec3(p.x, 0.0f, p.z));
        found = true;
      }
    }
  }
  // Caps: y = ±h with x² + z² <= r², entered from outside the slab.
  if (std::abs(d.y) > 1e-12f) {
    const float capY = o.y > 0.0f ? s.halfHeight : -s.halfHeight;
    const float t = (capY - o.y) / d.y;
    const Vec3 p = o + t * d;
    if (t >= 0.0f && t <= best && p.x * p.x + p.z * p.z <= s.radius * s.radius) {
      best = t;
      bestNormal = Vec3(0.0f, capY > 0.0f ? 1.0f : -1.0f, 0.0f);
      found = true;
    }
  }
  if (!found) return std::nullopt;
  return RayHit{best, o + best * d, bestNormal, 0};
}

}  // namespace collide::detail
