// Capsule proxy: the points within `radius` of a segment on the local y axis (lecture, slide 56).
#include "shapes/shape_functions.h"

#include <cmath>

namespace collide::detail {

Aabb computeLocalBounds(const Capsule& s) {
  const Vec3 extent(s.radius, s.halfHeight + s.radius, s.radius);
  return {-extent, extent};
}

Aabb computeWorldBounds(const Capsule& s, const Transform& t) {
  const Vec3 a = t.applyToPoint(Vec3(0.0f, -s.halfHeight, 0.0f));
  const Vec3 b = t.applyToPoint(Vec3(0.0f, s.halfHeight, 0.0f));
  const Vec3 r(s.radius * t.scale);
  return {glm::min(a, b) - r, glm::max(a, b) + r};
}

Vec3 computeSupport(const Capsule& s, const Vec3& direction) {
  const Vec3 end(0.0f, direction.y >= 0.0f ? s.halfHeight : -s.halfHeight, 0.0f);
  return end + s.radius * glm::normalize(direction);
}

MassProperties computeMassProperties(const Capsule& s, float density) {
  const float r = s.radius, h = s.halfHeight;
  const float cylinderMass = density * kPi * r * r * 2.0f * h;
  const float sphereMass = density * 4.0f / 3.0f * kPi * r * r * r;  // both hemispheres
  MassProperties m;
  m.mass = cylinderMass + sphereMass;
  m.volume = m.mass / density;
  // Each hemisphere: 83/320 m r^2 about its own centre of mass, which lies 3r/8 from the flat face;
  // moved by the parallel-axis theorem to the capsule's centre, both add up to m_s (2r²/5 + h² + 3hr/4).
  const float axial = cylinderMass * r * r / 2.0f + sphereMass * 0.4f * r * r;
  const float transverse =
      cylinderMass * (r * r / 4.0f + h * h / 3.0f) + sphereMass * (0.4f * r * r + h * h + 0.75f * h * r);
  m.inertia = Mat3(0.0f);
  m.inertia[0][0] = transverse;
  m.inertia[1][1] = axial;
  m.inertia[2][2] = transverse;
  return m;
}

bool localContains(const Capsule& s, const Vec3& p) {
  const Vec3 axisPoint(0.0f, glm::clamp(p.y, -s.halfHeight, s.halfHeight), 0.0f);
  const Vec3 d = p - axisPoint;
  return glm::dot(d, d) <= s.radius * s.radius;
}

SurfacePoint localClosestPoint(const Capsule& s, const Vec3& p) {
  const Vec3 axisPoint(0.0f, glm::clamp(p.y, -s.halfHeight, s.halfHeight), 0.0f);
  const Vec3 d = p - axisPoint;
  const float distance = glm::length(d);
  // On the axis every radial direction is nearest; pick +x so the answer is deterministic.
  const Vec3 normal = distance > 1e-12f ? d / distance : Vec3(1.0f, 0.0f, 0.0f);
  return {axisPoint + s.radius * normal, normal, distance - s.radius};
}

std::optional<RayHit> localRayCast(const Capsule& s, const Ray& ray) {
  if (localContains(s, ray.origin)) return RayHit{0.0f, ray.origin, -ray.direction, 0};
  // The ray enters the capsule through the side of its cylinder or through one of its end spheres.
  // Outside the capsule, the first entry among those three surfaces is the capsule's entry.
  float best = ray.maxDistance;
  Vec3 bestNormal(0.0f);
  bool found = false;
  const Vec3& o = ray.origin;
  const Vec3& d = ray.direction;
  // Infinite cylinder x^2 + z^2 = r^2, restricted to |y| <= h.
  const float a = d.x * d.x + d.z * d.z;
  if (a > 1e-12f) {
    const float b = o.x * d.x + o.z * d.z;
    const float c = o.x * o.x + o.z * o.z - s.radius * s.radius;
    const float discriminant = b * b - a * c;
    if (discriminant >= 0.0f) {
      const float t = (-b - std::sqrt(discriminant)) / a;
      const float y = o.y + t * d.y;
      if (t >= 0.0f && t <= best && std::abs(y) <= s.halfHeight) {
        best = t;
        const Vec3 p = o + t * d;
        bestNormal = glm::normalize(Vec3(p.x, 0.0f, p.z));
        found = true;
      }
    }
  }
  for (float endY : {-s.halfHeight, s.halfHeight}) {
    const Vec3 oc = o - Vec3(0.0f, endY, 0.0f);
    const float b = glm::dot(oc, d);
    const float c = glm::dot(oc, oc) - s.radius * s.radius;
    const float discriminant = b * b - c;
    if (discriminant < 0.0f) continue;
    const float t = -b - std::sqrt(discriminant);
    if (t >= 0.0f && t <= best) {
      best = t;
      bestNormal = (oc + t * d) / s.radius;
      found = true;
    }
  }
  if (!found) return std::nullopt;
  return RayHit{best, o + best * d, glm::normalize(bestNormal), 0};
}

}  // namespace collide::detail
