// PLACEHOLDER: to be implemented (helper task). Replace every function body.
#include "shapes/shape_functions.h"

namespace collide::detail {

Aabb computeLocalBounds(const TriangleMesh&) { throw Error("mesh: not implemented"); }
Aabb computeWorldBounds(const TriangleMesh&, const Transform&) { throw Error("mesh: not implemented"); }
MassProperties computeMassProperties(const TriangleMesh&, float) { throw Error("mesh: not implemented"); }
bool localContains(const TriangleMesh&, const Vec3&) { throw Error("mesh: not implemented"); }
SurfacePoint localClosestPoint(const TriangleMesh&, const Vec3&) { throw Error("mesh: not implemented"); }
std::optional<RayHit> localRayCast(const TriangleMesh&, const Ray&) { throw Error("mesh: not implemented"); }

}  // namespace collide::detail
namespace collide {
TriangleMesh TriangleMesh::fromTriangles(std::vector<Vec3>, std::vector<MeshTriangle>) { throw Error("mesh: not implemented"); }
std::array<Vec3, 3> TriangleMesh::triangle(std::uint32_t) const { return {}; }
}
