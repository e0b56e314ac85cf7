// What the narrow phase knows about one mesh triangle while it builds contacts: its frame (edges,
// outward side normals, normal, size), the names of its features in contact ids, and which contact
// normals the surface can give there (internal edges: the idea of Jolt's active edges and Bullet's
// internal-edge adjustment, with the mesh's adjacency in SatTriangle). Shared by the polyhedron
// (sat_polyhedra.cpp) and the generic (triangle_generic.cpp) triangle contacts.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "geometry/clipping.h"
#include "narrowphase/pair_functions.h"

namespace collide::detail {

// The triangle half of a contact id while clipping against the triangle's sides: bit k set when
// the point lies on side k (edge v[k] -> v[k+1]); none for the face, two for a corner.
inline constexpr std::uint32_t kSideBits = 0x7u;

inline int cornerBetween(std::uint32_t bits) {
  // Sides k and k + 1 meet at vertex k + 1.
  for (int k = 0; k < 3; ++k) {
    if (bits == ((1u << k) | (1u << ((k + 1) % 3)))) return (k + 1) % 3;
  }
  return -1;
}

struct TriangleFrame {
  std::array<Vec3, 3> v;
  std::array<Vec3, 3> edge;     // v[k+1] - v[k]
  std::array<Vec3, 3> outward;  // unit, in the plane, away from the triangle across edge k
  Vec3 normal{0.0f};            // unit, counter-clockwise
  float size = 0.0f;
};

// The vertices, edges and normal: enough for the face tests that reject most triangles.
inline TriangleFrame planeFrameOf(const std::array<Vec3, 3>& v) {
  TriangleFrame t;
  t.v = v;
  for (int k = 0; k < 3; ++k) t.edge[k] = v[(k + 1) % 3] - v[k];
  t.normal = glm::normalize(glm::cross(t.edge[0], -t.edge[2]));
  return t;
}

// The side normals and the size, for the edge tests and clipping.
inline void completeFrame(TriangleFrame& t) {
  for (int k = 0; k < 3; ++k) t.outward[k] = glm::normalize(glm::cross(t.edge[k], t.normal));
  t.size = std::max({glm::length(t.edge[0]), glm::length(t.edge[1]), glm::length(t.edge[2])});
}

inline TriangleFrame frameOf(const std::array<Vec3, 3>& v) {
  TriangleFrame t = planeFrameOf(v);
  completeFrame(t);
  return t;
}

// The mesh half of a contact's id from the side bits of its point on the triangle.
inline std::uint32_t meshFeature(const SatTriangle& triangle, std::uint32_t bits) {
  if (bits == 0) return triangle.faceFeature;
  for (int k = 0; k < 3; ++k) {
    if (bits == (1u << k)) return triangle.edgeFeature[k];
  }
  const int corner = cornerBetween(bits);
  return corner >= 0 ? triangle.vertexFeature[corner] : triangle.faceFeature;
}

// Whether a contact point named by its side bits lies inside a flat patch of the mesh (on an edge
// between coplanar triangles, or at a vertex all of whose edges are such): the neighbours'
// points then span the contact region without it.
inline bool insideFlatPatch(const SatTriangle& triangle, std::uint32_t bits) {
  for (int k = 0; k < 3; ++k) {
    if (bits == (1u << k)) return (triangle.flatEdges >> k) & 1u;
  }
  const int corner = cornerBetween(bits);
  return corner >= 0 && ((triangle.flatVertices >> corner) & 1u);
}

// The points of the other shape clipped to the triangle (their ids: side bits low, the shape's
// feature high) as contacts of a triangle face contact along `normal` (from the triangle, whose
// plane is normal . x = offset): each within the margin, on the triangle's plane in A, and not
// inside a flat patch (its neighbours' points span the region without it).
inline void appendClippedFaceContacts(std::span<const ClipVertex> points, const SatTriangle& triangle,
                                      const Vec3& normal, float offset, float margin,
                                      Array<NormalContact>& contacts) {
  for (const ClipVertex& clipped : points) {
    const Vec3 p = clipped.position;
    const float separation = glm::dot(normal, p) - offset;
    if (separation > margin) continue;
    const std::uint32_t bits = clipped.featureId & kSideBits;
    if (insideFlatPatch(triangle, bits)) continue;
    NormalContact contact;
    contact.normal = normal;
    contact.point.pointOnA = p - separation * normal;
    contact.point.pointOnB = p;
    contact.point.depth = -separation;
    contact.point.featureId = featurePair(meshFeature(triangle, bits), clipped.featureId >> 16);
    contacts.push_back(contact);
  }
}

// Whether a contact normal (from the triangle) is one the surface can give: the triangle's face
// normal, or the normal of an edge or vertex of the triangle that is active (on the mesh's outline
// or a convex bend, seen from the normal's side). The triangle's features touching along the
// normal are its vertices farthest along it.
inline bool normalAllowed(const TriangleFrame& t, const SatTriangle& triangle, const Vec3& normal) {
  const float along = glm::dot(normal, t.normal);
  const Vec3 inPlane = normal - along * t.normal;
  if (glm::length(inPlane) <= 1e-4f) return true;  // the face normal (within 0.006°)
  const std::uint8_t active = along >= 0.0f ? triangle.activeEdgesFront : triangle.activeEdgesBack;
  float heights[3], highest = -1e30f;
  for (int k = 0; k < 3; ++k) highest = std::max(highest, heights[k] = glm::dot(normal, t.v[k]));
  const float tolerance = 1e-4f * t.size;
  std::uint32_t top = 0;  // vertex bits
  for (int k = 0; k < 3; ++k) {
    if (heights[k] >= highest - tolerance) top |= 1u << k;
  }
  for (int k = 0; k < 3; ++k) {
    const std::uint32_t edgeBits = (1u << k) | (1u << ((k + 1) % 3));
    // An active edge (outline or convex bend) has the normals between its two faces': beyond the
    // bend (the per-triangle SAT's edge-edge axis can be anywhere on the triangle's half circle) the
    // neighbour's face is nearer, and the face contacts hold the shape (an edge axis far outside a
    // shallow bend would push the shape sideways across the mesh). 1e-3 rad of slack for rounding.
    if (top == edgeBits) {
      if (!((active >> k) & 1u)) return false;
      const float bend = triangle.bendCosine[k];
      if (bend <= -1.0f) return true;  // the outline: any normal on its outer half circle
      // cos(bend angle + 1e-3) ~ cos(bend) - 1e-3 sin(bend), and 1e-6 for rounding.
      const float slack = 1e-3f * std::sqrt(std::max(0.0f, 1.0f - bend * bend)) + 1e-6f;
      return std::abs(along) >= bend - slack;
    }
    // A vertex: active unless it lies inside a flat patch and neither of the triangle's edges at it
    // is active (an outline vertex or a vertex at a bend may push any way).
    if (top == (1u << k)) {
      return !((triangle.flatVertices >> k) & 1u) || ((active >> k) & 1u) || ((active >> ((k + 2) % 3)) & 1u);
    }
  }
  return true;
}

}  // namespace collide::detail
