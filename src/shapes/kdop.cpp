// k-DOP proxy (lecture, slide 51; Klosowski et al., "Efficient collision detection using bounding
// volume hierarchies of k-DOPs", IEEE TVCG 1998): k/2 slabs along fixed axes. Point and ray tests
// use the slabs, which is exact and cheap; support and mass use the polytope the slabs enclose.
#include "base/fail.h"
#include "shapes/hull_builder.h"
#include "shapes/shape_functions.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace collide {

namespace {

constexpr float kInvSqrt2 = 0.70710678118654752f;
constexpr float kInvSqrt3 = 0.57735026918962576f;

// Face axes, then the 4 cube diagonals, then the 6 edge diagonals.
constexpr std::array<Vec3, 13> kAxes26 = {
    Vec3(1, 0, 0),
    Vec3(0, 1, 0),
    Vec3(0, 0, 1),
    Vec3(kInvSqrt3, kInvSqrt3, kInvSqrt3),
    Vec3(kInvSqrt3, -kInvSqrt3, kInvSqrt3),
    Vec3(-kInvSqrt3, kInvSqrt3, kInvSqrt3),
    Vec3(-kInvSqrt3, -kInvSqrt3, kInvSqrt3),
    Vec3(kInvSqrt2, kInvSqrt2, 0),
    Vec3(kInvSqrt2, -kInvSqrt2, 0),
    Vec3(kInvSqrt2, 0, kInvSqrt2),
    Vec3(kInvSqrt2, 0, -kInvSqrt2),
    Vec3(0, kInvSqrt2, kInvSqrt2),
    Vec3(0, kInvSqrt2, -kInvSqrt2),
};
constexpr std::array<Vec3, 9> kAxes18 = {kAxes26[0], kAxes26[1],  kAxes26[2],  kAxes26[7], kAxes26[8],
                                         kAxes26[9], kAxes26[10], kAxes26[11], kAxes26[12]};

std::string format(float v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

// Every point where three slab planes of independent axes meet and which no slab excludes is a
// vertex of the k-DOP (all its vertices are such points); their hull is the polytope.
std::shared_ptr<const ConvexHull> enclosedPolytope(int k, const std::array<float, 13>& slabMin,
                                                   const std::array<float, 13>& slabMax) {
  const std::span<const Vec3> axes = Kdop::axes(k);
  const int n = static_cast<int>(axes.size());
  // Float slabs are only good to a few ulps of their magnitude; corners closer than a small fraction
  // of the extent are the same corner.
  double magnitude = 0.0, extent = 0.0;
  for (int i = 0; i < n; ++i) {
    magnitude = std::max({magnitude, std::abs(double(slabMin[i])), std::abs(double(slabMax[i]))});
    extent = std::max(extent, double(slabMax[i]) - double(slabMin[i]));
  }
  const double tolerance = 1e-6 * (magnitude + extent);
  const double sameCorner = 1e-5 * extent + 2e-6 * magnitude;
  Array<glm::dvec3> candidates;
  for (int a = 0; a < n; ++a) {
    for (int b = a + 1; b < n; ++b) {
      for (int c = b + 1; c < n; ++c) {
        const glm::dvec3 na(axes[a]), nb(axes[b]), nc(axes[c]);
        const glm::dvec3 bc = glm::cross(nb, nc), ca = glm::cross(nc, na), ab = glm::cross(na, nb);
        const double det = glm::dot(na, bc);
        if (std::abs(det) < 1e-6) continue;  // axes in one plane: the three planes share no point
        for (int corner = 0; corner < 8; ++corner) {
          const double da = corner & 1 ? slabMax[a] : slabMin[a];
          const double db = corner & 2 ? slabMax[b] : slabMin[b];
          const double dc = corner & 4 ? slabMax[c] : slabMin[c];
          const glm::dvec3 p = (da * bc + db * ca + dc * ab) / det;  // Cramer's rule
          bool inside = true;
          for (int i = 0; i < n && inside; ++i) {
            const double d = glm::dot(glm::dvec3(axes[i]), p);
            inside = d >= slabMin[i] - tolerance && d <= slabMax[i] + tolerance;
          }
          if (!inside) continue;
          // Several plane triples meet at one corner (e.g. a box corner cut by no diagonal slab).
          const bool known = std::any_of(candidates.begin(), candidates.end(), [&](const glm::dvec3& q) {
            return glm::length(q - p) <= sameCorner;
          });
          if (!known) candidates.push_back(p);
        }
      }
    }
  }
  if (candidates.size() < 4) {
    COLLIDE_FAIL("kdop: the slabs enclose no volume (" + std::to_string(candidates.size()) +
                     " corner points satisfy every slab)",
                 nullptr);
  }
  Array<Vec3> points(candidates.begin(), candidates.end());
  ConvexHull hull = detail::withErrorContext(
      "kdop: the slabs enclose a flat polytope (", [&] { return ConvexHull::fromPoints(points); }, ")");
  COLLIDE_RETURN_IF_FAILED(nullptr);
  return std::make_shared<const ConvexHull>(std::move(hull));
}

bool requireSupportedK(int k) {
  if (k != 6 && k != 14 && k != 18 && k != 26)
    COLLIDE_FAIL("kdop: k must be 6, 14, 18 or 26, got " + std::to_string(k), false);
  return true;
}

}  // namespace

std::span<const Vec3> Kdop::axes(int k) {
  if (!requireSupportedK(k)) return {};
  switch (k) {
    case 6:
      return std::span<const Vec3>(kAxes26.data(), 3);
    case 14:
      return std::span<const Vec3>(kAxes26.data(), 7);
    case 18:
      return kAxes18;
    default:
      return kAxes26;
  }
}

Kdop Kdop::fromPoints(int k, std::span<const Vec3> points) {
  const detail::ErrorScope scope;
  const std::span<const Vec3> axes = Kdop::axes(k);
  COLLIDE_RETURN_IF_FAILED({});
  requireSolidPointSet("kdop", points);
  COLLIDE_RETURN_IF_FAILED({});
  Kdop kdop;
  kdop.k_ = k;
  for (std::size_t i = 0; i < axes.size(); ++i) {
    kdop.min_[i] = std::numeric_limits<float>::max();
    kdop.max_[i] = -std::numeric_limits<float>::max();
    for (const Vec3& p : points) {
      const float d = glm::dot(axes[i], p);
      kdop.min_[i] = std::min(kdop.min_[i], d);
      kdop.max_[i] = std::max(kdop.max_[i], d);
    }
  }
  kdop.polytope_ = enclosedPolytope(k, kdop.min_, kdop.max_);
  COLLIDE_RETURN_IF_FAILED({});
  return kdop;
}

Kdop Kdop::fromSlabs(int k, std::span<const float> slabMin, std::span<const float> slabMax) {
  const detail::ErrorScope scope;
  const std::size_t count = Kdop::axes(k).size();
  COLLIDE_RETURN_IF_FAILED({});
  if (slabMin.size() != count || slabMax.size() != count) {
    COLLIDE_FAIL("kdop: a " + std::to_string(k) + "-DOP needs " + std::to_string(count) +
                     " slab minima and maxima, got " + std::to_string(slabMin.size()) + " and " +
                     std::to_string(slabMax.size()),
                 {});
  }
  Kdop kdop;
  kdop.k_ = k;
  for (std::size_t i = 0; i < count; ++i) {
    if (!isFinite(slabMin[i]) || !isFinite(slabMax[i])) {
      COLLIDE_FAIL("kdop: slab " + std::to_string(i) + " must be finite, got [" + format(slabMin[i]) + ", " +
                       format(slabMax[i]) + "]",
                   {});
    }
    if (!(slabMin[i] < slabMax[i])) {
      COLLIDE_FAIL("kdop: slab " + std::to_string(i) + " must have min < max, got [" + format(slabMin[i]) +
                       ", " + format(slabMax[i]) + "]",
                   {});
    }
    kdop.min_[i] = slabMin[i];
    kdop.max_[i] = slabMax[i];
  }
  kdop.polytope_ = enclosedPolytope(k, kdop.min_, kdop.max_);
  COLLIDE_RETURN_IF_FAILED({});
  return kdop;
}

}  // namespace collide

namespace collide::detail {

Aabb computeLocalBounds(const Kdop& s) { return s.polytope().bounds(); }

Aabb computeWorldBounds(const Kdop& s, const Transform& t) { return computeWorldBounds(s.polytope(), t); }

Vec3 computeSupport(const Kdop& s, const Vec3& direction) { return s.polytope().support(direction); }

MassProperties computeMassProperties(const Kdop& s, float density) {
  return computeMassProperties(s.polytope(), density);
}

bool localContains(const Kdop& s, const Vec3& p) {
  const std::span<const Vec3> axes = Kdop::axes(s.k());
  for (int i = 0; i < s.axisCount(); ++i) {
    const float d = glm::dot(axes[i], p);
    if (d < s.slabMin(i) || d > s.slabMax(i)) return false;
  }
  return true;
}

SurfacePoint localClosestPoint(const Kdop& s, const Vec3& p) { return localClosestPoint(s.polytope(), p); }

// The slab test of an AABB generalised to k/2 axes (Klosowski et al. 1998): the last slab the ray
// enters gives the hit and its normal.
std::optional<RayHit> localRayCast(const Kdop& s, const Ray& ray) {
  if (localContains(s, ray.origin)) return RayHit{0.0f, ray.origin, -ray.direction, 0};
  const std::span<const Vec3> axes = Kdop::axes(s.k());
  float tEnter = -1e30f;
  float tExit = ray.maxDistance;
  int enterAxis = -1;
  float enterSign = 0.0f;
  for (int i = 0; i < s.axisCount(); ++i) {
    const float o = glm::dot(axes[i], ray.origin), d = glm::dot(axes[i], ray.direction);
    if (std::abs(d) < 1e-12f) {
      if (o < s.slabMin(i) || o > s.slabMax(i)) return std::nullopt;
      continue;
    }
    const float inverse = 1.0f / d;
    float t0 = (s.slabMin(i) - o) * inverse;
    float t1 = (s.slabMax(i) - o) * inverse;
    float sign = -1.0f;  // moving along +axis, the ray enters through the min plane
    if (t0 > t1) {
      std::swap(t0, t1);
      sign = 1.0f;
    }
    if (t0 > tEnter) tEnter = t0, enterAxis = i, enterSign = sign;
    tExit = std::min(tExit, t1);
    if (tEnter > tExit) return std::nullopt;
  }
  if (enterAxis < 0 || tEnter < 0.0f) return std::nullopt;
  return RayHit{tEnter, ray.origin + tEnter * ray.direction, enterSign * axes[enterAxis], 0};
}

}  // namespace collide::detail
