// The geometric proxies (lecture, slide 51): sphere, capsule, half-space, box, k-DOP, ellipsoid,
// cylinder, convex hull, triangle mesh and compound. A Shape is one of them, in its own local frame;
// a Transform places it in the world. Every proxy can serve as a bounding volume or as a collider:
// the data type is the same, only the use differs (lecture, slide 50).
#pragma once

#include <collide/error.h>
#include <collide/math.h>

#include <array>
#include <memory>
#include <optional>
#include <span>
#include <string_view>
#include <variant>
#include <vector>

namespace collide {

enum class ShapeType : std::uint8_t {
  Sphere,
  Capsule,
  Plane,
  Box,
  Kdop,
  Ellipsoid,
  Cylinder,
  ConvexHull,
  Mesh,
  Compound,
};
inline constexpr int kShapeTypeCount = 10;

std::string_view toString(ShapeType type);

// ---- The simple proxies: a few numbers each, centred on the local origin. ----

struct Sphere {
  float radius = 0.5f;
};

// The points within `radius` of the segment from (0, -halfHeight, 0) to (0, +halfHeight, 0).
struct Capsule {
  float radius = 0.5f;
  float halfHeight = 0.5f;
};

// Plane (the half-space proxy) is declared in math.h: surface normal·x = distance, solid below.

// Axis-aligned in its local frame; oriented by its transform.
struct Box {
  Vec3 halfExtents{0.5f};
};

// Axes along local x, y and z.
struct Ellipsoid {
  Vec3 radii{0.5f};
};

// Axis along local y, from -halfHeight to +halfHeight.
struct Cylinder {
  float radius = 0.5f;
  float halfHeight = 0.5f;
};

// ---- Polyhedra. Built by validating factories; immutable afterwards, shared between bodies. ----

// A convex polyhedron with its topology kept for the separating-axis test and face clipping:
// faces are convex polygons (coplanar triangles merged) with outward planes, and every edge is a
// pair of twin half-edges, so that a face's neighbours and an edge's two faces are one step away
// (Gregorius, "The Separating Axis Test between Convex Polyhedra", GDC 2013).
class ConvexHull {
 public:
  struct HalfEdge {
    std::uint32_t origin;  // vertex index
    std::uint32_t twin;    // the same edge walked by the neighbouring face
    std::uint32_t next;    // next half-edge around this face, counter-clockwise seen from outside
    std::uint32_t face;
  };
  struct Face {
    Plane plane;              // outward unit normal
    std::uint32_t firstEdge;  // any half-edge of the face
    std::uint32_t edgeCount;
    std::uint32_t firstVertex;  // the origin of firstEdge: a vertex on the face without the link
  };
  // An edge once (its smaller half-edge), with its end points and its two faces: what the
  // separating-axis test walks, without skipping twins or following links.
  struct Edge {
    std::uint32_t halfEdge;
    std::uint32_t origin, end;   // vertex indices, along the half-edge
    std::uint32_t face1, face2;  // the half-edge's face, its twin's
  };

  // The convex hull of `points` (through Qhull). Throws Error for fewer than 4 points, non-finite
  // coordinates, or points that are all (nearly) coplanar.
  static ConvexHull fromPoints(std::span<const Vec3> points);

  // Without exceptions, what a failed fromPoints returns (collide/error.h).
  bool isEmpty() const { return vertices_.empty(); }
  std::span<const Vec3> vertices() const { return vertices_; }
  std::span<const HalfEdge> halfEdges() const { return halfEdges_; }
  std::span<const Face> faces() const { return faces_; }
  std::size_t edgeCount() const { return halfEdges_.size() / 2; }
  // Every edge once, in the order of their half-edges.
  std::span<const Edge> edges() const { return edges_; }
  // The vertices of a face, counter-clockwise seen from outside.
  std::vector<Vec3> faceVertices(std::uint32_t face) const;
  // The faces around a vertex, in increasing order: one short array to read where walking the
  // half-edges would chase links or scan them all.
  std::span<const std::uint32_t> facesAround(std::uint32_t vertex) const {
    const std::uint32_t* table = vertexFaces_.data();
    return {table + table[vertex], table + table[vertex + 1]};
  }
  // The table behind facesAround, whole: one array, for the caller that prefetches it.
  std::span<const std::uint32_t> vertexFaceTable() const { return vertexFaces_; }

  Vec3 support(const Vec3& direction) const;
  float volume() const { return volume_; }
  Vec3 centroid() const { return centroid_; }
  // Inertia tensor per unit density about the centroid.
  const Mat3& unitInertia() const { return unitInertia_; }
  Aabb bounds() const { return bounds_; }
  // Different for every hull built and shared by its copies: what a cache of placed hulls keys on
  // with the address, since a hull freed and another built in its place may share the address.
  std::uint64_t serial() const { return serial_; }

 private:
  friend class HullBuilder;
  Array<Vec3> vertices_;
  // The vertices again as blocks of x, y and z coordinates, for support() (geometry/support_scan.h).
  Array<float> blockedVertices_;
  Array<HalfEdge> halfEdges_;
  Array<Edge> edges_;
  Array<Face> faces_;
  // facesAround: the vertex count + 1 offsets into this same array, then each vertex's faces; the
  // faces of vertex v are at [vertexFaces_[v], vertexFaces_[v + 1]).
  Array<std::uint32_t> vertexFaces_;
  float volume_ = 0.0f;
  Vec3 centroid_{0.0f};
  Mat3 unitInertia_{0.0f};
  Aabb bounds_;
  std::uint64_t serial_ = 0;
};

// A discrete oriented polytope (k-DOP): the intersection of k/2 slabs along fixed axes. k = 6 is an
// AABB; 14 adds the 4 cube diagonals; 18 adds the 6 edge diagonals of the cube to the 3 axes; 26
// has all 13. Kept both as slabs (exact ray and point tests) and as the polyhedron they enclose
// (support, mass properties).
class Kdop {
 public:
  // The tightest k-DOP around the points. Throws Error for an unsupported k, fewer than 4 points,
  // non-finite coordinates, or a flat point set.
  static Kdop fromPoints(int k, std::span<const Vec3> points);
  // A k-DOP from its slab extents: min[i] < max[i] along axes(k)[i]. Throws Error on empty slabs.
  static Kdop fromSlabs(int k, std::span<const float> slabMin, std::span<const float> slabMax);

  // The unit axes of a k-DOP: k/2 of them.
  static std::span<const Vec3> axes(int k);

  // Without exceptions, what a failed fromPoints or fromSlabs returns (collide/error.h).
  bool isEmpty() const { return !polytope_; }
  int k() const { return k_; }
  int axisCount() const { return k_ / 2; }
  float slabMin(int axis) const { return min_[axis]; }
  float slabMax(int axis) const { return max_[axis]; }
  const ConvexHull& polytope() const { return *polytope_; }

 private:
  int k_ = 6;
  std::array<float, 13> min_{};
  std::array<float, 13> max_{};
  std::shared_ptr<const ConvexHull> polytope_;
};

struct MeshTriangle {
  std::array<std::uint32_t, 3> v;  // counter-clockwise seen from the front (outside)
};

// A triangle mesh with its own bounding volume hierarchy (an AABB tree over the triangles).
// Meshes are surfaces: they collide on both sides (each triangle is seen from the side the other
// shape is on). A closed, consistently oriented mesh also has an inside (point containment, volume,
// mass).
class TriangleMesh {
 public:
  struct BvhNode {
    Aabb bounds;
    // Leaf: count > 0 triangles from firstTriangle in triangleOrder(). Inner: count == 0,
    // children at index+1 and `secondChild`.
    std::uint32_t firstTriangleOrSecondChild;
    std::uint32_t count;
  };

  // Throws Error for no triangles, non-finite vertices, indices out of range, or triangles with
  // (nearly) zero area.
  static TriangleMesh fromTriangles(std::vector<Vec3> vertices, std::vector<MeshTriangle> triangles);

  // Without exceptions, what a failed fromTriangles returns (collide/error.h).
  bool isEmpty() const { return triangles_.empty(); }
  std::span<const Vec3> vertices() const { return vertices_; }
  std::span<const MeshTriangle> triangles() const { return triangles_; }
  std::span<const BvhNode> bvh() const { return nodes_; }
  std::span<const std::uint32_t> triangleOrder() const { return triangleOrder_; }
  std::array<Vec3, 3> triangle(std::uint32_t index) const;
  // Every edge shared by exactly two triangles with opposite orientation: a watertight surface.
  bool isClosed() const { return closed_; }
  Aabb bounds() const { return nodes_.front().bounds; }
  // Signed volume, centroid and unit-density inertia about the centroid, from the divergence
  // theorem over the surface; only meaningful for a closed mesh.
  float volume() const { return volume_; }
  Vec3 centroid() const { return centroid_; }
  const Mat3& unitInertia() const { return unitInertia_; }

  // Calls visit(triangleIndex) for every triangle whose box overlaps `box` (local frame).
  template <class Visitor>
  void forEachTriangleOverlapping(const Aabb& box, Visitor&& visit) const;

  // Adjacency, for the narrow phase's internal-edge handling. How the surface continues across
  // edge k (from v[k] to v[k+1]) of a triangle, seen from the triangle's front: no single
  // neighbour (an outline, or an edge of three and more triangles), bending away from the front
  // (convex), coplanar within 0.1° (flat), or bending towards it (concave).
  enum class EdgeKind : std::uint8_t { Boundary, Convex, Flat, Concave };
  EdgeKind edgeKind(std::uint32_t triangle, int edge) const { return edgeKinds_[3 * triangle + edge]; }
  // The cosine of the angle between the normals of the two triangles at edge k (oriented alike), -1
  // on the outline: the normals the surface has along that edge lie between the two faces'.
  float edgeBendCosine(std::uint32_t triangle, int edge) const { return bendCosines_[3 * triangle + edge]; }
  // A vertex inside a flat patch: every edge at it is flat.
  bool isFlatVertex(std::uint32_t vertex) const { return flatVertices_[vertex] != 0; }
  // Triangles joined by flat edges share a patch number.
  std::uint32_t flatPatch(std::uint32_t triangle) const { return patches_[triangle]; }

 private:
  Array<Vec3> vertices_;
  Array<MeshTriangle> triangles_;
  Array<BvhNode> nodes_;
  Array<std::uint32_t> triangleOrder_;
  Array<EdgeKind> edgeKinds_;
  Array<float> bendCosines_;
  Array<std::uint8_t> flatVertices_;
  Array<std::uint32_t> patches_;
  bool closed_ = false;
  float volume_ = 0.0f;
  Vec3 centroid_{0.0f};
  Mat3 unitInertia_{0.0f};
};

class Shape;

// Child shapes with local transforms. A child is any shape but a plane.
class Compound {
 public:
  struct Child;
  // Throws Error for no children, a plane child, or an invalid child transform.
  static Compound fromChildren(std::vector<Child> children);

  std::span<const Child> children() const;
  // Without exceptions, what a failed fromChildren returns (collide/error.h).
  bool isEmpty() const { return children_.empty(); }
  Aabb bounds() const { return bounds_; }

 private:
  Array<Child> children_;
  Aabb bounds_;
};

// ---- Shape: one proxy of any type. A small value; polyhedra are shared, immutable. ----

namespace detail {
bool validateShape(const Shape& shape);
}  // namespace detail

class Shape {
 public:
  // Each constructor validates and reports Error naming the bad field (collide/error.h).
  Shape(const Sphere& sphere);
  Shape(const Capsule& capsule);
  Shape(const Plane& plane);
  Shape(const Box& box);
  Shape(const Ellipsoid& ellipsoid);
  Shape(const Cylinder& cylinder);
  Shape(Kdop kdop);
  Shape(ConvexHull hull);
  Shape(TriangleMesh mesh);
  Shape(Compound compound);
  Shape(std::shared_ptr<const ConvexHull> hull);
  Shape(std::shared_ptr<const TriangleMesh> mesh);

  ShapeType type() const { return static_cast<ShapeType>(data_.index()); }
  // Sphere, capsule, box, k-DOP, ellipsoid, cylinder and hull have a support function.
  bool isConvex() const;

  const Sphere& sphere() const { return std::get<Sphere>(data_); }
  const Capsule& capsule() const { return std::get<Capsule>(data_); }
  const Plane& plane() const { return std::get<Plane>(data_); }
  const Box& box() const { return std::get<Box>(data_); }
  const Kdop& kdop() const { return *std::get<std::shared_ptr<const Kdop>>(data_); }
  const Ellipsoid& ellipsoid() const { return std::get<Ellipsoid>(data_); }
  const Cylinder& cylinder() const { return std::get<Cylinder>(data_); }
  const ConvexHull& convexHull() const { return *std::get<std::shared_ptr<const ConvexHull>>(data_); }
  const TriangleMesh& mesh() const { return *std::get<std::shared_ptr<const TriangleMesh>>(data_); }
  const Compound& compound() const { return *std::get<std::shared_ptr<const Compound>>(data_); }

  // Calls f with the concrete shape (const Sphere&, …, const ConvexHull&, …).
  template <class F>
  decltype(auto) visit(F&& f) const;

 private:
  friend bool detail::validateShape(const Shape& shape);
  // The alternatives' order is ShapeType's order.
  std::variant<Sphere, Capsule, Plane, Box, std::shared_ptr<const Kdop>, Ellipsoid, Cylinder,
               std::shared_ptr<const ConvexHull>, std::shared_ptr<const TriangleMesh>,
               std::shared_ptr<const Compound>>
      data_;
};

struct Compound::Child {
  Shape shape;
  Transform transform;
};

// ---- What every proxy answers. Local queries take the shape's own frame; the others a transform. ----

// The tightest box around the shape in its local frame. A plane's box is infinite (±1e30).
Aabb localBounds(const Shape& shape);
// The box around the shape placed by `transform`: exact for every convex primitive and hull,
// conservative (the transformed local box) for meshes; the union of children for compounds.
Aabb worldBounds(const Shape& shape, const Transform& transform);
// A sphere around the shape in its local frame (not necessarily the minimal one; see bounding.h).
BoundingSphere localBoundingSphere(const Shape& shape);

// The farthest point of a convex shape in `direction` (local frame, need not be unit). Throws
// Error for plane, mesh and compound, which have no support function.
Vec3 support(const Shape& shape, const Vec3& direction);

// Mass properties assuming uniform density (lecture, slide 49: barycenter and moment of inertia).
struct MassProperties {
  float mass = 0.0f;
  float volume = 0.0f;
  Vec3 centerOfMass{0.0f};  // local frame
  Mat3 inertia{0.0f};       // about the centre of mass, in the local frame axes
};
// Throws Error for a plane (infinite), an open mesh, density <= 0 or a scale <= 0.
MassProperties massProperties(const Shape& shape, float density, float scale = 1.0f);

// Point tests. Meshes have an inside only when closed; an open mesh contains no point.
bool containsPoint(const Shape& shape, const Transform& transform, const Vec3& point);

struct SurfacePoint {
  Vec3 point{0.0f};             // the nearest point on the shape's surface
  Vec3 normal{0.0f};            // outward unit surface normal there
  float signedDistance = 0.0f;  // negative when the query point is inside
};
// The nearest surface point to `point`, world frame.
SurfacePoint closestPoint(const Shape& shape, const Transform& transform, const Vec3& point);

// The first hit of a ray with the shape, world frame. A ray starting inside a solid shape hits at
// distance 0 with normal = -direction. A hit farther than float's range is none. Throws Error for a
// non-finite ray or a non-unit direction.
std::optional<RayHit> rayCast(const Shape& shape, const Transform& transform, const Ray& ray);

}  // namespace collide

#include <collide/detail/shapes_inl.h>
