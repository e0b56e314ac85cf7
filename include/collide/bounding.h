// Fitting bounding volumes to a point set (lecture, slide 52: "choosing geometric proxies: things to
// consider": the work to compute a proxy, the memory it takes, how tightly it encloses the object
// and how cheap its tests are). Every fitter is world-free: it takes points in one frame and returns
// a proxy in that frame. All of them validate their input and throw collide::Error naming the problem
// (no points, a non-finite point, or a flat set where a solid is needed). docs/bounding-volumes.md
// compares the proxies.
#pragma once

#include <collide/error.h>
#include <collide/math.h>
#include <collide/shapes.h>

#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace collide {

// The exact smallest sphere containing every point (Welzl 1991, move-to-front variant), computed in
// double precision. Works for any non-empty finite set: one point gives radius 0, two points their
// diametral sphere, collinear and coplanar sets their smallest circle's sphere. The stored radius is
// rounded up so that every input point is inside in double precision.
BoundingSphere minimalBoundingSphere(std::span<const Vec3> points);

// The smallest axis-aligned box containing every point (min and max per axis). Any non-empty finite
// set; flat sets give a box of zero thickness.
Aabb boundingBox(std::span<const Vec3> points);

// An oriented box: a Box shape placed by a rotation and translation (scale 1).
struct OrientedBox {
  Box box;
  Transform transform;

  float volume() const { return 8.0f * box.halfExtents.x * box.halfExtents.y * box.halfExtents.z; }
};

// A tight oriented bounding box: over the candidate directions (every face normal of the convex hull,
// the three principal axes of the points and the three coordinate axes) the smallest volume of
// [minimum-area rectangle of the hull projected on the plane] x [extent along the direction]. The
// rectangle comes from rotating calipers (Freeman & Shapira 1975: one side is collinear with an edge
// of the 2D hull; Toussaint 1983). Not O'Rourke's exact O(n^3) minimum, but never larger than the
// AABB (the coordinate axes are candidates) and exact when the optimum has a face on a hull face.
// Throws Error unless the points span a volume (at least 4, not collinear or coplanar).
OrientedBox fitOrientedBox(std::span<const Vec3> points);

// A capsule placed by a rotation (local y onto the fitted axis) and a translation (scale 1).
struct FittedCapsule {
  Capsule capsule;
  Transform transform;

  float volume() const {
    const float r = capsule.radius;
    return kPi * r * r * (2.0f * capsule.halfHeight + 4.0f / 3.0f * r);
  }
};

// A capsule around the points: the axis direction is the principal axis of largest variance (PCA of
// the covariance matrix), the axis line passes through the centre of the smallest circle around the
// points projected across the axis, the radius is that circle's radius, and the segment is the
// shortest one whose end hemispheres still contain every point. Any non-empty finite set: a single
// point gives radius 0 and half height 0, collinear points radius 0 (a Capsule shape needs both > 0;
// fitAllProxies takes care of that).
FittedCapsule fitCapsule(std::span<const Vec3> points);

// One fitted proxy and what it costs (lecture, slide 52).
struct ProxyFit {
  std::string
      name;     // "sphere", "aabb", "obb", "capsule", "6-dop", "14-dop", "18-dop", "26-dop", "convex_hull"
  Shape shape;  // in the proxy's own frame
  Transform transform;  // places the shape in the points' frame
  float volume = 0.0f;
  float tightness = 1.0f;  // volume / convex hull volume: >= 1, the hull itself is 1
  std::size_t bytes = 0;   // memory to store the proxy: its numbers, or the arrays of a polytope
};

// Fits every proxy above, plus the 6-, 14-, 18- and 26-DOP and the convex hull, in that order:
// sphere, aabb, obb, capsule, 6-dop, 14-dop, 18-dop, 26-dop, convex_hull. Throws Error unless the
// points span a volume, and for points farther apart than kMaxFitExtent along an axis (the proxies'
// volumes, and the queries around them, would overflow float).
inline constexpr float kMaxFitExtent = 1e12f;
std::vector<ProxyFit> fitAllProxies(std::span<const Vec3> points);
// The same for the vertices of a mesh.
std::vector<ProxyFit> fitAllProxies(const TriangleMesh& mesh);

}  // namespace collide
