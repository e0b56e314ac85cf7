// Spheres and capsules against mesh triangles by closest points, with internal-edge handling.
//
// A sphere is a point core and a capsule a segment core with a radius (convex_support.h), so the
// contact with a triangle follows from the closest points of the core and the triangle: for a
// sphere the point of the triangle nearest the centre (Ericson, "Real-Time Collision Detection",
// 5.1.5), for a capsule the nearest of its two ends' closest points and the three
// segment–edge closest pairs (5.1.9), which is exact whenever the segment does not pierce the
// triangle. Where it does (a deep overlap), GJK/EPA answers, as for every other convex shape.
//
// Which feature of the triangle holds the closest point (face, edge or vertex) is known from that
// computation, so the mesh's adjacency can judge the normal (the idea of Jolt's active edges and
// its InternalEdgeRemovingCollector; here with TriangleMesh::edgeKind): a normal from an edge or a
// vertex inside a flat patch, or from a concave fold, would be a bump for a ball rolling across
// it. Such a contact is replaced by the triangle's own face contact, the core clipped to the
// triangle's prism; for a sphere, whose nearest point then lies outside this triangle, that is
// nothing, and the neighbour whose face lies under the centre holds the contact. Points on flat
// edges are likewise left to the neighbours, as in the polyhedron path (sat_polyhedra.cpp).
//
// A capsule whose closest point lies on the face gets the clipped ends of its segment (two points
// when it lies flat), so it rests on a tessellated floor without rocking, with ids (mesh patch,
// capsule end) that do not change as it rolls from triangle to triangle of a flat patch.
#include <algorithm>
#include <cmath>

#include "geometry/closest_points.h"
#include "geometry/triangle.h"
#include "narrowphase/convex_distance.h"
#include "narrowphase/convex_support.h"
#include "narrowphase/pair_functions.h"

namespace collide::detail {

namespace {

// Where on a triangle a closest point lies: its face, edge k (v[k] to v[k+1]) or vertex k.
struct TriangleFeature {
  enum class Kind : std::uint8_t { Face, Edge, Vertex };
  Kind kind = Kind::Face;
  int index = 0;
};

TriangleFeature featureFromBarycentric(const Vec3& weights) {
  int zeros = 0, zero = 0, nonZero = 0;
  for (int k = 0; k < 3; ++k) {
    if (weights[k] <= 0.0f) {
      ++zeros;
      zero = k;
    } else {
      nonZero = k;
    }
  }
  if (zeros == 0) return {};
  // One zero weight: the edge opposite that vertex, which runs from v[zero + 1] to v[zero + 2].
  if (zeros == 1) return {TriangleFeature::Kind::Edge, (zero + 1) % 3};
  return {TriangleFeature::Kind::Vertex, nonZero};
}

// A point at parameter t of edge k.
TriangleFeature featureOnEdge(int k, float t) {
  if (t <= 0.0f) return {TriangleFeature::Kind::Vertex, k};
  if (t >= 1.0f) return {TriangleFeature::Kind::Vertex, (k + 1) % 3};
  return {TriangleFeature::Kind::Edge, k};
}

struct TrianglePlane {
  Vec3 normal{0.0f};             // unit, counter-clockwise
  std::array<Vec3, 3> inward{};  // unit, in the plane, into the triangle across edge k
  float size = 0.0f;             // longest edge
};

TrianglePlane planeOf(const SatTriangle& triangle) {
  const auto& v = triangle.vertices;
  TrianglePlane t;
  t.normal = glm::normalize(glm::cross(v[1] - v[0], v[2] - v[0]));
  for (int k = 0; k < 3; ++k) {
    const Vec3 edge = v[(k + 1) % 3] - v[k];
    t.inward[k] = glm::normalize(glm::cross(t.normal, edge));
    t.size = std::max(t.size, glm::length(edge));
  }
  return t;
}

// Below this length of its in-plane part (about 0.006°) a normal is the face's.
constexpr float kFaceNormalTolerance = 1e-4f;

bool isFaceNormal(const TrianglePlane& t, const Vec3& normal) {
  const Vec3 inPlane = normal - glm::dot(normal, t.normal) * t.normal;
  return glm::dot(inPlane, inPlane) <= kFaceNormalTolerance * kFaceNormalTolerance;
}

// Whether the surface can push along `normal` at `feature`: always at the face; at an edge if it
// is active seen from the normal's side (an outline or a convex bend); at a vertex unless it lies
// inside a flat patch and neither of the triangle's edges at it is active (the rule of
// sat_polyhedra.cpp's normalAllowed).
bool normalAllowed(const TrianglePlane& t, const SatTriangle& triangle, TriangleFeature feature,
                   const Vec3& normal) {
  if (feature.kind == TriangleFeature::Kind::Face || isFaceNormal(t, normal)) return true;
  const std::uint8_t active =
      glm::dot(normal, t.normal) >= 0.0f ? triangle.activeEdgesFront : triangle.activeEdgesBack;
  const int k = feature.index;
  if (feature.kind == TriangleFeature::Kind::Edge) return (active >> k) & 1u;
  return !((triangle.flatVertices >> k) & 1u) || ((active >> k) & 1u) || ((active >> ((k + 2) % 3)) & 1u);
}

std::uint16_t meshFeature(const SatTriangle& triangle, TriangleFeature feature) {
  switch (feature.kind) {
    case TriangleFeature::Kind::Face:
      return triangle.faceFeature;
    case TriangleFeature::Kind::Edge:
      return triangle.edgeFeature[feature.index];
    case TriangleFeature::Kind::Vertex:
      return triangle.vertexFeature[feature.index];
  }
  return triangle.faceFeature;
}

std::uint32_t capsuleFeature(float s) {
  return s <= 0.0f ? kCapsuleEnd0 : (s >= 1.0f ? kCapsuleEnd1 : kCapsuleSide);
}

// A contact from the closest points: `onTriangle` and `onCore` (the core's point) at distance
// `distance` > 0, the rounded surface `radius` out from the core along the normal.
NormalContact closestPointContact(const Vec3& onTriangle, const Vec3& onCore, float distance, float radius,
                                  std::uint32_t featureId) {
  NormalContact contact;
  contact.normal = (onCore - onTriangle) / distance;
  contact.point.pointOnA = onTriangle;
  contact.point.pointOnB = onCore - radius * contact.normal;
  contact.point.depth = radius - distance;
  contact.point.featureId = featureId;
  return contact;
}

// The triangle's face contact with a segment core [p0, p1] (p0 == p1 for a sphere) on the side
// `side`: the segment clipped to the triangle's prism (Cyrus–Beck on its three side planes), its
// ends within the margin, except ends on flat edges (the neighbour across holds them). The core's
// closest point at parameter `closestS` (if >= 0) stays in: a closest point on an edge whose normal
// is the face's lies on the prism's side within rounding, and a segment nearly parallel to that
// side would otherwise be cut far from it.
void faceContact(const SatTriangle& triangle, const TrianglePlane& t, float side, const Vec3& p0,
                 const Vec3& p1, float radius, float margin, bool isCapsule, float closestS,
                 Array<NormalContact>& contacts) {
  const Vec3 normal = side * t.normal;
  const Vec3 direction = p1 - p0;
  float t0 = 0.0f, t1 = 1.0f;
  int clip0 = -1, clip1 = -1;
  for (int k = 0; k < 3; ++k) {
    const float start = glm::dot(t.inward[k], p0 - triangle.vertices[k]);
    const float rate = glm::dot(t.inward[k], direction);
    if (std::abs(rate) <= 1e-12f * (1.0f + std::abs(start))) {
      if (start < 0.0f) return;
      continue;
    }
    const float crossing = -start / rate;
    if (rate > 0.0f) {
      if (crossing > t0) {
        t0 = crossing;
        clip0 = k;
      }
    } else if (crossing < t1) {
      t1 = crossing;
      clip1 = k;
    }
  }
  if (closestS >= 0.0f) {
    if (t0 > t1) {
      t0 = t1 = closestS;
    } else {
      t0 = std::min(t0, closestS);
      t1 = std::max(t1, closestS);
    }
  }
  if (t0 > t1) return;
  const float offset = glm::dot(normal, triangle.vertices[0]);
  auto add = [&](float s, int clip) {
    const Vec3 core = p0 + s * direction;
    const float separation = glm::dot(normal, core) - offset - radius;
    if (separation > margin) return;
    if (clip >= 0 && ((triangle.flatEdges >> clip) & 1u)) return;
    const std::uint16_t meshCode = clip >= 0 ? triangle.edgeFeature[clip] : triangle.faceFeature;
    const std::uint32_t coreCode = !isCapsule ? 0u : (clip >= 0 ? kCapsuleSide : capsuleFeature(s));
    NormalContact contact;
    contact.normal = normal;
    contact.point.pointOnB = core - radius * normal;
    contact.point.pointOnA = contact.point.pointOnB - separation * normal;
    contact.point.depth = -separation;
    contact.point.featureId = featurePair(meshCode, coreCode);
    contacts.push_back(contact);
  };
  add(t0, clip0);
  // One point when the clipped segment is a point (a sphere, or a capsule standing on the face).
  if (isCapsule && (t1 - t0) * glm::length(direction) > 1e-6f * t.size) add(t1, clip1);
}

// Deep overlap (the core touches or pierces the triangle): GJK/EPA on the triangle and the shape.
void generalContact(const SatTriangle& triangle, const ConvexSupport& shape, float margin,
                    std::uint32_t featureId, Array<NormalContact>& contacts) {
  const ConvexSupport support = makePointsSupport(triangle.vertices.data(), 3, Transform::identity());
  DistanceResult distance;
  if (!convexSignedDistance(support, shape, margin, distance)) return;
  NormalContact contact;
  contact.normal = distance.normal;
  contact.point.pointOnA = distance.pointOnA;
  contact.point.pointOnB = distance.pointOnB;
  contact.point.depth = -distance.distance;
  contact.point.featureId = featureId;
  contacts.push_back(contact);
}

void sphereTriangle(const SatTriangle& triangle, const Vec3& center, float radius, const ConvexSupport& shape,
                    float margin, Array<NormalContact>& contacts) {
  const auto& v = triangle.vertices;
  const TriangleClosestPoint closest = closestPointOnTriangle(center, v[0], v[1], v[2]);
  const Vec3 offset = center - closest.point;
  const float distanceSquared = glm::dot(offset, offset);
  const float reach = radius + margin;
  if (distanceSquared > reach * reach) return;
  const TrianglePlane t = planeOf(triangle);
  const float distance = std::sqrt(distanceSquared);
  if (distance <= 1e-6f * t.size) {
    // The centre on the triangle: no direction from the closest points.
    generalContact(triangle, shape, margin, featurePair(triangle.faceFeature, 0), contacts);
    return;
  }
  TriangleFeature feature = featureFromBarycentric(closest.barycentric);
  const Vec3 normal = offset / distance;
  if (isFaceNormal(t, normal)) feature = {};
  if (!normalAllowed(t, triangle, feature, normal)) {
    // The face's contact replaces the internal edge's: the sphere's lowest point over this
    // triangle's plane lies outside the triangle (its nearest point is on the boundary), so it is
    // empty; the neighbour under the centre (flat) or the fold's other face (concave) holds the
    // contact.
    faceContact(triangle, t, glm::dot(normal, t.normal) >= 0.0f ? 1.0f : -1.0f, center, center, radius,
                margin, false, -1.0f, contacts);
    return;
  }
  contacts.push_back(closestPointContact(closest.point, center, distance, radius,
                                         featurePair(meshFeature(triangle, feature), 0)));
}

void capsuleTriangle(const SatTriangle& triangle, const Vec3& p0, const Vec3& p1, float radius,
                     const ConvexSupport& shape, float margin, Array<NormalContact>& contacts) {
  const auto& v = triangle.vertices;
  const TrianglePlane t = planeOf(triangle);
  // A segment crossing the triangle's plane inside it pierces the triangle.
  const float h0 = glm::dot(t.normal, p0 - v[0]), h1 = glm::dot(t.normal, p1 - v[0]);
  if ((h0 < 0.0f && h1 > 0.0f) || (h0 > 0.0f && h1 < 0.0f)) {
    const Vec3 crossing = p0 + (h0 / (h0 - h1)) * (p1 - p0);
    bool inside = true;
    for (int k = 0; k < 3; ++k) inside = inside && glm::dot(t.inward[k], crossing - v[k]) >= 0.0f;
    if (inside) {
      generalContact(triangle, shape, margin, featurePair(triangle.faceFeature, kCapsuleSide), contacts);
      return;
    }
  }
  // The closest pair: from an end to the triangle, or from the segment to an edge. On ties the ends
  // win (a capsule lying flat over the face is nearest the face, not the edges it passes over).
  float best = 1e30f, bestS = 0.0f;
  Vec3 onTriangle(0.0f), onCore(0.0f);
  TriangleFeature feature;
  for (int end = 0; end < 2; ++end) {
    const Vec3& p = end == 0 ? p0 : p1;
    const TriangleClosestPoint closest = closestPointOnTriangle(p, v[0], v[1], v[2]);
    const Vec3 d = p - closest.point;
    const float distanceSquared = glm::dot(d, d);
    if (distanceSquared < best) {
      best = distanceSquared;
      bestS = float(end);
      onTriangle = closest.point;
      onCore = p;
      feature = featureFromBarycentric(closest.barycentric);
    }
  }
  for (int k = 0; k < 3; ++k) {
    const SegmentPair pair = closestPointsSegmentSegment(p0, p1, v[k], v[(k + 1) % 3]);
    if (pair.distanceSquared < best * (1.0f - 1e-5f)) {
      best = pair.distanceSquared;
      bestS = pair.s;
      onTriangle = pair.pointOnSecond;
      onCore = pair.pointOnFirst;
      feature = featureOnEdge(k, pair.t);
    }
  }
  const float reach = radius + margin;
  if (best > reach * reach) return;
  const float distance = std::sqrt(best);
  if (distance <= 1e-6f * t.size) {
    generalContact(triangle, shape, margin, featurePair(triangle.faceFeature, kCapsuleSide), contacts);
    return;
  }
  const Vec3 normal = (onCore - onTriangle) / distance;
  const bool face = feature.kind == TriangleFeature::Kind::Face || isFaceNormal(t, normal);
  if (face || !normalAllowed(t, triangle, feature, normal)) {
    // On the face, or an internal edge replaced by the face: the segment clipped to the prism.
    faceContact(triangle, t, glm::dot(normal, t.normal) >= 0.0f ? 1.0f : -1.0f, p0, p1, radius, margin, true,
                face ? bestS : -1.0f, contacts);
    return;
  }
  contacts.push_back(closestPointContact(onTriangle, onCore, distance, radius,
                                         featurePair(meshFeature(triangle, feature), capsuleFeature(bestS))));
}

}  // namespace

bool isRoundedForTriangles(const Shape& shape) {
  return shape.type() == ShapeType::Sphere || shape.type() == ShapeType::Capsule;
}

void collideTrianglesRounded(std::span<const SatTriangle> triangles, const Shape& shape,
                             const Transform& transform, float margin, Array<NormalContact>& contacts) {
  const ConvexSupport support = makeConvexSupport(shape, transform);
  if (shape.type() == ShapeType::Sphere) {
    const float radius = shape.sphere().radius * transform.scale;
    for (const SatTriangle& triangle : triangles) {
      sphereTriangle(triangle, transform.position, radius, support, margin, contacts);
    }
    return;
  }
  const Capsule& capsule = shape.capsule();
  const float radius = capsule.radius * transform.scale;
  const Vec3 p0 = transform.applyToPoint(Vec3(0.0f, -capsule.halfHeight, 0.0f));
  const Vec3 p1 = transform.applyToPoint(Vec3(0.0f, capsule.halfHeight, 0.0f));
  for (const SatTriangle& triangle : triangles)
    capsuleTriangle(triangle, p0, p1, radius, support, margin, contacts);
}

}  // namespace collide::detail
