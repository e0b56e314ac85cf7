// GJK: the distance between two convex cores through the support mapping of their Minkowski
// difference (Gilbert, Johnson and Keerthi 1988; van den Bergen, "A Fast and Robust GJK
// Implementation for Collision Detection of Convex Objects", 1999). The closest points come from
// the barycentric coordinates of the origin's projection on the final simplex.
#pragma once

#include "narrowphase/convex_support.h"

namespace collide::detail {

// A vertex of the Minkowski difference A - B with the two support points that made it.
struct SimplexVertex {
  Vec3 a{0.0f};
  Vec3 b{0.0f};
  Vec3 w{0.0f};  // a - b
};

struct Simplex {
  SimplexVertex vertices[4];
  // Barycentric coordinates of the closest point, in double precision like the solve (gjk.cpp).
  double lambda[4] = {1.0, 0.0, 0.0, 0.0};
  int count = 0;
};

// The support of A - B in direction d: A's farthest point along d minus B's farthest along -d.
inline SimplexVertex minkowskiSupport(const ConvexSupport& a, const ConvexSupport& b, const Vec3& d) {
  SimplexVertex v;
  v.a = a.supportCore(d);
  v.b = b.supportCore(-d);
  v.w = v.a - v.b;
  return v;
}

struct GjkResult {
  enum class Status : std::uint8_t {
    Separated,    // distance > 0, closest points valid
    Overlapping,  // the cores touch or overlap; `simplex` encloses the origin (within tolerance)
    BeyondBound,  // proven farther apart than the caller's bound; nothing else is valid
  };
  Status status = Status::Separated;
  float distance = 0.0f;  // between the cores
  Vec3 pointOnA{0.0f};    // on A's core
  Vec3 pointOnB{0.0f};    // on B's core
  // Separated: unit, from A to B, the direction of the closest point of A - B (more accurate than
  // pointOnB - pointOnA, whose float rounding is large against a small distance).
  Vec3 normal{0.0f, 1.0f, 0.0f};
  Simplex simplex;
  int iterations = 0;
};

// What one GJK query leaves for the next query of the same pair (frame coherence): its final
// simplex as points in the two shapes' local frames.
// Box2D's b2SimplexCache keeps vertex indices instead; local points serve every support kind. The
// cached points, placed by the new transforms, are still points of A and B, so they make a valid
// starting simplex however far the shapes moved: a pair that barely moved converges in one or two
// support calls instead of five to ten. A default-constructed cache is empty (a cold start).
struct GjkCache {
  Vec3 localA[4];
  Vec3 localB[4];
  int count = 0;
};

// The closest points of the cores of A and B (their radii are ignored). Stops early with
// BeyondBound as soon as the distance is proven larger than `bound`. With a cache, starts from the
// cached simplex and updates it; the cache must belong to this pair in this order (A, B).
GjkResult gjkDistance(const ConvexSupport& a, const ConvexSupport& b, float bound = 1e30f,
                      GjkCache* cache = nullptr);

// Reduces the simplex to the smallest sub-simplex whose hull holds its point closest to the origin,
// sets the barycentric coordinates and returns that point. Returns false when the origin lies
// inside a tetrahedron (then the simplex is unchanged and the point is the origin).
bool closestPointOfSimplex(Simplex& simplex, Vec3& outClosest);

// Barycentric coordinates (u, v, w) of the point of triangle abc closest to p. Degenerate
// triangles fall back to their edges.
Vec3 closestBarycentricOnTriangle(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& p);

}  // namespace collide::detail
