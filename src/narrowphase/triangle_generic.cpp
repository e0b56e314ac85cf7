// Cylinders and ellipsoids (and any convex shape without a closed form) against mesh triangles:
// GJK/EPA finds the best axis, the triangle's face is preferred while it is nearly as good, and a
// face contact is the shape's own lowest features clipped to the triangle, so that a cylinder
// resting on a tessellated floor gets the manifold it gets on a plane (plane_pairs.cpp).
//
// For each triangle (meshes are two-sided: the face is seen from the side the shape is on):
//   1. the face axis: the shape's support against the face normal; beyond the margin, no contact;
//   2. GJK/EPA on the triangle as a three-point polytope: the signed distance s and its normal,
//      the largest separation over all axes (s >= the face's separation);
//   3. the face wins unless s is clearly larger (2 % of the face's separation plus 1e-3 of the
//      sizes, the tolerance of the polyhedron SAT in sat_polyhedra.cpp), so that the floor stays
//      the reference under a resting body whatever the triangle's size;
//   4. otherwise the contact is at an edge or vertex of the triangle, GJK's one point, if the mesh
//      lets the surface push that way there (triangle_features.h: an outline or a convex bend);
//      at an internal edge (flat or concave) the face contact replaces it, which for a shape whose
//      lowest point lies over the neighbour is empty: the neighbour holds that contact.
//
// The face contact: a cylinder standing on a cap (axis within ~2.6° of the normal) gives four rim
// points at fixed angles (local +x, +z, -x, -z) as a square, lying or tilted the lowest points of
// its two rims as a segment (kept where within the margin); an ellipsoid its support point. That
// polygon is clipped to the triangle's prism (Sutherland–Hodgman); clipped points on flat edges
// are dropped, as in the polyhedron path: the neighbours' points span the region without them.
// The ids pair the mesh's flat patch (or the outline edge a point was clipped to) with the rim
// point, so a cylinder keeps its four (or two) ids while it slides from triangle to triangle.
#include <algorithm>
#include <array>
#include <cmath>

#include "geometry/clipping.h"
#include "narrowphase/convex_distance.h"
#include "narrowphase/convex_support.h"
#include "narrowphase/pair_functions.h"
#include "narrowphase/triangle_features.h"

namespace collide::detail {

namespace {

// Shape feature codes (the shape's 16 bits of a contact id). Cylinder rim points as in the plane
// pair: 8 * cap + i for the standing rim points (i = 0..3 at local +x, +z, -x, -z), 4 and 12 for
// the lowest points of the -halfHeight and +halfHeight rims. A point made by clipping the polygon
// to the triangle: kClippedShapePoint | the smaller code of the two points it lies between.
constexpr std::uint32_t kLowestRimPoint = 4;
constexpr std::uint32_t kClippedShapePoint = 0x20;

// The shape's lowest features against a plane with normal `up` (towards the shape): a polygon of one,
// two or four points, each with its shape code.
std::size_t faceFeatures(const Shape& shape, const Transform& transform, const Vec3& up,
                         std::array<ClipVertex, 4>& polygon) {
  const Vec3 localDown = transform.inverseApplyToDirection(-up);
  if (shape.type() == ShapeType::Cylinder) {
    const Cylinder& cylinder = shape.cylinder();
    if (std::abs(localDown.y) > 0.999f) {
      const float y = localDown.y > 0.0f ? cylinder.halfHeight : -cylinder.halfHeight;
      const std::uint32_t cap = localDown.y > 0.0f ? 1u : 0u;
      const float r = cylinder.radius;
      const Vec3 rim[4] = {{r, y, 0.0f}, {0.0f, y, r}, {-r, y, 0.0f}, {0.0f, y, -r}};
      for (std::uint32_t i = 0; i < 4; ++i) polygon[i] = {transform.applyToPoint(rim[i]), cap * 8 + i};
      return 4;
    }
    const float radial = std::sqrt(localDown.x * localDown.x + localDown.z * localDown.z);
    const Vec3 outward(cylinder.radius * localDown.x / radial, 0.0f, cylinder.radius * localDown.z / radial);
    polygon[0] = {transform.applyToPoint(outward - Vec3(0.0f, cylinder.halfHeight, 0.0f)), kLowestRimPoint};
    polygon[1] = {transform.applyToPoint(outward + Vec3(0.0f, cylinder.halfHeight, 0.0f)),
                  8 + kLowestRimPoint};
    return 2;
  }
  polygon[0] = {transform.applyToPoint(collide::support(shape, localDown)), 0};
  return 1;
}

// The face contact of the triangle seen from `side`: the shape's lowest features clipped to the
// triangle's prism, the points within the margin, except those on flat edges and at flat vertices.
void faceContact(const TriangleFrame& t, const SatTriangle& triangle, float side, const Shape& shape,
                 const Transform& transform, float margin, Array<NormalContact>& contacts) {
  const Vec3 normal = side * t.normal;  // from the triangle to the shape
  const float offset = glm::dot(normal, t.v[0]);
  std::array<ClipVertex, 4> features;
  const std::size_t featureCount = faceFeatures(shape, transform, normal, features);
  // The triangle half of an id is the side bits while clipping (triangle_features.h).
  constexpr std::size_t kMaxClip = 16;
  std::array<ClipVertex, kMaxClip> bufferA, bufferB;
  std::size_t count = 0;
  for (std::size_t i = 0; i < featureCount; ++i) {
    // A tilted cylinder's rim point beyond the margin does not touch (the plane pair drops it too):
    // the segment becomes its lower end.
    if (featureCount == 2 && glm::dot(normal, features[i].position) - offset > margin) continue;
    bufferA[count++] = {features[i].position, featurePair(0, features[i].featureId)};
  }
  ClipVertex* in = bufferA.data();
  ClipVertex* next = bufferB.data();
  auto clip = [&](const Plane& plane, std::uint32_t sideBit) {
    if (count == 2) {
      // A segment: Sutherland–Hodgman would walk it as a two-sided polygon and repeat the crossing.
      const float d0 = plane.signedDistance(in[0].position), d1 = plane.signedDistance(in[1].position);
      if (d0 > 0.0f && d1 > 0.0f) {
        count = 0;
      } else if ((d0 > 0.0f) != (d1 > 0.0f)) {
        const int outside = d0 > 0.0f ? 0 : 1;
        const float t01 = d0 / (d0 - d1);
        const std::uint32_t code = std::min(in[0].featureId >> 16, in[1].featureId >> 16) & 0x1fu;
        const std::uint32_t bits = ((in[0].featureId & in[1].featureId) & kSideBits) | sideBit;
        in[outside] = {in[0].position + t01 * (in[1].position - in[0].position),
                       featurePair(bits, kClippedShapePoint | code)};
      }
      return;
    }
    count = clipPolygon(std::span<const ClipVertex>(in, count), plane, std::span<ClipVertex>(next, kMaxClip),
                        [&](const ClipVertex& a, const ClipVertex& b) {
                          const std::uint32_t bits = ((a.featureId & b.featureId) & kSideBits) | sideBit;
                          const std::uint32_t code = std::min(a.featureId >> 16, b.featureId >> 16) & 0x1fu;
                          return featurePair(bits, kClippedShapePoint | code);
                        });
    std::swap(in, next);
  };
  for (std::uint32_t k = 0; k < 3 && count > 0; ++k) {
    clip(Plane{t.outward[k], glm::dot(t.outward[k], t.v[k])}, 1u << k);
  }
  appendClippedFaceContacts(std::span<const ClipVertex>(in, count), triangle, normal, offset, margin,
                            contacts);
}

// The triangle's feature touching along a contact normal (from the triangle), as side bits: its
// vertices farthest along the normal, within rounding; 0 for the face (all three).
std::uint32_t supportFeature(const TriangleFrame& t, const Vec3& normal) {
  float heights[3], highest = -1e30f;
  for (int k = 0; k < 3; ++k) highest = std::max(highest, heights[k] = glm::dot(normal, t.v[k]));
  std::uint32_t top = 0;
  for (int k = 0; k < 3; ++k) {
    if (heights[k] >= highest - 1e-4f * t.size) top |= 1u << k;
  }
  for (int k = 0; k < 3; ++k) {
    // Edge k joins vertices k and k + 1; vertex k lies on sides k - 1 and k.
    if (top == ((1u << k) | (1u << ((k + 1) % 3)))) return 1u << k;
    if (top == (1u << k)) return (1u << k) | (1u << ((k + 2) % 3));
  }
  return 0;
}

float shapeSize(const Shape& shape, const Transform& transform) {
  return glm::length(localBounds(shape).halfExtents()) * transform.scale;
}

}  // namespace

void collideTrianglesGeneric(std::span<const SatTriangle> triangles, const Shape& shape,
                             const Transform& transform, float margin, Array<NormalContact>& contacts) {
  const ConvexSupport support = makeConvexSupport(shape, transform);
  const float size = shapeSize(shape, transform);
  for (const SatTriangle& triangle : triangles) {
    const TriangleFrame t = frameOf(triangle.vertices);
    // 1. The face, from the side the shape is on.
    const float planeOffset = glm::dot(t.normal, t.v[0]);
    const float front = glm::dot(t.normal, support.supportCore(-t.normal)) - planeOffset;
    const float back = planeOffset - glm::dot(t.normal, support.supportCore(t.normal));
    const float side = front >= back ? 1.0f : -1.0f;
    const float faceSeparation = std::max(front, back);
    if (faceSeparation > margin) continue;
    // 2. The best axis of all: GJK/EPA on the triangle.
    const ConvexSupport triangleSupport =
        makePointsSupport(triangle.vertices.data(), 3, Transform::identity());
    DistanceResult distance;
    if (!convexSignedDistance(triangleSupport, support, margin, distance)) continue;
    // 3. The face unless the best axis is clearly better.
    const float tolerance = 0.02f * std::abs(faceSeparation) + 1e-3f * std::min(t.size, size);
    const std::size_t before = contacts.size();
    const bool faceFirst = distance.distance <= faceSeparation + tolerance;
    if (faceFirst) {
      faceContact(t, triangle, side, shape, transform, margin, contacts);
      // Empty when nothing of the shape's lowest features lies over this triangle: then the
      // contact is at its boundary after all, for step 4 to judge.
      if (contacts.size() > before) continue;
    }
    // 4. An edge or vertex of the triangle (its vertices farthest along the normal): GJK's point
    // where the surface may push that way, else the face's contact (the neighbour across an
    // internal edge holds the rest).
    const std::uint32_t bits = supportFeature(t, distance.normal);
    // A face-like normal whose face contact was empty (the shape's sampled lowest features, such as
    // a cap's four rim points, all lie beyond this triangle): inside a patch the neighbours hold the
    // contact; a triangle on the outline or a bend may be all there is, and GJK's point stands.
    const std::uint8_t active = side > 0.0f ? triangle.activeEdgesFront : triangle.activeEdgesBack;
    const bool alone = bits == 0 && faceFirst && active != 0;
    if ((bits != 0 && normalAllowed(t, triangle, distance.normal)) || alone) {
      NormalContact contact;
      contact.normal = distance.normal;
      contact.point.pointOnA = distance.pointOnA;
      contact.point.pointOnB = distance.pointOnB;
      contact.point.depth = -distance.distance;
      const std::uint32_t shapeCode = shape.type() == ShapeType::Cylinder ? kLowestRimPoint : 0u;
      contact.point.featureId = featurePair(meshFeature(triangle, bits), shapeCode);
      contacts.push_back(contact);
    } else if (!faceFirst) {
      faceContact(t, triangle, side, shape, transform, margin, contacts);
    }
  }
}

}  // namespace collide::detail
