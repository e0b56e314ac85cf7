// A property-test harness that takes any Shape: random transforms and rays, surface samples found
// independently of the query under test, and checks that hold for every proxy (ray hits lie on the
// surface, world boxes contain the surface, support points maximise over the surface, containment
// agrees with the signed distance, closestPoint is no farther than any surface sample), plus a Monte
// Carlo estimate of the mass properties from containsPoint alone. shape_properties_test.cpp runs it
// over a list of shapes; a new proxy joins by adding one line to that list.
//
// Tolerances are in world units and scale with the size of the numbers involved: kUlps float
// epsilons of the largest coordinate magnitude in the query (the transform's offset plus a few
// shape radii). A query does a few dozen float operations, so its rounding error is a few dozen
// ulps of that magnitude.
#pragma once

#include <collide/shapes.h>
#include <gtest/gtest.h>

#include "support/test_random.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <functional>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace collide::test {

inline constexpr float kUlps = 64.0f;

// Collects property violations so a failing property prints its first few counter-examples once,
// instead of thousands of lines.
class FailureLog {
 public:
  template <class... Parts>
  void fail(const Parts&... parts) {
    ++count_;
    if (count_ <= 5) {
      std::ostringstream out;
      (out << ... << parts);
      messages_ += "  " + out.str() + "\n";
    }
  }
  int count() const { return count_; }
  const std::string& messages() const { return messages_; }

 private:
  int count_ = 0;
  std::string messages_;
};

inline std::string str(const Vec3& v) {
  std::ostringstream out;
  out << '(' << v.x << ", " << v.y << ", " << v.z << ')';
  return out.str();
}

inline std::string str(const Transform& t) {
  std::ostringstream out;
  out << "{pos " << str(t.position) << ", rot (" << t.rotation.w << ", " << t.rotation.x << ", "
      << t.rotation.y << ", " << t.rotation.z << "), scale " << t.scale << '}';
  return out.str();
}

inline bool isInfinite(const Shape& shape) {
  const Vec3 size = localBounds(shape).max - localBounds(shape).min;
  return std::max({size.x, size.y, size.z}) > 1e20f;
}

// The region where the shape's interesting geometry is, in world coordinates: its bounding sphere
// for a finite shape, a ball on the surface near the transform's origin for a half-space.
struct Region {
  Vec3 center{0.0f};
  float radius = 1.0f;
  float tolerance = 1e-5f;  // kUlps ulps of the coordinates a query in this region handles
};

inline Region regionOf(const Shape& shape, const Transform& t) {
  Region region;
  if (isInfinite(shape)) {
    region.center = closestPoint(shape, t, t.position).point;
    region.radius = 2.0f * t.scale;
  } else {
    const BoundingSphere sphere = localBoundingSphere(shape);
    region.center = t.applyToPoint(sphere.center);
    region.radius = sphere.radius * t.scale;
  }
  // Ray origins sit up to 3 radii out; that and the offset bound every coordinate we touch.
  const float magnitude = glm::length(region.center) + 4.0f * region.radius;
  region.tolerance = kUlps * FLT_EPSILON * magnitude;
  return region;
}

// A ray from outside the region (outside the shape, if finite) towards a point inside it.
inline Ray rayTowardsRegion(const Region& region, std::mt19937& rng) {
  std::uniform_real_distribution<float> distance(1.5f, 3.0f);
  const Vec3 origin = region.center + randomUnitVector(rng) * (distance(rng) * region.radius);
  const Vec3 target = region.center + randomInUnitBall(rng) * region.radius;
  return Ray{origin, glm::normalize(target - origin), 1e30f};
}

// Surface points found by ray casts from outside: independent of closestPoint and support, so
// they can check those.
inline std::vector<Vec3> surfaceSamplesByRays(const Shape& shape, const Transform& t, const Region& region,
                                              int count, std::mt19937& rng) {
  std::vector<Vec3> samples;
  for (int attempt = 0; attempt < 20 * count && static_cast<int>(samples.size()) < count; ++attempt) {
    const Ray ray = rayTowardsRegion(region, rng);
    const std::optional<RayHit> hit = rayCast(shape, t, ray);
    if (hit && hit->distance > 0.0f) samples.push_back(hit->point);
  }
  return samples;
}

// Surface points as the nearest points of random points around the shape.
inline std::vector<Vec3> surfaceSamplesByClosestPoint(const Shape& shape, const Transform& t,
                                                      const Region& region, int count, std::mt19937& rng) {
  std::vector<Vec3> samples;
  for (int i = 0; i < count; ++i) {
    samples.push_back(
        closestPoint(shape, t, region.center + 1.5f * region.radius * randomInUnitBall(rng)).point);
  }
  return samples;
}

// ---- (1) Ray casts ----
// A hit from outside lies on the surface at |point - origin| = distance; the ray is outside just
// before it and (for a convex solid, when the chord is long enough to tell) inside just after; the
// hit normal is an outward normal there (closestPoint from a little way out along it returns the
// hit point and that normal), and closestPoint's own normal at the hit point is too, so the two
// agree except on edges, where both lie in the edge's normal cone. A hit at 0 means the origin is
// inside; a miss means the origin and the points along the ray are outside; maxDistance cuts hits
// beyond it and keeps the ones before it unchanged.
inline void checkRayCasts(const Shape& shape, const Transform& t, std::mt19937& rng, int rays,
                          FailureLog& log) {
  const Region region = regionOf(shape, t);
  const float tol = region.tolerance;
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  for (int i = 0; i < rays; ++i) {
    Ray ray = rayTowardsRegion(region, rng);
    if (i % 4 == 3) ray.direction = randomUnitVector(rng);  // some rays that mostly miss
    const std::optional<RayHit> hit = rayCast(shape, t, ray);
    const std::string where = std::string(toString(shape.type())) + " " + str(t) + " ray " + str(ray.origin) +
                              " dir " + str(ray.direction);
    if (!hit) {
      if (containsPoint(shape, t, ray.origin)) log.fail("miss from a contained origin: ", where);
      const float reach =
          std::min(ray.maxDistance, glm::length(ray.origin - region.center) + 2.0f * region.radius);
      for (int k = 0; k <= 64; ++k) {
        const Vec3 p = ray.origin + (reach * k / 64.0f) * ray.direction;
        if (containsPoint(shape, t, p) && closestPoint(shape, t, p).signedDistance < -tol) {
          log.fail("miss, but the ray passes the inside point ", str(p), ": ", where);
          break;
        }
      }
      continue;
    }
    // A far hit (a half-space seen at a grazing angle) carries the rounding of its distance too.
    const float hitTol = tol + kUlps * FLT_EPSILON * hit->distance;
    if (std::abs(glm::length(hit->normal) - 1.0f) > 1e-4f)
      log.fail("non-unit normal ", str(hit->normal), ": ", where);
    if (std::abs(glm::length(hit->point - ray.origin) - hit->distance) > hitTol) {
      log.fail("distance ", hit->distance, " but |point - origin| = ", glm::length(hit->point - ray.origin),
               ": ", where);
    }
    if (hit->distance == 0.0f) {
      if (!containsPoint(shape, t, ray.origin)) log.fail("hit at 0 from an outside origin: ", where);
      if (glm::length(hit->normal + ray.direction) > 1e-4f)
        log.fail("hit at 0 with normal != -direction: ", where);
      continue;
    }
    const SurfacePoint onHit = closestPoint(shape, t, hit->point);
    if (std::abs(onHit.signedDistance) > hitTol) {
      log.fail("hit point off the surface by ", onHit.signedDistance, " (tol ", hitTol, "): ", where);
    }
    // The normal faces the ray's origin side.
    const float cosine = -glm::dot(hit->normal, ray.direction);
    if (cosine < -1e-4f) log.fail("hit normal faces away from the ray: ", where);
    // The hit normal is a normal of the surface at the hit point.
    const float step = 1e-3f * region.radius;
    const SurfacePoint outAlongHit = closestPoint(shape, t, hit->point + step * hit->normal);
    if (glm::length(outAlongHit.point - hit->point) > 4.0f * hitTol ||
        glm::length(outAlongHit.normal - hit->normal) > 1e-2f) {
      log.fail("hit normal ", str(hit->normal),
               " is not a surface normal at the hit (closestPoint from outside says ", str(outAlongHit.point),
               " normal ", str(outAlongHit.normal), "): ", where);
    }
    // closestPoint's normal at the hit point is a surface normal there too; it may differ from
    // the hit normal only where the normal cone is wider than a line (an edge or corner).
    const SurfacePoint outAlongClosest = closestPoint(shape, t, hit->point + step * onHit.normal);
    if (glm::length(outAlongClosest.point - hit->point) > 4.0f * hitTol) {
      log.fail("closestPoint normal ", str(onHit.normal), " at the hit disagrees with the hit normal ",
               str(hit->normal), " and is not a surface normal there (local hit ",
               str(t.inverseApplyToPoint(hit->point)), ", closestPoint from outside along it ",
               str(outAlongClosest.point), "): ", where);
    }
    // Outside just before the hit. Only away from grazing incidence, where a few ulps in t move
    // the point across the surface.
    if (cosine > 0.05f) {
      const float delta = 8.0f * hitTol / cosine;
      if (hit->distance > delta &&
          containsPoint(shape, t, ray.origin + (hit->distance - delta) * ray.direction)) {
        log.fail("inside just before the hit: ", where);
      }
      if (shape.isConvex()) {
        // The chord, from the last exit seen by a ray cast back from beyond the shape.
        const float beyond = hit->distance + 4.0f * region.radius;
        const Ray back{ray.origin + beyond * ray.direction, -ray.direction, 1e30f};
        const std::optional<RayHit> exit = rayCast(shape, t, back);
        const float chord = exit ? beyond - exit->distance - hit->distance : 0.0f;
        if (chord > 3.0f * delta &&
            !containsPoint(shape, t, ray.origin + (hit->distance + delta) * ray.direction)) {
          log.fail("outside just after the hit (chord ", chord, "): ", where);
        }
      }
    }
    // A shorter ray misses a hit beyond its end and keeps a hit before it.
    Ray shorter = ray;
    shorter.maxDistance = hit->distance * 2.0f * u01(rng);
    const std::optional<RayHit> cut = rayCast(shape, t, shorter);
    if (shorter.maxDistance < hit->distance - hitTol && cut) {
      log.fail("hit at ", cut->distance, " beyond maxDistance ", shorter.maxDistance, ": ", where);
    }
    if (shorter.maxDistance > hit->distance + hitTol &&
        (!cut || std::abs(cut->distance - hit->distance) > hitTol)) {
      log.fail("maxDistance ", shorter.maxDistance, " lost or moved the hit at ", hit->distance, ": ", where);
    }
  }
}

// ---- (2) World bounds contain the surface; exact bounds touch it along every world axis ----
inline void checkWorldBounds(const Shape& shape, const Transform& t, std::mt19937& rng, bool exact,
                             FailureLog& log) {
  const Region region = regionOf(shape, t);
  const float tol = region.tolerance;
  const Aabb box = worldBounds(shape, t);
  const Aabb grown = box.expanded(tol);
  std::vector<Vec3> samples = surfaceSamplesByRays(shape, t, region, 24, rng);
  const std::vector<Vec3> more = surfaceSamplesByClosestPoint(shape, t, region, 24, rng);
  samples.insert(samples.end(), more.begin(), more.end());
  for (const Vec3& p : samples) {
    if (!grown.contains(p)) {
      log.fail("surface point ", str(p), " outside the world box ", str(box.min), "-", str(box.max), ": ",
               toString(shape.type()), " ", str(t));
    }
  }
  if (!exact || !shape.isConvex()) return;
  for (int axis = 0; axis < 3; ++axis) {
    for (float sign : {-1.0f, 1.0f}) {
      Vec3 direction(0.0f);
      direction[axis] = sign;
      const Vec3 extreme = t.applyToPoint(support(shape, t.inverseApplyToDirection(direction)));
      const float face = sign > 0.0f ? box.max[axis] : box.min[axis];
      if (std::abs(extreme[axis] - face) > tol) {
        log.fail("box face ", face, " along ", sign > 0 ? "+" : "-", axis, " but the support reaches ",
                 extreme[axis], ": ", toString(shape.type()), " ", str(t));
      }
    }
  }
}

// ---- (3) Support points lie on the surface and maximise dot(d, x) over surface samples ----
inline void checkSupport(const Shape& shape, const Transform& t, std::mt19937& rng, int directions,
                         FailureLog& log) {
  if (!shape.isConvex()) return;
  const Region region = regionOf(shape, t);
  const float tol = region.tolerance;
  const std::vector<Vec3> samples = surfaceSamplesByRays(shape, t, region, 64, rng);
  for (int i = 0; i < directions; ++i) {
    const Vec3 d = randomUnitVector(rng);
    const Vec3 local = t.inverseApplyToDirection(d);
    const Vec3 s = t.applyToPoint(support(shape, local));
    const std::string where = std::string(toString(shape.type())) + " " + str(t) + " d " + str(d);
    const SurfacePoint at = closestPoint(shape, t, s);
    if (std::abs(at.signedDistance) > tol)
      log.fail("support point off the surface by ", at.signedDistance, ": ", where);
    for (const Vec3& x : samples) {
      if (glm::dot(d, x) > glm::dot(d, s) + tol) {
        log.fail("surface point ", str(x), " beyond the support ", str(s), ": ", where);
        break;
      }
    }
    // The direction need not be unit: only its direction matters.
    for (float magnitude : {1e-3f, 1e3f}) {
      const Vec3 scaled = t.applyToPoint(support(shape, magnitude * local));
      if (std::abs(glm::dot(d, scaled) - glm::dot(d, s)) > tol) {
        log.fail("support depends on |d|: ", str(scaled), " vs ", str(s), " at |d| = ", magnitude, ": ",
                 where);
      }
    }
  }
}

// ---- (4) containsPoint agrees with the sign of the signed distance; (5) closestPoint is the
// nearest surface point: no sample is nearer, the distance is |query - point|, and the point is on
// the surface with the solid behind its normal ----
inline void checkClosestPoints(const Shape& shape, const Transform& t, std::mt19937& rng, int queries,
                               FailureLog& log) {
  const Region region = regionOf(shape, t);
  const float tol = region.tolerance;
  const std::vector<Vec3> samples = surfaceSamplesByRays(shape, t, region, 256, rng);
  std::optional<Vec3> interior;
  // The centroid is interior for a convex shape, and for the closed test meshes (all convex).
  if (shape.isConvex() || (shape.type() == ShapeType::Mesh && shape.mesh().isClosed()))
    interior = t.applyToPoint(massProperties(shape, 1.0f).centerOfMass);
  for (int i = 0; i < queries; ++i) {
    const Vec3 q = region.center + 1.5f * region.radius * randomInUnitBall(rng);
    const SurfacePoint cp = closestPoint(shape, t, q);
    const bool inside = containsPoint(shape, t, q);
    const std::string where = std::string(toString(shape.type())) + " " + str(t) + " query " + str(q);
    if (std::abs(cp.signedDistance) > tol && inside != (cp.signedDistance < 0.0f)) {
      log.fail("containsPoint ", inside, " but signed distance ", cp.signedDistance, ": ", where);
    }
    if (std::abs(glm::length(q - cp.point) - std::abs(cp.signedDistance)) > tol) {
      log.fail("|query - point| = ", glm::length(q - cp.point), " but signed distance ", cp.signedDistance,
               ": ", where);
    }
    if (std::abs(glm::length(cp.normal) - 1.0f) > 1e-4f)
      log.fail("non-unit normal ", str(cp.normal), ": ", where);
    float nearest = 1e30f;
    for (const Vec3& s : samples) nearest = std::min(nearest, glm::length(q - s));
    if (std::abs(cp.signedDistance) > nearest + tol) {
      log.fail("closest point at ", std::abs(cp.signedDistance), " but a surface sample is at ", nearest,
               ": ", where);
    }
    // On the surface: outside a little way along the normal, inside a little way against it. At a
    // sharp vertex of a polyhedron the normal (the offset direction, anywhere in the normal cone)
    // can point past the narrow solid angle, so for a convex shape stepping towards its centroid,
    // always interior, also shows the solid side.
    const float step = 1e-3f * region.radius;
    const bool solidBehind =
        containsPoint(shape, t, cp.point - step * cp.normal) ||
        (interior && containsPoint(shape, t, cp.point + step * glm::normalize(*interior - cp.point)));
    if (containsPoint(shape, t, cp.point + step * cp.normal) || !solidBehind) {
      log.fail("closest point ", str(cp.point), " normal ", str(cp.normal),
               " is not on the surface: ", where);
    }
  }
}

// ---- Monte Carlo mass properties from containsPoint alone ----
// N points uniform in the box around the shape scaled by `scale`; each estimate is the box volume
// times the mean of g(x) = [x inside] * f(x), so its standard error is boxVolume * sd(g) / sqrt(N),
// computed from the same samples.
struct MonteCarloMass {
  double volume = 0.0, volumeError = 0.0;
  Vec3 centroid{0.0f}, centroidError{0.0f};
  Mat3 inertia{0.0f}, inertiaError{0.0f};  // unit density, about the given centre
  int inside = 0;
};

inline MonteCarloMass estimateMassProperties(const Shape& shape, float scale, const Vec3& about, int n,
                                             std::uint32_t seed) {
  const Transform t{Vec3(0.0f), Quat(1.0f, 0.0f, 0.0f, 0.0f), scale};
  const Aabb box = worldBounds(shape, t);
  const double boxVolume = double(box.volume());
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> ux(box.min.x, box.max.x), uy(box.min.y, box.max.y),
      uz(box.min.z, box.max.z);
  // Sums of g and g^2 for: indicator, x_i, and the 6 inertia components about `about`.
  double sum[10] = {}, sumSquares[10] = {};
  for (int i = 0; i < n; ++i) {
    const Vec3 p(ux(rng), uy(rng), uz(rng));
    if (!containsPoint(shape, t, p)) continue;
    const double x = p.x, y = p.y, z = p.z;
    const double rx = x - about.x, ry = y - about.y, rz = z - about.z;
    const double g[10] = {
        1.0, x, y, z, ry * ry + rz * rz, rx * rx + rz * rz, rx * rx + ry * ry, -rx * ry, -ry * rz, -rz * rx};
    for (int k = 0; k < 10; ++k) {
      sum[k] += g[k];
      sumSquares[k] += g[k] * g[k];
    }
  }
  double mean[10], error[10];
  for (int k = 0; k < 10; ++k) {
    mean[k] = boxVolume * sum[k] / n;
    const double m = sum[k] / n;
    error[k] = boxVolume * std::sqrt(std::max(0.0, sumSquares[k] / n - m * m) / n);
  }
  MonteCarloMass r;
  r.inside = static_cast<int>(sum[0]);
  r.volume = mean[0];
  r.volumeError = error[0];
  for (int i = 0; i < 3; ++i) {
    r.centroid[i] = float(mean[1 + i] / mean[0]);
    // The ratio's error is dominated by the numerator's when the volume is known to 1/sqrt(N).
    r.centroidError[i] =
        float(error[1 + i] / mean[0] + std::abs(mean[1 + i]) * error[0] / (mean[0] * mean[0]));
  }
  const int diagonal[3] = {4, 5, 6};
  for (int i = 0; i < 3; ++i) {
    r.inertia[i][i] = float(mean[diagonal[i]]);
    r.inertiaError[i][i] = float(error[diagonal[i]]);
  }
  const int pairs[3][3] = {{0, 1, 7}, {1, 2, 8}, {2, 0, 9}};
  for (const auto& pair : pairs) {
    r.inertia[pair[0]][pair[1]] = r.inertia[pair[1]][pair[0]] = float(mean[pair[2]]);
    r.inertiaError[pair[0]][pair[1]] = r.inertiaError[pair[1]][pair[0]] = float(error[pair[2]]);
  }
  return r;
}

// Compares massProperties(shape, density, scale) with the Monte Carlo estimate: every quantity
// within kSigmas standard errors (plus float rounding of the analytic value). With a fixed seed
// the outcome is deterministic; 5 sigmas keep an honest formula from ever failing by chance over
// the few hundred comparisons (p ~ 6e-7 each) while a wrong term of a few percent stands out.
inline void expectMassPropertiesMatchMonteCarlo(const Shape& shape, float density, float scale,
                                                int n = 200000, std::uint32_t seed = 12345) {
  constexpr double kSigmas = 5.0;
  const MassProperties m = massProperties(shape, density, scale);
  const MonteCarloMass mc = estimateMassProperties(shape, scale, m.centerOfMass, n, seed);
  const std::string what = std::string(toString(shape.type())) + " at scale " + std::to_string(scale);
  ASSERT_GT(mc.inside, n / 20) << what << ": too few samples inside to estimate anything";
  const double size = std::cbrt(mc.volume);
  EXPECT_NEAR(m.volume, mc.volume, kSigmas * mc.volumeError + 1e-5 * mc.volume) << what << " volume";
  EXPECT_NEAR(m.mass, density * mc.volume, density * (kSigmas * mc.volumeError + 1e-5 * mc.volume))
      << what << " mass";
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(m.centerOfMass[i], mc.centroid[i], kSigmas * mc.centroidError[i] + 1e-5 * size)
        << what << " centre of mass [" << i << "]";
  }
  const double inertiaScale = double(mc.inertia[0][0] + mc.inertia[1][1] + mc.inertia[2][2]);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      EXPECT_NEAR(m.inertia[i][j], density * mc.inertia[i][j],
                  density * (kSigmas * mc.inertiaError[i][j] + 1e-5 * inertiaScale))
          << what << " inertia[" << i << "][" << j << "]";
    }
  }
}

}  // namespace collide::test
