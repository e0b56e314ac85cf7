// Principal component analysis of a point set: the eigenvectors of its covariance matrix are the
// directions of largest and smallest spread (Gottschalk, Lin & Manocha, "OBBTree", SIGGRAPH 1996,
// used them to orient boxes; here they orient capsules and seed the box search).
#include "bounding/point_set.h"

#include "geometry/symmetric_eigen.h"

#include <glm/gtc/quaternion.hpp>

namespace collide::bounding {

PrincipalAxes principalAxes(std::span<const Vec3> points) {
  PrincipalAxes result;
  glm::dvec3 sum(0.0);
  for (const Vec3& p : points) sum += glm::dvec3(p);
  result.mean = sum / double(points.size());
  // Two passes (mean first) so that a cloud far from the origin loses no precision.
  glm::dmat3 covariance(0.0);
  for (const Vec3& p : points) {
    const glm::dvec3 d = glm::dvec3(p) - result.mean;
    covariance += glm::outerProduct(d, d);
  }
  covariance /= double(points.size());
  const SymmetricEigen3 eigen = symmetricEigen(covariance);
  result.axes = eigen.vectors;
  result.variances = eigen.values;
  return result;
}

Quat rotationFromAxes(const glm::dmat3& axes) {
  const glm::dquat q = glm::quat_cast(axes);
  return Quat(glm::normalize(glm::quat(float(q.w), float(q.x), float(q.y), float(q.z))));
}

}  // namespace collide::bounding
