// PLACEHOLDER: to be implemented (helper task). Replace every function body.
#include "shapes/shape_functions.h"

namespace collide::detail {

Aabb computeLocalBounds(const Compound&) { throw Error("compound: not implemented"); }
Aabb computeWorldBounds(const Compound&, const Transform&) { throw Error("compound: not implemented"); }
MassProperties computeMassProperties(const Compound&, float) { throw Error("compound: not implemented"); }
bool localContains(const Compound&, const Vec3&) { throw Error("compound: not implemented"); }
SurfacePoint localClosestPoint(const Compound&, const Vec3&) { throw Error("compound: not implemented"); }
std::optional<RayHit> localRayCast(const Compound&, const Ray&) { throw Error("compound: not implemented"); }

}  // namespace collide::detail
namespace collide {
Compound Compound::fromChildren(std::vector<Child>) { throw Error("compound: not implemented"); }
}
