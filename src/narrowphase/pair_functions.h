// The collide functions of the pair table (dispatch.cpp), one per specialised pair, and the small
// tools they share. Every function has the same signature: it fills `out` (normal from A to B, up to
// four points) for contacts whose separation is at most `margin`, and returns out.count > 0.
// Transforms are already validated. A function for (X, Y) serves (Y, X) through the mirroring
// wrapper of dispatch.cpp, so each pair is written once.
#pragma once

#include <collide/narrowphase.h>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace collide::detail {

using CollideFunction = bool (*)(const Shape& shapeA, const Transform& transformA, const Shape& shapeB,
                                 const Transform& transformB, float margin, Manifold& out);
using OverlapFunction = bool (*)(const Shape& shapeA, const Transform& transformA, const Shape& shapeB,
                                 const Transform& transformB);

// Recursion for compounds and meshes: the table's answer for any pair, without validation.
bool collidePair(const Shape& shapeA, const Transform& transformA, const Shape& shapeB,
                 const Transform& transformB, float margin, Manifold& out);

// ---- Feature ids: A's feature in the low 16 bits, B's in the high 16 (narrowphase.h). ----
constexpr std::uint32_t featurePair(std::uint32_t featureA, std::uint32_t featureB) {
  return (featureA & 0xffffu) | (featureB << 16);
}
constexpr std::uint32_t swapFeatures(std::uint32_t id) { return (id >> 16) | (id << 16); }
// Capsule features: its two ends (the bottom -halfHeight end is 0) and the side between them.
constexpr std::uint32_t kCapsuleEnd0 = 0;
constexpr std::uint32_t kCapsuleEnd1 = 1;
constexpr std::uint32_t kCapsuleSide = 2;
// A box feature is three ternary digits, one per local axis: 0 at the -extent face, 2 at the
// +extent face, 1 in between. Vertices have no 1 digit, faces two; the interior 13 is unused.
constexpr std::uint32_t boxFeature(int digitX, int digitY, int digitZ) {
  return static_cast<std::uint32_t>(digitX + 3 * digitY + 9 * digitZ);
}

// ---- Manifold building ----
// Reduces candidate contacts (sharing `normal`) to at most four: the deepest, then the ones
// spanning the largest area, the usual choice for stable stacking (Gregorius, "Robust Contact
// Creation for Physics Simulations", GDC 2015). Writes out.points and out.count; not out.normal.
void reduceContacts(std::span<const ContactPoint> candidates, const Vec3& normal, Manifold& out);
// A contact carrying its own normal, before it joins a manifold.
struct NormalContact {
  ContactPoint point;
  Vec3 normal{0.0f};
};
// One manifold from contacts of several sub-shapes (compound children, mesh triangles), whose
// normals differ: the deepest contact's normal, and the contacts whose normal is within ~25 degrees
// of it re-measured along it, reduced to four. Returns out.count > 0.
bool mergeContacts(std::span<const NormalContact> contacts, float margin, Manifold& out);
// One contact from a signed-distance answer, if it is within the margin.
bool manifoldFromDistance(const DistanceResult& distance, std::uint32_t featureId, float margin,
                          Manifold& out);

// ---- Generic and analytic pairs ----
bool collideConvexGeneric(const Shape&, const Transform&, const Shape&, const Transform&, float, Manifold&);

bool collideSphereSphere(const Shape&, const Transform&, const Shape&, const Transform&, float, Manifold&);
bool collideSphereCapsule(const Shape&, const Transform&, const Shape&, const Transform&, float, Manifold&);
bool collideSphereBox(const Shape&, const Transform&, const Shape&, const Transform&, float, Manifold&);
bool collideCapsuleCapsule(const Shape&, const Transform&, const Shape&, const Transform&, float, Manifold&);
bool collideCapsuleBox(const Shape&, const Transform&, const Shape&, const Transform&, float, Manifold&);
// Cylinder (A) against a box, k-DOP, convex hull or cylinder (cylinder_pairs.cpp).
bool collideCylinderConvex(const Shape&, const Transform&, const Shape&, const Transform&, float, Manifold&);
// Box, k-DOP and hull against each other: SAT with face clipping (sat_polyhedra.cpp).
bool collidePolyhedra(const Shape&, const Transform&, const Shape&, const Transform&, float, Manifold&);
// Box against box: the same answer as collidePolyhedra, specialised (box_box.cpp).
bool collideBoxBox(const Shape&, const Transform&, const Shape&, const Transform&, float, Manifold&);
// The separating-axis test alone, without the face preference: the largest separation over the
// face normals and the Gauss-map-pruned edge pairs, and its axis (from A to B). For tests.
struct SatAxis {
  float separation = 0.0f;
  Vec3 axis{0.0f};
};
SatAxis polyhedraSeparation(const Shape& shapeA, const Transform& transformA, const Shape& shapeB,
                            const Transform& transformB);

// One triangle of a mesh for the polyhedron–triangle SAT (sat_polyhedra.cpp): world vertices,
// what the mesh knows about its edges (TriangleMesh::edgeKind), and the mesh's 16-bit feature codes.
struct SatTriangle {
  std::array<Vec3, 3> vertices{};
  std::uint8_t activeEdgesFront = 0x7;  // bit k: edge k may give a contact normal, seen from the front
  std::uint8_t activeEdgesBack = 0x7;   // the same seen from the back (convex and concave swap)
  std::uint8_t flatEdges = 0;           // bit k: edge k joins a coplanar neighbour
  std::uint8_t flatVertices = 0;        // bit k: vertex k lies inside a flat patch
  // Edge k's bend (TriangleMesh::edgeBendCosine): a normal at an active edge may turn from the face
  // normal by at most that angle; -1 (any) for loose triangles and the outline.
  std::array<float, 3> bendCosine{-1.0f, -1.0f, -1.0f};
  std::uint16_t faceFeature = 0;
  std::array<std::uint16_t, 3> edgeFeature{};
  std::array<std::uint16_t, 3> vertexFeature{};
};
// Contacts of each triangle (A) with a box, k-DOP or hull (B), normal from the triangle: SAT with
// the triangle as a flat polyhedron (faces ±n, three edges), face clipping, and the replacement
// of normals on inactive edges by the face's contact. Appends to `contacts` (merge them after).
void collideTrianglesPolyhedron(std::span<const SatTriangle> triangles, const Shape& polyhedron,
                                const Transform& transform, float margin, Array<NormalContact>& contacts);

// Contacts of each triangle (A) with a sphere or capsule (B), normal from the triangle: closest
// points of the core and the triangle, a capsule's clipped segment on a face, and the mesh's
// internal edges replaced by face contacts (triangle_rounded.cpp). Appends to `contacts`.
bool isRoundedForTriangles(const Shape& shape);
void collideTrianglesRounded(std::span<const SatTriangle> triangles, const Shape& shape,
                             const Transform& transform, float margin, Array<NormalContact>& contacts);

// Contacts of each triangle (A) with any other convex shape (B; the table sends ellipsoids and
// cylinders), normal from the triangle: GJK/EPA for the best axis, the face preferred, a face
// contact from the shape's lowest features (a cylinder's rim points) clipped to the triangle, and
// internal edges replaced by face contacts (triangle_generic.cpp). Appends to `contacts`.
void collideTrianglesGeneric(std::span<const SatTriangle> triangles, const Shape& shape,
                             const Transform& transform, float margin, Array<NormalContact>& contacts);

bool collidePlaneSphere(const Shape&, const Transform&, const Shape&, const Transform&, float, Manifold&);
bool collidePlaneCapsule(const Shape&, const Transform&, const Shape&, const Transform&, float, Manifold&);
bool collidePlaneBox(const Shape&, const Transform&, const Shape&, const Transform&, float, Manifold&);
bool collidePlanePolytope(const Shape&, const Transform&, const Shape&, const Transform&, float, Manifold&);
bool collidePlaneCylinder(const Shape&, const Transform&, const Shape&, const Transform&, float, Manifold&);
bool collidePlaneConvex(const Shape&, const Transform&, const Shape&, const Transform&, float, Manifold&);
bool collidePlaneMesh(const Shape&, const Transform&, const Shape&, const Transform&, float, Manifold&);

bool collideMeshConvex(const Shape&, const Transform&, const Shape&, const Transform&, float, Manifold&);
bool collideMeshMesh(const Shape&, const Transform&, const Shape&, const Transform&, float, Manifold&);
bool collideCompoundAny(const Shape&, const Transform&, const Shape&, const Transform&, float, Manifold&);

// The bodies of the mesh and compound entries, open to tests without building a mesh or compound:
// triangles given in the frame of `trianglesTransform` (each tested), children of a compound
// placed by `compoundTransform` (the compound is A).
bool collideTrianglesConvex(std::span<const std::array<Vec3, 3>> triangles,
                            const Transform& trianglesTransform, const Shape& convex,
                            const Transform& convexTransform, float margin, Manifold& out);
bool collideChildrenAny(std::span<const Compound::Child> children, const Transform& compoundTransform,
                        const Shape& other, const Transform& otherTransform, float margin, Manifold& out);

// Throws Error naming the query and the shape ("A" or "B") for an invalid transform.
bool requireValidTransform(const Transform& transform, const char* query, const char* which);
// The transform with its rotation normalised, for the public queries (dispatch.cpp).
Transform withUnitRotation(const Transform& transform);

// The plane of a plane shape in world space.
Plane worldPlane(const Plane& plane, const Transform& transform);

}  // namespace collide::detail
