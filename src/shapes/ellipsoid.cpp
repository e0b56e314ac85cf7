// Ellipsoid proxy: (x/a)² + (y/b)² + (z/c)² <= 1, axes along the local frame (lecture, slide 51).
#include "shapes/shape_functions.h"

#include <algorithm>
#include <cmath>

namespace collide::detail {

Aabb computeLocalBounds(const Ellipsoid& s) { return {-s.radii, s.radii}; }

Aabb computeWorldBounds(const Ellipsoid& s, const Transform& t) {
  // The support of the rotated ellipsoid along world axis i has half extent
  // sqrt(sum_j (R_ij r_j)^2): exact, not the box of the local box.
  const Mat3 rotation = glm::mat3_cast(t.rotation);
  Vec3 extentSquared(0.0f);
  for (int j = 0; j < 3; ++j) {
    const Vec3 column = rotation[j] * s.radii[j];
    extentSquared += column * column;
  }
  return Aabb::fromCenterHalfExtents(t.position, t.scale * glm::sqrt(extentSquared));
}

Vec3 computeSupport(const Ellipsoid& s, const Vec3& direction) {
  // The ellipsoid is the unit sphere scaled by r: support(d) = r ∘ normalize(r ∘ d).
  const Vec3 scaled = s.radii * direction;
  return s.radii * glm::normalize(scaled);
}

MassProperties computeMassProperties(const Ellipsoid& s, float density) {
  const Vec3 r = s.radii;
  MassProperties m;
  m.volume = 4.0f / 3.0f * kPi * r.x * r.y * r.z;
  m.mass = density * m.volume;
  m.inertia = Mat3(0.0f);
  m.inertia[0][0] = m.mass / 5.0f * (r.y * r.y + r.z * r.z);
  m.inertia[1][1] = m.mass / 5.0f * (r.x * r.x + r.z * r.z);
  m.inertia[2][2] = m.mass / 5.0f * (r.x * r.x + r.y * r.y);
  return m;
}

bool localContains(const Ellipsoid& s, const Vec3& p) {
  const Vec3 q = p / s.radii;
  return glm::dot(q, q) <= 1.0f;
}

SurfacePoint localClosestPoint(const Ellipsoid& s, const Vec3& p) {
  // The nearest point x satisfies p - x ∥ ∇(x), which gives x_i = r_i² p_i / (r_i² + t) for a scalar
  // t with F(t) = sum (r_i p_i / (r_i² + t))² - 1 = 0. F decreases on t > -min r_i², so bisection
  // finds the one root there, for points inside (t < 0) and outside (t > 0) alike (Eberly,
  // "Distance from a Point to an Ellipse, an Ellipsoid, or a Hyperellipsoid", 2013).
  // We solve for u = t + min r_i² > 0 instead of t: near the plane of the shortest axis, deep
  // inside, the root sits just above t = -min r_i², where t itself has too few significant digits
  // left for r_i² + t (a point 1e-12 off the plane came out 1e-4 off the surface).
  const double r[3] = {s.radii.x, s.radii.y, s.radii.z};
  const double q[3] = {std::abs(double(p.x)), std::abs(double(p.y)), std::abs(double(p.z))};
  int smallest = 0;
  for (int i = 1; i < 3; ++i) {
    if (r[i] < r[smallest]) smallest = i;
  }
  const double rMin2 = r[smallest] * r[smallest];
  double gap[3];  // r_i² - min r², exactly 0 on the shortest axis
  for (int i = 0; i < 3; ++i) gap[i] = r[i] * r[i] - rMin2;
  auto f = [&](double u) {
    double sum = 0.0;
    for (int i = 0; i < 3; ++i) {
      const double v = r[i] * q[i] / (gap[i] + u);
      sum += v * v;
    }
    return sum - 1.0;
  };
  double x[3];
  // F(u = ε) < 0 only when p lies (almost) on the plane of the shortest axis, deep inside: then
  // the nearest points sit on the "waist" where that axis' coordinate leaves the plane.
  const double tiny = rMin2 * 1e-12;
  bool waist = false;
  if (f(tiny) < 0.0) {
    double sum = 0.0;
    for (int i = 0; i < 3; ++i) {
      if (i == smallest) continue;
      x[i] = gap[i] > 0.0 ? r[i] * r[i] * q[i] / gap[i] : q[i];
      sum += (x[i] / r[i]) * (x[i] / r[i]);
    }
    if (sum < 1.0) {
      x[smallest] = r[smallest] * std::sqrt(1.0 - sum);
      waist = true;
    }
  }
  if (!waist) {
    // F(tiny) >= 0 > F(hi): the root is in between. The root may be many orders of magnitude
    // below hi, so bisect geometrically (on log u) to full relative precision.
    double lo = tiny;
    double hi =
        std::max({r[0], r[1], r[2]}) * std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]) + 1.0 + rMin2;
    for (int iteration = 0; iteration < 200 && hi - lo > 1e-15 * lo; ++iteration) {
      const double mid = std::sqrt(lo * hi);
      (f(mid) > 0.0 ? lo : hi) = mid;
    }
    const double u = 0.5 * (lo + hi);
    for (int i = 0; i < 3; ++i) x[i] = r[i] * r[i] * q[i] / (gap[i] + u);
  }
  Vec3 point;
  for (int i = 0; i < 3; ++i) point[i] = static_cast<float>(std::copysign(x[i], double(p[i])));
  const Vec3 gradient = point / (s.radii * s.radii);
  const Vec3 normal = glm::normalize(gradient);
  const float distance = glm::length(p - point);
  return {point, normal, localContains(s, p) ? -distance : distance};
}

std::optional<RayHit> localRayCast(const Ellipsoid& s, const Ray& ray) {
  if (localContains(s, ray.origin)) return RayHit{0.0f, ray.origin, -ray.direction, 0};
  // In coordinates divided by the radii the ellipsoid is the unit sphere; t keeps its meaning.
  const Vec3 o = ray.origin / s.radii;
  const Vec3 d = ray.direction / s.radii;
  const float a = glm::dot(d, d);
  const float b = glm::dot(o, d);
  const float c = glm::dot(o, o) - 1.0f;
  if (b > 0.0f) return std::nullopt;
  const float discriminant = b * b - a * c;
  if (discriminant < 0.0f) return std::nullopt;
  const float t = (-b - std::sqrt(discriminant)) / a;
  if (t < 0.0f || t > ray.maxDistance) return std::nullopt;
  const Vec3 point = ray.origin + t * ray.direction;
  return RayHit{t, point, glm::normalize(point / (s.radii * s.radii)), 0};
}

}  // namespace collide::detail
