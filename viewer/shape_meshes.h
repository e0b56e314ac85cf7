// Triangle meshes for drawing the proxies: one mesh per distinct shape, generated once and then
// placed by the body's transform every frame (the viewer never re-tessellates while stepping).
#pragma once

#include <collide/shapes.h>

#include <vector>

namespace collide::viewer {

struct MeshVertex {
  Vec3 position;
  Vec3 normal;
};

// Non-indexed triangles (three vertices each), counter-clockwise seen from outside, in the
// shape's local frame (before the body's scale).
struct DrawMesh {
  std::vector<MeshVertex> vertices;
};

// The tessellation of one convex or mesh proxy: sphere, capsule, box, cylinder, ellipsoid and
// hull as closed surfaces, a k-DOP as its polytope, a triangle mesh as its triangles, a plane as
// a square of `planeSize` metres centred on the point of the plane nearest the origin. A compound
// is not drawn as one mesh (its children are); it throws Error.
DrawMesh shapeMesh(const Shape& shape, float planeSize = 200.0f);

}  // namespace collide::viewer
