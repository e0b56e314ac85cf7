// The per-proxy functions behind the Shape queries of shapes.h, one overload set per concept.
// Every function works in the shape's local frame at scale 1; shape.cpp maps world queries to
// local ones (inverse transform, divide by scale) and the answers back.
#pragma once

#include <collide/shapes.h>

#include "base/fail.h"

#include <optional>

namespace collide::detail {

// Whether a shape handed to a free function may be used. With exceptions every Shape is: its
// constructor threw instead. Without them a Shape can carry a bad value or a failed factory's empty
// polyhedron (collide/error.h): it is reported (again) and refused.
inline bool usableShape(const Shape& shape) {
#if COLLIDE_EXCEPTIONS
  static_cast<void>(shape);
  return true;
#else
  return validateShape(shape);
#endif
}

// Bounds in the local frame.
Aabb computeLocalBounds(const Sphere& s);
Aabb computeLocalBounds(const Capsule& s);
Aabb computeLocalBounds(const Plane& s);
Aabb computeLocalBounds(const Box& s);
Aabb computeLocalBounds(const Kdop& s);
Aabb computeLocalBounds(const Ellipsoid& s);
Aabb computeLocalBounds(const Cylinder& s);
Aabb computeLocalBounds(const ConvexHull& s);
Aabb computeLocalBounds(const TriangleMesh& s);
Aabb computeLocalBounds(const Compound& s);

// Bounds in the world frame: as tight as each shape allows cheaply (see shapes.h).
Aabb computeWorldBounds(const Sphere& s, const Transform& t);
Aabb computeWorldBounds(const Capsule& s, const Transform& t);
Aabb computeWorldBounds(const Plane& s, const Transform& t);
Aabb computeWorldBounds(const Box& s, const Transform& t);
Aabb computeWorldBounds(const Kdop& s, const Transform& t);
Aabb computeWorldBounds(const Ellipsoid& s, const Transform& t);
Aabb computeWorldBounds(const Cylinder& s, const Transform& t);
Aabb computeWorldBounds(const ConvexHull& s, const Transform& t);
Aabb computeWorldBounds(const TriangleMesh& s, const Transform& t);
Aabb computeWorldBounds(const Compound& s, const Transform& t);

// Asks the memory system for what placing the shape in the world reads, without waiting for it: in
// a scene of thousands of distinct hulls their data is out of cache, and a placement that waits for
// each line in turn spends most of its time waiting. Two stages, since a polyhedron's arrays are
// found through the polyhedron: first the polyhedron itself (prefetchShapeHeader), then, some work
// later, once it has arrived, its vertices, faces, vertex-to-faces table and edges
// (prefetchShapeArrays): what a placement, the separating-axis test and an incident face read.
// Nothing for the other shapes.
void prefetchShapeHeader(const Shape& shape);
void prefetchShapeArrays(const Shape& shape);

// Support mapping of the convex proxies (direction need not be unit, must be non-zero).
Vec3 computeSupport(const Sphere& s, const Vec3& direction);
Vec3 computeSupport(const Capsule& s, const Vec3& direction);
Vec3 computeSupport(const Box& s, const Vec3& direction);
Vec3 computeSupport(const Kdop& s, const Vec3& direction);
Vec3 computeSupport(const Ellipsoid& s, const Vec3& direction);
Vec3 computeSupport(const Cylinder& s, const Vec3& direction);
Vec3 computeSupport(const ConvexHull& s, const Vec3& direction);

// Mass properties at unit scale for the given density.
MassProperties computeMassProperties(const Sphere& s, float density);
MassProperties computeMassProperties(const Capsule& s, float density);
MassProperties computeMassProperties(const Box& s, float density);
MassProperties computeMassProperties(const Kdop& s, float density);
MassProperties computeMassProperties(const Ellipsoid& s, float density);
MassProperties computeMassProperties(const Cylinder& s, float density);
MassProperties computeMassProperties(const ConvexHull& s, float density);
MassProperties computeMassProperties(const TriangleMesh& s, float density);
MassProperties computeMassProperties(const Compound& s, float density);

bool localContains(const Sphere& s, const Vec3& p);
bool localContains(const Capsule& s, const Vec3& p);
bool localContains(const Plane& s, const Vec3& p);
bool localContains(const Box& s, const Vec3& p);
bool localContains(const Kdop& s, const Vec3& p);
bool localContains(const Ellipsoid& s, const Vec3& p);
bool localContains(const Cylinder& s, const Vec3& p);
bool localContains(const ConvexHull& s, const Vec3& p);
bool localContains(const TriangleMesh& s, const Vec3& p);
bool localContains(const Compound& s, const Vec3& p);

SurfacePoint localClosestPoint(const Sphere& s, const Vec3& p);
SurfacePoint localClosestPoint(const Capsule& s, const Vec3& p);
SurfacePoint localClosestPoint(const Plane& s, const Vec3& p);
SurfacePoint localClosestPoint(const Box& s, const Vec3& p);
SurfacePoint localClosestPoint(const Kdop& s, const Vec3& p);
SurfacePoint localClosestPoint(const Ellipsoid& s, const Vec3& p);
SurfacePoint localClosestPoint(const Cylinder& s, const Vec3& p);
SurfacePoint localClosestPoint(const ConvexHull& s, const Vec3& p);
SurfacePoint localClosestPoint(const TriangleMesh& s, const Vec3& p);
SurfacePoint localClosestPoint(const Compound& s, const Vec3& p);

// Rays in the local frame: unit direction, maxDistance in local units. A ray starting inside a
// solid hits at distance 0 with normal -direction.
std::optional<RayHit> localRayCast(const Sphere& s, const Ray& ray);
std::optional<RayHit> localRayCast(const Capsule& s, const Ray& ray);
std::optional<RayHit> localRayCast(const Plane& s, const Ray& ray);
std::optional<RayHit> localRayCast(const Box& s, const Ray& ray);
std::optional<RayHit> localRayCast(const Kdop& s, const Ray& ray);
std::optional<RayHit> localRayCast(const Ellipsoid& s, const Ray& ray);
std::optional<RayHit> localRayCast(const Cylinder& s, const Ray& ray);
std::optional<RayHit> localRayCast(const ConvexHull& s, const Ray& ray);
std::optional<RayHit> localRayCast(const TriangleMesh& s, const Ray& ray);
std::optional<RayHit> localRayCast(const Compound& s, const Ray& ray);

// Mass properties helpers shared by the shapes.
// Moves an inertia tensor about the centre of mass to one about `offset` from it (parallel axis).
Mat3 shiftInertia(const Mat3& inertiaAtCom, float mass, const Vec3& offset);
// Accumulates the volume, centroid and unit-density inertia (about the origin) of a closed,
// outward-oriented triangle surface (Mirtich 1996 / Eberly, "Polyhedral Mass Properties").
struct PolyhedronIntegrals {
  double volume = 0.0;
  double firstMoment[3] = {0, 0, 0};
  double secondMoment[6] = {0, 0, 0, 0, 0, 0};  // xx, yy, zz, xy, yz, zx
  void addTriangle(const Vec3& a, const Vec3& b, const Vec3& c);
  // Volume, centroid and inertia about the centroid for unit density.
  void finish(float& outVolume, Vec3& outCentroid, Mat3& outUnitInertia) const;
};

}  // namespace collide::detail
