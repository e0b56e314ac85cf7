// Sphere proxy: the points within `radius` of the origin (lecture, slide 54).
#include "shapes/shape_functions.h"

#include <cmath>

namespace collide::detail {

Aabb computeLocalBounds(const Sphere& s) { return {Vec3(-s.radius), Vec3(s.radius)}; }

Aabb computeWorldBounds(const Sphere& s, const Transform& t) {
  return Aabb::fromCenterHalfExtents(t.position, Vec3(s.radius * t.scale));
}

Vec3 computeSupport(const Sphere& s, const Vec3& direction) { return s.radius * glm::normalize(direction); }

MassProperties computeMassProperties(const Sphere& s, float density) {
  MassProperties m;
  m.volume = 4.0f / 3.0f * kPi * s.radius * s.radius * s.radius;
  m.mass = density * m.volume;
  m.inertia = Mat3(0.4f * m.mass * s.radius * s.radius);
  return m;
}

bool localContains(const Sphere& s, const Vec3& p) { return glm::dot(p, p) <= s.radius * s.radius; }

SurfacePoint localClosestPoint(const Sphere& s, const Vec3& p) {
  const float distance = glm::length(p);
  // At the centre every direction is nearest; pick +y so the answer is deterministic.
  const Vec3 normal = distance > 1e-12f ? p / distance : Vec3(0.0f, 1.0f, 0.0f);
  return {s.radius * normal, normal, distance - s.radius};
}

std::optional<RayHit> localRayCast(const Sphere& s, const Ray& ray) {
  // |o + t d|^2 = r^2 with |d| = 1: t^2 + 2 b t + c = 0.
  const float b = glm::dot(ray.origin, ray.direction);
  const float c = glm::dot(ray.origin, ray.origin) - s.radius * s.radius;
  if (c <= 0.0f) return RayHit{0.0f, ray.origin, -ray.direction, 0};
  if (b > 0.0f) return std::nullopt;  // outside and pointing away
  const float discriminant = b * b - c;
  if (discriminant < 0.0f) return std::nullopt;
  const float t = -b - std::sqrt(discriminant);
  if (t > ray.maxDistance) return std::nullopt;
  const Vec3 point = ray.origin + t * ray.direction;
  // Normalised rather than divided by the radius: at grazing incidence the computed point can sit
  // a few ulps off the sphere, and the normal must stay unit.
  return RayHit{t, point, glm::normalize(point), 0};
}

}  // namespace collide::detail
