// Polygon clipping against a half-space (Sutherland and Hodgman, "Reentrant polygon clipping",
// CACM 1974), for contact manifolds: the incident face of one polyhedron is clipped against the
// side planes of the other's reference face. Vertices carry a feature id, so that the contact cache
// can match the points from one step to the next.
#pragma once

#include <collide/math.h>

#include <cstdint>
#include <span>

namespace collide::detail {

struct ClipVertex {
  Vec3 position{0.0f};
  std::uint32_t featureId = 0;
};

// Keeps the part of the convex polygon `in` (in order) where plane.signedDistance(p) <= 0, writing
// at most `out.size()` vertices to `out` and returning their count. A vertex made where an edge from
// a to b crosses the plane gets makeId(a, b) as its feature id. A convex polygon of n vertices
// clipped by one plane has at most n + 1 vertices.
template <class MakeId>
std::size_t clipPolygon(std::span<const ClipVertex> in, const Plane& plane, std::span<ClipVertex> out,
                        MakeId&& makeId) {
  std::size_t count = 0;
  if (in.empty()) return 0;
  const ClipVertex* a = &in.back();
  float distanceA = plane.signedDistance(a->position);
  for (const ClipVertex& b : in) {
    const float distanceB = plane.signedDistance(b.position);
    if ((distanceA <= 0.0f) != (distanceB <= 0.0f) && count < out.size()) {
      // The edge crosses the plane: the crossing point, interpolated from the inside end so that
      // it lies on the plane within rounding.
      const float t = distanceA / (distanceA - distanceB);
      out[count++] = {a->position + t * (b.position - a->position), makeId(*a, b)};
    }
    if (distanceB <= 0.0f && count < out.size()) out[count++] = b;
    a = &b;
    distanceA = distanceB;
  }
  return count;
}

}  // namespace collide::detail
