// PLACEHOLDER: to be implemented (helper task). Replace every function body.
#include "shapes/shape_functions.h"

namespace collide::detail {

Aabb computeLocalBounds(const ConvexHull&) { throw Error("convex_hull: not implemented"); }
Aabb computeWorldBounds(const ConvexHull&, const Transform&) { throw Error("convex_hull: not implemented"); }
MassProperties computeMassProperties(const ConvexHull&, float) { throw Error("convex_hull: not implemented"); }
bool localContains(const ConvexHull&, const Vec3&) { throw Error("convex_hull: not implemented"); }
SurfacePoint localClosestPoint(const ConvexHull&, const Vec3&) { throw Error("convex_hull: not implemented"); }
std::optional<RayHit> localRayCast(const ConvexHull&, const Ray&) { throw Error("convex_hull: not implemented"); }

}  // namespace collide::detail
namespace collide {
ConvexHull ConvexHull::fromPoints(std::span<const Vec3>) { throw Error("convex_hull: not implemented"); }
std::vector<Vec3> ConvexHull::faceVertices(std::uint32_t) const { return {}; }
Vec3 ConvexHull::support(const Vec3&) const { return {}; }
namespace detail { Vec3 computeSupport(const ConvexHull& s, const Vec3& d) { return s.support(d); } }
}
