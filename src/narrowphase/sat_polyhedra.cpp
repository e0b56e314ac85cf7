// Polyhedron pairs (box, k-DOP, convex hull) by the separating-axis test with face clipping
// (Gregorius, "The Separating Axis Test between Convex Polyhedra", GDC 2013):
//   1. the face normals of A, then of B: the separation of each face plane from the other's support;
//   2. the cross products of edge pairs, only for pairs whose arcs cross on the Gauss map (those and
//      only those edges make a face of the Minkowski difference A - B);
//   3. the largest separation found is the answer: above the margin the pair is apart. Otherwise a
//      face contact (reference face, incident face clipped against its side planes, points below the
//      reference plane, reduced to four) or an edge contact (the closest points of the two edges).
// Face contacts are preferred over an edge contact that is barely shallower, and A's face over B's,
// as Box2D and Jolt do: a resting box then keeps the same reference face and the same contact ids
// from step to step instead of flickering between near-equal axes.
//
// A box is the cached unit-cube hull scaled by its half extents, so one routine serves every pair;
// its features are named by the box's ternary codes (pair_functions.h) so that box ids mean the
// same in every cell.
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "geometry/clipping.h"
#include "geometry/closest_points.h"
#include "narrowphase/pair_functions.h"
#include "narrowphase/triangle_features.h"

namespace collide::detail {

namespace {

// Hull feature codes (16 bits, the shape's half of a contact id): vertex i is i, face f is
// kFaceTag | f, edge e (the smaller half-edge index of the pair) is kEdgeTag | e; a point made by
// clipping gets kClipTag and a mix of the two incident features it lies between.
constexpr std::uint32_t kFaceTag = 0x4000u;
constexpr std::uint32_t kEdgeTag = 0x8000u;
constexpr std::uint32_t kClipTag = 0xC000u;
constexpr std::uint32_t kIndexMask = 0x3fffu;

// The unit cube [-1, 1]³ as a hull, with the box code of each of its vertices, faces and edges.
struct UnitCube {
  ConvexHull hull;
  std::array<std::uint16_t, 8> vertexCode{};
  std::array<std::uint16_t, 6> faceCode{};
  std::array<std::uint16_t, 24> edgeCode{};  // per half-edge

  UnitCube() : hull(makeHull()) {
    auto digit = [](float c) { return c > 0.5f ? 2 : (c < -0.5f ? 0 : 1); };
    auto code = [&](const Vec3& p) {
      return static_cast<std::uint16_t>(boxFeature(digit(p.x), digit(p.y), digit(p.z)));
    };
    for (std::size_t i = 0; i < hull.vertices().size(); ++i) vertexCode[i] = code(hull.vertices()[i]);
    for (std::size_t f = 0; f < hull.faces().size(); ++f) faceCode[f] = code(hull.faces()[f].plane.normal);
    for (std::size_t h = 0; h < hull.halfEdges().size(); ++h) {
      const ConvexHull::HalfEdge& edge = hull.halfEdges()[h];
      const Vec3 mid =
          0.5f * (hull.vertices()[edge.origin] + hull.vertices()[hull.halfEdges()[edge.next].origin]);
      edgeCode[h] = code(mid);
    }
  }

  static ConvexHull makeHull() {
    std::array<Vec3, 8> corners;
    for (int i = 0; i < 8; ++i) {
      corners[i] = Vec3((i & 1) ? 1.0f : -1.0f, (i & 2) ? 1.0f : -1.0f, (i & 4) ? 1.0f : -1.0f);
    }
    return ConvexHull::fromPoints(corners);
  }
};

const UnitCube& unitCube() {
  static const UnitCube cube;
  return cube;
}

// A polyhedron placed in the world: the hull's topology with world vertices and face planes.
struct WorldPolyhedron {
  const ConvexHull* hull = nullptr;
  const UnitCube* cube = nullptr;  // set for a box: its features are named by box codes
  std::span<const Vec3> vertices;  // world
  std::span<const Plane> planes;   // world, outward unit normals
  Vec3 center{0.0f};               // a point inside, to orient edge axes
  float size = 0.0f;               // a length of the shape's scale, for tolerances

  std::uint32_t vertexFeature(std::uint32_t v) const { return cube ? cube->vertexCode[v] : (v & kIndexMask); }
  std::uint32_t faceFeature(std::uint32_t f) const {
    return cube ? cube->faceCode[f] : (kFaceTag | (f & kIndexMask));
  }
  std::uint32_t edgeFeature(std::uint32_t h) const {
    if (cube) return cube->edgeCode[h];
    return kEdgeTag | (std::min(h, hull->halfEdges()[h].twin) & kIndexMask);
  }
  Vec3 edgeEnd(std::uint32_t h) const {
    return vertices[hull->halfEdges()[hull->halfEdges()[h].next].origin];
  }
};

// Per-thread scratch for the world vertices and planes of both shapes: no allocation once warm.
struct Scratch {
  std::vector<Vec3> vertices[2];
  std::vector<Plane> planes[2];
};

WorldPolyhedron place(const Shape& shape, const Transform& transform, int slot, Scratch& scratch) {
  WorldPolyhedron poly;
  Vec3 localScale(transform.scale);
  switch (shape.type()) {
    case ShapeType::Box:
      poly.cube = &unitCube();
      poly.hull = &poly.cube->hull;
      localScale *= shape.box().halfExtents;
      break;
    case ShapeType::Kdop:
      poly.hull = &shape.kdop().polytope();
      break;
    default:
      poly.hull = &shape.convexHull();
      break;
  }
  const ConvexHull& hull = *poly.hull;
  const Mat3 rotation = glm::mat3_cast(transform.rotation);
  std::vector<Vec3>& vertices = scratch.vertices[slot];
  std::vector<Plane>& planes = scratch.planes[slot];
  vertices.resize(hull.vertices().size());
  planes.resize(hull.faces().size());
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    vertices[i] = transform.position + rotation * (localScale * hull.vertices()[i]);
  }
  for (std::size_t f = 0; f < planes.size(); ++f) {
    const ConvexHull::Face& face = hull.faces()[f];
    // A box's faces are axis-aligned, so its non-uniform scale leaves their normals alone.
    const Vec3 normal = rotation * face.plane.normal;
    planes[f] = {normal, glm::dot(normal, vertices[hull.halfEdges()[face.firstEdge].origin])};
  }
  poly.vertices = vertices;
  poly.planes = planes;
  const Aabb bounds = hull.bounds();
  poly.center = transform.position + rotation * (localScale * bounds.center());
  poly.size = glm::length(localScale * bounds.halfExtents());
  return poly;
}

struct FaceQuery {
  float separation = -1e30f;
  std::uint32_t face = 0;
};

// The largest separation of B from a face plane of A: the plane's distance to B's support against
// its normal.
FaceQuery queryFaces(const WorldPolyhedron& a, const WorldPolyhedron& b) {
  FaceQuery best;
  for (std::uint32_t f = 0; f < a.planes.size(); ++f) {
    const Plane& plane = a.planes[f];
    float lowest = 1e30f;
    for (const Vec3& v : b.vertices) lowest = std::min(lowest, glm::dot(plane.normal, v));
    const float separation = lowest - plane.distance;
    if (separation > best.separation) {
      best.separation = separation;
      best.face = f;
    }
  }
  return best;
}

struct EdgeQuery {
  float separation = -1e30f;
  std::uint32_t edgeA = 0, edgeB = 0;  // half-edge indices
  Vec3 axis{0.0f};                     // from A to B
};

// Whether the arcs (a, b) and (c, d) cross on the unit sphere. Arc (a, b) is the Gauss image of an
// edge of A between faces with normals a and b; (c, d) that of an edge of B, negated (the Minkowski
// difference A - B has -B's normals). Two arcs cross when each one's endpoints lie on opposite sides
// of the other's great circle, and they lie on the same hemisphere (Gregorius 2013).
bool arcsCross(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 bxa = glm::cross(b, a);
  const Vec3 dxc = glm::cross(d, c);
  const float cba = glm::dot(c, bxa);
  const float dba = glm::dot(d, bxa);
  const float adc = glm::dot(a, dxc);
  const float bdc = glm::dot(b, dxc);
  return cba * dba < 0.0f && adc * bdc < 0.0f && cba * bdc > 0.0f;
}

EdgeQuery queryEdges(const WorldPolyhedron& a, const WorldPolyhedron& b) {
  EdgeQuery best;
  const auto edgesA = a.hull->halfEdges();
  const auto edgesB = b.hull->halfEdges();
  for (std::uint32_t i = 0; i < edgesA.size(); ++i) {
    const ConvexHull::HalfEdge& edgeA = edgesA[i];
    if (edgeA.twin < i) continue;  // each edge once
    const Vec3 pA = a.vertices[edgeA.origin];
    const Vec3 directionA = a.edgeEnd(i) - pA;
    const Vec3 normalA1 = a.planes[edgeA.face].normal;
    const Vec3 normalA2 = a.planes[edgesA[edgeA.twin].face].normal;
    for (std::uint32_t j = 0; j < edgesB.size(); ++j) {
      const ConvexHull::HalfEdge& edgeB = edgesB[j];
      if (edgeB.twin < j) continue;
      const Vec3 normalB1 = b.planes[edgeB.face].normal;
      const Vec3 normalB2 = b.planes[edgesB[edgeB.twin].face].normal;
      if (!arcsCross(normalA1, normalA2, -normalB1, -normalB2)) continue;
      const Vec3 pB = b.vertices[edgeB.origin];
      const Vec3 directionB = b.edgeEnd(j) - pB;
      Vec3 axis = glm::cross(directionA, directionB);
      const float length = glm::length(axis);
      // Parallel edges: their cross product has no direction (the face axes cover that case).
      if (length < 1e-5f * glm::length(directionA) * glm::length(directionB)) continue;
      axis /= length;
      if (glm::dot(axis, pA - a.center) < 0.0f) axis = -axis;
      const float separation = glm::dot(axis, pB - pA);
      if (separation > best.separation) {
        best.separation = separation;
        best.edgeA = i;
        best.edgeB = j;
        best.axis = axis;
      }
    }
  }
  return best;
}

// The face of `poly` whose normal is most anti-parallel to `normal`.
std::uint32_t incidentFace(const WorldPolyhedron& poly, const Vec3& normal) {
  std::uint32_t best = 0;
  float lowest = 1e30f;
  for (std::uint32_t f = 0; f < poly.planes.size(); ++f) {
    const float d = glm::dot(poly.planes[f].normal, normal);
    if (d < lowest) {
      lowest = d;
      best = f;
    }
  }
  return best;
}

// Twice the area of a face (world), from the cross products of its fan.
float faceArea(const WorldPolyhedron& poly, std::uint32_t face) {
  const ConvexHull::Face& f = poly.hull->faces()[face];
  const auto edges = poly.hull->halfEdges();
  const Vec3 origin = poly.vertices[edges[f.firstEdge].origin];
  Vec3 sum(0.0f);
  std::uint32_t h = edges[f.firstEdge].next;
  for (std::uint32_t k = 1; k + 1 < f.edgeCount; ++k) {
    sum += glm::cross(poly.vertices[edges[h].origin] - origin, poly.edgeEnd(h) - origin);
    h = edges[h].next;
  }
  return glm::length(sum);
}

std::uint32_t mixClip(std::uint32_t a, std::uint32_t b) {
  if (a > b) std::swap(a, b);
  return kClipTag | ((a * 0x9E37u ^ b * 0x7F4Bu ^ (a >> 7)) & kIndexMask);
}

// Face contact: the incident face of `inc` clipped against the side planes of `ref`'s face, the
// points below the reference plane. refIsA says which shape is A (the manifold's normal goes from
// A to B). Clip vertex ids hold the reference half in the low 16 bits during clipping.
bool faceContact(const WorldPolyhedron& ref, std::uint32_t refFace, const WorldPolyhedron& inc, bool refIsA,
                 float margin, Manifold& out) {
  const Plane& refPlane = ref.planes[refFace];
  const std::uint32_t incFace = incidentFace(inc, refPlane.normal);

  constexpr std::size_t kMaxClip = 64;
  std::array<ClipVertex, kMaxClip> bufferA, bufferB;
  std::size_t count = 0;
  {
    const ConvexHull::Face& face = inc.hull->faces()[incFace];
    std::uint32_t h = face.firstEdge;
    for (std::uint32_t k = 0; k < face.edgeCount && count < kMaxClip; ++k) {
      const std::uint32_t v = inc.hull->halfEdges()[h].origin;
      bufferA[count++] = {inc.vertices[v], featurePair(ref.faceFeature(refFace), inc.vertexFeature(v))};
      h = inc.hull->halfEdges()[h].next;
    }
  }
  ClipVertex* in = bufferA.data();
  ClipVertex* outBuffer = bufferB.data();
  const ConvexHull::Face& face = ref.hull->faces()[refFace];
  std::uint32_t h = face.firstEdge;
  for (std::uint32_t k = 0; k < face.edgeCount && count > 0; ++k) {
    const Vec3 start = ref.vertices[ref.hull->halfEdges()[h].origin];
    const Vec3 end = ref.edgeEnd(h);
    // Outward in the face's plane: the face winds counter-clockwise around its normal.
    const Vec3 side = glm::normalize(glm::cross(end - start, refPlane.normal));
    const std::uint32_t sideFeature = ref.edgeFeature(h);
    count = clipPolygon(std::span<const ClipVertex>(in, count), Plane{side, glm::dot(side, start)},
                        std::span<ClipVertex>(outBuffer, kMaxClip),
                        [&](const ClipVertex& a, const ClipVertex& b) {
                          return featurePair(sideFeature, mixClip(a.featureId >> 16, b.featureId >> 16));
                        });
    std::swap(in, outBuffer);
    h = ref.hull->halfEdges()[h].next;
  }

  // Deep or skewed overlaps can leave no clipped point below the reference plane although the
  // face axis is the best: the incident shape's deepest vertex then stands for the contact (its
  // separation is the axis's).
  if (count == 0 || std::none_of(in, in + count, [&](const ClipVertex& v) {
        return refPlane.signedDistance(v.position) <= margin;
      })) {
    std::uint32_t deepest = 0;
    for (std::uint32_t v = 1; v < inc.vertices.size(); ++v) {
      if (glm::dot(inc.vertices[v], refPlane.normal) < glm::dot(inc.vertices[deepest], refPlane.normal))
        deepest = v;
    }
    in[0] = {inc.vertices[deepest], featurePair(ref.faceFeature(refFace), inc.vertexFeature(deepest))};
    count = 1;
  }

  std::array<ContactPoint, kMaxClip> candidates;
  std::size_t kept = 0;
  for (std::size_t i = 0; i < count; ++i) {
    const Vec3 p = in[i].position;
    const float separation = refPlane.signedDistance(p);
    if (separation > margin) continue;
    ContactPoint& point = candidates[kept++];
    const Vec3 onRef = p - separation * refPlane.normal;
    point.depth = -separation;
    if (refIsA) {
      point.pointOnA = onRef;
      point.pointOnB = p;
      point.featureId = in[i].featureId;
    } else {
      point.pointOnA = p;
      point.pointOnB = onRef;
      point.featureId = swapFeatures(in[i].featureId);
    }
  }
  out.normal = refIsA ? refPlane.normal : -refPlane.normal;
  reduceContacts(std::span<const ContactPoint>(candidates.data(), kept), out.normal, out);
  return out.count > 0;
}

bool edgeContact(const WorldPolyhedron& a, const WorldPolyhedron& b, const EdgeQuery& query, float margin,
                 Manifold& out) {
  const Vec3 pA = a.vertices[a.hull->halfEdges()[query.edgeA].origin];
  const Vec3 pB = b.vertices[b.hull->halfEdges()[query.edgeB].origin];
  const SegmentPair closest =
      closestPointsSegmentSegment(pA, a.edgeEnd(query.edgeA), pB, b.edgeEnd(query.edgeB));
  ContactPoint& point = out.points[0];
  point.pointOnA = closest.pointOnFirst;
  point.pointOnB = closest.pointOnSecond;
  point.depth = glm::dot(point.pointOnA - point.pointOnB, query.axis);
  point.featureId = featurePair(a.edgeFeature(query.edgeA), b.edgeFeature(query.edgeB));
  out.normal = query.axis;
  out.count = point.depth >= -margin ? 1 : 0;
  return out.count > 0;
}

}  // namespace

SatAxis polyhedraSeparation(const Shape& shapeA, const Transform& transformA, const Shape& shapeB,
                            const Transform& transformB) {
  thread_local Scratch scratch;
  const WorldPolyhedron a = place(shapeA, transformA, 0, scratch);
  const WorldPolyhedron b = place(shapeB, transformB, 1, scratch);
  const FaceQuery faceA = queryFaces(a, b);
  const FaceQuery faceB = queryFaces(b, a);
  const EdgeQuery edge = queryEdges(a, b);
  SatAxis best{faceA.separation, a.planes[faceA.face].normal};
  if (faceB.separation > best.separation) best = {faceB.separation, -b.planes[faceB.face].normal};
  if (edge.separation > best.separation) best = {edge.separation, edge.axis};
  return best;
}

bool collidePolyhedra(const Shape& shapeA, const Transform& transformA, const Shape& shapeB,
                      const Transform& transformB, float margin, Manifold& out) {
  out.count = 0;
  thread_local Scratch scratch;
  const WorldPolyhedron a = place(shapeA, transformA, 0, scratch);
  const WorldPolyhedron b = place(shapeB, transformB, 1, scratch);

  const FaceQuery faceA = queryFaces(a, b);
  if (faceA.separation > margin) return false;
  const FaceQuery faceB = queryFaces(b, a);
  if (faceB.separation > margin) return false;
  const EdgeQuery edge = queryEdges(a, b);
  if (edge.separation > margin) return false;

  // Prefer a face over an edge pair unless the edge is clearly better (Box2D's relative 0.98 plus
  // an absolute tolerance, here relative to the shapes' size), so that a resting pair keeps its
  // reference face from step to step. Between two faces within that tolerance, the larger face is
  // the reference (the ground under a box), whichever order the pair comes in, so that
  // collide(B, A) mirrors collide(A, B); equal areas fall back to the better separation.
  constexpr float kRelative = 0.98f;
  const float absolute = 1e-3f * std::min(a.size, b.size);
  const float tolerance =
      (1.0f - kRelative) * std::max(std::abs(faceA.separation), std::abs(faceB.separation)) + absolute;
  bool referenceIsB = faceB.separation > faceA.separation;
  if (std::abs(faceA.separation - faceB.separation) <= tolerance) {
    const float areaA = faceArea(a, faceA.face), areaB = faceArea(b, faceB.face);
    if (std::abs(areaA - areaB) > 1e-4f * std::max(areaA, areaB)) referenceIsB = areaB > areaA;
  }
  const float faceSeparation = referenceIsB ? faceB.separation : faceA.separation;
  if (edge.separation > kRelative * faceSeparation + absolute && edgeContact(a, b, edge, margin, out)) {
    return true;
  }
  if (referenceIsB) return faceContact(b, faceB.face, a, false, margin, out);
  return faceContact(a, faceA.face, b, true, margin, out);
}

// ---- A triangle against a polyhedron ----
//
// The triangle is a flat polyhedron: two faces (n and -n) and three edges. Its Gauss map is the
// two poles ±n joined by three half circles, one per edge, each through the edge's outward
// in-plane normal: an edge's arc spans 180°, so the arc test above (for arcs shorter than a half
// circle) does not serve it. Instead, the polyhedron's negated arc (-m1, -m2) must cross the
// great circle of directions perpendicular to the edge, and the crossing point must lie on the
// edge's side of the triangle.

namespace {

// Face contact on the triangle's face, seen from `side` (+1: the polyhedron above the front):
// the polyhedron's incident face clipped against the triangle's three side planes.
void triangleFaceContact(const TriangleFrame& t, const SatTriangle& triangle, float side,
                         const WorldPolyhedron& poly, float margin, std::vector<NormalContact>& contacts) {
  const Vec3 normal = side * t.normal;  // from the triangle to the polyhedron
  const float offset = glm::dot(normal, t.v[0]);
  const std::uint32_t incFace = incidentFace(poly, normal);
  constexpr std::size_t kMaxClip = 64;
  std::array<ClipVertex, kMaxClip> bufferA, bufferB;
  std::size_t count = 0;
  const ConvexHull::Face& face = poly.hull->faces()[incFace];
  std::uint32_t h = face.firstEdge;
  for (std::uint32_t k = 0; k < face.edgeCount && count < kMaxClip; ++k) {
    const std::uint32_t vertex = poly.hull->halfEdges()[h].origin;
    bufferA[count++] = {poly.vertices[vertex], featurePair(0, poly.vertexFeature(vertex))};
    h = poly.hull->halfEdges()[h].next;
  }
  ClipVertex* in = bufferA.data();
  ClipVertex* next = bufferB.data();
  for (std::uint32_t k = 0; k < 3 && count > 0; ++k) {
    count = clipPolygon(std::span<const ClipVertex>(in, count),
                        Plane{t.outward[k], glm::dot(t.outward[k], t.v[k])},
                        std::span<ClipVertex>(next, kMaxClip), [&](const ClipVertex& a, const ClipVertex& b) {
                          const std::uint32_t bits = ((a.featureId & b.featureId) & kSideBits) | (1u << k);
                          return featurePair(bits, mixClip(a.featureId >> 16, b.featureId >> 16));
                        });
    std::swap(in, next);
  }
  for (std::size_t i = 0; i < count; ++i) {
    const Vec3 p = in[i].position;
    const float separation = glm::dot(normal, p) - offset;
    if (separation > margin) continue;
    const std::uint32_t bits = in[i].featureId & kSideBits;
    if (insideFlatPatch(triangle, bits)) continue;
    NormalContact contact;
    contact.normal = normal;
    contact.point.pointOnA = p - separation * normal;
    contact.point.pointOnB = p;
    contact.point.depth = -separation;
    contact.point.featureId = featurePair(meshFeature(triangle, bits), in[i].featureId >> 16);
    contacts.push_back(contact);
  }
}

// Face contact on a face of the polyhedron: the triangle clipped against its side planes.
void polyhedronFaceContact(const TriangleFrame& t, const SatTriangle& triangle, const WorldPolyhedron& poly,
                           std::uint32_t refFace, float margin, std::vector<NormalContact>& contacts) {
  const Plane& refPlane = poly.planes[refFace];
  constexpr std::size_t kMaxClip = 64;
  std::array<ClipVertex, kMaxClip> bufferA, bufferB;
  std::size_t count = 3;
  // Vertex k lies on sides k - 1 and k.
  for (int k = 0; k < 3; ++k) {
    bufferA[k] = {t.v[k], featurePair((1u << k) | (1u << ((k + 2) % 3)), poly.faceFeature(refFace))};
  }
  ClipVertex* in = bufferA.data();
  ClipVertex* next = bufferB.data();
  const ConvexHull::Face& face = poly.hull->faces()[refFace];
  std::uint32_t h = face.firstEdge;
  for (std::uint32_t k = 0; k < face.edgeCount && count > 0; ++k) {
    const Vec3 start = poly.vertices[poly.hull->halfEdges()[h].origin];
    const Vec3 side = glm::normalize(glm::cross(poly.edgeEnd(h) - start, refPlane.normal));
    const std::uint32_t sideFeature = poly.edgeFeature(h);
    count = clipPolygon(std::span<const ClipVertex>(in, count), Plane{side, glm::dot(side, start)},
                        std::span<ClipVertex>(next, kMaxClip), [&](const ClipVertex& a, const ClipVertex& b) {
                          const std::uint32_t bits = a.featureId & b.featureId & kSideBits;
                          return featurePair(bits, mixClip(sideFeature, (a.featureId ^ b.featureId) >> 16));
                        });
    std::swap(in, next);
    h = poly.hull->halfEdges()[h].next;
  }
  if (count == 0 || std::none_of(in, in + count, [&](const ClipVertex& v) {
        return refPlane.signedDistance(v.position) <= margin;
      })) {
    int deepest = 0;
    for (int k = 1; k < 3; ++k) {
      if (refPlane.signedDistance(t.v[k]) < refPlane.signedDistance(t.v[deepest])) deepest = k;
    }
    in[0] = {t.v[deepest],
             featurePair((1u << deepest) | (1u << ((deepest + 2) % 3)), poly.faceFeature(refFace))};
    count = 1;
  }
  for (std::size_t i = 0; i < count; ++i) {
    const Vec3 p = in[i].position;
    const float separation = refPlane.signedDistance(p);
    if (separation > margin) continue;
    NormalContact contact;
    contact.normal = -refPlane.normal;
    contact.point.pointOnA = p;
    contact.point.pointOnB = p - separation * refPlane.normal;
    contact.point.depth = -separation;
    contact.point.featureId =
        featurePair(meshFeature(triangle, in[i].featureId & kSideBits), in[i].featureId >> 16);
    contacts.push_back(contact);
  }
}

}  // namespace

void collideTrianglesPolyhedron(std::span<const SatTriangle> triangles, const Shape& shape,
                                const Transform& transform, float margin,
                                std::vector<NormalContact>& contacts) {
  thread_local Scratch scratch;
  const WorldPolyhedron poly = place(shape, transform, 0, scratch);
  const auto edges = poly.hull->halfEdges();
  for (const SatTriangle& triangle : triangles) {
    const TriangleFrame t = frameOf(triangle.vertices);
    // 1. The triangle's face, from the side the polyhedron is on.
    float lowest = 1e30f, highest = -1e30f;
    for (const Vec3& p : poly.vertices) {
      const float d = glm::dot(t.normal, p);
      lowest = std::min(lowest, d);
      highest = std::max(highest, d);
    }
    const float planeOffset = glm::dot(t.normal, t.v[0]);
    const float frontSeparation = lowest - planeOffset, backSeparation = planeOffset - highest;
    const float side = frontSeparation >= backSeparation ? 1.0f : -1.0f;
    const float triangleSeparation = std::max(frontSeparation, backSeparation);
    if (triangleSeparation > margin) continue;
    // 2. The polyhedron's faces against the triangle's vertices.
    float faceSeparation = -1e30f;
    std::uint32_t face = 0;
    for (std::uint32_t f = 0; f < poly.planes.size(); ++f) {
      const Plane& plane = poly.planes[f];
      const float s = std::min({glm::dot(plane.normal, t.v[0]), glm::dot(plane.normal, t.v[1]),
                                glm::dot(plane.normal, t.v[2])}) -
                      plane.distance;
      if (s > faceSeparation) {
        faceSeparation = s;
        face = f;
      }
    }
    if (faceSeparation > margin) continue;
    // 3. Edge pairs crossing on the Gauss map.
    float edgeSeparation = -1e30f;
    int edgeT = 0;
    std::uint32_t edgeP = 0;
    Vec3 edgeAxis(0.0f);
    for (std::uint32_t j = 0; j < edges.size(); ++j) {
      const ConvexHull::HalfEdge& halfEdge = edges[j];
      if (halfEdge.twin < j) continue;
      const Vec3 a = -poly.planes[halfEdge.face].normal, b = -poly.planes[edges[halfEdge.twin].face].normal;
      const Vec3 origin = poly.vertices[halfEdge.origin];
      const Vec3 direction = poly.edgeEnd(j) - origin;
      for (int k = 0; k < 3; ++k) {
        const float da = glm::dot(a, t.edge[k]), db = glm::dot(b, t.edge[k]);
        if (!(da * db < 0.0f)) continue;
        const Vec3 crossing = (db > 0.0f ? 1.0f : -1.0f) * (db * a - da * b);
        if (glm::dot(crossing, t.outward[k]) <= 0.0f) continue;
        Vec3 axis = glm::cross(t.edge[k], direction);
        const float length = glm::length(axis);
        if (length < 1e-5f * glm::length(t.edge[k]) * glm::length(direction)) continue;
        axis /= length;
        if (glm::dot(axis, crossing) < 0.0f) axis = -axis;
        const float separation = glm::dot(axis, origin - t.v[k]);
        if (separation > edgeSeparation) {
          edgeSeparation = separation;
          edgeT = k;
          edgeP = j;
          edgeAxis = axis;
        }
      }
    }
    if (edgeSeparation > margin) continue;

    // The triangle's face is the reference unless the polyhedron's face is clearly better, and a
    // face unless an edge pair is clearly better (the tolerances of collidePolyhedra): the surface
    // under a resting body stays the reference whatever the triangle's size.
    constexpr float kRelative = 0.98f;
    const float absolute = 1e-3f * std::min(t.size, poly.size);
    const bool polyhedronFace = faceSeparation > kRelative * triangleSeparation + absolute;
    const float bestFace = polyhedronFace ? faceSeparation : triangleSeparation;
    const std::size_t before = contacts.size();
    Vec3 normal = side * t.normal;
    if (edgeSeparation > kRelative * bestFace + absolute) {
      const SegmentPair closest = closestPointsSegmentSegment(
          t.v[edgeT], t.v[(edgeT + 1) % 3], poly.vertices[edges[edgeP].origin], poly.edgeEnd(edgeP));
      NormalContact contact;
      contact.normal = edgeAxis;
      contact.point.pointOnA = closest.pointOnFirst;
      contact.point.pointOnB = closest.pointOnSecond;
      contact.point.depth = glm::dot(closest.pointOnFirst - closest.pointOnSecond, edgeAxis);
      contact.point.featureId = featurePair(triangle.edgeFeature[edgeT], poly.edgeFeature(edgeP));
      if (contact.point.depth >= -margin) {
        contacts.push_back(contact);
        normal = edgeAxis;
      }
    }
    if (contacts.size() == before && polyhedronFace) {
      polyhedronFaceContact(t, triangle, poly, face, margin, contacts);
      normal = -poly.planes[face].normal;
    }
    if (contacts.size() == before) {
      triangleFaceContact(t, triangle, side, poly, margin, contacts);
    } else if (!normalAllowed(t, triangle, normal)) {
      // Internal edge: the contact would push along an edge or vertex inside a flat patch or a
      // concave fold (a bump for a body sliding over it). The face's contact replaces it.
      contacts.resize(before);
      triangleFaceContact(t, triangle, side, poly, margin, contacts);
    }
  }
}

}  // namespace collide::detail
