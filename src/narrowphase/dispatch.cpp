// The pair table: one cell per ordered pair of shape types, each with a collide function (collider
// semantics), an overlap function (bounding-volume semantics) and a note on its algorithm. One
// function fills it (as Box2D v3's contact.c does): the generic GJK/EPA entry under every convex
// pair first, then the specialised entries over it (as Jolt's CollisionDispatch lets shapes
// override the generic one). A pair is written once, for one order; the mirroring wrapper serves
// the other order by swapping A and B and flipping the normal.
#include <array>
#include <cmath>
#include <iterator>
#include <sstream>
#include <string>

#include "base/fail.h"
#include "narrowphase/pair_functions.h"
#include "shapes/shape_functions.h"

namespace collide {

namespace detail {

namespace {

struct PairEntry {
  CollideFunction collide = nullptr;
  OverlapFunction overlap = nullptr;
  PairAlgorithm algorithm = PairAlgorithm::NotSupported;
  std::string_view description;
};

using PairTable = std::array<std::array<PairEntry, kShapeTypeCount>, kShapeTypeCount>;

constexpr std::size_t index(ShapeType type) { return static_cast<std::size_t>(type); }

// ---- Mirroring: (B, A) answered by the (A, B) function. ----

template <CollideFunction F>
bool collideMirrored(const Shape& shapeA, const Transform& transformA, const Shape& shapeB,
                     const Transform& transformB, float margin, Manifold& out) {
  if (!F(shapeB, transformB, shapeA, transformA, margin, out)) return false;
  out.normal = -out.normal;
  for (int i = 0; i < out.count; ++i) {
    ContactPoint& point = out.points[i];
    std::swap(point.pointOnA, point.pointOnB);  // depth = (pA - pB)·n keeps its sign
    point.featureId = swapFeatures(point.featureId);
  }
  return true;
}

// A pair of the same type whose function is not symmetric in its arguments (a reference face
// chosen by order, a clip against the first shape's cap) answers (B, A) as the mirror of (A, B) for
// one order of the two, the same whichever way it is asked: collide(b, a) is then exactly the mirror
// of collide(a, b), and a world's contacts do not depend on which body was created first.
template <CollideFunction F>
bool collideInCanonicalOrder(const Shape& shapeA, const Transform& transformA, const Shape& shapeB,
                             const Transform& transformB, float margin, Manifold& out) {
  const auto key = [](const Shape& shape, const Transform& t) {
    const Cylinder& c = shape.cylinder();
    return std::array<float, 10>{t.position.x, t.position.y, t.position.z, t.rotation.w, t.rotation.x,
                                 t.rotation.y, t.rotation.z, t.scale,      c.radius,     c.halfHeight};
  };
  if (key(shapeB, transformB) < key(shapeA, transformA))
    return collideMirrored<F>(shapeA, transformA, shapeB, transformB, margin, out);
  return F(shapeA, transformA, shapeB, transformB, margin, out);
}

template <OverlapFunction F>
bool overlapMirrored(const Shape& shapeA, const Transform& transformA, const Shape& shapeB,
                     const Transform& transformB) {
  return F(shapeB, transformB, shapeA, transformA);
}

// ---- Unsupported cells ----

bool collidePlanePlane(const Shape&, const Transform&, const Shape&, const Transform&, float, Manifold&) {
  COLLIDE_FAIL(
      "collide: plane–plane is not supported: two half-spaces are infinite static proxies, which the "
      "world never pairs; make one of the bodies a box",
      false);
}

// ---- Bounding-volume semantics ----

// A world box cheap to get: exact for the primitives, the transformed local box for polyhedra
// (whose exact box would transform every vertex).
Aabb cheapWorldBounds(const Shape& shape, const Transform& transform) {
  switch (shape.type()) {
    case ShapeType::Kdop:
    case ShapeType::ConvexHull:
    case ShapeType::Mesh:
      return transformAabb(localBounds(shape), transform);
    default:
      return worldBounds(shape, transform);
  }
}

bool overlapBounds(const Shape& shapeA, const Transform& transformA, const Shape& shapeB,
                   const Transform& transformB) {
  return cheapWorldBounds(shapeA, transformA).overlaps(cheapWorldBounds(shapeB, transformB));
}

bool overlapSphereSphere(const Shape& shapeA, const Transform& transformA, const Shape& shapeB,
                         const Transform& transformB) {
  const float reach = shapeA.sphere().radius * transformA.scale + shapeB.sphere().radius * transformB.scale;
  const Vec3 d = transformB.position - transformA.position;
  return glm::dot(d, d) <= reach * reach;
}

bool overlapPlaneAny(const Shape& shapeA, const Transform& transformA, const Shape& shapeB,
                     const Transform& transformB) {
  return classify(worldPlane(shapeA.plane(), transformA), cheapWorldBounds(shapeB, transformB)) !=
         Side::Outside;
}

bool overlapPlanePlane(const Shape& shapeA, const Transform& transformA, const Shape& shapeB,
                       const Transform& transformB) {
  // Two half-spaces meet unless they face each other apart: n·x <= dA and -n·x <= dB need -dB <= dA.
  const Plane a = worldPlane(shapeA.plane(), transformA);
  const Plane b = worldPlane(shapeB.plane(), transformB);
  if (glm::dot(a.normal, b.normal) > -1.0f + 1e-6f) return true;
  return a.distance + b.distance >= 0.0f;
}

// ---- The registration function ----

class TableBuilder {
 public:
  constexpr TableBuilder() {
    for (auto& row : table_) {
      for (PairEntry& entry : row) entry.overlap = overlapBounds;
    }
  }

  // Registers F for (a, b) and its mirror for (b, a).
  template <CollideFunction F>
  constexpr void add(ShapeType a, ShapeType b, PairAlgorithm algorithm, std::string_view description) {
    PairEntry& forward = table_[index(a)][index(b)];
    forward.collide = F;
    forward.algorithm = algorithm;
    forward.description = description;
    if (a == b) return;
    PairEntry& backward = table_[index(b)][index(a)];
    backward.collide = collideMirrored<F>;
    backward.algorithm = algorithm;
    backward.description = description;
  }

  template <OverlapFunction F>
  constexpr void addOverlap(ShapeType a, ShapeType b) {
    table_[index(a)][index(b)].overlap = F;
    if (a != b) table_[index(b)][index(a)].overlap = overlapMirrored<F>;
  }

  constexpr const PairTable& table() const { return table_; }

 private:
  PairTable table_{};
};

constexpr ShapeType kConvexTypes[] = {ShapeType::Sphere,    ShapeType::Capsule,   ShapeType::Box,
                                      ShapeType::Kdop,      ShapeType::Ellipsoid, ShapeType::Cylinder,
                                      ShapeType::ConvexHull};
constexpr ShapeType kAllTypes[] = {
    ShapeType::Sphere,    ShapeType::Capsule,  ShapeType::Plane,      ShapeType::Box,  ShapeType::Kdop,
    ShapeType::Ellipsoid, ShapeType::Cylinder, ShapeType::ConvexHull, ShapeType::Mesh, ShapeType::Compound};

// Kept whole although it is long: the table is data, one registration per cell, and its order is
// its meaning (the generic entry first, the specialised ones over it), read top to bottom here.
constexpr PairTable buildPairTable() {
  using T = ShapeType;
  using A = PairAlgorithm;
  TableBuilder b;

  // Bounding-volume semantics: world boxes everywhere, exact where it is as cheap.
  for (const ShapeType type : kAllTypes) b.addOverlap<overlapPlaneAny>(T::Plane, type);
  b.addOverlap<overlapPlanePlane>(T::Plane, T::Plane);
  b.addOverlap<overlapSphereSphere>(T::Sphere, T::Sphere);

  // 1. The generic entry under every convex pair.
  for (const ShapeType a : kConvexTypes) {
    for (const ShapeType c : kConvexTypes) {
      b.add<collideConvexGeneric>(a, c, A::GjkEpa,
                                  "GJK distance on the core shapes (sphere = point, capsule = segment, "
                                  "radius subtracted), EPA when the cores overlap; one contact point");
    }
  }

  // 2. Half-space against every convex shape: the shape's points below the surface.
  b.add<collidePlaneSphere>(T::Plane, T::Sphere, A::Analytic, "lowest point of the sphere; one point");
  b.add<collidePlaneCapsule>(T::Plane, T::Capsule, A::Analytic,
                             "lowest points of the two end spheres; two points when lying flat");
  b.add<collidePlaneBox>(T::Plane, T::Box, A::Analytic, "box vertices below the surface; up to four points");
  b.add<collidePlanePolytope>(T::Plane, T::Kdop, A::Analytic,
                              "polytope vertices below the surface, reduced to four");
  b.add<collidePlanePolytope>(T::Plane, T::ConvexHull, A::Analytic,
                              "hull vertices below the surface, reduced to four");
  b.add<collidePlaneConvex>(T::Plane, T::Ellipsoid, A::Analytic, "support point along -normal; one point");
  b.add<collidePlaneCylinder>(
      T::Plane, T::Cylinder, A::Analytic,
      "lowest rim points: four on a cap standing flat, two lying on the side, else one");

  // 3. Dedicated routines over the generic entry: closed forms, and capsule × box.
  b.add<collideSphereSphere>(T::Sphere, T::Sphere, A::Analytic, "distance of the centres; one point");
  b.add<collideSphereCapsule>(T::Sphere, T::Capsule, A::Analytic,
                              "centre against the capsule's segment; one point");
  b.add<collideSphereBox>(T::Sphere, T::Box, A::Analytic,
                          "centre clamped to the box (nearest face when inside); one point");
  b.add<collideCapsuleCapsule>(T::Capsule, T::Capsule, A::Analytic,
                               "closest points of the two segments (lecture, slide 61); two points when "
                               "parallel and overlapping");
  b.add<collideCapsuleBox>(T::Capsule, T::Box, A::GjkEpaClip,
                           "GJK/EPA on the core segment, clipped to the box face when lying on it; up to two "
                           "points");
  for (const ShapeType other : {T::Box, T::Kdop, T::ConvexHull}) {
    b.add<collideCylinderConvex>(
        T::Cylinder, other, A::GjkEpaClip,
        "GJK/EPA for the axis; a cap's four rim points or the side line clipped to the "
        "face (or cap) facing the cylinder, up to four points; else one point");
  }
  b.add<collideInCanonicalOrder<collideCylinderConvex>>(
      T::Cylinder, T::Cylinder, A::GjkEpaClip,
      "GJK/EPA for the axis; a cap's four rim points or the side line clipped to the "
      "face (or cap) facing the cylinder, up to four points; else one point");

  // Polyhedra: the separating-axis test with face clipping.
  constexpr ShapeType kPolyhedra[] = {T::Box, T::Kdop, T::ConvexHull};
  for (std::size_t i = 0; i < std::size(kPolyhedra); ++i) {
    for (std::size_t j = i; j < std::size(kPolyhedra); ++j) {
      b.add<collidePolyhedra>(kPolyhedra[i], kPolyhedra[j], A::Sat,
                              "separating axes (faces, then edge pairs crossing on the Gauss map); face "
                              "contact: incident face clipped to the reference face, up to four points; "
                              "edge contact: one point");
    }
  }
  // Two boxes: the same test specialised (15 axes in A's frame, axis-aligned clipping).
  b.add<collideBoxBox>(T::Box, T::Box, A::Sat,
                       "separating axes in A's frame (3 + 3 faces, 9 edge directions); face contact: "
                       "incident face clipped to the reference face, up to four points; edge contact: one "
                       "point");

  // 4. Triangle meshes: per triangle near the other shape, merged.
  for (const ShapeType c : kConvexTypes) {
    const bool polyhedron = c == T::Box || c == T::Kdop || c == T::ConvexHull;
    const bool rounded = c == T::Sphere || c == T::Capsule;
    b.add<collideMeshConvex>(
        T::Mesh, c, A::Mesh,
        polyhedron ? "BVH triangles near the shape, each by triangle SAT with clipping; internal edges "
                     "replaced by face contacts; merged to four"
        : rounded  ? "BVH triangles near the shape, each by closest points of the core (a capsule's segment "
                     "clipped on a face); internal edges replaced by face contacts; merged to four"
                  : "BVH triangles near the shape, each by GJK/EPA as a 3-point polytope, the face preferred "
                    "and its contact the shape's lowest features clipped to the triangle (a cylinder's "
                    "rim: four points on a cap, two on its side); internal edges replaced by face "
                    "contacts; merged to four");
  }
  b.add<collidePlaneMesh>(T::Plane, T::Mesh, A::Mesh, "mesh vertices below the surface, reduced to four");
  b.add<collideMeshMesh>(T::Mesh, T::Mesh, A::Mesh,
                         "triangle pairs from both BVHs by GJK/EPA (for a movable closed mesh; two static "
                         "meshes are never paired)");

  // 5. Compounds: per child against anything, through this table; merged.
  for (const ShapeType type : kAllTypes) {
    b.add<collideCompoundAny>(
        T::Compound, type, A::Compound,
        "each child whose box meets the other shape, through this table; merged to four");
  }

  // 6. What cannot occur.
  b.add<collidePlanePlane>(T::Plane, T::Plane, A::NotSupported,
                           "two half-spaces are infinite, static proxies: the world never pairs them");
  return b.table();
}

constinit const PairTable kPairTable = buildPairTable();

// ---- Validation ----

std::string format(const Vec3& v) {
  std::ostringstream out;
  out << '[' << v.x << ", " << v.y << ", " << v.z << ']';
  return out.str();
}

void reportInvalidTransform(const Transform& t, const char* query, const char* which) {
  std::ostringstream out;
  out << query << ": transform of shape " << which
      << " must have a finite position, a unit rotation and a finite scale > 0, got position "
      << format(t.position) << ", rotation (w " << t.rotation.w << ", x " << t.rotation.x << ", y "
      << t.rotation.y << ", z " << t.rotation.z << "), scale " << t.scale;
  raiseError(out.str());
}

// The same test as isValid() but cheap enough for the cheapest pairs: one NaN/infinity probe
// (x * 0 is 0 only for finite x), then the unit quaternion and the positive scale.
inline bool requireValid(const Transform& t, const char* query, const char* which) {
  const float probe = (t.position.x + t.position.y + t.position.z + t.rotation.x + t.rotation.y +
                       t.rotation.z + t.rotation.w + t.scale) *
                      0.0f;
  const float norm = t.rotation.x * t.rotation.x + t.rotation.y * t.rotation.y + t.rotation.z * t.rotation.z +
                     t.rotation.w * t.rotation.w;
  if (probe == 0.0f && std::abs(norm - 1.0f) < 1e-3f && t.scale > 0.0f) [[likely]]
    return true;
  if (isValid(t)) return true;  // the probe may overflow for huge values
  reportInvalidTransform(t, query, which);
  return false;
}

}  // namespace

bool collidePair(const Shape& shapeA, const Transform& transformA, const Shape& shapeB,
                 const Transform& transformB, float margin, Manifold& out) {
  out.count = 0;
  return kPairTable[index(shapeA.type())][index(shapeB.type())].collide(shapeA, transformA, shapeB,
                                                                        transformB, margin, out);
}

}  // namespace detail

std::string_view toString(PairAlgorithm algorithm) {
  switch (algorithm) {
    case PairAlgorithm::Analytic:
      return "analytic";
    case PairAlgorithm::Sat:
      return "SAT";
    case PairAlgorithm::GjkEpa:
      return "GJK/EPA";
    case PairAlgorithm::GjkEpaClip:
      return "GJK/EPA + clip";
    case PairAlgorithm::Mesh:
      return "mesh";
    case PairAlgorithm::Compound:
      return "compound";
    case PairAlgorithm::NotSupported:
      return "not supported";
  }
  return "unknown";
}

PairInfo pairInfo(ShapeType a, ShapeType b) {
  const auto& entry = detail::kPairTable[detail::index(a)][detail::index(b)];
  return {entry.algorithm, entry.description};
}

std::string describePairTable() {
  std::string text;
  for (const ShapeType a : detail::kAllTypes) {
    for (const ShapeType b : detail::kAllTypes) {
      const PairInfo info = pairInfo(a, b);
      text += std::string(toString(a)) + " x " + std::string(toString(b)) + ": " +
              std::string(toString(info.algorithm)) + " (" + std::string(info.description) + ")\n";
    }
  }
  return text;
}

bool overlap(const Shape& shapeA, const Transform& transformA, const Shape& shapeB,
             const Transform& transformB) {
  if (!detail::usableShape(shapeA) || !detail::usableShape(shapeB) ||
      !detail::requireValid(transformA, "overlap", "A") || !detail::requireValid(transformB, "overlap", "B"))
    return false;
  return detail::kPairTable[detail::index(shapeA.type())][detail::index(shapeB.type())].overlap(
      shapeA, detail::withUnitRotation(transformA), shapeB, detail::withUnitRotation(transformB));
}

bool collide(const Shape& shapeA, const Transform& transformA, const Shape& shapeB,
             const Transform& transformB, Manifold& out, float speculativeMargin) {
  out.count = 0;
  if (!detail::usableShape(shapeA) || !detail::usableShape(shapeB) ||
      !detail::requireValid(transformA, "collide", "A") || !detail::requireValid(transformB, "collide", "B"))
    return false;
  if (!(speculativeMargin >= 0.0f) || !std::isfinite(speculativeMargin)) {
    std::ostringstream message;
    message << "collide: speculative margin must be finite and >= 0, got " << speculativeMargin;
    COLLIDE_FAIL(message.str(), false);
  }
  return detail::collidePair(shapeA, detail::withUnitRotation(transformA), shapeB,
                             detail::withUnitRotation(transformB), speculativeMargin, out);
}

namespace detail {
// Shared with distance() in convex_distance.cpp.
bool requireValidTransform(const Transform& transform, const char* query, const char* which) {
  return requireValid(transform, query, which);
}

// The caller's transform with its rotation normalised: a valid rotation may be off unit length by
// up to 1e-3, and rotating by it stretches every vector by its squared length, which took a manifold's
// normal 1.5e-3 off unit length (narrowphase_fuzzer). A rotation within 1e-5 of unit (every one the
// world normalised, whose squared length is within a few float ulps of 1) is left as it is: normalised
// again it could change in its last bit, and with it the world's results.
Transform withUnitRotation(const Transform& transform) {
  const float squaredLength = glm::dot(transform.rotation, transform.rotation);
  if (std::abs(squaredLength - 1.0f) <= 1e-5f) return transform;
  Transform unit = transform;
  unit.rotation = transform.rotation / std::sqrt(squaredLength);
  return unit;
}
}  // namespace detail

}  // namespace collide
