// Mass-property helpers shared by the proxies: polyhedron integrals and the parallel-axis theorem.
#include "shapes/shape_functions.h"

namespace collide::detail {

Mat3 shiftInertia(const Mat3& inertiaAtCom, float mass, const Vec3& offset) {
  // Parallel-axis theorem in tensor form: I_p = I_com + m (|d|^2 E - d d^T).
  const Mat3 outer = glm::outerProduct(offset, offset);
  return inertiaAtCom + mass * (glm::dot(offset, offset) * Mat3(1.0f) - outer);
}

void PolyhedronIntegrals::addTriangle(const Vec3& a, const Vec3& b, const Vec3& c) {
  // Each triangle and the origin span a signed tetrahedron; its second moment is the canonical
  // tetrahedron's covariance mapped by A = [a b c] (Blow and Binstock, "How to find the inertia
  // tensor (or other mass properties) of a 3D solid body represented by a triangle mesh", 2004).
  const double ax = a.x, ay = a.y, az = a.z, bx = b.x, by = b.y, bz = b.z, cx = c.x, cy = c.y, cz = c.z;
  const double det = ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx);
  volume += det / 6.0;
  firstMoment[0] += det / 24.0 * (ax + bx + cx);
  firstMoment[1] += det / 24.0 * (ay + by + cy);
  firstMoment[2] += det / 24.0 * (az + bz + cz);
  // ∫ x_i x_j dV over the tetrahedron = det/120 * (sum_k p_ki p_kj + (sum_k p_ki)(sum_k p_kj)).
  auto moment = [&](double a0, double b0, double c0, double a1, double b1, double c1) {
    return det / 120.0 * (a0 * a1 + b0 * b1 + c0 * c1 + (a0 + b0 + c0) * (a1 + b1 + c1));
  };
  secondMoment[0] += moment(ax, bx, cx, ax, bx, cx);
  secondMoment[1] += moment(ay, by, cy, ay, by, cy);
  secondMoment[2] += moment(az, bz, cz, az, bz, cz);
  secondMoment[3] += moment(ax, bx, cx, ay, by, cy);
  secondMoment[4] += moment(ay, by, cy, az, bz, cz);
  secondMoment[5] += moment(az, bz, cz, ax, bx, cx);
}

void PolyhedronIntegrals::finish(float& outVolume, Vec3& outCentroid, Mat3& outUnitInertia) const {
  const double v = volume;
  const double cx = firstMoment[0] / v, cy = firstMoment[1] / v, cz = firstMoment[2] / v;
  // Second moments about the centroid.
  const double xx = secondMoment[0] - v * cx * cx;
  const double yy = secondMoment[1] - v * cy * cy;
  const double zz = secondMoment[2] - v * cz * cz;
  const double xy = secondMoment[3] - v * cx * cy;
  const double yz = secondMoment[4] - v * cy * cz;
  const double zx = secondMoment[5] - v * cz * cx;
  outVolume = static_cast<float>(v);
  outCentroid = Vec3(static_cast<float>(cx), static_cast<float>(cy), static_cast<float>(cz));
  // Inertia = trace(C) E - C, with C the covariance (second-moment) matrix.
  Mat3 inertia(0.0f);
  inertia[0][0] = static_cast<float>(yy + zz);
  inertia[1][1] = static_cast<float>(xx + zz);
  inertia[2][2] = static_cast<float>(xx + yy);
  inertia[0][1] = inertia[1][0] = static_cast<float>(-xy);
  inertia[1][2] = inertia[2][1] = static_cast<float>(-yz);
  inertia[0][2] = inertia[2][0] = static_cast<float>(-zx);
  outUnitInertia = inertia;
}

}  // namespace collide::detail
