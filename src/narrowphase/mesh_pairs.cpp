// Triangle-mesh pairs. The mesh's BVH yields the triangles near the other shape; their contacts are
// merged into one manifold (the deepest contact's normal, at most four points).
//   - Polyhedra (box, k-DOP, hull): each triangle is a flat polyhedron for the separating-axis
//     test with face clipping (sat_polyhedra.cpp), so a box on a tessellated floor gets its four
//     corners. Internal edges are handled there with the mesh's adjacency (TriangleMesh::edgeKind,
//     the idea of Jolt's active edges): a contact whose normal belongs to an edge or vertex
//     inside a flat patch or on a concave fold is replaced by the triangle's face contact, and
//     clipped points on such edges are left to the neighbours, whose points span the region.
//   - Spheres and capsules: closest points of the core and each triangle, with the same
//     internal-edge handling; a capsule lying on a face gets its two clipped ends
//     (triangle_rounded.cpp).
//   - Ellipsoids and cylinders: GJK/EPA per triangle for the best axis, the face preferred, and a
//     face contact from the shape's lowest features (a cylinder's rim points, as on a plane)
//     clipped to the triangle, with the same internal-edge handling (triangle_generic.cpp).
#include <vector>

#include "narrowphase/convex_distance.h"
#include "narrowphase/convex_support.h"
#include "narrowphase/pair_functions.h"

namespace collide::detail {

namespace {

// The box of `shape` in the local frame of `frame`, grown by a world margin: the shape's own world
// box in that frame, exact for primitives and polyhedra (their vertices placed), so that the BVH
// yields only the triangles the shape can reach (the rotated local box is up to √3 times wider).
Aabb boundsInFrame(const Shape& shape, const Transform& transform, const Transform& frame, float margin) {
  return worldBounds(shape, frame.inverse() * transform).expanded(margin / frame.scale);
}

bool isPolyhedron(const Shape& shape) {
  return shape.type() == ShapeType::Box || shape.type() == ShapeType::Kdop ||
         shape.type() == ShapeType::ConvexHull;
}

// Mesh feature codes (the mesh's 16 bits of a contact id): a flat patch 0x4000 | patch, an edge
// 0x8000 | a hash of its two vertices, a vertex 0xC000 | index. A point on the face of a patch
// keeps its id while it slides from triangle to triangle of the patch.
constexpr std::uint16_t kMeshFace = 0x4000u, kMeshEdge = 0x8000u, kMeshVertex = 0xC000u;
constexpr std::uint16_t kMeshIndex = 0x3fffu;

// The mesh's placement as a matrix, made once per pair rather than a quaternion product per vertex.
struct MeshPlacement {
  Mat3 rotation;
  Vec3 position;
  float scale;
  explicit MeshPlacement(const Transform& t)
      : rotation(glm::mat3_cast(t.rotation)), position(t.position), scale(t.scale) {}
  Vec3 apply(const Vec3& local) const { return position + rotation * (scale * local); }
};

SatTriangle satTriangle(const TriangleMesh& mesh, std::uint32_t index, const MeshPlacement& placement) {
  using Kind = TriangleMesh::EdgeKind;
  SatTriangle t;
  const MeshTriangle& indices = mesh.triangles()[index];
  for (int k = 0; k < 3; ++k) t.vertices[k] = placement.apply(mesh.vertices()[indices.v[k]]);
  t.activeEdgesFront = t.activeEdgesBack = 0;
  for (int k = 0; k < 3; ++k) {
    const Kind kind = mesh.edgeKind(index, k);
    // Seen from the back, a convex bend is concave and the other way round.
    if (kind == Kind::Boundary || kind == Kind::Convex) t.activeEdgesFront |= 1u << k;
    if (kind == Kind::Boundary || kind == Kind::Concave) t.activeEdgesBack |= 1u << k;
    if (kind == Kind::Flat) t.flatEdges |= 1u << k;
    if (mesh.isFlatVertex(indices.v[k])) t.flatVertices |= 1u << k;
    t.bendCosine[k] = mesh.edgeBendCosine(index, k);
    const std::uint32_t a = indices.v[k], b = indices.v[(k + 1) % 3];
    const std::uint32_t low = std::min(a, b), high = std::max(a, b);
    t.edgeFeature[k] =
        static_cast<std::uint16_t>(kMeshEdge | ((low * 0x9E37u ^ high * 0x7F4Bu) & kMeshIndex));
    t.vertexFeature[k] = static_cast<std::uint16_t>(kMeshVertex | (indices.v[k] & kMeshIndex));
  }
  t.faceFeature = static_cast<std::uint16_t>(kMeshFace | (mesh.flatPatch(index) & kMeshIndex));
  return t;
}

// A triangle placed in the world frame has a plane float can hold: finite corners and a finite,
// non-zero normal. A mesh valid in its own frame can still be turned or moved past float's range
// (corners near 3e38 m); such a triangle is beyond anything it could touch.
bool hasFinitePlane(const SatTriangle& triangle) {
  const std::array<Vec3, 3>& v = triangle.vertices;
  if (!isFinite(v[0]) || !isFinite(v[1]) || !isFinite(v[2])) return false;
  const Vec3 normal = glm::cross(v[1] - v[0], v[2] - v[0]);
  return isFinite(normal) && glm::dot(normal, normal) > 0.0f && isFinite(glm::normalize(normal));
}

}  // namespace

namespace {

// The triangles' contacts with a convex shape by the routine for its kind.
void collideTriangles(std::span<const SatTriangle> triangles, const Shape& convex, const Transform& transform,
                      float margin, Array<NormalContact>& contacts) {
  if (isPolyhedron(convex)) {
    collideTrianglesPolyhedron(triangles, convex, transform, margin, contacts);
  } else if (isRoundedForTriangles(convex)) {
    collideTrianglesRounded(triangles, convex, transform, margin, contacts);
  } else {
    collideTrianglesGeneric(triangles, convex, transform, margin, contacts);
  }
}

}  // namespace

bool collideTrianglesConvex(std::span<const std::array<Vec3, 3>> triangles,
                            const Transform& trianglesTransform, const Shape& convex,
                            const Transform& convexTransform, float margin, Manifold& out) {
  // Loose triangles: no adjacency, every edge active.
  Array<SatTriangle> placed(triangles.size());
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    for (int k = 0; k < 3; ++k) placed[i].vertices[k] = trianglesTransform.applyToPoint(triangles[i][k]);
    placed[i].faceFeature = static_cast<std::uint16_t>(kMeshFace | (i & kMeshIndex));
    for (int k = 0; k < 3; ++k) {
      placed[i].edgeFeature[k] = static_cast<std::uint16_t>(kMeshEdge | ((3 * i + k) & kMeshIndex));
      placed[i].vertexFeature[k] = static_cast<std::uint16_t>(kMeshVertex | ((3 * i + k) & kMeshIndex));
    }
  }
  std::erase_if(placed, [](const SatTriangle& t) { return !hasFinitePlane(t); });
  Array<NormalContact> contacts;
  collideTriangles(placed, convex, convexTransform, margin, contacts);
  return mergeContacts(contacts, margin, out);
}

bool collideMeshConvex(const Shape& shapeA, const Transform& transformA, const Shape& shapeB,
                       const Transform& transformB, float margin, Manifold& out) {
  const TriangleMesh& mesh = shapeA.mesh();
  thread_local Array<SatTriangle> triangles;
  triangles.clear();
  // Two valid poses can still be farther apart than float holds in the mesh's frame (a body at
  // 3e38 m, a small mesh near the origin): no triangle reaches that far.
  if (!isValid(transformA.inverse() * transformB)) return mergeContacts({}, margin, out);
  const Aabb bounds = boundsInFrame(shapeB, transformB, transformA, margin);
  const MeshPlacement placement(transformA);
  mesh.forEachTriangleOverlapping(bounds, [&](std::uint32_t index) {
    const SatTriangle triangle = satTriangle(mesh, index, placement);
    if (hasFinitePlane(triangle)) triangles.push_back(triangle);
  });
  // Per-thread, like the triangles: no allocation once warm (the step calls this per pair).
  thread_local Array<NormalContact> contacts;
  contacts.clear();
  collideTriangles(triangles, shapeB, transformB, margin, contacts);
  return mergeContacts(contacts, margin, out);
}
bool collideMeshMesh(const Shape& shapeA, const Transform& transformA, const Shape& shapeB,
                     const Transform& transformB, float margin, Manifold& out) {
  // Triangles of A near B, then triangles of B near each of them. Two static meshes never meet
  // (the broad phase pairs movable bodies only); this serves a movable closed mesh.
  const TriangleMesh& meshA = shapeA.mesh();
  const TriangleMesh& meshB = shapeB.mesh();
  const Transform bInA = transformA.inverse() * transformB;
  const Transform aInB = transformB.inverse() * transformA;
  if (!isValid(bInA) || !isValid(aInB)) return mergeContacts({}, margin, out);  // beyond float range apart
  const Aabb boundsB = transformAabb(meshB.bounds(), bInA).expanded(margin / transformA.scale);
  Array<NormalContact> contacts;
  meshA.forEachTriangleOverlapping(boundsB, [&](std::uint32_t indexA) {
    const std::array<Vec3, 3> triangleA = meshA.triangle(indexA);
    const ConvexSupport supportA = makePointsSupport(triangleA.data(), 3, transformA);
    Aabb boxA;
    for (const Vec3& v : triangleA) boxA.grow(v);
    meshB.forEachTriangleOverlapping(
        transformAabb(boxA, aInB).expanded(margin / transformB.scale), [&](std::uint32_t indexB) {
          const std::array<Vec3, 3> triangleB = meshB.triangle(indexB);
          const ConvexSupport supportB = makePointsSupport(triangleB.data(), 3, transformB);
          DistanceResult distance;
          if (!convexSignedDistance(supportA, supportB, margin, distance)) return;
          NormalContact contact;
          contact.point.pointOnA = distance.pointOnA;
          contact.point.pointOnB = distance.pointOnB;
          contact.point.depth = -distance.distance;
          contact.point.featureId = indexA * 0x9E3779B1u ^ indexB;
          contact.normal = distance.normal;
          contacts.push_back(contact);
        });
  });
  return mergeContacts(contacts, margin, out);
}

}  // namespace collide::detail
