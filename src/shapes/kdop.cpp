// PLACEHOLDER: to be implemented (helper task). Replace every function body.
#include "shapes/shape_functions.h"

namespace collide::detail {

Aabb computeLocalBounds(const Kdop&) { throw Error("kdop: not implemented"); }
Aabb computeWorldBounds(const Kdop&, const Transform&) { throw Error("kdop: not implemented"); }
MassProperties computeMassProperties(const Kdop&, float) { throw Error("kdop: not implemented"); }
bool localContains(const Kdop&, const Vec3&) { throw Error("kdop: not implemented"); }
SurfacePoint localClosestPoint(const Kdop&, const Vec3&) { throw Error("kdop: not implemented"); }
std::optional<RayHit> localRayCast(const Kdop&, const Ray&) { throw Error("kdop: not implemented"); }

}  // namespace collide::detail
namespace collide {
Kdop Kdop::fromPoints(int, std::span<const Vec3>) { throw Error("kdop: not implemented"); }
Kdop Kdop::fromSlabs(int, std::span<const float>, std::span<const float>) { throw Error("kdop: not implemented"); }
std::span<const Vec3> Kdop::axes(int) { return {}; }
namespace detail { Vec3 computeSupport(const Kdop&, const Vec3&) { return {}; } }
}
