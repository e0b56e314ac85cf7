// Convex hull proxy (lecture, slide 51): the queries on a finished half-edge polyhedron. Building it
// from points is shapes/hull_builder.cpp.
#include "base/fail.h"
#include "geometry/support_scan.h"
#include "shapes/hull_builder.h"
#include "shapes/shape_functions.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace collide {

ConvexHull ConvexHull::fromPoints(std::span<const Vec3> points) { return HullBuilder::build(points); }

std::vector<Vec3> ConvexHull::faceVertices(std::uint32_t face) const {
  if (face >= faces_.size()) {
    COLLIDE_FAIL("convex_hull: face index " + std::to_string(face) + " out of range, the hull has " +
                     std::to_string(faces_.size()) + " faces",
                 {});
  }
  std::vector<Vec3> loop;
  loop.reserve(faces_[face].edgeCount);
  std::uint32_t edge = faces_[face].firstEdge;
  for (std::uint32_t i = 0; i < faces_[face].edgeCount; ++i) {
    loop.push_back(vertices_[halfEdges_[edge].origin]);
    edge = halfEdges_[edge].next;
  }
  return loop;
}

// A linear scan, four vertices at a time over the blocked coordinates (geometry/support_scan.h).
// Game hulls have tens of vertices; hill climbing over the half-edges was measured slower at 32
// (dependent loads and unpredictable branches against contiguous dot products).
Vec3 ConvexHull::support(const Vec3& direction) const {
  return vertices_[detail::farthestAlong(blockedVertices_.data(),
                                         static_cast<std::uint32_t>(vertices_.size()), direction)];
}

}  // namespace collide

namespace collide::detail {

namespace {

// Points this close to the surface (relative to the hull's size) count as on it.
float surfaceTolerance(const ConvexHull& s) { return 1e-5f * glm::length(s.bounds().max - s.bounds().min); }

Vec3 closestPointOnSegment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const float lengthSquared = glm::dot(ab, ab);
  if (lengthSquared <= 0.0f) return a;
  const float t = std::clamp(glm::dot(p - a, ab) / lengthSquared, 0.0f, 1.0f);
  return a + t * ab;
}

// The nearest point of a convex face polygon: the projection if it falls inside every edge,
// otherwise the nearest point on the boundary.
Vec3 closestPointOnFace(const ConvexHull& s, const ConvexHull::Face& face, const Vec3& p) {
  const Vec3 projected = p - face.plane.signedDistance(p) * face.plane.normal;
  const auto vertices = s.vertices();
  const auto edges = s.halfEdges();
  bool inside = true;
  std::uint32_t e = face.firstEdge;
  for (std::uint32_t i = 0; i < face.edgeCount; ++i, e = edges[e].next) {
    const Vec3& a = vertices[edges[e].origin];
    const Vec3& b = vertices[edges[edges[e].next].origin];
    // Counter-clockwise seen from outside: the inside of edge ab is on the side of n x (b - a).
    if (glm::dot(glm::cross(b - a, projected - a), face.plane.normal) < 0.0f) {
      inside = false;
      break;
    }
  }
  if (inside) return projected;
  Vec3 best = projected;
  float bestDistanceSquared = std::numeric_limits<float>::max();
  e = face.firstEdge;
  for (std::uint32_t i = 0; i < face.edgeCount; ++i, e = edges[e].next) {
    const Vec3 q = closestPointOnSegment(p, vertices[edges[e].origin], vertices[edges[edges[e].next].origin]);
    const float d = glm::dot(p - q, p - q);
    if (d < bestDistanceSquared) bestDistanceSquared = d, best = q;
  }
  return best;
}

}  // namespace

Aabb computeLocalBounds(const ConvexHull& s) { return s.bounds(); }

// Every vertex transformed: exact, and cheap for the vertex counts of game hulls.
Aabb computeWorldBounds(const ConvexHull& s, const Transform& t) {
  Aabb box;
  for (const Vec3& v : s.vertices()) box.grow(t.applyToPoint(v));
  return box;
}

Vec3 computeSupport(const ConvexHull& s, const Vec3& direction) { return s.support(direction); }

MassProperties computeMassProperties(const ConvexHull& s, float density) {
  MassProperties m;
  m.volume = s.volume();
  m.mass = density * s.volume();
  m.centerOfMass = s.centroid();
  m.inertia = density * s.unitInertia();
  return m;
}

bool localContains(const ConvexHull& s, const Vec3& p) {
  const float tolerance = surfaceTolerance(s);
  for (const ConvexHull::Face& face : s.faces()) {
    if (face.plane.signedDistance(p) > tolerance) return false;
  }
  return true;
}

SurfacePoint localClosestPoint(const ConvexHull& s, const Vec3& p) {
  const auto faces = s.faces();
  std::size_t leastDeep = 0;
  float largestDistance = -std::numeric_limits<float>::max();
  for (std::size_t i = 0; i < faces.size(); ++i) {
    const float d = faces[i].plane.signedDistance(p);
    if (d > largestDistance) largestDistance = d, leastDeep = i;
  }
  if (largestDistance <= 0.0f) {
    // Inside: the nearest surface point is on the plane of the face of least depth.
    const Plane& plane = faces[leastDeep].plane;
    return {p - largestDistance * plane.normal, plane.normal, largestDistance};
  }
  // Outside: the nearest point lies on a face whose plane the point is in front of (the offset to
  // it is in the normal cone there, which the incident faces' normals span).
  Vec3 best(0.0f);
  Vec3 bestNormal = faces[leastDeep].plane.normal;
  float bestDistanceSquared = std::numeric_limits<float>::max();
  for (const ConvexHull::Face& face : faces) {
    if (face.plane.signedDistance(p) <= 0.0f) continue;
    const Vec3 q = closestPointOnFace(s, face, p);
    const float d = glm::dot(p - q, p - q);
    if (d < bestDistanceSquared) bestDistanceSquared = d, best = q, bestNormal = face.plane.normal;
  }
  const float distance = std::sqrt(bestDistanceSquared);
  // Far enough off the surface, the offset is the normal (at an edge or a vertex too); right on it,
  // the face normal is the better-conditioned direction.
  const Vec3 normal =
      distance > 1e-6f * glm::length(s.bounds().max - s.bounds().min) ? (p - best) / distance : bestNormal;
  return {best, normal, distance};
}

// Cyrus and Beck, "Generalized two- and three-dimensional clipping", 1978: clip the ray against
// every face plane; the last entering plane is the face it hits.
std::optional<RayHit> localRayCast(const ConvexHull& s, const Ray& ray) {
  if (localContains(s, ray.origin)) return RayHit{0.0f, ray.origin, -ray.direction, 0};
  float tEnter = -std::numeric_limits<float>::max();
  float tExit = ray.maxDistance;
  const ConvexHull::Face* enterFace = nullptr;
  for (const ConvexHull::Face& face : s.faces()) {
    const float distance = face.plane.signedDistance(ray.origin);
    const float approach = glm::dot(face.plane.normal, ray.direction);
    if (std::abs(approach) < 1e-12f) {
      if (distance > 0.0f) return std::nullopt;  // parallel and in front: never inside
      continue;
    }
    const float t = -distance / approach;
    if (approach < 0.0f) {
      if (t > tEnter) tEnter = t, enterFace = &face;
    } else {
      tExit = std::min(tExit, t);
    }
    if (tEnter > tExit) return std::nullopt;
  }
  if (!enterFace || tEnter < 0.0f || tEnter > tExit) return std::nullopt;
  return RayHit{tEnter, ray.origin + tEnter * ray.direction, enterFace->plane.normal, 0};
}

}  // namespace collide::detail
