// Capsule fitting. The axis direction is the principal axis of largest variance (PCA); across it the
// points are enclosed by their smallest circle (the minimal sphere of the points projected on the
// plane across the axis, which is that circle's sphere), and along it the segment is made as short as
// the end hemispheres allow: a point at axial coordinate t and distance d from the axis is inside a
// capsule of radius r on the segment [low, high] iff low <= t + sqrt(r^2 - d^2) and
// high >= t - sqrt(r^2 - d^2), so the shortest segment is [min(t + s), max(t - s)], or a single point
// when those cross (then the capsule is the sphere of radius r there).
#include <collide/bounding.h>

#include "bounding/point_set.h"

#include <cmath>
#include <limits>
#include <vector>

namespace collide {

namespace {

using DVec3 = glm::dvec3;

float roundUp(double value) {
  float f = static_cast<float>(value);
  if (double(f) < value) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

}  // namespace

FittedCapsule fitCapsule(std::span<const Vec3> points) {
  bounding::requireFinitePoints("fit_capsule", points);
  const bounding::PrincipalAxes pca = bounding::principalAxes(points);

  // Local frame: y along the axis of largest variance (the capsule's axis), x along the second
  // principal axis, z completing a right-handed frame.
  FittedCapsule fit;
  const DVec3 yAxis = pca.axes[0];
  const DVec3 xAxis = pca.axes[1];
  const DVec3 zAxis = glm::cross(xAxis, yAxis);
  fit.transform.rotation = bounding::rotationFromAxes(glm::dmat3(xAxis, yAxis, zAxis));
  // Work with the axes of the float rotation that is returned, so that the radius and the segment
  // are measured in the frame the capsule is actually placed in.
  const glm::dmat3 axes = glm::dmat3(glm::mat3_cast(fit.transform.rotation));
  const DVec3 axis = axes[1];

  // Smallest circle across the axis: project the points on the plane through the mean across the
  // axis; their minimal sphere is centred in that plane.
  std::vector<Vec3> across;
  across.reserve(points.size());
  for (const Vec3& p : points) {
    const DVec3 d = DVec3(p) - pca.mean;
    across.emplace_back(d - glm::dot(d, axis) * axis);
  }
  const BoundingSphere circle = minimalBoundingSphere(across);
  DVec3 linePoint = pca.mean + DVec3(circle.center);
  linePoint -= glm::dot(linePoint - pca.mean, axis) * axis;  // keep it in the plane exactly

  // The radius: the farthest distance from the axis line, measured (not taken from the circle) so
  // that rounding cannot leave a point outside.
  double radius = 0.0;
  for (const Vec3& p : points) {
    const DVec3 d = DVec3(p) - linePoint;
    radius = std::max(radius, glm::length(d - glm::dot(d, axis) * axis));
  }
  fit.capsule.radius = roundUp(radius);
  const double r = fit.capsule.radius;

  double low = std::numeric_limits<double>::infinity();    // min over points of t + s
  double high = -std::numeric_limits<double>::infinity();  // max over points of t - s
  for (const Vec3& p : points) {
    const DVec3 d = DVec3(p) - linePoint;
    const double t = glm::dot(d, axis);
    const double distanceSquared = glm::dot(d, d) - t * t;
    const double s = std::sqrt(std::max(0.0, r * r - distanceSquared));
    low = std::min(low, t + s);
    high = std::max(high, t - s);
  }
  if (low > high) low = high = 0.5 * (low + high);  // every point fits in one sphere of radius r
  fit.transform.position = Vec3(linePoint + 0.5 * (low + high) * axis);

  // The centre was rounded to float, which moves the axis line by a rounding error: measure the
  // radius from the stored line again, then the half height the stored centre needs (max over points
  // of |t| - s, t now measured from the stored centre), both rounded up, so that every point is inside
  // the capsule actually returned.
  const DVec3 center(fit.transform.position);
  double storedRadius = 0.0;
  for (const Vec3& p : points) {
    const DVec3 d = DVec3(p) - center;
    storedRadius = std::max(storedRadius, glm::length(d - glm::dot(d, axis) * axis));
  }
  fit.capsule.radius = std::max(fit.capsule.radius, roundUp(storedRadius));
  const double finalRadius = fit.capsule.radius;
  double halfHeight = 0.0;
  for (const Vec3& p : points) {
    const DVec3 d = DVec3(p) - center;
    const double t = glm::dot(d, axis);
    const double distanceSquared = std::max(0.0, glm::dot(d, d) - t * t);
    halfHeight = std::max(
        halfHeight, std::abs(t) - std::sqrt(std::max(0.0, finalRadius * finalRadius - distanceSquared)));
  }
  fit.capsule.halfHeight = roundUp(halfHeight);
  return fit;
}

}  // namespace collide
