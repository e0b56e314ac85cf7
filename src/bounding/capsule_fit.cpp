// Capsule fitting. For a given axis direction the tightest capsule is found exactly: across the axis
// the points are enclosed by their smallest circle (the minimal sphere of the points projected on the
// plane across the axis, which is that circle's sphere), and along it the segment is made as short as
// the end hemispheres allow: a point at axial coordinate t and distance d from the axis is inside a
// capsule of radius r on the segment [low, high] iff low <= t + sqrt(r^2 - d^2) and
// high >= t - sqrt(r^2 - d^2), so the shortest segment is [min(t + s), max(t - s)], or a single point
// when those cross (then the capsule is the sphere of radius r there).
//
// The direction starts as the principal axis of largest variance (PCA). For sampled surfaces PCA is
// noisy (a 2000-point capsule surface tilts it by ~0.03 rad, which widens the radius by ~h * 0.03),
// so a compass search (Torczon 1997: try a step each way along two directions across the axis, halve
// the step when none helps) then lowers the capsule's volume from there. Deterministic, local, and
// never worse than the PCA capsule. Past kSearchPoints points the search runs on the set's extreme
// points along fixed directions (point_set.h), a few hundred, which a capsule holding them nearly
// holds all; the radius and the segment are measured over every point at the end, as always.
#include <collide/bounding.h>

#include "bounding/point_set.h"

#include <cmath>
#include <limits>
#include <vector>

namespace collide {

namespace {

using DVec3 = glm::dvec3;
using bounding::basisAcross;

float roundUp(double value) {
  float f = static_cast<float>(value);
  if (double(f) < value) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

struct AxisFit {
  DVec3 center{0.0};  // midpoint of the segment
  double radius = 0.0;
  double halfHeight = 0.0;
  double volume = std::numeric_limits<double>::infinity();
};

// The tightest capsule with its axis along the unit vector `axis`.
constexpr std::size_t kSearchPoints = 4096;
constexpr int kSearchDirections = 256;

AxisFit fitAlong(std::span<const Vec3> points, const DVec3& mean, const DVec3& axis) {
  Array<Vec3> across;
  across.reserve(points.size());
  for (const Vec3& p : points) {
    const DVec3 d = DVec3(p) - mean;
    across.emplace_back(d - glm::dot(d, axis) * axis);
  }
  const BoundingSphere circle = minimalBoundingSphere(across);
  DVec3 linePoint = mean + DVec3(circle.center);
  linePoint -= glm::dot(linePoint - mean, axis) * axis;  // in the plane through the mean exactly

  // The radius is measured from the line (not taken from the float circle).
  AxisFit fit;
  for (const Vec3& p : points) {
    const DVec3 d = DVec3(p) - linePoint;
    fit.radius = std::max(fit.radius, glm::length(d - glm::dot(d, axis) * axis));
  }
  const double r = fit.radius;
  double low = std::numeric_limits<double>::infinity();    // min over points of t + s
  double high = -std::numeric_limits<double>::infinity();  // max over points of t - s
  for (const Vec3& p : points) {
    const DVec3 d = DVec3(p) - linePoint;
    const double t = glm::dot(d, axis);
    const double s = std::sqrt(std::max(0.0, r * r - (glm::dot(d, d) - t * t)));
    low = std::min(low, t + s);
    high = std::max(high, t - s);
  }
  if (low > high) low = high = 0.5 * (low + high);  // every point fits in one sphere of radius r
  fit.center = linePoint + 0.5 * (low + high) * axis;
  fit.halfHeight = 0.5 * (high - low);
  fit.volume = M_PI * r * r * (2.0 * fit.halfHeight + 4.0 / 3.0 * r);
  return fit;
}

}  // namespace

FittedCapsule fitCapsule(std::span<const Vec3> points) {
  if (!bounding::requireFinitePoints("fit_capsule", points)) return {};
  const bounding::PrincipalAxes pca = bounding::principalAxes(points);

  const Array<Vec3> extremes =
      points.size() > kSearchPoints ? bounding::extremePoints(points, kSearchDirections) : Array<Vec3>();
  const std::span<const Vec3> searched = extremes.empty() ? points : std::span<const Vec3>(extremes);
  DVec3 axis = pca.axes[0];
  AxisFit best = fitAlong(searched, pca.mean, axis);
  // Compass search on the direction: steps from ~6 degrees down to ~0.006 degrees.
  for (double step = 0.1; step > 1e-4 && best.volume > 0.0;) {
    DVec3 u, v;
    basisAcross(axis, u, v);
    bool improved = false;
    for (const DVec3& offset : {u, -u, v, -v}) {
      const DVec3 candidateAxis = glm::normalize(axis + step * offset);
      const AxisFit candidate = fitAlong(searched, pca.mean, candidateAxis);
      if (candidate.volume < best.volume) {
        best = candidate;
        axis = candidateAxis;
        improved = true;
        break;
      }
    }
    if (!improved) step *= 0.5;
  }

  // Local frame: y along the axis, x and z across it, right-handed.
  FittedCapsule fit;
  DVec3 xAxis, unused;
  basisAcross(axis, xAxis, unused);
  fit.transform.rotation = bounding::rotationFromAxes(glm::dmat3(xAxis, axis, glm::cross(xAxis, axis)));
  fit.transform.position = Vec3(best.center);

  // The rotation and the centre were rounded to float, which moves the axis line by a rounding
  // error: measure the radius from the stored line again, then the half height the stored centre
  // needs (max over points of |t| - s, t measured from the stored centre), both rounded up, so that
  // every point is inside the capsule actually returned.
  const DVec3 storedAxis = glm::dvec3(glm::mat3_cast(fit.transform.rotation)[1]);
  const DVec3 center(fit.transform.position);
  double radius = 0.0;
  for (const Vec3& p : points) {
    const DVec3 d = DVec3(p) - center;
    radius = std::max(radius, glm::length(d - glm::dot(d, storedAxis) * storedAxis));
  }
  fit.capsule.radius = roundUp(radius);
  const double r = fit.capsule.radius;
  double halfHeight = 0.0;
  for (const Vec3& p : points) {
    const DVec3 d = DVec3(p) - center;
    const double t = glm::dot(d, storedAxis);
    const double distanceSquared = std::max(0.0, glm::dot(d, d) - t * t);
    halfHeight = std::max(halfHeight, std::abs(t) - std::sqrt(std::max(0.0, r * r - distanceSquared)));
  }
  fit.capsule.halfHeight = roundUp(halfHeight);
  return fit;
}

}  // namespace collide
