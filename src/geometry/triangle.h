// Point and ray queries against a single triangle, shared by the mesh proxy and the narrow phase.
#pragma once

#include <collide/math.h>

#include <optional>

namespace collide::detail {

// The unnormalised normal (b - a) x (c - a): its length is twice the area, and it points to the
// side from which a, b, c run counter-clockwise.
inline Vec3 triangleAreaNormal(const Vec3& a, const Vec3& b, const Vec3& c) {
  return glm::cross(b - a, c - a);
}

struct TriangleClosestPoint {
  Vec3 point{0.0f};
  // Weights of a, b and c (they sum to 1). A zero weight says the point lies on the opposite edge,
  // two zeros that it is a vertex: the feature the narrow phase needs for contact ids.
  Vec3 barycentric{1.0f, 0.0f, 0.0f};
};

// The point of triangle abc nearest to p, by Voronoi regions (Ericson, Real-Time Collision
// Detection, 5.1.5). Works for any non-degenerate triangle; a degenerate one gives a point on it.
TriangleClosestPoint closestPointOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

struct RayTriangleHit {
  float distance = 0.0f;  // along the ray
  float u = 0.0f;         // barycentric weight of b
  float v = 0.0f;         // barycentric weight of c; a has 1 - u - v
};

// Two-sided ray vs triangle (Möller and Trumbore, "Fast, minimum storage ray-triangle
// intersection", 1997): hits with distance in [0, ray.maxDistance]. The barycentric tests accept a
// relative slack of kRayTriangleEdgeSlack so that a ray through an edge shared by two triangles
// cannot slip through the crack between them in float arithmetic.
inline constexpr float kRayTriangleEdgeSlack = 1e-6f;
std::optional<RayTriangleHit> intersectRayTriangle(const Ray& ray, const Vec3& a, const Vec3& b,
                                                   const Vec3& c);

}  // namespace collide::detail
