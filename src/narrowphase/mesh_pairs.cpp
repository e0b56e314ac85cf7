// Triangle-mesh pairs, the simple correct fallback: the mesh's BVH yields the triangles near the
// other shape, each triangle is a three-point polytope for GJK/EPA (meshes are two-sided
// surfaces), and the per-triangle contacts are merged into one manifold. Internal-edge removal and
// SAT triangle clipping are later refinements of the same cells.
#include <vector>

#include "narrowphase/convex_distance.h"
#include "narrowphase/convex_support.h"
#include "narrowphase/pair_functions.h"

namespace collide::detail {

namespace {

// The contact of one triangle (local vertices, placed by `transform`) with a convex shape.
bool triangleContact(const std::array<Vec3, 3>& triangle, const Transform& transform,
                     const ConvexSupport& convex, float margin, std::uint32_t featureId,
                     std::vector<NormalContact>& contacts) {
  const ConvexSupport support = makePointsSupport(triangle.data(), 3, transform);
  DistanceResult distance;
  if (!convexSignedDistance(support, convex, margin, distance)) return false;
  NormalContact contact;
  contact.point.pointOnA = distance.pointOnA;
  contact.point.pointOnB = distance.pointOnB;
  contact.point.depth = -distance.distance;
  contact.point.featureId = featureId;
  contact.normal = distance.normal;
  contacts.push_back(contact);
  return true;
}

// The box of `shape` in the local frame of `frame`, grown by a world margin.
Aabb boundsInFrame(const Shape& shape, const Transform& transform, const Transform& frame, float margin) {
  return transformAabb(localBounds(shape), frame.inverse() * transform).expanded(margin / frame.scale);
}

}  // namespace

bool collideTrianglesConvex(std::span<const std::array<Vec3, 3>> triangles,
                            const Transform& trianglesTransform, const Shape& convex,
                            const Transform& convexTransform, float margin, Manifold& out) {
  const ConvexSupport support = makeConvexSupport(convex, convexTransform);
  std::vector<NormalContact> contacts;
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    triangleContact(triangles[i], trianglesTransform, support, margin, static_cast<std::uint32_t>(i),
                    contacts);
  }
  return mergeContacts(contacts, margin, out);
}

bool collideMeshConvex(const Shape& shapeA, const Transform& transformA, const Shape& shapeB,
                       const Transform& transformB, float margin, Manifold& out) {
  // Contacts carry the triangle index as their whole feature id.
  const TriangleMesh& mesh = shapeA.mesh();
  const ConvexSupport support = makeConvexSupport(shapeB, transformB);
  std::vector<NormalContact> contacts;
  mesh.forEachTriangleOverlapping(
      boundsInFrame(shapeB, transformB, transformA, margin), [&](std::uint32_t index) {
        triangleContact(mesh.triangle(index), transformA, support, margin, index, contacts);
      });
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
  const Aabb boundsB = transformAabb(meshB.bounds(), bInA).expanded(margin / transformA.scale);
  std::vector<NormalContact> contacts;
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
