// Closest point on a triangle (Ericson 5.1.5) and the Möller-Trumbore ray test.
#include "geometry/triangle.h"

#include <cmath>

namespace collide::detail {

TriangleClosestPoint closestPointOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  // Ericson, Real-Time Collision Detection, 5.1.5: test the vertex regions, then the edge regions,
  // using only dot products of the edges with p's offsets; the face region is what remains.
  const Vec3 ab = b - a;
  const Vec3 ac = c - a;
  const Vec3 ap = p - a;
  const float d1 = glm::dot(ab, ap);
  const float d2 = glm::dot(ac, ap);
  if (d1 <= 0.0f && d2 <= 0.0f) return {a, {1.0f, 0.0f, 0.0f}};

  const Vec3 bp = p - b;
  const float d3 = glm::dot(ab, bp);
  const float d4 = glm::dot(ac, bp);
  if (d3 >= 0.0f && d4 <= d3) return {b, {0.0f, 1.0f, 0.0f}};

  const float vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) {
    const float v = d1 / (d1 - d3);
    return {a + v * ab, {1.0f - v, v, 0.0f}};
  }

  const Vec3 cp = p - c;
  const float d5 = glm::dot(ab, cp);
  const float d6 = glm::dot(ac, cp);
  if (d6 >= 0.0f && d5 <= d6) return {c, {0.0f, 0.0f, 1.0f}};

  const float vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) {
    const float w = d2 / (d2 - d6);
    return {a + w * ac, {1.0f - w, 0.0f, w}};
  }

  const float va = d3 * d6 - d5 * d4;
  if (va <= 0.0f && (d4 - d3) >= 0.0f && (d5 - d6) >= 0.0f) {
    const float w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {b + w * (c - b), {0.0f, 1.0f - w, w}};
  }

  const float sum = va + vb + vc;
  if (!(sum > 0.0f)) return {a, {1.0f, 0.0f, 0.0f}};  // degenerate triangle: no face region
  const float denominator = 1.0f / sum;
  const float v = vb * denominator;
  const float w = vc * denominator;
  return {a + ab * v + ac * w, {1.0f - v - w, v, w}};
}

std::optional<RayTriangleHit> intersectRayTriangle(const Ray& ray, const Vec3& a, const Vec3& b,
                                                   const Vec3& c) {
  // Möller-Trumbore: solve o + t d = a + u (b - a) + v (c - a) by Cramer's rule with scalar triple
  // products. det = -d·((b - a) x (c - a)); its sign only says which side the ray comes from, and
  // both sides count.
  const Vec3 e1 = b - a;
  const Vec3 e2 = c - a;
  const Vec3 pvec = glm::cross(ray.direction, e2);
  const float det = glm::dot(e1, pvec);
  // Parallel to the plane (relative to the triangle's size): no single crossing point.
  const float scale = glm::length(glm::cross(e1, e2));
  if (!(std::abs(det) > 1e-9f * scale)) return std::nullopt;
  const float inverseDet = 1.0f / det;
  const Vec3 tvec = ray.origin - a;
  const float u = glm::dot(tvec, pvec) * inverseDet;
  if (u < -kRayTriangleEdgeSlack || u > 1.0f + kRayTriangleEdgeSlack) return std::nullopt;
  const Vec3 qvec = glm::cross(tvec, e1);
  const float v = glm::dot(ray.direction, qvec) * inverseDet;
  if (v < -kRayTriangleEdgeSlack || u + v > 1.0f + kRayTriangleEdgeSlack) return std::nullopt;
  const float t = glm::dot(e2, qvec) * inverseDet;
  if (t < 0.0f || t > ray.maxDistance) return std::nullopt;
  return RayTriangleHit{t, u, v};
}

}  // namespace collide::detail
