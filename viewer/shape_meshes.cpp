#include "shape_meshes.h"

#include <collide/error.h>

#include <cmath>
#include <numbers>

namespace collide::viewer {
namespace {

constexpr int kSlices = 32;  // around the axis
constexpr int kStacks = 16;  // pole to pole

void addTriangle(DrawMesh& mesh, const MeshVertex& a, const MeshVertex& b, const MeshVertex& c) {
  mesh.vertices.push_back(a);
  mesh.vertices.push_back(b);
  mesh.vertices.push_back(c);
}

// A flat-shaded triangle: the normal from its winding.
void addFlatTriangle(DrawMesh& mesh, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 cross = glm::cross(b - a, c - a);
  const float length = glm::length(cross);
  const Vec3 normal = length > 0.0f ? cross / length : Vec3(0.0f, 1.0f, 0.0f);
  addTriangle(mesh, {a, normal}, {b, normal}, {c, normal});
}

// The unit direction at latitude index `stack` (0 = north pole) and longitude index `slice`.
Vec3 sphereDirection(int stack, int slice) {
  const float theta = std::numbers::pi_v<float> * float(stack) / float(kStacks);
  const float phi = 2.0f * std::numbers::pi_v<float> * float(slice) / float(kSlices);
  return {std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi)};
}

// A quad strip between two rings of vertices, counter-clockwise seen from outside when `upper`
// lies above `lower` on a surface around +y.
void addBand(DrawMesh& mesh, const std::vector<MeshVertex>& upper, const std::vector<MeshVertex>& lower) {
  for (int i = 0; i < kSlices; ++i) {
    const int j = (i + 1) % kSlices;
    addTriangle(mesh, upper[i], lower[i], lower[j]);
    addTriangle(mesh, upper[i], lower[j], upper[j]);
  }
}

// Sphere-like surfaces: a ring of points per latitude. `point(direction, stack)` places the
// vertex; `normal(direction)` gives its normal. A capsule splits its equator into two rings.
template <class PointFn, class NormalFn>
DrawMesh latitudeSurface(PointFn point, NormalFn normal, bool splitEquator) {
  std::vector<std::vector<MeshVertex>> rings;
  for (int stack = 0; stack <= kStacks; ++stack) {
    const int copies = splitEquator && stack == kStacks / 2 ? 2 : 1;
    for (int copy = 0; copy < copies; ++copy) {
      std::vector<MeshVertex> ring;
      for (int slice = 0; slice < kSlices; ++slice) {
        const Vec3 d = sphereDirection(stack, slice);
        // The first copy of a split equator belongs to the upper half.
        const bool upperHalf = stack < kStacks / 2 || (stack == kStacks / 2 && copy == 0 && copies == 2);
        ring.push_back({point(d, upperHalf), normal(d)});
      }
      rings.push_back(std::move(ring));
    }
  }
  DrawMesh mesh;
  for (std::size_t r = 0; r + 1 < rings.size(); ++r) addBand(mesh, rings[r], rings[r + 1]);
  return mesh;
}

DrawMesh sphereMesh(const Vec3& radii) {
  return latitudeSurface([&](const Vec3& d, bool) { return d * radii; },
                         // The ellipsoid's normal is the gradient of sum (x_i / r_i)^2.
                         [&](const Vec3& d) { return glm::normalize(d / radii); }, false);
}

DrawMesh capsuleMesh(const Capsule& capsule) {
  return latitudeSurface(
      [&](const Vec3& d, bool upper) {
        return d * capsule.radius + Vec3(0.0f, upper ? capsule.halfHeight : -capsule.halfHeight, 0.0f);
      },
      [](const Vec3& d) { return d; }, true);
}

DrawMesh cylinderMesh(const Cylinder& cylinder) {
  DrawMesh mesh;
  std::vector<MeshVertex> top, bottom;
  for (int slice = 0; slice < kSlices; ++slice) {
    const Vec3 d = sphereDirection(kStacks / 2, slice);
    top.push_back({d * cylinder.radius + Vec3(0.0f, cylinder.halfHeight, 0.0f), d});
    bottom.push_back({d * cylinder.radius - Vec3(0.0f, cylinder.halfHeight, 0.0f), d});
  }
  addBand(mesh, top, bottom);
  const Vec3 up(0.0f, 1.0f, 0.0f);
  for (int i = 0; i < kSlices; ++i) {
    const int j = (i + 1) % kSlices;
    addTriangle(mesh, {Vec3(0.0f, cylinder.halfHeight, 0.0f), up}, {top[i].position, up},
                {top[j].position, up});
    addTriangle(mesh, {Vec3(0.0f, -cylinder.halfHeight, 0.0f), -up}, {bottom[j].position, -up},
                {bottom[i].position, -up});
  }
  return mesh;
}

DrawMesh boxMesh(const Box& box) {
  DrawMesh mesh;
  const Vec3 h = box.halfExtents;
  // Each face: its outward axis and two in-plane axes whose cross product is that axis.
  for (int axis = 0; axis < 3; ++axis) {
    for (float sign : {1.0f, -1.0f}) {
      Vec3 n(0.0f), u(0.0f), v(0.0f);
      n[axis] = sign;
      u[(axis + 1) % 3] = 1.0f;
      v[(axis + 2) % 3] = sign;
      const Vec3 c = n * h, du = u * h, dv = v * h;
      const Vec3 p0 = c - du - dv, p1 = c + du - dv, p2 = c + du + dv, p3 = c - du + dv;
      addTriangle(mesh, {p0, n}, {p1, n}, {p2, n});
      addTriangle(mesh, {p0, n}, {p2, n}, {p3, n});
    }
  }
  return mesh;
}

DrawMesh hullMesh(const ConvexHull& hull) {
  DrawMesh mesh;
  for (std::uint32_t face = 0; face < hull.faces().size(); ++face) {
    const std::vector<Vec3> polygon = hull.faceVertices(face);
    const Vec3 n = hull.faces()[face].plane.normal;
    for (std::size_t i = 1; i + 1 < polygon.size(); ++i) {
      addTriangle(mesh, {polygon[0], n}, {polygon[i], n}, {polygon[i + 1], n});
    }
  }
  return mesh;
}

DrawMesh triangleMesh(const TriangleMesh& triangles) {
  DrawMesh mesh;
  for (std::uint32_t t = 0; t < triangles.triangles().size(); ++t) {
    const std::array<Vec3, 3> corners = triangles.triangle(t);
    addFlatTriangle(mesh, corners[0], corners[1], corners[2]);
  }
  return mesh;
}

DrawMesh planeMesh(const Plane& plane, float size) {
  // Two in-plane axes from the normal (Frisvad-style choice of a helper axis far from it).
  const Vec3 n = plane.normal;
  const Vec3 helper = std::abs(n.y) < 0.9f ? Vec3(0.0f, 1.0f, 0.0f) : Vec3(1.0f, 0.0f, 0.0f);
  const Vec3 u = glm::normalize(glm::cross(helper, n)) * (0.5f * size);
  const Vec3 v = glm::cross(n, u);
  const Vec3 c = n * plane.distance;
  DrawMesh mesh;
  const Vec3 p0 = c - u - v, p1 = c + u - v, p2 = c + u + v, p3 = c - u + v;
  // u x v points along n, so p0 p1 p2 is counter-clockwise seen from the front.
  addTriangle(mesh, {p0, n}, {p1, n}, {p2, n});
  addTriangle(mesh, {p0, n}, {p2, n}, {p3, n});
  return mesh;
}

}  // namespace

DrawMesh shapeMesh(const Shape& shape, float planeSize) {
  switch (shape.type()) {
    case ShapeType::Sphere:
      return sphereMesh(Vec3(shape.sphere().radius));
    case ShapeType::Ellipsoid:
      return sphereMesh(shape.ellipsoid().radii);
    case ShapeType::Capsule:
      return capsuleMesh(shape.capsule());
    case ShapeType::Cylinder:
      return cylinderMesh(shape.cylinder());
    case ShapeType::Box:
      return boxMesh(shape.box());
    case ShapeType::ConvexHull:
      return hullMesh(shape.convexHull());
    case ShapeType::Kdop:
      return hullMesh(shape.kdop().polytope());
    case ShapeType::Mesh:
      return triangleMesh(shape.mesh());
    case ShapeType::Plane:
      return planeMesh(shape.plane(), planeSize);
    case ShapeType::Compound:
      break;
  }
  throw Error("shapeMesh: a compound has no single mesh; draw its children");
}

}  // namespace collide::viewer
