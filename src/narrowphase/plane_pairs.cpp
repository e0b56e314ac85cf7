// Half-space pairs (lecture, slide 59: the side of a point is the sign of n·q - d). The plane is
// always A here; the normal of the manifold is the plane's outward normal, the direction that
// lifts the other shape out of the solid. Every point of the other shape below the surface (plus
// the margin) is a contact, so each pair lists the shape's candidate points: its deepest ones.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "narrowphase/convex_support.h"
#include "narrowphase/pair_functions.h"

namespace collide::detail {

Plane worldPlane(const Plane& plane, const Transform& transform) {
  Vec3 normal = transform.applyToDirection(plane.normal);
  float distance = plane.distance;
  // A normal and a rotation each within the validation's tolerance of unit (1e-3) give a world
  // normal up to 2e-3 off; normals and depths are promised unit and metric, so such a plane is made
  // unit here. A unit normal by a unit rotation (length within float rounding, far below 1e-6) is
  // kept bit for bit.
  const float lengthSquared = glm::dot(normal, normal);
  if (std::abs(lengthSquared - 1.0f) > 1e-6f) {
    const float length = std::sqrt(lengthSquared);
    normal /= length;
    distance /= glm::length(plane.normal);
  }
  return {normal, distance * transform.scale + glm::dot(normal, transform.position)};
}

namespace {

// Appends a contact for world point `p` of B if it lies within the margin of the surface.
bool addIfBelow(const Plane& plane, const Vec3& p, float margin, std::uint32_t featureB, ContactPoint* points,
                int& count) {
  const float height = plane.signedDistance(p);
  if (height > margin) return false;
  ContactPoint& point = points[count++];
  point.pointOnB = p;
  point.pointOnA = p - height * plane.normal;
  point.depth = -height;
  point.featureId = featurePair(0, featureB);
  return true;
}

bool finish(const Plane& plane, const ContactPoint* candidates, int count, Manifold& out) {
  out.normal = plane.normal;
  reduceContacts(std::span<const ContactPoint>(candidates, static_cast<std::size_t>(count)), plane.normal,
                 out);
  return out.count > 0;
}

}  // namespace

bool collidePlaneSphere(const Shape& shapeA, const Transform& transformA, const Shape& shapeB,
                        const Transform& transformB, float margin, Manifold& out) {
  const Plane plane = worldPlane(shapeA.plane(), transformA);
  const float radius = shapeB.sphere().radius * transformB.scale;
  out.count = 0;
  addIfBelow(plane, transformB.position - radius * plane.normal, margin, 0, out.points.data(), out.count);
  out.normal = plane.normal;
  return out.count > 0;
}

bool collidePlaneCapsule(const Shape& shapeA, const Transform& transformA, const Shape& shapeB,
                         const Transform& transformB, float margin, Manifold& out) {
  // The deepest points of a capsule are its end spheres' lowest points: one end when tilted, both
  // when it lies flat.
  const Plane plane = worldPlane(shapeA.plane(), transformA);
  const Capsule& capsule = shapeB.capsule();
  const Vec3 down = capsule.radius * transformB.scale * plane.normal;
  out.count = 0;
  addIfBelow(plane, transformB.applyToPoint(Vec3(0.0f, -capsule.halfHeight, 0.0f)) - down, margin,
             kCapsuleEnd0, out.points.data(), out.count);
  addIfBelow(plane, transformB.applyToPoint(Vec3(0.0f, capsule.halfHeight, 0.0f)) - down, margin,
             kCapsuleEnd1, out.points.data(), out.count);
  out.normal = plane.normal;
  return out.count > 0;
}

bool collidePlaneBox(const Shape& shapeA, const Transform& transformA, const Shape& shapeB,
                     const Transform& transformB, float margin, Manifold& out) {
  // The box's vertices below the surface; a box lying on a face has four, named by their corner,
  // so they keep their ids while the box wobbles.
  const Plane plane = worldPlane(shapeA.plane(), transformA);
  const Vec3 h = shapeB.box().halfExtents;
  // Early out: the box's lowest point is its centre minus its projected radius.
  const Vec3 localNormal = transformB.inverseApplyToDirection(plane.normal);
  const float projectedRadius = transformB.scale * glm::dot(h, glm::abs(localNormal));
  if (plane.signedDistance(transformB.position) - projectedRadius > margin) {
    out.count = 0;
    return false;
  }
  ContactPoint candidates[8];
  int count = 0;
  for (int corner = 0; corner < 8; ++corner) {
    const int dx = (corner & 1) ? 2 : 0, dy = (corner & 2) ? 2 : 0, dz = (corner & 4) ? 2 : 0;
    const Vec3 local(dx ? h.x : -h.x, dy ? h.y : -h.y, dz ? h.z : -h.z);
    addIfBelow(plane, transformB.applyToPoint(local), margin, boxFeature(dx, dy, dz), candidates, count);
  }
  return finish(plane, candidates, count, out);
}

bool collidePlanePolytope(const Shape& shapeA, const Transform& transformA, const Shape& shapeB,
                          const Transform& transformB, float margin, Manifold& out) {
  // Convex hull or k-DOP: every vertex below the surface, reduced to four; ids are vertex indices.
  const Plane plane = worldPlane(shapeA.plane(), transformA);
  const ConvexHull& hull = shapeB.type() == ShapeType::Kdop ? shapeB.kdop().polytope() : shapeB.convexHull();
  const ConvexSupport support = makeConvexSupport(shapeB, transformB);
  if (plane.signedDistance(support.supportCore(-plane.normal)) > margin) {
    out.count = 0;
    return false;
  }
  Array<ContactPoint> candidates(hull.vertices().size());
  int count = 0;
  for (std::size_t i = 0; i < hull.vertices().size(); ++i) {
    addIfBelow(plane, transformB.applyToPoint(hull.vertices()[i]), margin, static_cast<std::uint32_t>(i),
               candidates.data(), count);
  }
  return finish(plane, candidates.data(), count, out);
}

bool collidePlaneCylinder(const Shape& shapeA, const Transform& transformA, const Shape& shapeB,
                          const Transform& transformB, float margin, Manifold& out) {
  // A cylinder's deepest points lie on its two rims. Standing on a cap (axis within ~2.6 degrees of
  // the normal), that cap's rim gives four points at fixed angles (local ±x, ±z), whose ids then
  // survive small wobbles; otherwise each rim's lowest point (two when it lies on its side).
  const Plane plane = worldPlane(shapeA.plane(), transformA);
  const Cylinder& cylinder = shapeB.cylinder();
  const Vec3 localDown = transformB.inverseApplyToDirection(-plane.normal);
  const float radial = std::sqrt(localDown.x * localDown.x + localDown.z * localDown.z);
  ContactPoint candidates[8];
  int count = 0;
  if (std::abs(localDown.y) > 0.999f) {
    const float y = localDown.y > 0.0f ? cylinder.halfHeight : -cylinder.halfHeight;
    const std::uint32_t cap = localDown.y > 0.0f ? 1u : 0u;
    const float r = cylinder.radius;
    const Vec3 rim[4] = {{r, y, 0.0f}, {0.0f, y, r}, {-r, y, 0.0f}, {0.0f, y, -r}};
    for (std::uint32_t i = 0; i < 4; ++i) {
      addIfBelow(plane, transformB.applyToPoint(rim[i]), margin, cap * 8 + i, candidates, count);
    }
  } else {
    const Vec3 outward(cylinder.radius * localDown.x / radial, 0.0f, cylinder.radius * localDown.z / radial);
    addIfBelow(plane, transformB.applyToPoint(outward + Vec3(0.0f, -cylinder.halfHeight, 0.0f)), margin, 4,
               candidates, count);
    addIfBelow(plane, transformB.applyToPoint(outward + Vec3(0.0f, cylinder.halfHeight, 0.0f)), margin, 12,
               candidates, count);
  }
  return finish(plane, candidates, count, out);
}

bool collidePlaneConvex(const Shape& shapeA, const Transform& transformA, const Shape& shapeB,
                        const Transform& transformB, float margin, Manifold& out) {
  // Smooth shapes (ellipsoid) touch a plane at one point: the support in -normal.
  const Plane plane = worldPlane(shapeA.plane(), transformA);
  const ConvexSupport support = makeConvexSupport(shapeB, transformB);
  const Vec3 deepest = support.supportCore(-plane.normal) - support.radius * plane.normal;
  out.count = 0;
  addIfBelow(plane, deepest, margin, 0, out.points.data(), out.count);
  out.normal = plane.normal;
  return out.count > 0;
}

bool collidePlaneMesh(const Shape& shapeA, const Transform& transformA, const Shape& shapeB,
                      const Transform& transformB, float margin, Manifold& out) {
  // Every vertex of the mesh's triangles below the surface, reduced to four; ids are vertex indices.
  // Only the triangles' vertices: a mesh may hold vertices no triangle uses (OBJ files often do),
  // and those are not on its surface (one below a plane whose triangles are all above it would be a
  // phantom contact). Visited in index order, not triangle order: each vertex counts once, and the
  // candidates come in the same order whatever order the triangles are listed in.
  const Plane plane = worldPlane(shapeA.plane(), transformA);
  const TriangleMesh& mesh = shapeB.mesh();
  Array<std::uint8_t> onSurface(mesh.vertices().size(), 0);
  for (const MeshTriangle& triangle : mesh.triangles()) {
    for (const std::uint32_t v : triangle.v) onSurface[v] = 1;
  }
  Array<ContactPoint> candidates(mesh.vertices().size());
  int count = 0;
  for (std::size_t i = 0; i < mesh.vertices().size(); ++i) {
    if (!onSurface[i]) continue;
    addIfBelow(plane, transformB.applyToPoint(mesh.vertices()[i]), margin, static_cast<std::uint32_t>(i),
               candidates.data(), count);
  }
  return finish(plane, candidates.data(), count, out);
}

}  // namespace collide::detail
