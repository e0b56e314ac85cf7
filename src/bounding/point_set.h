// What the fitters share about a point set: input validation and its principal axes.
#pragma once

#include <collide/error.h>
#include <collide/math.h>

#include <span>
#include <string>
#include <string_view>

#include <glm/glm.hpp>

namespace collide::bounding {

// Throws Error, prefixed with `who`, for an empty set or a non-finite point (naming its index and
// value).
void requireFinitePoints(std::string_view who, std::span<const Vec3> points);

std::string formatPoint(const Vec3& p);

// Mean and principal axes of the points (eigenvectors of the covariance matrix, largest variance
// first; a right-handed basis).
struct PrincipalAxes {
  glm::dvec3 mean{0.0};
  glm::dmat3 axes{1.0};       // column i: unit axis i
  glm::dvec3 variances{0.0};  // descending
};
PrincipalAxes principalAxes(std::span<const Vec3> points);

// A unit quaternion (float) for the rotation whose columns are the given right-handed orthonormal
// axes.
Quat rotationFromAxes(const glm::dmat3& axes);

}  // namespace collide::bounding
