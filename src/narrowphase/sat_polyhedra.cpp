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
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "geometry/clipping.h"
#include "geometry/closest_points.h"
#include "geometry/support_scan.h"
#include "narrowphase/pair_functions.h"
#include "narrowphase/triangle_features.h"
#include "simd/simd.h"

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

// An edge of a placed polyhedron, once (the smaller of its two half-edges), with what the edge
// query needs: its world segment and its two faces (the half-edge's, then its twin's). Made only
// for the edges of B that the query keeps (facesBehind).
struct WorldEdge {
  Vec3 origin{0.0f};
  Vec3 direction{0.0f};  // end - origin
  std::uint32_t halfEdge = 0;
  std::uint32_t face1 = 0, face2 = 0;
};

// A polyhedron placed in the world: the hull's topology with world vertices and face planes.
struct WorldPolyhedron {
  const ConvexHull* hull = nullptr;
  const UnitCube* cube = nullptr;  // set for a box: its features are named by box codes
  std::span<const Vec3> vertices;  // world
  std::span<const Plane> planes;   // world, outward unit normals
  // The face normals and distances again as blocks of x, y, z and d (blockStride each: the face
  // count rounded up to kFaceBlock, the padding faces with a zero normal and a distance of 1e30, so
  // that they never separate anything), for loops over the faces that the compiler vectorises
  // without a remainder loop.
  std::span<const float> normalBlocks;
  std::size_t blockStride = 0;
  // The world vertices again as blocks of x, y and z (blockCoordinates' layout: vertexStride each,
  // padded with copies of vertex 0), for the face query's exact test and the farthest vertex.
  std::span<const float> vertexBlocks;
  std::size_t vertexStride = 0;
  Vec3 inside{0.0f};  // a point inside the solid (its centroid): edge axes point away from it
  // The radius of the ball about `inside` that the solid holds: its least distance to a face plane.
  float inradius = 0.0f;
  float size = 0.0f;  // a length of the shape's scale, for tolerances

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

// The face loops run over whole blocks of this many faces (and vertices): one FloatW, the block of
// blockedLanes (support_scan.h), which pads both the faces and the vertices.
constexpr std::size_t kFaceBlock = kLanes;
static_assert(blockedLanes(1) == kFaceBlock);
constexpr float kPaddingDistance = 1e30f;

// The first index of the largest of values[0, count) (NaNs never win; 0 if all are NaN); `padded`
// of them (a multiple of kFaceBlock) may be read, those past `count` being no larger than the real
// ones.
std::uint32_t firstLargest(const float* __restrict values, std::size_t count, std::size_t padded) {
  FloatW best = splat(-std::numeric_limits<float>::infinity());
  for (std::size_t f = 0; f < padded; f += kFaceBlock) best = maxW(loadW(values + f), best);
  float largest = laneOf(best, 0);
  for (int j = 1; j < kLanes; ++j) largest = laneOf(best, j) > largest ? laneOf(best, j) : largest;
  for (std::uint32_t index = 0; index < count; ++index) {
    if (values[index] == largest) return index;
  }
  return 0;
}

// Per-thread scratch for the world vertices and planes of both shapes: no allocation once warm.
struct Scratch {
  Array<Vec3> vertices[2];
  Array<Plane> planes[2];
  Array<float> normalBlocks[2];
  Array<float> lowest;             // per face: the face query's bound, the triangle test's separation
  Array<float> arcSides;           // the triangle test's face normals dotted with each triangle edge
  Array<WorldEdge> edgesB;         // the edges of B that the edge query keeps
  Array<float> keptEdgeBlocks;     // their face and arc normals as blocks (queryEdges)
  Array<std::uint32_t> behind[2];  // per face: which of the other shape's points lie behind it
};

// The placed polyhedra of this thread, by hull and pose: within a step each body keeps its pose, so
// one placed for a pair serves every other pair of that body (a hull meets the terrain and each of
// its neighbours). Direct-mapped; an entry is the same computation's result, so a hit changes
// nothing. Slot 0 of a query is placed first; slot 1 never takes slot 0's entry from under it.
struct PlacementCache {
  static constexpr std::size_t kEntries = 256;
  struct Entry {
    const ConvexHull* hull = nullptr;
    std::uint64_t serial = 0;  // with the address: a hull freed and another built in its place differ here
    Vec3 scale{0.0f};
    Transform transform;
    Array<Vec3> vertices;
    Array<Plane> planes;
    Array<float> normalBlocks;
    WorldPolyhedron poly;
  };
  std::array<Entry, kEntries> entries;
  std::size_t slotEntry[2] = {kEntries, kEntries};
};

// On the hull's serial, not its address: the same inputs then use the same entries in every run,
// so that even the work saved is reproducible (and a fuzzer's coverage with it).
std::size_t placementHash(const ConvexHull& hull, const Transform& transform) {
  std::uint32_t bits[3];
  std::memcpy(bits, &transform.position, sizeof bits);
  std::uint64_t h = hull.serial() * 0x9E3779B97F4A7C15ull;
  for (const std::uint32_t b : bits) h = (h ^ b) * 0x100000001B3ull;
  return static_cast<std::size_t>(h ^ (h >> 29));
}

void placeInto(const ConvexHull& hull, const Transform& transform, const Vec3& localScale,
               Array<Vec3>& vertices, Array<Plane>& planes, Array<float>& blocks, WorldPolyhedron& poly) {
  const Mat3 rotation = glm::mat3_cast(transform.rotation);
  vertices.resize(hull.vertices().size());
  planes.resize(hull.faces().size());
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    vertices[i] = transform.position + rotation * (localScale * hull.vertices()[i]);
  }
  for (std::size_t f = 0; f < planes.size(); ++f) {
    const ConvexHull::Face& face = hull.faces()[f];
    // A box's faces are axis-aligned, so its non-uniform scale leaves their normals alone. The
    // face's vertex by its index, not through its half-edge, so that the placement reads only the
    // face record: with a large scene's hulls out of cache, each link followed is a dependent load
    // that misses.
    const Vec3 normal = rotation * face.plane.normal;
    planes[f] = {normal, glm::dot(normal, vertices[face.firstVertex])};
  }
  const std::size_t stride = blockedLanes(planes.size());
  const std::size_t vertexStride = blockedLanes(vertices.size());
  blocks.assign(4 * stride + 3 * vertexStride, 0.0f);
  for (std::size_t f = 0; f < planes.size(); ++f) {
    for (int axis = 0; axis < 3; ++axis) blocks[axis * stride + f] = planes[f].normal[axis];
    blocks[3 * stride + f] = planes[f].distance;
  }
  for (std::size_t f = planes.size(); f < stride; ++f) blocks[3 * stride + f] = kPaddingDistance;
  float* vertexBlocks = blocks.data() + 4 * stride;
  blockCoordinatesInto(vertices, vertexBlocks);
  poly.vertices = vertices;
  poly.planes = planes;
  poly.normalBlocks = std::span<const float>(blocks.data(), 4 * stride);
  poly.blockStride = stride;
  poly.vertexBlocks = std::span<const float>(vertexBlocks, 3 * vertexStride);
  poly.vertexStride = vertexStride;
  const Aabb bounds = hull.bounds();
  poly.inside = transform.position + rotation * (localScale * hull.centroid());
  poly.inradius = 1e30f;
  for (const Plane& plane : planes) {
    poly.inradius = std::min(poly.inradius, plane.distance - glm::dot(plane.normal, poly.inside));
  }
  poly.size = glm::length(localScale * bounds.halfExtents());
}

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
  thread_local PlacementCache cache;
  const std::size_t index = placementHash(hull, transform) % PlacementCache::kEntries;
  if (slot == 0) cache.slotEntry[1] = PlacementCache::kEntries;  // a new query: slot 1 is free again
  if (slot == 1 && index == cache.slotEntry[0]) {
    // Slot 0 of this query holds the entry: placed apart, uncached.
    placeInto(hull, transform, localScale, scratch.vertices[slot], scratch.planes[slot],
              scratch.normalBlocks[slot], poly);
    return poly;
  }
  PlacementCache::Entry& entry = cache.entries[index];
  cache.slotEntry[slot] = index;
  if (entry.hull == poly.hull && entry.serial == hull.serial() && entry.scale == localScale &&
      entry.transform.position == transform.position && entry.transform.rotation == transform.rotation &&
      entry.transform.scale == transform.scale) {
    return entry.poly;
  }
  placeInto(hull, transform, localScale, entry.vertices, entry.planes, entry.normalBlocks, poly);
  entry.hull = poly.hull;
  entry.serial = hull.serial();
  entry.scale = localScale;
  entry.transform = transform;
  entry.poly = poly;
  return poly;
}

struct FaceQuery {
  float separation = -1e30f;
  std::uint32_t face = 0;
};

// The separation of B from face f of A: the plane's distance to B's lowest vertex against it,
// B's vertices a block at a time.
float faceSeparation(const WorldPolyhedron& a, std::uint32_t f, const WorldPolyhedron& b) {
  const std::size_t stride = a.blockStride;
  const float* blocks = a.normalBlocks.data();
  const FloatW x = splat(blocks[f]), y = splat(blocks[stride + f]), z = splat(blocks[2 * stride + f]);
  const std::size_t vertexStride = b.vertexStride;
  const float* xs = b.vertexBlocks.data();
  const float* ys = xs + vertexStride;
  const float* zs = ys + vertexStride;
  FloatW low = splat(1e30f);
  for (std::size_t i = 0; i < vertexStride; i += kFaceBlock) {
    low = minW(loadW(xs + i) * x + loadW(ys + i) * y + loadW(zs + i) * z, low);
  }
  float lowest = laneOf(low, 0);
  for (int j = 1; j < kLanes; ++j) lowest = laneOf(low, j) < lowest ? laneOf(low, j) : lowest;
  return lowest - blocks[3 * stride + f];
}

// The largest separation of B from a face plane of A (the first such face on a tie). B holds the
// ball of radius r about its centroid c (WorldPolyhedron::inradius), so B's lowest point along a
// face normal n is at most n . c - r, and its separation from that face (n, d) at most
// n . c - r - d. Those bounds, all faces at once over the blocked normals, leave the exact test
// (every vertex of B) to the faces that can still beat the best found: for a touching pair, the
// few that face B.
FaceQuery queryFaces(const WorldPolyhedron& a, const WorldPolyhedron& b, Scratch& scratch) {
  const std::size_t stride = a.blockStride;
  const std::size_t faces = a.planes.size();
  Array<float>& bounds = scratch.lowest;
  bounds.resize(stride);
  const float* __restrict xs = a.normalBlocks.data();
  const float* __restrict ys = xs + stride;
  const float* __restrict zs = ys + stride;
  const float* __restrict ds = zs + stride;
  float* __restrict bound = bounds.data();
  const Vec3 c = b.inside;
  // Rounding of the bound and of the exact separation, both within 1e-6 of the shapes' size.
  const float reach = b.inradius - 1e-4f * (a.size + b.size);
  for (std::size_t j = 0; j < stride; ++j) bound[j] = xs[j] * c.x + ys[j] * c.y + zs[j] * c.z - ds[j] - reach;
  FaceQuery best;
  const std::uint32_t first = firstLargest(bound, faces, stride);
  best.face = first;
  best.separation = faceSeparation(a, first, b);
  // The candidates a block at a time against the first face's separation, then each against the
  // best so far.
  const FloatW firstSeparation = splat(best.separation);
  for (std::size_t block = 0; block < stride; block += kFaceBlock) {
    unsigned candidates = ~maskBits(greaterW(firstSeparation, loadW(bound + block))) & ((1u << kLanes) - 1u);
    while (candidates != 0) {
      const auto f = static_cast<std::uint32_t>(block + static_cast<unsigned>(std::countr_zero(candidates)));
      candidates &= candidates - 1;
      if (f >= faces) break;
      if (f == first || !(bound[f] >= best.separation)) continue;
      const float separation = faceSeparation(a, f, b);
      if (separation > best.separation || (separation == best.separation && f < best.face)) {
        best.separation = separation;
        best.face = f;
      }
    }
  }
  return best;
}

struct EdgeQuery {
  float separation = -1e30f;
  std::uint32_t edgeA = 0, edgeB = 0;  // half-edge indices
  Vec3 axis{0.0f};                     // from A to B
};

// Which edges can be part of an edge pair whose separation exceeds `threshold` (<= 0 here)
// against the other shape, of which `others` are points. The pair's axis L lies on the edge's
// Gauss-map arc (between its faces' normals n1 and n2, where the edge is its shape's support), and
// the separation along L is at most L · (q - p) for any q of the other shape and p on the edge. Over
// the arc that linear function peaks at an end unless its direction lies inside the arc, where one
// end already sees a positive value; so when n1 · (q - p) and n2 · (q - p) are both at most the
// threshold, so is every pair of this edge. p lies on both faces' planes: those are q's signed
// distances from them, one per face for all edges. Bit k of mask[f] says that others[k] lies
// behind face f by more than -threshold (the planes hold their vertices to the hull's merge
// tolerance, 1e-6 of its size, well inside the callers' rounding allowance); an edge whose two
// faces share a bit cannot matter.
void facesBehind(const WorldPolyhedron& poly, std::span<const Vec3> others, float threshold,
                 Array<std::uint32_t>& mask) {
  const std::size_t stride = poly.blockStride;
  mask.assign(stride, 0);
  const float* __restrict xs = poly.normalBlocks.data();
  const float* __restrict ys = xs + stride;
  const float* __restrict zs = ys + stride;
  const float* __restrict ds = zs + stride;
  std::uint32_t* __restrict out = mask.data();
  for (std::size_t k = 0; k < others.size(); ++k) {
    const Vec3 q = others[k];
    const std::uint32_t bit = 1u << k;
    for (std::size_t j = 0; j < stride; ++j) {
      const float distance = xs[j] * q.x + ys[j] * q.y + zs[j] * q.z - ds[j];
      out[j] |= distance <= threshold ? bit : 0u;
    }
  }
}

// A vertex of `poly` farthest along `direction`.
Vec3 farthestVertex(const WorldPolyhedron& poly, const Vec3& direction) {
  const auto count = static_cast<std::uint32_t>(poly.vertices.size());
  return poly.vertices[farthestAlong(poly.vertexBlocks.data(), count, direction)];
}

// The edges of B whose faces facesBehind does not rule out: made once per query, so that the loop
// over A's edges reads them without following B's topology.
void keepEdges(const WorldPolyhedron& b, const Array<std::uint32_t>& behindB, Array<WorldEdge>& kept) {
  kept.clear();
  for (const ConvexHull::Edge& edge : b.hull->edges()) {
    if (behindB[edge.face1] & behindB[edge.face2]) continue;
    // Written in place, field by field: a whole struct built on the stack and copied in would be
    // read back before its parts are stored, a store-forwarding stall per edge.
    WorldEdge& kept1 = kept.emplace_back();
    kept1.origin = b.vertices[edge.origin];
    kept1.direction = b.vertices[edge.end] - kept1.origin;
    kept1.halfEdge = edge.halfEdge;
    kept1.face1 = edge.face1;
    kept1.face2 = edge.face2;
  }
}

// The kept edges of B again as blocks: the normals n1 and n2 of each edge's two faces and its arc
// normal cross(n2, n1) (the arc's ends lie on either side of a plane through the origin exactly
// when their dot products with it differ in sign, Gregorius 2013), nine rows of `stride` floats
// (padding lanes zero, which never pass the arc test). The Gauss-map test of an edge of A then runs
// against a block of B's edges at a time, without a branch per pair (the pairs that pass are few,
// and which ones is unpredictable); those that pass go on one by one, in the order of B's edges, so
// the answer is the one the pair-by-pair loop gives. Returns the stride.
std::size_t blockKeptEdges(const WorldPolyhedron& b, const Array<WorldEdge>& kept, Array<float>& blocks) {
  const std::size_t keptCount = kept.size();
  const std::size_t stride = blockedLanes(keptCount);
  blocks.assign(9 * stride, 0.0f);
  for (std::size_t k = 0; k < keptCount; ++k) {
    const Vec3& n1 = b.planes[kept[k].face1].normal;
    const Vec3& n2 = b.planes[kept[k].face2].normal;
    const Vec3 arcNormal = glm::cross(n2, n1);
    for (int axis = 0; axis < 3; ++axis) {
      blocks[axis * stride + k] = n1[axis];
      blocks[(3 + axis) * stride + k] = n2[axis];
      blocks[(6 + axis) * stride + k] = arcNormal[axis];
    }
  }
  return stride;
}

// The edge pairs whose Gauss-map arcs cross, and the largest separation along their cross
// products. Arc (a, b) is the Gauss image of an edge of A between faces with normals a and b; (c, d)
// that of an edge of B, negated (the Minkowski difference A - B has -B's normals). Two arcs cross
// when each one's endpoints lie on opposite sides of the other's great circle, and they lie on the
// same hemisphere (Gregorius 2013). The first half of that test needs, for an edge of A, the side
// of every face normal of B against A's arc: computed once per edge of A over B's blocked normals
// (F_B dot products, vectorised) instead of twice per pair, it rejects most pairs with two loads and
// a product; the survivors take the rest of the test and then their axis.
//
// Pairs whose separation cannot exceed `irrelevantBelow` are skipped (facesBehind): the caller
// decides nothing by them (a face is preferred unless an edge pair is clearly better, and only a
// separation above the margin makes the pair apart), and for resting pairs that is most edges of
// both shapes, those facing away from the other. The answer is the plain pairwise test's whenever
// its separation exceeds irrelevantBelow. Returns as soon as a separation above `stopAbove` is
// found (the pair is apart: the caller needs no more).
EdgeQuery queryEdges(const WorldPolyhedron& a, const WorldPolyhedron& b, float stopAbove,
                     float irrelevantBelow, const Vec3& towardB, Scratch& scratch) {
  EdgeQuery best;
  // Rounding of the bound: the pruned separations are below the threshold by more than this.
  const float threshold = std::min(irrelevantBelow, 0.0f) - 1e-5f * (a.size + b.size);
  // Points of each shape to prune the other's edges with: its centroid and its vertex deepest
  // towards the other along the reference normal (near the contact, where the relevant edges are).
  const Vec3 pointsOfA[2] = {a.inside, farthestVertex(a, towardB)};
  const Vec3 pointsOfB[2] = {b.inside, farthestVertex(b, -towardB)};
  Array<std::uint32_t>& behindA = scratch.behind[0];
  Array<std::uint32_t>& behindB = scratch.behind[1];
  facesBehind(a, pointsOfB, threshold, behindA);
  facesBehind(b, pointsOfA, threshold, behindB);
  Array<WorldEdge>& kept = scratch.edgesB;
  keepEdges(b, behindB, kept);
  if (kept.empty()) return best;
  Array<float>& blocks = scratch.keptEdgeBlocks;
  const std::size_t stride = blockKeptEdges(b, kept, blocks);
  const FloatW zero = zeroW();
  for (const ConvexHull::Edge& edge : a.hull->edges()) {
    if (behindA[edge.face1] & behindA[edge.face2]) continue;
    const std::uint32_t h = edge.halfEdge;
    const Vec3 originA = a.vertices[edge.origin];
    const Vec3 normalA1 = a.planes[edge.face1].normal;
    const Vec3 normalA2 = a.planes[edge.face2].normal;
    const Vec3 u = glm::cross(normalA2, normalA1);
    const Vec3 directionA = a.vertices[edge.end] - originA;
    const FloatW ux = splat(u.x), uy = splat(u.y), uz = splat(u.z);
    const FloatW a1x = splat(normalA1.x), a1y = splat(normalA1.y), a1z = splat(normalA1.z);
    const FloatW a2x = splat(normalA2.x), a2y = splat(normalA2.y), a2z = splat(normalA2.z);
    for (std::size_t block = 0; block < stride; block += kFaceBlock) {
      const float* row = blocks.data() + block;
      // With c = -nB1 and d = -nB2 (B's arc), the arcs cross where (c · u)(d · u) < 0,
      // (a · (d x c))(b · (d x c)) < 0 and (c · u)(b · (d x c)) > 0 (Gregorius 2013); c · u is
      // -side1, d · u is -side2, and the signs are those of the products below.
      const FloatW side1 = loadW(row) * ux + loadW(row + stride) * uy + loadW(row + 2 * stride) * uz;
      const FloatW side2 =
          loadW(row + 3 * stride) * ux + loadW(row + 4 * stride) * uy + loadW(row + 5 * stride) * uz;
      const FloatW arcX = loadW(row + 6 * stride), arcY = loadW(row + 7 * stride),
                   arcZ = loadW(row + 8 * stride);
      const FloatW adc = a1x * arcX + a1y * arcY + a1z * arcZ;
      const FloatW bdc = a2x * arcX + a2y * arcY + a2z * arcZ;
      unsigned crossing = maskBits(
          andW(andW(greaterW(zero, side1 * side2), greaterW(zero, adc * bdc)), greaterW(zero, side1 * bdc)));
      while (crossing != 0) {
        const WorldEdge& edgeB = kept[block + static_cast<unsigned>(std::countr_zero(crossing))];
        crossing &= crossing - 1;
        Vec3 axis = glm::cross(directionA, edgeB.direction);
        const float length = glm::length(axis);
        // Parallel edges: their cross product has no direction (the face axes cover that case).
        if (length < 1e-5f * glm::length(directionA) * glm::length(edgeB.direction)) continue;
        axis /= length;
        if (glm::dot(axis, originA - a.inside) < 0.0f) axis = -axis;
        const float separation = glm::dot(axis, edgeB.origin - originA);
        if (separation > best.separation) {
          best.separation = separation;
          best.edgeA = h;
          best.edgeB = edgeB.halfEdge;
          best.axis = axis;
          if (separation > stopAbove) return best;
        }
      }
    }
  }
  return best;
}

// The incident face for a reference face with outward `normal`: of the faces around `poly`'s
// deepest vertex along -normal, the one most anti-parallel to the normal. The most anti-parallel face
// of the whole polyhedron need not hold that vertex (a hull resting on a ridge whose two faces are
// steep, next to a flatter face at one end of it), and clipping it would lose the deepest point: the
// hull would sink into the terrain at the vertex its manifold left out. Every face around the
// deepest vertex holds it, and among them the most anti-parallel one is the face a resting body
// lies on (for a box: the face the global search finds).
std::uint32_t incidentFace(const WorldPolyhedron& poly, const Vec3& normal) {
  std::uint32_t deepest = 0;
  for (std::uint32_t v = 1; v < poly.vertices.size(); ++v) {
    if (glm::dot(poly.vertices[v], normal) < glm::dot(poly.vertices[deepest], normal)) deepest = v;
  }
  // The faces around it, in increasing order: the first of the most anti-parallel wins.
  std::uint32_t best = 0;
  float lowest = 1e30f;
  for (const std::uint32_t face : poly.hull->facesAround(deepest)) {
    const float d = glm::dot(poly.planes[face].normal, normal);
    if (d < lowest) {
      lowest = d;
      best = face;
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
  const FaceQuery faceA = queryFaces(a, b, scratch);
  const FaceQuery faceB = queryFaces(b, a, scratch);
  const EdgeQuery edge = queryEdges(a, b, 1e30f, -1e30f, Vec3(0.0f, 1.0f, 0.0f), scratch);
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

  const FaceQuery faceA = queryFaces(a, b, scratch);
  if (faceA.separation > margin) return false;
  const FaceQuery faceB = queryFaces(b, a, scratch);
  if (faceB.separation > margin) return false;

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
  // Edge pairs matter only if they separate the pair (beyond the margin) or beat the face.
  const float edgeMatters = std::min(margin, kRelative * faceSeparation + absolute);
  const Vec3 referenceNormal = referenceIsB ? -b.planes[faceB.face].normal : a.planes[faceA.face].normal;
  const EdgeQuery edge = queryEdges(a, b, margin, edgeMatters, referenceNormal, scratch);
  if (edge.separation > margin) return false;
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
                         const WorldPolyhedron& poly, float margin, Array<NormalContact>& contacts) {
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
  appendClippedFaceContacts(std::span<const ClipVertex>(in, count), triangle, normal, offset, margin,
                            contacts);
}

// Face contact on a face of the polyhedron: the triangle clipped against its side planes.
void polyhedronFaceContact(const TriangleFrame& t, const SatTriangle& triangle, const WorldPolyhedron& poly,
                           std::uint32_t refFace, float margin, Array<NormalContact>& contacts) {
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

// ---- The stages of collideTrianglesPolyhedron, one triangle at a time ----

// 1. The triangle's face, from the side the polyhedron is on (`side` +1: the polyhedron above the
// front). Every triangle near the shape pays for it, and a triangle the polyhedron is clear of
// stops here, before anything else is computed.
float triangleFaceSeparation(const TriangleFrame& t, const WorldPolyhedron& poly, float& side) {
  float lowest = 1e30f, highest = -1e30f;
  for (const Vec3& p : poly.vertices) {
    const float d = glm::dot(t.normal, p);
    lowest = std::min(lowest, d);
    highest = std::max(highest, d);
  }
  const float planeOffset = glm::dot(t.normal, t.v[0]);
  const float frontSeparation = lowest - planeOffset, backSeparation = planeOffset - highest;
  side = frontSeparation >= backSeparation ? 1.0f : -1.0f;
  return std::max(frontSeparation, backSeparation);
}

// 2. The polyhedron's faces against the triangle's vertices, all faces at once over the blocked
// normals so that the loop vectorises; the first of the largest separations wins.
FaceQuery deepestFaceOverTriangle(const WorldPolyhedron& poly, const TriangleFrame& t, Scratch& scratch) {
  const std::size_t stride = poly.blockStride;
  const float* __restrict xs = poly.normalBlocks.data();
  const float* __restrict ys = xs + stride;
  const float* __restrict zs = ys + stride;
  const float* __restrict ds = zs + stride;
  Array<float>& lowestOnFace = scratch.lowest;
  lowestOnFace.resize(stride);
  float* __restrict low = lowestOnFace.data();
  const Vec3 v0 = t.v[0], v1 = t.v[1], v2 = t.v[2];
  for (std::size_t j = 0; j < stride; ++j) {
    const float d0 = xs[j] * v0.x + ys[j] * v0.y + zs[j] * v0.z;
    const float d1 = xs[j] * v1.x + ys[j] * v1.y + zs[j] * v1.z;
    const float d2 = xs[j] * v2.x + ys[j] * v2.y + zs[j] * v2.z;
    const float d01 = d1 < d0 ? d1 : d0;
    low[j] = (d2 < d01 ? d2 : d01) - ds[j];
  }
  const std::uint32_t face = firstLargest(low, poly.planes.size(), stride);
  return {low[face], face};
}

// The best pair of a triangle edge and a polyhedron edge.
struct TriangleEdgeQuery {
  float separation = -1e30f;
  int edgeT = 0;            // triangle edge k, from vertex k
  std::uint32_t edgeP = 0;  // the polyhedron's half-edge
  Vec3 axis{0.0f};          // from the triangle to the polyhedron
};

// 3. Edge pairs crossing on the Gauss map: the polyhedron's negated arc (-n1, -n2) crosses the
// great circle perpendicular to triangle edge k where n1 · e_k and n2 · e_k differ in sign, so
// each face normal's dot product with the three edges is computed once (vectorised over the
// blocked normals) rather than twice per pair. Edges of the polyhedron whose pairs cannot exceed
// `edgeMatters` are skipped (facesBehind: a point of the triangle lies behind both of their faces).
TriangleEdgeQuery queryTriangleEdges(const TriangleFrame& t, const WorldPolyhedron& poly, float margin,
                                     float edgeMatters, Scratch& scratch) {
  const std::size_t stride = poly.blockStride;
  const float* __restrict xs = poly.normalBlocks.data();
  const float* __restrict ys = xs + stride;
  const float* __restrict zs = ys + stride;
  const Vec3 trianglePoints[4] = {(t.v[0] + t.v[1] + t.v[2]) / 3.0f, t.v[0], t.v[1], t.v[2]};
  Array<std::uint32_t>& behind = scratch.behind[0];
  facesBehind(poly, trianglePoints, edgeMatters, behind);
  Array<float>& along = scratch.arcSides;
  along.resize(3 * stride);
  for (int k = 0; k < 3; ++k) {
    const Vec3 e = t.edge[k];
    float* __restrict out = along.data() + k * stride;
    for (std::size_t j = 0; j < stride; ++j) out[j] = xs[j] * e.x + ys[j] * e.y + zs[j] * e.z;
  }
  TriangleEdgeQuery best;
  for (const ConvexHull::Edge& edge : poly.hull->edges()) {
    const std::uint32_t face1 = edge.face1, face2 = edge.face2;
    if (behind[face1] & behind[face2]) continue;
    const std::uint32_t h = edge.halfEdge;
    const Vec3 origin = poly.vertices[edge.origin];
    const Vec3 direction = poly.vertices[edge.end] - origin;
    for (int k = 0; k < 3; ++k) {
      // da = (-n1) · e_k, db = (-n2) · e_k.
      const float da = -along[k * stride + face1], db = -along[k * stride + face2];
      if (!(da * db < 0.0f)) continue;
      const Vec3 a = -poly.planes[face1].normal, b = -poly.planes[face2].normal;
      const Vec3 crossing = (db > 0.0f ? 1.0f : -1.0f) * (db * a - da * b);
      if (glm::dot(crossing, t.outward[k]) <= 0.0f) continue;
      Vec3 axis = glm::cross(t.edge[k], direction);
      const float length = glm::length(axis);
      if (length < 1e-5f * glm::length(t.edge[k]) * glm::length(direction)) continue;
      axis /= length;
      if (glm::dot(axis, crossing) < 0.0f) axis = -axis;
      const float separation = glm::dot(axis, origin - t.v[k]);
      if (separation > best.separation) {
        best.separation = separation;
        best.edgeT = k;
        best.edgeP = h;
        best.axis = axis;
      }
    }
    if (best.separation > margin) break;  // apart: the rest cannot change that
  }
  return best;
}

// 4. Edge contact: the closest points of the two edges. False when they lie beyond the margin, and
// a face contact answers instead.
bool triangleEdgeContact(const TriangleFrame& t, const SatTriangle& triangle, const WorldPolyhedron& poly,
                         const TriangleEdgeQuery& edge, float margin, Array<NormalContact>& contacts) {
  const auto edges = poly.hull->halfEdges();
  const SegmentPair closest =
      closestPointsSegmentSegment(t.v[edge.edgeT], t.v[(edge.edgeT + 1) % 3],
                                  poly.vertices[edges[edge.edgeP].origin], poly.edgeEnd(edge.edgeP));
  NormalContact contact;
  contact.normal = edge.axis;
  contact.point.pointOnA = closest.pointOnFirst;
  contact.point.pointOnB = closest.pointOnSecond;
  contact.point.depth = glm::dot(closest.pointOnFirst - closest.pointOnSecond, edge.axis);
  contact.point.featureId = featurePair(triangle.edgeFeature[edge.edgeT], poly.edgeFeature(edge.edgeP));
  if (!(contact.point.depth >= -margin)) return false;
  contacts.push_back(contact);
  return true;
}

}  // namespace

void collideTrianglesPolyhedron(std::span<const SatTriangle> triangles, const Shape& shape,
                                const Transform& transform, float margin, Array<NormalContact>& contacts) {
  thread_local Scratch scratch;
  const WorldPolyhedron poly = place(shape, transform, 0, scratch);
  for (const SatTriangle& triangle : triangles) {
    TriangleFrame t = planeFrameOf(triangle.vertices);
    float side = 1.0f;
    const float triangleSeparation = triangleFaceSeparation(t, poly, side);
    if (triangleSeparation > margin) continue;
    const FaceQuery deepest = deepestFaceOverTriangle(poly, t, scratch);
    const std::uint32_t face = deepest.face;
    const float faceSeparation = deepest.separation;
    if (faceSeparation > margin) continue;
    completeFrame(t);
    // The triangle's face is the reference unless the polyhedron's face is clearly better, and a
    // face unless an edge pair is clearly better (the tolerances of collidePolyhedra): the surface
    // under a resting body stays the reference whatever the triangle's size.
    constexpr float kRelative = 0.98f;
    const float absolute = 1e-3f * std::min(t.size, poly.size);
    const bool polyhedronFace = faceSeparation > kRelative * triangleSeparation + absolute;
    const float bestFace = polyhedronFace ? faceSeparation : triangleSeparation;
    // Edge pairs matter only if they separate the pair (beyond the margin) or beat the face.
    const float edgeMatters =
        std::min(std::min(margin, kRelative * bestFace + absolute), 0.0f) - 1e-5f * (t.size + poly.size);
    const TriangleEdgeQuery edge = queryTriangleEdges(t, poly, margin, edgeMatters, scratch);
    if (edge.separation > margin) continue;

    const std::size_t before = contacts.size();
    Vec3 normal = side * t.normal;
    if (edge.separation > kRelative * bestFace + absolute &&
        triangleEdgeContact(t, triangle, poly, edge, margin, contacts)) {
      normal = edge.axis;
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
