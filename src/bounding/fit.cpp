// Every proxy fitted to one point set, with what it costs (lecture, slide 52: work to compute,
// memory, tightness): the table behind docs/bounding-volumes.md. Tightness is measured against the
// convex hull, the tightest convex proxy.
#include <collide/bounding.h>

#include "base/fail.h"
#include "bounding/obb_fit.h"
#include "bounding/point_set.h"

#include <algorithm>
#include <limits>
#include <memory>
#include <sstream>
#include <string>

namespace collide {

namespace {

std::size_t polytopeBytes(const ConvexHull& hull) {
  return hull.vertices().size() * sizeof(Vec3) + hull.halfEdges().size() * sizeof(ConvexHull::HalfEdge) +
         hull.faces().size() * sizeof(ConvexHull::Face);
}

}  // namespace

std::vector<ProxyFit> fitAllProxies(std::span<const Vec3> points) {
  const detail::ErrorScope scope;
  if (!bounding::requireFinitePoints("fit_all_proxies", points)) return {};
  const Aabb bounds = boundingBox(points);
  const Vec3 extent = bounds.max - bounds.min;
  const float widest = std::max({extent.x, extent.y, extent.z});
  if (!(widest <= kMaxFitExtent)) {
    std::ostringstream message;
    message << "fit_all_proxies: the points span " << widest
            << " m along an axis; proxies are fitted to sets up to " << kMaxFitExtent
            << " m across, whose volumes stay finite in float";
    COLLIDE_FAIL(message.str(), {});
  }
  auto hull = std::make_shared<const ConvexHull>(detail::withErrorContext(
      "fit_all_proxies: the proxies need points that span a volume (",
      [&] { return ConvexHull::fromPoints(points); }, ")"));
  COLLIDE_RETURN_IF_FAILED({});
  const float hullVolume = hull->volume();
  std::vector<ProxyFit> fits;
  // Memory counts what the proxy needs beyond the points' frame: a sphere its centre and radius, a
  // box its corners or its centre, rotation and half extents, a polytope its arrays.
  auto add = [&](std::string name, Shape shape, const Transform& transform, float volume, std::size_t bytes) {
    fits.push_back({std::move(name), std::move(shape), transform, volume, volume / hullVolume, bytes});
  };

  const BoundingSphere sphere = minimalBoundingSphere(points);
  add("sphere", Sphere{sphere.radius}, Transform{sphere.center, Quat(1, 0, 0, 0), 1.0f},
      4.0f / 3.0f * kPi * sphere.radius * sphere.radius * sphere.radius, sizeof(BoundingSphere));

  const Aabb box = boundingBox(points);
  add("aabb", Box{box.halfExtents()}, Transform{box.center(), Quat(1, 0, 0, 0), 1.0f}, box.volume(),
      sizeof(Aabb));

  const OrientedBox orientedBox = bounding::fitOrientedBoxOnHull(points, *hull);
  add("obb", orientedBox.box, orientedBox.transform, orientedBox.volume(),
      sizeof(Box) + sizeof(Vec3) + sizeof(Quat));

  FittedCapsule capsule = fitCapsule(points);
  // A Capsule shape needs a segment: a round cloud may fit with half height 0, so give it the
  // smallest positive one (enlarging the capsule, never shrinking it).
  capsule.capsule.halfHeight = std::max(capsule.capsule.halfHeight, std::numeric_limits<float>::min());
  add("capsule", capsule.capsule, capsule.transform, capsule.volume(),
      sizeof(Capsule) + sizeof(Vec3) + sizeof(Quat));

  for (int k : {6, 14, 18, 26}) {
    Kdop kdop = Kdop::fromPoints(k, points);
    COLLIDE_RETURN_IF_FAILED({});
    const float volume = kdop.polytope().volume();
    // The slabs are k floats; collide also keeps the polytope they enclose, for support mapping.
    const std::size_t bytes = std::size_t(k) * sizeof(float) + polytopeBytes(kdop.polytope());
    add(std::to_string(k) + "-dop", Shape(std::move(kdop)), Transform{}, volume, bytes);
  }

  add("convex_hull", Shape(hull), Transform{}, hullVolume, polytopeBytes(*hull));
  return fits;
}

std::vector<ProxyFit> fitAllProxies(const TriangleMesh& mesh) { return fitAllProxies(mesh.vertices()); }

}  // namespace collide
