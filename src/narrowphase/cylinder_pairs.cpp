// A cylinder against a box, a convex hull, a k-DOP or another cylinder: GJK/EPA finds the axis, and
// where a flat face meets the cylinder's cap or side the manifold is that face against the
// cylinder's feature, clipped, as the plane pair and the mesh triangles give it (plane_pairs.cpp,
// triangle_generic.cpp): a cylinder standing on a box gets four points, one lying on it two, so that
// it rests instead of rocking on GJK's single point. Elsewhere (a rim on an edge, a tilted cylinder
// on a corner) GJK's point stands.
//
// The reference face is the other shape's face (or cap, a disc) turned towards the cylinder within
// kFaceAligned of the axis; the incident feature is the cylinder's lowest features along the axis
// (its cap's four rim points at local +x, +z, -x, -z, or its two rims' lowest points, the side
// line), clipped to the face's side planes (Sutherland-Hodgman) or to the disc, kept within the
// margin and reduced to four. Between two cylinders whose caps meet, each cap's rim points inside
// the other disc are candidates. Depths are measured against the reference face's plane.
#include <algorithm>
#include <array>
#include <cmath>

#include "geometry/clipping.h"
#include "narrowphase/convex_distance.h"
#include "narrowphase/convex_support.h"
#include "narrowphase/pair_functions.h"

namespace collide::detail {

namespace {

// cos of about 2.6 degrees: the plane pair's test for a cylinder standing on its cap.
constexpr float kFaceAligned = 0.999f;
// A reference face's feature code: the box's face code, or kFaceCode | face index for a polytope.
constexpr std::uint32_t kFaceCode = 0x4000u;
// A cylinder's feature codes, as in the plane pair: 8 * cap + i for a cap's rim points, 4 and 12 for
// the two rims' lowest points; kClipped | code for a point made by clipping.
constexpr std::uint32_t kLowestRim = 4;
constexpr std::uint32_t kClipped = 0x20;
constexpr std::size_t kMaxFace = 64;  // polytope faces with more vertices fall back to GJK's point

// The reference: a polygon (counter-clockwise seen from outside) or a disc, on a plane whose
// normal points out of the reference shape, towards the cylinder.
struct ReferenceFace {
  Plane plane;
  std::array<Vec3, kMaxFace> vertices;
  std::size_t vertexCount = 0;
  bool disc = false;
  Vec3 center{0.0f};
  float radius = 0.0f;
  std::uint32_t feature = 0;
};

// The cylinder's features nearest along `towards` (world): a cap's four rim points when the axis is
// within kFaceAligned of it, else the lowest points of its two rims.
std::size_t cylinderFeatures(const Cylinder& cylinder, const Transform& transform, const Vec3& towards,
                             std::array<ClipVertex, 4>& out) {
  const Vec3 local = transform.inverseApplyToDirection(towards);
  if (std::abs(local.y) > kFaceAligned) {
    const float y = local.y > 0.0f ? cylinder.halfHeight : -cylinder.halfHeight;
    const std::uint32_t cap = local.y > 0.0f ? 1u : 0u;
    const float r = cylinder.radius;
    const Vec3 rim[4] = {{r, y, 0.0f}, {0.0f, y, r}, {-r, y, 0.0f}, {0.0f, y, -r}};
    for (std::uint32_t i = 0; i < 4; ++i) out[i] = {transform.applyToPoint(rim[i]), cap * 8 + i};
    return 4;
  }
  const float radial = std::sqrt(local.x * local.x + local.z * local.z);
  const Vec3 outward(cylinder.radius * local.x / radial, 0.0f, cylinder.radius * local.z / radial);
  out[0] = {transform.applyToPoint(outward - Vec3(0.0f, cylinder.halfHeight, 0.0f)), kLowestRim};
  out[1] = {transform.applyToPoint(outward + Vec3(0.0f, cylinder.halfHeight, 0.0f)), 8 + kLowestRim};
  return 2;
}

// The cap of a cylinder facing `outward` (world), if its axis is within kFaceAligned of it.
bool capFacing(const Cylinder& cylinder, const Transform& transform, const Vec3& outward,
               ReferenceFace& face) {
  const Vec3 local = transform.inverseApplyToDirection(outward);
  if (std::abs(local.y) <= kFaceAligned) return false;
  const float sign = local.y > 0.0f ? 1.0f : -1.0f;
  const Vec3 normal = transform.applyToDirection(Vec3(0.0f, sign, 0.0f));
  face.disc = true;
  face.center = transform.applyToPoint(Vec3(0.0f, sign * cylinder.halfHeight, 0.0f));
  face.radius = cylinder.radius * transform.scale;
  face.plane = Plane{normal, glm::dot(normal, face.center)};
  face.feature = sign > 0.0f ? 8u : 0u;
  return true;
}

// A box's or polytope's face whose outward normal is nearest `outward` (world), if within kFaceAligned.
bool polyhedronFaceFacing(const Shape& shape, const Transform& transform, const Vec3& outward,
                          ReferenceFace& face) {
  const Vec3 local = transform.inverseApplyToDirection(outward);
  if (shape.type() == ShapeType::Box) {
    int axis = 0;
    for (int k = 1; k < 3; ++k)
      if (std::abs(local[k]) > std::abs(local[axis])) axis = k;
    if (std::abs(local[axis]) <= kFaceAligned) return false;
    const float sign = local[axis] > 0.0f ? 1.0f : -1.0f;
    const Vec3 h = shape.box().halfExtents;
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    // Counter-clockwise seen from outside: (u, v) then back, with v x u along -axis for sign < 0.
    const float su[4] = {1.0f, -1.0f, -1.0f, 1.0f}, sv[4] = {1.0f, 1.0f, -1.0f, -1.0f};
    for (int i = 0; i < 4; ++i) {
      Vec3 corner(0.0f);
      corner[axis] = sign * h[axis];
      corner[u] = su[i] * h[u];
      corner[v] = sign * sv[i] * h[v];
      face.vertices[i] = transform.applyToPoint(corner);
    }
    face.vertexCount = 4;
    int digits[3] = {1, 1, 1};
    digits[axis] = sign > 0.0f ? 2 : 0;
    face.feature = boxFeature(digits[0], digits[1], digits[2]);
    Vec3 localNormal(0.0f);
    localNormal[axis] = sign;
    const Vec3 normal = transform.applyToDirection(localNormal);
    face.plane = Plane{normal, glm::dot(normal, face.vertices[0])};
    return true;
  }
  const ConvexHull& hull = shape.type() == ShapeType::Kdop ? shape.kdop().polytope() : shape.convexHull();
  std::uint32_t best = 0;
  float bestDot = -2.0f;
  for (std::uint32_t f = 0; f < hull.faces().size(); ++f) {
    const float d = glm::dot(hull.faces()[f].plane.normal, local);
    if (d > bestDot) {
      bestDot = d;
      best = f;
    }
  }
  const ConvexHull::Face& chosen = hull.faces()[best];
  if (bestDot <= kFaceAligned || chosen.edgeCount > kMaxFace) return false;
  std::uint32_t edge = chosen.firstEdge;
  for (std::uint32_t i = 0; i < chosen.edgeCount; ++i) {
    face.vertices[i] = transform.applyToPoint(hull.vertices()[hull.halfEdges()[edge].origin]);
    edge = hull.halfEdges()[edge].next;
  }
  face.vertexCount = chosen.edgeCount;
  face.feature = kFaceCode | best;
  const Vec3 normal = transform.applyToDirection(chosen.plane.normal);
  face.plane = Plane{normal, glm::dot(normal, face.vertices[0])};
  return true;
}

std::uint32_t clippedCode(const ClipVertex& a, const ClipVertex& b) {
  return kClipped | (std::min(a.featureId, b.featureId) & 0x1fu);
}

// The incident points clipped to a polygon face's side planes.
std::size_t clipToPolygon(const ReferenceFace& face, std::span<const ClipVertex> incident,
                          std::array<ClipVertex, kMaxFace + 4>& out) {
  std::array<ClipVertex, kMaxFace + 4> buffer;
  std::copy(incident.begin(), incident.end(), out.begin());
  std::size_t count = incident.size();
  ClipVertex* in = out.data();
  ClipVertex* next = buffer.data();
  for (std::size_t i = 0; i < face.vertexCount && count > 0; ++i) {
    const Vec3& a = face.vertices[i];
    const Vec3& b = face.vertices[(i + 1) % face.vertexCount];
    const Vec3 side = glm::normalize(glm::cross(b - a, face.plane.normal));
    const Plane plane{side, glm::dot(side, a)};
    if (count == 2) {
      // A segment: clipped in place (a polygon walk would repeat the crossing).
      const float d0 = plane.signedDistance(in[0].position), d1 = plane.signedDistance(in[1].position);
      if (d0 > 0.0f && d1 > 0.0f) return 0;
      if ((d0 > 0.0f) != (d1 > 0.0f)) {
        const int outside = d0 > 0.0f ? 0 : 1;
        const float t = d0 / (d0 - d1);
        in[outside] = {in[0].position + t * (in[1].position - in[0].position), clippedCode(in[0], in[1])};
      }
      continue;
    }
    count = clipPolygon(std::span<const ClipVertex>(in, count), plane,
                        std::span<ClipVertex>(next, kMaxFace + 4), clippedCode);
    std::swap(in, next);
  }
  if (in != out.data()) std::copy(in, in + count, out.begin());
  return count;
}

// The incident points inside a disc (seen along its normal); a segment crossing its rim is cut there.
std::size_t clipToDisc(const ReferenceFace& face, std::span<const ClipVertex> incident,
                       std::array<ClipVertex, kMaxFace + 4>& out) {
  const Vec3 n = face.plane.normal;
  const auto radial = [&](const Vec3& p) {
    const Vec3 d = p - face.center;
    return d - glm::dot(d, n) * n;
  };
  const float r2 = face.radius * face.radius * (1.0f + 1e-4f);
  if (incident.size() == 2) {
    Vec3 p0 = incident[0].position, p1 = incident[1].position;
    const Vec3 a = radial(p0), d = radial(p1) - a;
    // |a + t d|^2 = r^2: the part of the segment inside the disc, t in [t0, t1].
    const float qa = glm::dot(d, d), qb = 2.0f * glm::dot(a, d), qc = glm::dot(a, a) - r2;
    float t0 = 0.0f, t1 = 1.0f;
    if (qa > 1e-12f) {
      const float discriminant = qb * qb - 4.0f * qa * qc;
      if (discriminant < 0.0f) return 0;
      const float root = std::sqrt(discriminant);
      t0 = std::max(0.0f, (-qb - root) / (2.0f * qa));
      t1 = std::min(1.0f, (-qb + root) / (2.0f * qa));
      if (t0 > t1) return 0;
    } else if (qc > 0.0f) {
      return 0;
    }
    const std::uint32_t code = clippedCode(incident[0], incident[1]);
    out[0] = {p0 + t0 * (p1 - p0), t0 > 0.0f ? code : incident[0].featureId};
    out[1] = {p0 + t1 * (p1 - p0), t1 < 1.0f ? code : incident[1].featureId};
    return 2;
  }
  std::size_t count = 0;
  for (const ClipVertex& v : incident) {
    const Vec3 d = radial(v.position);
    if (glm::dot(d, d) <= r2) out[count++] = v;
  }
  return count;
}

// Contact points from incident points (on the incident shape) against the reference face: the
// signed distance above the face's plane, kept within the margin.
void addAgainstFace(const ReferenceFace& face, std::span<const ClipVertex> points, bool incidentIsA,
                    float margin, std::array<ContactPoint, 2 * kMaxFace + 8>& candidates,
                    std::size_t& count) {
  for (const ClipVertex& v : points) {
    const float above = face.plane.signedDistance(v.position);
    if (above > margin || count == candidates.size()) continue;
    const Vec3 onFace = v.position - above * face.plane.normal;
    ContactPoint& c = candidates[count++];
    c.depth = -above;
    c.pointOnA = incidentIsA ? v.position : onFace;
    c.pointOnB = incidentIsA ? onFace : v.position;
    c.featureId =
        incidentIsA ? featurePair(v.featureId, face.feature) : featurePair(face.feature, v.featureId);
  }
}

bool finish(std::span<const ContactPoint> candidates, const Vec3& normal, Manifold& out) {
  out.normal = normal;
  if (candidates.size() <= Manifold::kMaxPoints) {
    std::copy(candidates.begin(), candidates.end(), out.points.begin());
    out.count = static_cast<int>(candidates.size());
  } else {
    reduceContacts(candidates, normal, out);
  }
  return out.count > 0;
}

}  // namespace

bool collideCylinderConvex(const Shape& shapeA, const Transform& transformA, const Shape& shapeB,
                           const Transform& transformB, float margin, Manifold& out) {
  out.count = 0;
  DistanceResult distance;
  if (!convexSignedDistance(makeConvexSupport(shapeA, transformA), makeConvexSupport(shapeB, transformB),
                            margin, distance))
    return false;
  const Vec3 n = distance.normal;  // from A (the cylinder) to B
  const Cylinder& cylinder = shapeA.cylinder();
  std::array<ClipVertex, 4> features;
  std::array<ClipVertex, kMaxFace + 4> clipped;
  std::array<ContactPoint, 2 * kMaxFace + 8> candidates;
  std::size_t count = 0;
  ReferenceFace face;
  const bool otherIsCylinder = shapeB.type() == ShapeType::Cylinder;
  const bool faceOnB = otherIsCylinder ? capFacing(shapeB.cylinder(), transformB, -n, face)
                                       : polyhedronFaceFacing(shapeB, transformB, -n, face);
  if (faceOnB) {
    // B's face or cap is the reference; the cylinder's nearest features meet it.
    const std::size_t featureCount = cylinderFeatures(cylinder, transformA, n, features);
    const std::span<const ClipVertex> incident(features.data(), featureCount);
    const std::size_t kept =
        face.disc ? clipToDisc(face, incident, clipped) : clipToPolygon(face, incident, clipped);
    addAgainstFace(face, std::span<const ClipVertex>(clipped.data(), kept), true, margin, candidates, count);
    if (otherIsCylinder) {
      // Cap on cap: B's rim points inside A's cap are contacts too.
      ReferenceFace capA;
      std::array<ClipVertex, 4> rimB;
      if (capFacing(cylinder, transformA, n, capA) &&
          cylinderFeatures(shapeB.cylinder(), transformB, -n, rimB) == 4) {
        const std::size_t insideA = clipToDisc(capA, rimB, clipped);
        addAgainstFace(capA, std::span<const ClipVertex>(clipped.data(), insideA), false, margin, candidates,
                       count);
      }
    }
    if (count > 0)
      return finish(std::span<const ContactPoint>(candidates.data(), count), -face.plane.normal, out);
  } else if (otherIsCylinder && capFacing(cylinder, transformA, n, face)) {
    // A's cap is the reference, B's side line the incident feature.
    const std::size_t featureCount = cylinderFeatures(shapeB.cylinder(), transformB, -n, features);
    const std::size_t kept =
        clipToDisc(face, std::span<const ClipVertex>(features.data(), featureCount), clipped);
    addAgainstFace(face, std::span<const ClipVertex>(clipped.data(), kept), false, margin, candidates, count);
    if (count > 0)
      return finish(std::span<const ContactPoint>(candidates.data(), count), face.plane.normal, out);
  }
  // An edge, a corner or a rim: GJK's point. The cylinder's code names its side.
  return manifoldFromDistance(distance, featurePair(kLowestRim, 0), margin, out);
}

}  // namespace collide::detail
