// Triangle mesh proxy: a surface with its own AABB tree; closed, consistently oriented meshes also
// have an inside (lecture, slide 51: "triangle mesh").
#include "geometry/triangle.h"
#include "shapes/shape_functions.h"

#include "base/fail.h"
#include "shapes/triangle_bvh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

namespace collide {

namespace {

std::string formatVec3(const Vec3& v) {
  std::ostringstream out;
  out << '[' << v.x << ", " << v.y << ", " << v.z << ']';
  return out.str();
}

// A triangle is degenerate when it is flat within the precision of the mesh's coordinates: its
// height over its longest edge (twice its area / that edge) is below this fraction of the mesh's
// diagonal. Float vertices carry a relative error of ~1e-7 of the mesh size, so a flatter
// triangle's normal would be rounding noise; intentionally collinear vertices land here too.
constexpr double kDegenerateRelativeHeight = 1e-6;

// Closed: every directed edge appears once and its reverse appears once, i.e. each undirected edge
// is shared by exactly two triangles that walk it in opposite directions.
bool isClosedSurface(std::span<const MeshTriangle> triangles) {
  Array<std::uint64_t> edges;
  edges.reserve(3 * triangles.size());
  for (const MeshTriangle& t : triangles) {
    for (int i = 0; i < 3; ++i) {
      edges.push_back(static_cast<std::uint64_t>(t.v[i]) << 32 | t.v[(i + 1) % 3]);
    }
  }
  std::sort(edges.begin(), edges.end());
  if (std::adjacent_find(edges.begin(), edges.end()) != edges.end()) return false;
  for (std::uint64_t e : edges) {
    const std::uint64_t reverse = (e << 32) | (e >> 32);
    if (!std::binary_search(edges.begin(), edges.end(), reverse)) return false;
  }
  return true;
}

// Edge adjacency: how the surface continues across each edge, for the narrow phase's internal-edge
// handling (the idea of Jolt's active edges and Bullet's internal-edge adjustment: a contact on an
// edge shared by coplanar or concave neighbours must not push along the edge's normal).
//
// Two triangles whose normals differ by less than this angle are coplanar: a tessellated floor's
// triangles are flat to rounding, and 0.1° is far above float noise yet far below any modelled bend.
constexpr double kFlatCosine = 0.99999847691;  // cos(0.1°)

struct Adjacency {
  Array<TriangleMesh::EdgeKind> edgeKinds;  // 3 per triangle
  Array<float> bendCosines;                 // 3 per triangle: -1 on the outline
  Array<std::uint8_t> flatVertices;
  Array<std::uint32_t> patches;
};

std::uint32_t findRoot(Array<std::uint32_t>& parent, std::uint32_t i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}

// A vertex is inside a flat patch when every edge at it is flat (then its fan is closed). A stage
// of its own: it reads only the finished edge kinds.
void flagFlatVertices(std::size_t vertexCount, std::span<const MeshTriangle> triangles,
                      const Array<TriangleMesh::EdgeKind>& edgeKinds, Array<std::uint8_t>& flat) {
  flat.assign(vertexCount, 0);
  for (const MeshTriangle& t : triangles) {
    for (const std::uint32_t v : t.v) flat[v] = 1;
  }
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      if (edgeKinds[3 * t + k] != TriangleMesh::EdgeKind::Flat) {
        flat[triangles[t].v[k]] = 0;
        flat[triangles[t].v[(k + 1) % 3]] = 0;
      }
    }
  }
}

Adjacency buildAdjacency(std::span<const Vec3> vertices, std::span<const MeshTriangle> triangles) {
  using Kind = TriangleMesh::EdgeKind;
  const std::size_t count = triangles.size();
  Array<glm::dvec3> normals(count);
  for (std::size_t t = 0; t < count; ++t) {
    const glm::dvec3 a(vertices[triangles[t].v[0]]), b(vertices[triangles[t].v[1]]),
        c(vertices[triangles[t].v[2]]);
    normals[t] = glm::normalize(glm::cross(b - a, c - a));
  }
  // Every triangle edge under its undirected key, sorted: the entries of one edge are adjacent.
  struct Entry {
    std::uint64_t key;
    std::uint32_t triangleEdge;  // 3 * triangle + k
  };
  Array<Entry> entries;
  entries.reserve(3 * count);
  for (std::size_t t = 0; t < count; ++t) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t i = triangles[t].v[k], j = triangles[t].v[(k + 1) % 3];
      entries.push_back({static_cast<std::uint64_t>(std::min(i, j)) << 32 | std::max(i, j),
                         static_cast<std::uint32_t>(3 * t + k)});
    }
  }
  std::sort(entries.begin(), entries.end(), [](const Entry& x, const Entry& y) {
    return x.key < y.key || (x.key == y.key && x.triangleEdge < y.triangleEdge);
  });

  Adjacency result;
  result.edgeKinds.assign(3 * count, Kind::Boundary);
  result.bendCosines.assign(3 * count, -1.0f);
  result.patches.resize(count);
  for (std::uint32_t t = 0; t < count; ++t) result.patches[t] = t;
  // The kind of edge k of triangle t against its neighbour u: the neighbour's far vertex below t's
  // plane bends away from t's front (convex), above it towards it (concave).
  auto kindAcross = [&](std::uint32_t t, std::uint32_t u) {
    if (std::abs(glm::dot(normals[t], normals[u])) >= kFlatCosine) return Kind::Flat;
    const MeshTriangle& other = triangles[u];
    const MeshTriangle& self = triangles[t];
    double height = 0.0;
    for (const std::uint32_t v : other.v) {
      if (v != self.v[0] && v != self.v[1] && v != self.v[2]) {
        height = glm::dot(normals[t], glm::dvec3(vertices[v]) - glm::dvec3(vertices[self.v[0]]));
      }
    }
    return height < 0.0 ? Kind::Convex : Kind::Concave;
  };
  for (std::size_t begin = 0; begin < entries.size();) {
    std::size_t end = begin + 1;
    while (end < entries.size() && entries[end].key == entries[begin].key) ++end;
    if (end - begin == 2) {  // a manifold edge; one triangle or three and more stay boundary
      const std::uint32_t t = entries[begin].triangleEdge / 3, u = entries[begin + 1].triangleEdge / 3;
      const Kind kindT = kindAcross(t, u), kindU = kindAcross(u, t);
      result.edgeKinds[entries[begin].triangleEdge] = kindT;
      result.edgeKinds[entries[begin + 1].triangleEdge] = kindU;
      // The bend: the angle between the two normals oriented alike across the edge (it runs one
      // way in each triangle of a consistently oriented pair; the same way means one is flipped).
      const int kt = static_cast<int>(entries[begin].triangleEdge % 3);
      const int ku = static_cast<int>(entries[begin + 1].triangleEdge % 3);
      const bool sameWay = triangles[t].v[kt] == triangles[u].v[ku];
      const double bend = (sameWay ? -1.0 : 1.0) * glm::dot(normals[t], normals[u]);
      result.bendCosines[entries[begin].triangleEdge] = static_cast<float>(bend);
      result.bendCosines[entries[begin + 1].triangleEdge] = static_cast<float>(bend);
      if (kindT == Kind::Flat) result.patches[findRoot(result.patches, t)] = findRoot(result.patches, u);
    }
    begin = end;
  }
  for (std::uint32_t t = 0; t < count; ++t) result.patches[t] = findRoot(result.patches, t);
  flagFlatVertices(vertices.size(), triangles, result.edgeKinds, result.flatVertices);
  return result;
}

}  // namespace

TriangleMesh TriangleMesh::fromTriangles(std::vector<Vec3> vertices, std::vector<MeshTriangle> triangles) {
  if (triangles.empty()) COLLIDE_FAIL("mesh: needs at least one triangle, got 0", {});
  if (triangles.size() > std::numeric_limits<std::uint32_t>::max() / 2) {
    COLLIDE_FAIL("mesh: too many triangles, got " + std::to_string(triangles.size()), {});
  }
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    if (!isFinite(vertices[i])) {
      COLLIDE_FAIL("mesh: vertex " + std::to_string(i) + " is not finite, got " + formatVec3(vertices[i]),
                   {});
    }
  }
  Aabb used;
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    const MeshTriangle& t = triangles[i];
    for (std::uint32_t index : t.v) {
      if (index >= vertices.size()) {
        COLLIDE_FAIL("mesh: triangle " + std::to_string(i) + " index " + std::to_string(index) +
                         " out of range (" + std::to_string(vertices.size()) + " vertices)",
                     {});
      }
      used.grow(vertices[index]);
    }
    if (t.v[0] == t.v[1] || t.v[1] == t.v[2] || t.v[2] == t.v[0]) {
      COLLIDE_FAIL("mesh: triangle " + std::to_string(i) + " has zero area: it repeats a vertex index (" +
                       std::to_string(t.v[0]) + ", " + std::to_string(t.v[1]) + ", " +
                       std::to_string(t.v[2]) + ")",
                   {});
    }
  }
  const double meshSize = glm::length(glm::dvec3(used.max) - glm::dvec3(used.min));
  const double minHeight = kDegenerateRelativeHeight * meshSize;
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    const glm::dvec3 a(vertices[triangles[i].v[0]]);
    const glm::dvec3 b(vertices[triangles[i].v[1]]);
    const glm::dvec3 c(vertices[triangles[i].v[2]]);
    const double doubleArea = glm::length(glm::cross(b - a, c - a));
    const double longestEdge = std::max({glm::length(b - a), glm::length(c - b), glm::length(a - c)});
    if (!(doubleArea > minHeight * longestEdge)) {
      std::ostringstream message;
      message << "mesh: triangle " << i << " has zero area (area " << 0.5 * doubleArea << "; its height "
              << doubleArea / longestEdge << " is below " << kDegenerateRelativeHeight << " of the mesh size "
              << meshSize << ")";
      COLLIDE_FAIL(message.str(), {});
    }
  }

  TriangleMesh mesh;
  mesh.vertices_.assign(vertices.begin(), vertices.end());
  mesh.triangles_.assign(triangles.begin(), triangles.end());
  detail::TriangleBvh bvh = detail::buildTriangleBvh(mesh.vertices_, mesh.triangles_);
  mesh.nodes_ = std::move(bvh.nodes);
  mesh.triangleOrder_ = std::move(bvh.triangleOrder);
  Adjacency adjacency = buildAdjacency(mesh.vertices_, mesh.triangles_);
  mesh.edgeKinds_ = std::move(adjacency.edgeKinds);
  mesh.bendCosines_ = std::move(adjacency.bendCosines);
  mesh.flatVertices_ = std::move(adjacency.flatVertices);
  mesh.patches_ = std::move(adjacency.patches);
  mesh.closed_ = isClosedSurface(mesh.triangles_);
  if (mesh.closed_) {
    // Integrate about the box centre: the moments of a mesh far from the origin would otherwise
    // lose their digits to the huge offset terms.
    const Vec3 origin = mesh.nodes_.front().bounds.center();
    detail::PolyhedronIntegrals integrals;
    for (const MeshTriangle& t : mesh.triangles_) {
      integrals.addTriangle(mesh.vertices_[t.v[0]] - origin, mesh.vertices_[t.v[1]] - origin,
                            mesh.vertices_[t.v[2]] - origin);
    }
    integrals.finish(mesh.volume_, mesh.centroid_, mesh.unitInertia_);
    mesh.centroid_ += origin;
  }
  return mesh;
}

std::array<Vec3, 3> TriangleMesh::triangle(std::uint32_t index) const {
  const MeshTriangle& t = triangles_[index];
  return {vertices_[t.v[0]], vertices_[t.v[1]], vertices_[t.v[2]]};
}

}  // namespace collide

namespace collide::detail {

namespace {

// Visits the leaves' triangles whose boxes the ray enters within [0, ray.maxDistance], nearer box
// first. The visitor may shrink ray.maxDistance (the best hit so far), which prunes the rest.
template <class Visitor>
void walkAlongRay(const TriangleMesh& mesh, Ray& ray, Visitor&& visit) {
  const auto nodes = mesh.bvh();
  const auto order = mesh.triangleOrder();
  struct Entry {
    std::uint32_t node;
    float entry;
  };
  // Nearer child first: at most one pending sibling per level, and depth < 60.
  Entry stack[64];
  int top = 0;
  const float rootEntry = rayAabbEntry(ray, nodes[0].bounds);
  if (rootEntry < 0.0f) return;
  stack[top++] = {0, rootEntry};
  while (top > 0) {
    const Entry e = stack[--top];
    if (e.entry > ray.maxDistance) continue;
    const TriangleMesh::BvhNode& node = nodes[e.node];
    if (node.count > 0) {
      for (std::uint32_t i = 0; i < node.count; ++i) visit(order[node.firstTriangleOrSecondChild + i]);
      continue;
    }
    Entry first{e.node + 1, rayAabbEntry(ray, nodes[e.node + 1].bounds)};
    Entry second{node.firstTriangleOrSecondChild,
                 rayAabbEntry(ray, nodes[node.firstTriangleOrSecondChild].bounds)};
    if (first.entry >= 0.0f && second.entry >= 0.0f && second.entry < first.entry) std::swap(first, second);
    if (second.entry >= 0.0f) stack[top++] = second;
    if (first.entry >= 0.0f) stack[top++] = first;
  }
}

float squaredDistanceToBox(const Vec3& p, const Aabb& box) {
  const Vec3 d = glm::max(glm::max(box.min - p, p - box.max), Vec3(0.0f));
  return glm::dot(d, d);
}

// The sign that turns the mesh's triangle normals outward: a closed mesh wound inside out has a
// negative signed volume.
float outwardSign(const TriangleMesh& s) { return s.isClosed() && s.volume() < 0.0f ? -1.0f : 1.0f; }

// Crossing parity along one ray, or nothing when the ray passes too close to an edge or vertex (or
// grazes a triangle's plane) to count crossings reliably in float arithmetic.
enum class Parity : std::uint8_t { Even, Odd, OnSurface, Ambiguous };

Parity crossingParity(const TriangleMesh& s, const Vec3& p, const Vec3& direction, float surfaceTolerance) {
  constexpr float kEdgeTolerance = 1e-5f;  // barycentric distance to an edge that we trust
  Ray ray{p, direction, 1e30f};
  int crossings = 0;
  bool ambiguous = false;
  bool onSurface = false;
  walkAlongRay(s, ray, [&](std::uint32_t index) {
    if (onSurface) return;  // decided; keep scanning after an ambiguity, p may still be on the surface
    const auto [a, b, c] = s.triangle(index);
    const Vec3 e1 = b - a;
    const Vec3 e2 = c - a;
    const Vec3 pvec = glm::cross(direction, e2);
    const float det = glm::dot(e1, pvec);
    const Vec3 tvec = p - a;
    if (!(std::abs(det) > 1e-6f * glm::length(glm::cross(e1, e2)))) {
      // Nearly parallel: only a problem when p lies near the triangle's plane (the ray may run
      // inside it); otherwise the line misses the triangle or crosses it far outside.
      const Vec3 n = glm::normalize(glm::cross(e1, e2));
      if (std::abs(glm::dot(n, tvec)) <= surfaceTolerance) ambiguous = true;
      return;
    }
    const float inverseDet = 1.0f / det;
    const float u = glm::dot(tvec, pvec) * inverseDet;
    const Vec3 qvec = glm::cross(tvec, e1);
    const float v = glm::dot(direction, qvec) * inverseDet;
    const float w = 1.0f - u - v;
    if (u < -kEdgeTolerance || v < -kEdgeTolerance || w < -kEdgeTolerance) return;  // clear miss
    const float t = glm::dot(e2, qvec) * inverseDet;
    if (std::abs(t) <= surfaceTolerance) {
      // p lies on this triangle, or within the tolerance of one of its edges.
      onSurface = true;
      return;
    }
    if (t < 0.0f) return;
    if (u <= kEdgeTolerance || v <= kEdgeTolerance || w <= kEdgeTolerance) {
      ambiguous = true;
      return;
    }
    ++crossings;
  });
  if (onSurface) return Parity::OnSurface;
  if (ambiguous) return Parity::Ambiguous;
  return crossings % 2 == 1 ? Parity::Odd : Parity::Even;
}

// Generalized winding number (Jacobson, Kavan and Sorkine-Hornung, "Robust inside-outside
// segmentation using generalized winding numbers", SIGGRAPH 2013): the sum of the signed solid
// angles of the triangles seen from p (Van Oosterom and Strackee, 1983), over 4 pi. It is ±1 inside
// a closed surface and 0 outside, and varies smoothly, so no edge case exists; it costs O(n).
double windingNumber(const TriangleMesh& s, const Vec3& p) {
  double total = 0.0;
  for (std::uint32_t i = 0; i < s.triangles().size(); ++i) {
    const auto [ta, tb, tc] = s.triangle(i);
    const glm::dvec3 a = glm::dvec3(ta) - glm::dvec3(p);
    const glm::dvec3 b = glm::dvec3(tb) - glm::dvec3(p);
    const glm::dvec3 c = glm::dvec3(tc) - glm::dvec3(p);
    const double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
    const double numerator = glm::dot(a, glm::cross(b, c));
    const double denominator = la * lb * lc + glm::dot(a, b) * lc + glm::dot(b, c) * la + glm::dot(c, a) * lb;
    total += 2.0 * std::atan2(numerator, denominator);
  }
  return total / (4.0 * 3.14159265358979323846);
}

}  // namespace

Aabb computeLocalBounds(const TriangleMesh& s) { return s.bounds(); }

// Conservative and O(1): the transformed root box. Exact bounds would cost a pass over the vertices.
Aabb computeWorldBounds(const TriangleMesh& s, const Transform& t) { return transformAabb(s.bounds(), t); }

MassProperties computeMassProperties(const TriangleMesh& s, float density) {
  if (!s.isClosed()) {
    COLLIDE_FAIL("mesh: an open triangle mesh encloses no volume and has no mass properties", {});
  }
  // An inside-out closed mesh integrates to minus the solid's moments; flip them back.
  const float sign = outwardSign(s);
  MassProperties m;
  m.volume = sign * s.volume();
  m.mass = density * m.volume;
  m.centerOfMass = s.centroid();
  m.inertia = (density * sign) * s.unitInertia();
  return m;
}

// Inside test for closed meshes: crossing parity of a ray along a fixed, generic direction, walked
// through the BVH (Jordan curve theorem). A ray that passes within a small tolerance of an edge or
// vertex, or grazes a plane, could count a crossing twice or not at all, so it is discarded and the
// next direction tried; if all are ambiguous (a point placed adversarially), the generalized winding
// number decides. Points on the surface (within 1e-6 of the mesh size) count as inside, like the
// solid primitives' closed sets.
bool localContains(const TriangleMesh& s, const Vec3& p) {
  if (!s.isClosed()) return false;
  if (!s.bounds().contains(p)) return false;
  static const Vec3 kDirections[] = {
      glm::normalize(Vec3(0.5773f, 0.6215f, 0.5297f)),
      glm::normalize(Vec3(-0.7071f, 0.3127f, 0.6343f)),
      glm::normalize(Vec3(0.2387f, -0.8419f, -0.4839f)),
  };
  const float surfaceTolerance = 1e-6f * glm::length(s.bounds().max - s.bounds().min);
  for (const Vec3& direction : kDirections) {
    switch (crossingParity(s, p, direction, surfaceTolerance)) {
      case Parity::Odd:
        return true;
      case Parity::Even:
        return false;
      case Parity::OnSurface:
        return true;
      case Parity::Ambiguous:
        break;
    }
  }
  return std::abs(windingNumber(s, p)) > 0.5;
}

// Nearest triangle by a best-first walk of the BVH: children are visited nearer box first, and any
// box farther than the best triangle so far is skipped.
SurfacePoint localClosestPoint(const TriangleMesh& s, const Vec3& p) {
  const auto nodes = s.bvh();
  const auto order = s.triangleOrder();
  float bestSquared = std::numeric_limits<float>::infinity();
  Vec3 bestPoint(0.0f);
  std::uint32_t bestTriangle = 0;
  struct Entry {
    std::uint32_t node;
    float squaredDistance;
  };
  Entry stack[64];
  int top = 0;
  stack[top++] = {0, squaredDistanceToBox(p, nodes[0].bounds)};
  while (top > 0) {
    const Entry e = stack[--top];
    if (e.squaredDistance >= bestSquared) continue;
    const TriangleMesh::BvhNode& node = nodes[e.node];
    if (node.count > 0) {
      for (std::uint32_t i = 0; i < node.count; ++i) {
        const std::uint32_t index = order[node.firstTriangleOrSecondChild + i];
        const auto [a, b, c] = s.triangle(index);
        const Vec3 q = closestPointOnTriangle(p, a, b, c).point;
        const float squared = glm::dot(p - q, p - q);
        if (squared < bestSquared) {
          bestSquared = squared;
          bestPoint = q;
          bestTriangle = index;
        }
      }
      continue;
    }
    Entry first{e.node + 1, squaredDistanceToBox(p, nodes[e.node + 1].bounds)};
    Entry second{node.firstTriangleOrSecondChild,
                 squaredDistanceToBox(p, nodes[node.firstTriangleOrSecondChild].bounds)};
    if (second.squaredDistance < first.squaredDistance) std::swap(first, second);
    if (second.squaredDistance < bestSquared) stack[top++] = second;
    if (first.squaredDistance < bestSquared) stack[top++] = first;
  }

  const auto [a, b, c] = s.triangle(bestTriangle);
  const Vec3 faceNormal = glm::normalize(triangleAreaNormal(a, b, c));
  const float distance = std::sqrt(bestSquared);
  SurfacePoint result;
  result.point = bestPoint;
  const Vec3 offset = p - bestPoint;
  const float tiny = 1e-6f * glm::length(s.bounds().max - s.bounds().min);
  if (s.isClosed()) {
    // Away from the surface the offset is the outward normal, at an edge or a vertex too (as for
    // the Box); right on it, the closest triangle's outward normal is the better-conditioned one.
    // The sign of the distance comes from containment.
    const bool inside = localContains(s, p);
    result.normal = distance > tiny ? (inside ? -offset : offset) / distance : outwardSign(s) * faceNormal;
    result.signedDistance = inside ? -distance : distance;
  } else {
    // A surface has two sides: the normal points from the surface towards the query point (the
    // triangle's normal turned to face it when the point lies on the surface).
    if (distance > tiny) {
      result.normal = offset / distance;
    } else {
      result.normal = glm::dot(faceNormal, offset) < 0.0f ? -faceNormal : faceNormal;
    }
    result.signedDistance = distance;
  }
  return result;
}

std::optional<RayHit> localRayCast(const TriangleMesh& s, const Ray& ray) {
  if (s.isClosed() && localContains(s, ray.origin)) return RayHit{0.0f, ray.origin, -ray.direction, 0};
  Ray search = ray;
  std::optional<RayTriangleHit> best;
  std::uint32_t bestTriangle = 0;
  walkAlongRay(s, search, [&](std::uint32_t index) {
    const auto [a, b, c] = s.triangle(index);
    const std::optional<RayTriangleHit> hit = intersectRayTriangle(search, a, b, c);
    if (hit && (!best || hit->distance < best->distance)) {
      best = hit;
      bestTriangle = index;
      search.maxDistance = hit->distance;
    }
  });
  if (!best) return std::nullopt;
  const auto [a, b, c] = s.triangle(bestTriangle);
  Vec3 normal = glm::normalize(triangleAreaNormal(a, b, c));
  if (glm::dot(normal, ray.direction) > 0.0f) normal = -normal;  // two-sided: face the origin
  return RayHit{best->distance, ray.origin + best->distance * ray.direction, normal, bestTriangle};
}

}  // namespace collide::detail
