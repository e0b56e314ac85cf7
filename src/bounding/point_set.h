// What the fitters share about a point set: input validation and its principal axes.
#pragma once

#include <collide/error.h>
#include <collide/math.h>

#include <cmath>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

namespace collide::bounding {

// Reports Error, prefixed with `who`, for an empty set or a non-finite point (naming its index and
// value); false then (collide/error.h).
bool requireFinitePoints(std::string_view who, std::span<const Vec3> points);

std::string formatPoint(const Vec3& p);

// Mean and principal axes of the points (eigenvectors of the covariance matrix, largest variance
// first; a right-handed basis).
struct PrincipalAxes {
  glm::dvec3 mean{0.0};
  glm::dmat3 axes{1.0};       // column i: unit axis i
  glm::dvec3 variances{0.0};  // descending
};
PrincipalAxes principalAxes(std::span<const Vec3> points);

// The indices of the points farthest each way along `directions` directions spread over the sphere
// (a golden spiral), without repeats, in increasing order. For a large set they are a coarse
// stand-in that a fitter can search on, before it measures its result over every point (DiTO:
// Larsson & Kallberg 2011, "Fast Computation of Tight-Fitting Oriented Bounding Boxes").
Array<std::size_t> extremeIndices(std::span<const glm::dvec3> points, int directions);
// The same for float points, as the points themselves.
Array<Vec3> extremePoints(std::span<const Vec3> points, int directions);

// A unit quaternion (float) for the rotation whose columns are the given right-handed orthonormal
// axes.
Quat rotationFromAxes(const glm::dmat3& axes);

// An orthonormal pair spanning the plane across a unit vector (Duff et al. 2017, "Building an
// orthonormal basis, revisited", in double).
inline void basisAcross(const glm::dvec3& n, glm::dvec3& outU, glm::dvec3& outV) {
  const double sign = std::copysign(1.0, n.z);
  const double a = -1.0 / (sign + n.z);
  const double b = n.x * n.y * a;
  outU = glm::dvec3(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
  outV = glm::dvec3(b, sign + n.y * n.y * a, -n.y);
}

}  // namespace collide::bounding
