// Convex hull building. Qhull (Barber, Dobkin and Huhdanpaa, "The Quickhull algorithm for convex
// hulls", ACM TOMS 1996) finds the facets and merges coplanar ones; we turn its facets into the
// half-edge polyhedron of shapes.h (Gregorius, "Implementing Quickhull", GDC 2014, explains why
// merged faces and twin half-edges are what SAT and contact clipping want).
#include "shapes/hull_builder.h"
#include "base/fail.h"
#include "geometry/support_scan.h"

#include "shapes/shape_functions.h"

#if COLLIDE_WITH_QHULL
extern "C" {
#include <libqhull_r/qhull_ra.h>
}
#endif

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace collide {

namespace {

using DVec3 = glm::dvec3;

// The half-edges by their directed endpoints: a half-edge's twin is the one from its end to its origin.
using EdgeMap = std::unordered_map<std::uint64_t, std::uint32_t>;
std::uint64_t edgeKey(std::uint32_t from, std::uint32_t to) { return (std::uint64_t(from) << 32) | to; }

std::string format(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

std::string format(const Vec3& v) {
  std::ostringstream out;
  out << '[' << v.x << ", " << v.y << ", " << v.z << ']';
  return out.str();
}

struct RawFace {
  Array<std::uint32_t> inputIndices;  // Qhull's order, oriented below
  DVec3 qhullNormal{0.0};
};

#if COLLIDE_WITH_QHULL
// Qhull reports through a FILE*: a stream in memory (POSIX's open_memstream) keeps it silent and
// lets us quote its error in ours without touching the file system for every hull. Where there is
// none, a temporary file does, and the null device is the last resort.
class QhullErrorStream {
 public:
  QhullErrorStream() {
#if defined(__unix__) || defined(__APPLE__)
    file_ = open_memstream(&buffer_, &size_);
#endif
    if (!file_) file_ = std::tmpfile();
    if (!file_) file_ = std::fopen("/dev/null", "w");
  }
  ~QhullErrorStream() {
    if (file_) std::fclose(file_);
    std::free(buffer_);  // open_memstream's buffer, valid after the close
  }
  QhullErrorStream(const QhullErrorStream&) = delete;
  QhullErrorStream& operator=(const QhullErrorStream&) = delete;

  FILE* file() const { return file_; }
  // The first line Qhull wrote, or "" (for the null device, or nothing written).
  std::string firstLine() const {
    if (!file_) return {};
    std::fflush(file_);  // a memory stream's buffer and size are current after a flush
    std::string line;
    if (buffer_) {
      line.assign(buffer_, size_);
    } else {
      std::rewind(file_);
      char text[512] = {};
      if (!std::fgets(text, sizeof text, file_)) return {};
      line = text;
    }
    line = line.substr(0, line.find('\n'));
    while (!line.empty() && line.back() == '\r') line.pop_back();
    return line;
  }

 private:
  FILE* file_ = nullptr;
  char* buffer_ = nullptr;
  std::size_t size_ = 0;
};

// Frees every Qhull allocation however we leave the builder.
class QhullSession {
 public:
  explicit QhullSession(FILE* errorFile) { qh_zero(&qh_, errorFile); }
  ~QhullSession() {
    qh_freeqhull(&qh_, !qh_ALL);
    int currentLong = 0, totalLong = 0;
    qh_memfreeshort(&qh_, &currentLong, &totalLong);
  }
  QhullSession(const QhullSession&) = delete;
  QhullSession& operator=(const QhullSession&) = delete;
  qhT* get() { return &qh_; }

 private:
  qhT qh_;
};

// Runs Qhull and reads each (merged) facet's vertices in order around it.
Array<RawFace> runQhull(std::span<const Vec3> points, double mergeDistance) {
  Array<coordT> coordinates;
  coordinates.reserve(points.size() * 3);
  for (const Vec3& p : points) {
    coordinates.push_back(p.x);
    coordinates.push_back(p.y);
    coordinates.push_back(p.z);
  }
  QhullErrorStream errors;
  QhullSession session(errors.file());
  qhT* qh = session.get();  // the FORALL/FOREACH macros expect this name
  // C-n: merge facets whose centrums are within n of each other's planes, so that a cube has 6 quads
  // rather than 12 triangles. No output file: Qhull prints nothing.
  char options[64];
  std::snprintf(options, sizeof options, "qhull C-%.6g", mergeDistance);
  const int exitCode = qh_new_qhull(qh, 3, static_cast<int>(points.size()), coordinates.data(), False,
                                    options, nullptr, errors.file());
  if (exitCode != 0) {
    const std::string detail = errors.firstLine();
    COLLIDE_FAIL("convex_hull: Qhull failed with code " + std::to_string(exitCode) +
                     (detail.empty() ? std::string() : ": " + detail),
                 {});
  }
  Array<RawFace> faces;
  facetT* facet;
  FORALLfacets {
    RawFace face;
    face.qhullNormal = DVec3(facet->normal[0], facet->normal[1], facet->normal[2]);
    setT* ordered = qh_facet3vertex(qh, facet);
    vertexT *vertex, **vertexp;
    FOREACHvertex_(ordered) {
      face.inputIndices.push_back(static_cast<std::uint32_t>(qh_pointid(qh, vertex->point)));
    }
    qh_settempfree(qh, &ordered);
    faces.push_back(std::move(face));
  }
  return faces;
}
#endif  // COLLIDE_WITH_QHULL

// The host's hull triangle finder (collide/hooks.h), if one is installed.
std::atomic<HullTriangleFinder> gHullTriangleFinder{nullptr};
std::atomic<void*> gHullTriangleFinderContext{nullptr};

// A finder's triangles as faces: each triangle turned outward (away from the points' centroid, which
// is inside a solid hull), then grown from a seed across shared edges into every neighbour whose
// corners lie within `mergeDistance` of the seed's plane, and each such patch walked around its
// boundary into one polygon, as Qhull's C-n merge makes them. A patch whose boundary is not one
// loop stays as its triangles. Throws Error unless the triangles close a surface.
Array<RawFace> mergeHullTriangles(std::span<const Vec3> points, std::span<const std::uint32_t> indices,
                                  double mergeDistance) {
  if (indices.size() < 12 || indices.size() % 3 != 0)
    COLLIDE_FAIL("convex_hull: the hull triangle finder returned " + std::to_string(indices.size()) +
                     " indices, not 3 per triangle for at least 4 triangles",
                 {});
  for (std::uint32_t index : indices) {
    if (index >= points.size())
      COLLIDE_FAIL("convex_hull: the hull triangle finder returned the index " + std::to_string(index) +
                       " for " + std::to_string(points.size()) + " points",
                   {});
  }
  DVec3 centroid(0.0);
  for (std::uint32_t index : indices) centroid += DVec3(points[index]);
  centroid /= double(indices.size());

  struct Triangle {
    std::array<std::uint32_t, 3> v;
    DVec3 normal;
    double offset;
  };
  const std::size_t count = indices.size() / 3;
  Array<Triangle> triangles(count);
  EdgeMap triangleByEdge;  // directed edge -> the triangle walking it
  for (std::size_t t = 0; t < count; ++t) {
    Triangle& tri = triangles[t];
    tri.v = {indices[3 * t], indices[3 * t + 1], indices[3 * t + 2]};
    const DVec3 a(points[tri.v[0]]), b(points[tri.v[1]]), c(points[tri.v[2]]);
    DVec3 normal = glm::cross(b - a, c - a);
    const double length = glm::length(normal);
    if (!(length > 0.0))
      COLLIDE_FAIL("convex_hull: the hull triangle finder returned a triangle of zero area", {});
    normal /= length;
    if (glm::dot(normal, centroid - a) > 0.0) {
      std::swap(tri.v[1], tri.v[2]);
      normal = -normal;
    }
    tri.normal = normal;
    tri.offset = glm::dot(normal, a);
    for (int i = 0; i < 3; ++i) {
      if (!triangleByEdge.try_emplace(edgeKey(tri.v[i], tri.v[(i + 1) % 3]), static_cast<std::uint32_t>(t))
               .second)
        COLLIDE_FAIL(
            "convex_hull: the hull triangle finder returned an edge shared by more than two triangles", {});
    }
  }
  for (const Triangle& tri : triangles) {  // every edge has its twin: the surface is closed
    for (int i = 0; i < 3; ++i) {
      if (!triangleByEdge.contains(edgeKey(tri.v[(i + 1) % 3], tri.v[i])))
        COLLIDE_FAIL(
            "convex_hull: the hull triangle finder returned an open surface (an edge with one triangle)", {});
    }
  }
  const auto neighbour = [&](std::uint32_t from, std::uint32_t to) {
    return triangleByEdge.find(edgeKey(to, from))->second;
  };

  constexpr std::uint32_t kNone = 0xFFFFFFFFu;
  Array<std::uint32_t> patchOf(count, kNone);
  Array<RawFace> faces;
  Array<std::uint32_t> patch, queue;
  for (std::uint32_t seed = 0; seed < count; ++seed) {
    if (patchOf[seed] != kNone) continue;
    const Triangle& plane = triangles[seed];
    patch.assign(1, seed);
    queue.assign(1, seed);
    patchOf[seed] = seed;
    while (!queue.empty()) {
      const Triangle& tri = triangles[queue.back()];
      queue.pop_back();
      for (int i = 0; i < 3; ++i) {
        const std::uint32_t next = neighbour(tri.v[i], tri.v[(i + 1) % 3]);
        if (patchOf[next] != kNone || glm::dot(triangles[next].normal, plane.normal) <= 0.0) continue;
        bool flat = true;
        for (std::uint32_t corner : triangles[next].v)
          flat =
              flat && std::abs(glm::dot(plane.normal, DVec3(points[corner])) - plane.offset) <= mergeDistance;
        if (!flat) continue;
        patchOf[next] = seed;
        patch.push_back(next);
        queue.push_back(next);
      }
    }
    // The patch's boundary: the edges whose other triangle is outside it, chained end to origin.
    std::unordered_map<std::uint32_t, std::uint32_t> nextAlongBoundary;
    bool simple = true;
    for (std::uint32_t t : patch) {
      for (int i = 0; i < 3; ++i) {
        const std::uint32_t from = triangles[t].v[i], to = triangles[t].v[(i + 1) % 3];
        if (patchOf[neighbour(from, to)] == seed) continue;
        simple = simple && nextAlongBoundary.try_emplace(from, to).second;
      }
    }
    RawFace face;
    face.qhullNormal = plane.normal;
    if (simple && !nextAlongBoundary.empty()) {
      std::uint32_t at = nextAlongBoundary.begin()->first;
      for (std::size_t walked = 0; walked < nextAlongBoundary.size(); ++walked) {
        face.inputIndices.push_back(at);
        at = nextAlongBoundary[at];
      }
      simple = at == face.inputIndices.front() &&
               std::unordered_set<std::uint32_t>(face.inputIndices.begin(), face.inputIndices.end()).size() ==
                   face.inputIndices.size();
    }
    if (simple) {
      faces.push_back(std::move(face));
      continue;
    }
    for (std::uint32_t t : patch) {
      RawFace single;
      single.qhullNormal = triangles[t].normal;
      single.inputIndices.assign(triangles[t].v.begin(), triangles[t].v.end());
      faces.push_back(std::move(single));
    }
  }
  return faces;
}

// The hull's faces: from the installed finder, else from Qhull.
Array<RawFace> findFaces(std::span<const Vec3> points, double size) {
  double largestCoordinate = 0.0;
  for (const Vec3& p : points)
    largestCoordinate =
        std::max({largestCoordinate, std::abs(double(p.x)), std::abs(double(p.y)), std::abs(double(p.z))});
  // Qhull's own round-off is that of doubles; ours is that of the float coordinates (a k-DOP's
  // corners are rounded to float), so faces merge within a few float ulps of the largest coordinate
  // plus the flatness tolerance of the set's size.
  const double mergeDistance = HullBuilder::kFlatness * size + 5e-7 * largestCoordinate;
  if (const HullTriangleFinder finder = gHullTriangleFinder.load()) {
    std::vector<float> xyz;
    xyz.reserve(3 * points.size());
    for (const Vec3& p : points) xyz.insert(xyz.end(), {p.x, p.y, p.z});
    std::vector<std::uint32_t> indices;
    if (!finder(xyz.data(), points.size(), indices, gHullTriangleFinderContext.load()))
      COLLIDE_FAIL("convex_hull: the hull triangle finder found no hull for " +
                       std::to_string(points.size()) + " points",
                   {});
    return mergeHullTriangles(points, indices, mergeDistance);
  }
#if COLLIDE_WITH_QHULL
  return runQhull(points, mergeDistance);
#else
  COLLIDE_FAIL(
      "convex_hull: this build of collide has no Qhull (COLLIDE_WITH_QHULL=OFF) and no hull triangle "
      "finder is installed (setHullTriangleFinder)",
      {});
#endif
}

// Newell's method: the area-weighted normal of a polygon, robust for nearly degenerate ones.
DVec3 newellNormal(const Array<DVec3>& polygon) {
  DVec3 normal(0.0);
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const DVec3& a = polygon[i];
    const DVec3& b = polygon[(i + 1) % polygon.size()];
    normal.x += (a.y - b.y) * (a.z + b.z);
    normal.y += (a.z - b.z) * (a.x + b.x);
    normal.z += (a.x - b.x) * (a.y + b.y);
  }
  return normal;
}

// Qhull's facets as faces and half-edge loops, each counter-clockwise seen from outside with its
// plane; only the points Qhull made vertices are kept, numbered in order of first use. Every
// half-edge goes into `edgeByEndpoints`, where its twin finds it. The one stage that reads Qhull's
// facets: the rest of the build works on the half-edges alone.
void addFaces(std::span<const Vec3> points, const Array<RawFace>& rawFaces, Array<Vec3>& vertices,
              Array<ConvexHull::Face>& faces, Array<ConvexHull::HalfEdge>& halfEdges,
              EdgeMap& edgeByEndpoints) {
  std::unordered_map<std::uint32_t, std::uint32_t> vertexIndex;
  auto remap = [&](std::uint32_t input) {
    const auto [it, inserted] = vertexIndex.try_emplace(input, static_cast<std::uint32_t>(vertices.size()));
    if (inserted) vertices.push_back(points[input]);
    return it->second;
  };
  for (const RawFace& raw : rawFaces) {
    Array<std::uint32_t> loop;
    Array<DVec3> polygon;
    for (std::uint32_t input : raw.inputIndices) {
      loop.push_back(remap(input));
      polygon.emplace_back(points[input]);
    }
    DVec3 normal = newellNormal(polygon);
    // Qhull's facet normal is outward; make the loop counter-clockwise seen from outside.
    if (glm::dot(normal, raw.qhullNormal) < 0.0) {
      std::reverse(loop.begin(), loop.end());
      std::reverse(polygon.begin(), polygon.end());
      normal = -normal;
    }
    const double length = glm::length(normal);
    if (!(length > 0.0)) COLLIDE_FAIL("convex_hull: Qhull returned a face of zero area");
    normal /= length;
    double offset = 0.0;
    for (const DVec3& p : polygon) offset += glm::dot(normal, p);
    offset /= double(polygon.size());

    const auto faceIndex = static_cast<std::uint32_t>(faces.size());
    const auto first = static_cast<std::uint32_t>(halfEdges.size());
    const auto count = static_cast<std::uint32_t>(loop.size());
    faces.push_back({Plane{Vec3(normal), float(offset)}, first, count, loop[0]});
    for (std::uint32_t i = 0; i < count; ++i) {
      const std::uint32_t from = loop[i], to = loop[(i + 1) % count];
      if (!edgeByEndpoints.try_emplace(edgeKey(from, to), first + i).second) {
        COLLIDE_FAIL("convex_hull: Qhull returned an edge walked twice in the same direction");
      }
      halfEdges.push_back({from, 0, first + (i + 1) % count, faceIndex});
    }
  }
}

// The table behind ConvexHull::facesAround. Each half-edge leaves one vertex for one face, and the
// half-edges go face by face, so filling in their order keeps each vertex's faces in increasing
// order.
void fillVertexFaces(std::size_t vertexCount, const Array<ConvexHull::HalfEdge>& halfEdges,
                     Array<std::uint32_t>& table) {
  table.assign(vertexCount + 1 + halfEdges.size(), 0);
  table[0] = static_cast<std::uint32_t>(vertexCount + 1);
  for (const ConvexHull::HalfEdge& edge : halfEdges) ++table[edge.origin + 1];
  for (std::size_t v = 0; v < vertexCount; ++v) table[v + 1] += table[v];
  Array<std::uint32_t> filled(table.begin(), table.begin() + static_cast<std::ptrdiff_t>(vertexCount));
  for (const ConvexHull::HalfEdge& edge : halfEdges) table[filled[edge.origin]++] = edge.face;
}

}  // namespace

double requireSolidPointSet(std::string_view who, std::span<const Vec3> points) {
  const std::string prefix(who);
  if (points.size() < 4) {
    COLLIDE_FAIL(
        prefix + ": need at least 4 points to enclose a volume, got " + std::to_string(points.size()), 0.0);
  }
  double largestCoordinate = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!isFinite(points[i])) {
      COLLIDE_FAIL(prefix + ": point " + std::to_string(i) + " is not finite, got " + format(points[i]), 0.0);
    }
    for (int axis = 0; axis < 3; ++axis)
      largestCoordinate = std::max(largestCoordinate, std::abs(double(points[i][axis])));
  }
  // The initial simplex of Quickhull: two far-apart points, the point farthest from their line, the
  // point farthest from their plane. Each step measures how far the set is from one dimension fewer.
  auto farthestFrom = [&](const DVec3& from) {
    std::size_t best = 0;
    double bestDistance = -1.0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const double d = glm::length(DVec3(points[i]) - from);
      if (d > bestDistance) bestDistance = d, best = i;
    }
    return best;
  };
  const DVec3 b(points[farthestFrom(DVec3(points[0]))]);
  const DVec3 a(points[farthestFrom(b)]);
  const double diameter = glm::length(b - a);  // within a factor 2 of the true diameter
  if (diameter == 0.0 || diameter <= HullBuilder::kFlatness * largestCoordinate) {
    COLLIDE_FAIL(
        prefix + ": points are all identical (within " + format(diameter) + " of " + format(Vec3(a)) + ")",
        0.0);
  }
  const double tolerance = HullBuilder::kFlatness * diameter;
  const DVec3 axis = (b - a) / diameter;
  double lineDistance = 0.0;
  DVec3 c = a;
  for (const Vec3& p : points) {
    const DVec3 offset = DVec3(p) - a;
    const double d = glm::length(offset - glm::dot(offset, axis) * axis);
    if (d > lineDistance) lineDistance = d, c = DVec3(p);
  }
  if (lineDistance <= tolerance) {
    COLLIDE_FAIL(prefix + ": points are collinear (all within " + format(lineDistance) +
                     " of a line, tolerance " + format(tolerance) + ")",
                 0.0);
  }
  const DVec3 normal = glm::normalize(glm::cross(b - a, c - a));
  double planeDistance = 0.0;
  for (const Vec3& p : points)
    planeDistance = std::max(planeDistance, std::abs(glm::dot(DVec3(p) - a, normal)));
  if (planeDistance <= tolerance) {
    COLLIDE_FAIL(prefix + ": points are coplanar (all within " + format(planeDistance) +
                     " of a plane, tolerance " + format(tolerance) + ")",
                 0.0);
  }
  return diameter;
}

void setHullTriangleFinder(HullTriangleFinder finder, void* context) {
  gHullTriangleFinderContext.store(context);
  gHullTriangleFinder.store(finder);
}

bool canBuildHulls() { return COLLIDE_WITH_QHULL != 0 || gHullTriangleFinder.load() != nullptr; }

ConvexHull HullBuilder::build(std::span<const Vec3> points) {
  const detail::ErrorScope scope;
  const double size = requireSolidPointSet("convex_hull", points);
  COLLIDE_RETURN_IF_FAILED({});
  const Array<RawFace> rawFaces = findFaces(points, size);
  COLLIDE_RETURN_IF_FAILED({});

  ConvexHull hull;
  static std::atomic<std::uint64_t> builtHulls{0};
  hull.serial_ = ++builtHulls;
  EdgeMap edgeByEndpoints;
  addFaces(points, rawFaces, hull.vertices_, hull.faces_, hull.halfEdges_, edgeByEndpoints);
  COLLIDE_RETURN_IF_FAILED({});
  for (std::uint32_t h = 0; h < hull.halfEdges_.size(); ++h) {
    ConvexHull::HalfEdge& edge = hull.halfEdges_[h];
    const std::uint32_t to = hull.halfEdges_[edge.next].origin;
    const auto twin = edgeByEndpoints.find(edgeKey(to, edge.origin));
    if (twin == edgeByEndpoints.end())
      COLLIDE_FAIL("convex_hull: Qhull returned an edge with only one face", {});
    edge.twin = twin->second;
  }
  finish(hull);
  COLLIDE_RETURN_IF_FAILED({});
  return hull;
}

// What a hull derives from its vertices, faces and half-edges: the edge list, the faces around each
// vertex, the blocked coordinates, the bounds and the mass properties.
void HullBuilder::finish(ConvexHull& hull) {
  for (std::uint32_t h = 0; h < hull.halfEdges_.size(); ++h) {
    const ConvexHull::HalfEdge& edge = hull.halfEdges_[h];
    if (edge.twin < h) continue;
    hull.edges_.push_back(
        {h, edge.origin, hull.halfEdges_[edge.next].origin, edge.face, hull.halfEdges_[edge.twin].face});
  }

  fillVertexFaces(hull.vertices_.size(), hull.halfEdges_, hull.vertexFaces_);
  hull.blockedVertices_ = detail::blockCoordinates(hull.vertices_);
  for (const Vec3& v : hull.vertices_) hull.bounds_.grow(v);
  // Integrate about the box centre: the polyhedron formulas lose precision far from the origin.
  const Vec3 reference = hull.bounds_.center();
  detail::PolyhedronIntegrals integrals;
  for (const ConvexHull::Face& face : hull.faces_) {
    const ConvexHull::HalfEdge* edge = &hull.halfEdges_[face.firstEdge];
    const Vec3 apex = hull.vertices_[edge->origin] - reference;
    edge = &hull.halfEdges_[edge->next];
    for (std::uint32_t i = 1; i + 1 < face.edgeCount; ++i) {
      const Vec3 b = hull.vertices_[edge->origin] - reference;
      edge = &hull.halfEdges_[edge->next];
      integrals.addTriangle(apex, b, hull.vertices_[edge->origin] - reference);
    }
  }
  integrals.finish(hull.volume_, hull.centroid_, hull.unitInertia_);
  hull.centroid_ += reference;
  if (!(hull.volume_ > 0.0f))
    COLLIDE_FAIL("convex_hull: the hull has no volume, got " + format(hull.volume_));
  // The arrays grew by push_back, to up to twice what they hold: a hull is built once and read for
  // as long as it lives (a scene of 2,000 different rocks keeps a megabyte and a half of slack).
  hull.vertices_.shrink_to_fit();
  hull.blockedVertices_.shrink_to_fit();
  hull.halfEdges_.shrink_to_fit();
  hull.edges_.shrink_to_fit();
  hull.faces_.shrink_to_fit();
  hull.vertexFaces_.shrink_to_fit();
}

ConvexHull HullBuilder::restore(std::span<const Vec3> vertices, std::span<const ConvexHull::Face> faces,
                                std::span<const ConvexHull::HalfEdge> halfEdges) {
  const std::uint32_t vertexCount = static_cast<std::uint32_t>(vertices.size());
  const std::uint32_t faceCount = static_cast<std::uint32_t>(faces.size());
  const std::uint32_t edgeCount = static_cast<std::uint32_t>(halfEdges.size());
  const detail::ErrorScope scope;
  const auto fail = [](const std::string& what) {
    detail::raiseError("convex_hull: " + what);
    return ConvexHull();
  };
  if (vertexCount < 4 || faceCount < 4 || edgeCount < 12 || edgeCount % 2 != 0)
    return fail("a hull needs at least 4 vertices, 4 faces and 12 half-edges, got " +
                std::to_string(vertexCount) + ", " + std::to_string(faceCount) + " and " +
                std::to_string(edgeCount));
  for (std::uint32_t v = 0; v < vertexCount; ++v) {
    if (!isFinite(vertices[v])) return fail("vertex " + std::to_string(v) + " is not finite");
  }
  for (std::uint32_t h = 0; h < edgeCount; ++h) {
    const ConvexHull::HalfEdge& e = halfEdges[h];
    if (e.origin >= vertexCount || e.twin >= edgeCount || e.next >= edgeCount || e.face >= faceCount ||
        e.twin == h)
      return fail("half-edge " + std::to_string(h) + " refers outside the hull");
  }
  for (std::uint32_t h = 0; h < edgeCount; ++h) {  // every index in range now
    const ConvexHull::HalfEdge& e = halfEdges[h];
    const ConvexHull::HalfEdge& twin = halfEdges[e.twin];
    if (twin.twin != h || twin.origin != halfEdges[e.next].origin || halfEdges[twin.next].origin != e.origin)
      return fail("half-edge " + std::to_string(h) + " and its twin do not join the same two vertices");
  }
  // Each face a loop of its own half-edges: walking `next` from the first comes back after edgeCount,
  // and every half-edge is walked once.
  Array<std::uint8_t> walked(edgeCount, 0);
  for (std::uint32_t f = 0; f < faceCount; ++f) {
    const ConvexHull::Face& face = faces[f];
    if (!isFinite(face.plane.normal) || !std::isfinite(face.plane.distance) ||
        std::abs(glm::length(face.plane.normal) - 1.0f) > 1e-3f)
      return fail("face " + std::to_string(f) + " has no unit normal");
    if (face.firstEdge >= edgeCount || face.edgeCount < 3 || face.edgeCount > edgeCount ||
        face.firstVertex != halfEdges[face.firstEdge].origin)
      return fail("face " + std::to_string(f) + " refers outside the hull");
    std::uint32_t h = face.firstEdge;
    for (std::uint32_t i = 0; i < face.edgeCount; ++i) {
      if (halfEdges[h].face != f || walked[h])
        return fail("face " + std::to_string(f) + "'s loop leaves the face");
      walked[h] = 1;
      h = halfEdges[h].next;
    }
    if (h != face.firstEdge) return fail("face " + std::to_string(f) + "'s loop does not close");
  }
  if (std::find(walked.begin(), walked.end(), 0) != walked.end())
    return fail("a half-edge belongs to no face's loop");
  ConvexHull hull;
  static std::atomic<std::uint64_t> restoredHulls{0};
  hull.serial_ = (std::uint64_t{1} << 63) | ++restoredHulls;  // apart from the serials of built hulls
  hull.vertices_.assign(vertices.begin(), vertices.end());
  hull.faces_.assign(faces.begin(), faces.end());
  hull.halfEdges_.assign(halfEdges.begin(), halfEdges.end());
  finish(hull);
  COLLIDE_RETURN_IF_FAILED({});
  for (const Vec3& v : hull.vertices_) {
    for (const ConvexHull::Face& face : hull.faces_) {
      if (face.plane.signedDistance(v) >
          1e-3f * std::max(1.0f, glm::length(hull.bounds_.max - hull.bounds_.min)))
        return fail("a vertex lies outside a face's plane: not convex");
    }
  }
  return hull;
}

}  // namespace collide
