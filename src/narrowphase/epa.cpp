// EPA penetration depth (see epa.h). Fixed-size storage on the stack: no allocation per query.
#include "narrowphase/epa.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace collide::detail {

namespace {

constexpr int kMaxVertices = 512;
// Removed faces' slots are reused; a closed polytope of V vertices has 2V - 4 faces.
constexpr int kMaxFaces = 2 * kMaxVertices + 64;
// Converged when the support along the nearest face's normal is within this of the face: the depth
// is then bracketed to kRelativeTolerance of itself, or kAbsoluteTolerance of the shapes' size.
constexpr float kRelativeTolerance = 1e-5f;
constexpr float kAbsoluteTolerance = 2e-6f;

struct Face {
  std::uint16_t v[3];            // counter-clockwise seen from outside
  std::int16_t adjacent[3];      // the face across edge e (from v[e] to v[e + 1])
  std::uint8_t adjacentEdge[3];  // that face's index of the same edge
  bool removed;
  bool degenerate;
  Vec3 normal;     // outward; unit unless degenerate
  float distance;  // of the face's plane from the origin
};

struct HorizonEdge {
  std::int16_t face;  // the face that stays
  std::uint8_t edge;  // its edge on the horizon
};

class Polytope {
 public:
  SimplexVertex vertices[kMaxVertices];
  int vertexCount = 0;
  Face faces[kMaxFaces];
  int faceCount = 0;
  float scaleSquared = 1.0f;
  // Faces that w sees by less than this count as coplanar and stay: removing a nearly coplanar
  // face on rounding noise would make the polytope fold (flat caps of cylinders, box faces).
  float visibleEpsilon = 0.0f;

  std::int16_t freeFaces[kMaxFaces];
  int freeCount = 0;

  void reset() {
    vertexCount = 0;
    faceCount = 0;
    freeCount = 0;
  }

  int addFace(int i, int j, int k) {
    int index;
    if (freeCount > 0) {
      index = freeFaces[--freeCount];
    } else {
      if (faceCount == kMaxFaces) return -1;
      index = faceCount++;
    }
    Face& face = faces[index];
    face.v[0] = static_cast<std::uint16_t>(i);
    face.v[1] = static_cast<std::uint16_t>(j);
    face.v[2] = static_cast<std::uint16_t>(k);
    face.removed = false;
    const Vec3& a = vertices[i].w;
    const Vec3 n = glm::cross(vertices[j].w - a, vertices[k].w - a);
    const float length = glm::length(n);
    face.degenerate = !(length > 1e-10f * scaleSquared);
    face.normal = face.degenerate ? n : n / length;
    face.distance = face.degenerate ? 1e30f : glm::dot(face.normal, a);
    return index;
  }

  static void link(Face* faces, int f, int e, int g, int eg) {
    faces[f].adjacent[e] = static_cast<std::int16_t>(g);
    faces[f].adjacentEdge[e] = static_cast<std::uint8_t>(eg);
    faces[g].adjacent[eg] = static_cast<std::int16_t>(f);
    faces[g].adjacentEdge[eg] = static_cast<std::uint8_t>(e);
  }

  // The initial tetrahedron, faces oriented away from its centroid and linked across their edges.
  void buildTetrahedron() {
    const Vec3 inner = 0.25f * (vertices[0].w + vertices[1].w + vertices[2].w + vertices[3].w);
    static constexpr int kFaces[4][3] = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
    for (const auto& f : kFaces) {
      int i = f[0], j = f[1], k = f[2];
      const Vec3 n = glm::cross(vertices[j].w - vertices[i].w, vertices[k].w - vertices[i].w);
      if (glm::dot(n, vertices[i].w - inner) < 0.0f) std::swap(j, k);
      addFace(i, j, k);
    }
    for (int f = 0; f < 4; ++f) {
      for (int e = 0; e < 3; ++e) {
        for (int g = f + 1; g < 4; ++g) {
          for (int eg = 0; eg < 3; ++eg) {
            if (faces[f].v[e] == faces[g].v[(eg + 1) % 3] && faces[f].v[(e + 1) % 3] == faces[g].v[eg]) {
              link(faces, f, e, g, eg);
            }
          }
        }
      }
    }
  }

  // A sliver face (no reliable normal) next to the visible region goes with it.
  bool sees(const Face& face, const Vec3& w) const {
    return face.degenerate || glm::dot(face.normal, w - vertices[face.v[0]].w) > visibleEpsilon;
  }

  // Walks the faces w sees, starting across edge `edge` of a removed face into `face`; the faces
  // that w does not see are the horizon (depth-first, as in Quickhull).
  bool walk(int face, int edge, const Vec3& w, HorizonEdge* horizon, int& horizonCount, int depth) {
    Face& f = faces[face];
    if (f.removed) return true;
    if (!sees(f, w)) {
      if (horizonCount == kMaxFaces) return false;
      horizon[horizonCount++] = {static_cast<std::int16_t>(face), static_cast<std::uint8_t>(edge)};
      return true;
    }
    if (depth > kMaxFaces || freeCount == kMaxFaces) return false;
    f.removed = true;
    freeFaces[freeCount++] = static_cast<std::int16_t>(face);
    for (int step = 1; step <= 2; ++step) {
      const int e = (edge + step) % 3;
      if (!walk(f.adjacent[e], f.adjacentEdge[e], w, horizon, horizonCount, depth + 1)) return false;
    }
    return true;
  }

  // Adds vertex `index`, seen by face `start`: removes the faces it sees and fans new faces from it
  // to the horizon. Returns false when storage runs out or rounding broke the horizon into more
  // than one loop; the caller then keeps its best answer so far.
  bool expand(int index, int start) {
    const Vec3 w = vertices[index].w;
    static thread_local HorizonEdge horizon[kMaxFaces];
    int horizonCount = 0;
    Face& first = faces[start];
    first.removed = true;
    freeFaces[freeCount++] = static_cast<std::int16_t>(start);
    for (int e = 0; e < 3; ++e) {
      if (!walk(first.adjacent[e], first.adjacentEdge[e], w, horizon, horizonCount, 0)) return false;
    }
    if (horizonCount < 3 || horizonCount > kMaxFaces - faceCount + freeCount) return false;
    static thread_local std::int16_t created[kMaxFaces];
    for (int h = 0; h < horizonCount; ++h) {
      const Face& kept = faces[horizon[h].face];
      const int a = kept.v[horizon[h].edge];
      const int b = kept.v[(horizon[h].edge + 1) % 3];
      const int face = addFace(b, a, index);  // edge b -> a faces the kept face's a -> b
      created[h] = static_cast<std::int16_t>(face);
      link(faces, face, 0, horizon[h].face, horizon[h].edge);
    }
    // New face k is (b_k, a_k, w): its edge a_k -> w meets the new face m whose edge w -> b_m has
    // b_m = a_k. Exactly one such m per k, or the horizon was not one simple loop.
    for (int k = 0; k < horizonCount; ++k) {
      int match = -1;
      for (int m = 0; m < horizonCount; ++m) {
        if (faces[created[m]].v[0] == faces[created[k]].v[1]) {
          if (match >= 0) return false;
          match = m;
        }
      }
      if (match < 0) return false;
      link(faces, created[k], 1, created[match], 2);
    }
    return true;
  }
};

EpaResult resultFromFace(const Polytope& polytope, const Face& face, int iterations) {
  const SimplexVertex& a = polytope.vertices[face.v[0]];
  const SimplexVertex& b = polytope.vertices[face.v[1]];
  const SimplexVertex& c = polytope.vertices[face.v[2]];
  const Vec3 l = closestBarycentricOnTriangle(a.w, b.w, c.w, face.distance * face.normal);
  EpaResult result;
  result.depth = face.distance;
  result.normal = face.normal;
  result.pointOnA = l.x * a.a + l.y * b.a + l.z * c.a;
  result.pointOnB = l.x * a.b + l.y * b.b + l.z * c.b;
  result.iterations = iterations;
  return result;
}

// Grows GJK's simplex in `polytope` to a solid tetrahedron, widening `scaleSquared` with each new
// vertex. GJK ends with the origin on (or within rounding of) its simplex, so adding vertices off the
// simplex's span keeps the origin in the closed polytope; EPA works with the origin on the boundary,
// where the nearest face has distance 0. A stage of its own: it runs once, before the expansion
// loop, and can end the query (false when A - B is flat around the origin; `touching` answers).
bool growToTetrahedron(const ConvexSupport& a, const ConvexSupport& b, Polytope& polytope,
                       float& scaleSquared, EpaResult& touching) {
  while (polytope.vertexCount < 4) {
    const Vec3& p0 = polytope.vertices[0].w;
    Vec3 candidates[8];
    int candidateCount = 0;
    if (polytope.vertexCount == 1) {
      for (int axis = 0; axis < 3; ++axis) {
        Vec3 d(0.0f);
        d[axis] = 1.0f;
        candidates[candidateCount++] = d;
        candidates[candidateCount++] = -d;
      }
    } else if (polytope.vertexCount == 2) {
      const Vec3 u = polytope.vertices[1].w - p0;
      const float length = glm::length(u);
      Vec3 t1, t2;
      orthonormalBasis(length > 0.0f ? u / length : Vec3(1.0f, 0.0f, 0.0f), t1, t2);
      const Vec3 directions[4] = {t1, t2, glm::normalize(t1 + t2), glm::normalize(t1 - t2)};
      for (const Vec3& d : directions) {
        candidates[candidateCount++] = d;
        candidates[candidateCount++] = -d;
      }
    } else {
      const Vec3 n = glm::cross(polytope.vertices[1].w - p0, polytope.vertices[2].w - p0);
      const float length = glm::length(n);
      const Vec3 unit = length > 0.0f ? n / length : Vec3(0.0f, 1.0f, 0.0f);
      candidates[candidateCount++] = unit;
      candidates[candidateCount++] = -unit;
    }
    // The support farthest from the current span gives the best-conditioned tetrahedron.
    float bestHeight = 0.0f;
    SimplexVertex best;
    for (int i = 0; i < candidateCount; ++i) {
      const SimplexVertex v = minkowskiSupport(a, b, candidates[i]);
      const float height = glm::dot(v.w - p0, candidates[i]);
      if (height > bestHeight) {
        bestHeight = height;
        best = v;
      }
    }
    if (!(bestHeight > 1e-6f * std::sqrt(scaleSquared))) {
      // A - B is flat around the origin: the shapes only touch (or are themselves flat).
      touching.depth = 0.0f;
      touching.normal = candidates[0];
      touching.pointOnA = polytope.vertices[0].a;
      touching.pointOnB = polytope.vertices[0].b;
      return false;
    }
    polytope.vertices[polytope.vertexCount++] = best;
    scaleSquared = std::max(scaleSquared, glm::dot(best.w, best.w));
  }
  return true;
}

}  // namespace

EpaResult epaPenetration(const ConvexSupport& a, const ConvexSupport& b, const Simplex& simplex) {
  // Its face and vertex arrays are too large for the stack: kept per thread.
  static thread_local Polytope polytope;
  polytope.reset();
  float scaleSquared = 1e-30f;
  for (int i = 0; i < simplex.count; ++i) {
    polytope.vertices[polytope.vertexCount++] = simplex.vertices[i];
    scaleSquared = std::max(scaleSquared, glm::dot(simplex.vertices[i].w, simplex.vertices[i].w));
  }
  EpaResult touching;
  if (!growToTetrahedron(a, b, polytope, scaleSquared, touching)) return touching;
  polytope.scaleSquared = scaleSquared;
  polytope.visibleEpsilon = 0.5f * kAbsoluteTolerance * std::sqrt(scaleSquared);
  polytope.buildTetrahedron();

  const float absoluteTolerance = kAbsoluteTolerance * std::sqrt(scaleSquared);
  Face best = polytope.faces[0];
  // Each nearest face's normal with its support distance, an upper bound of the depth: the best of
  // them answers when the polytope can grow no further before converging (rounding on a cylinder's
  // rim, the vertex budget), so the depth returned is always one that separates along the normal.
  Face tightest = best;
  float tightestUpper = std::numeric_limits<float>::infinity();
  bool converged = false;
  int iteration = 0;
  for (; iteration < kMaxVertices; ++iteration) {
    int bestIndex = -1;
    for (int f = 0; f < polytope.faceCount; ++f) {
      const Face& face = polytope.faces[f];
      if (face.removed || face.degenerate) continue;
      if (bestIndex < 0 || face.distance < polytope.faces[bestIndex].distance) bestIndex = f;
    }
    if (bestIndex < 0) break;
    best = polytope.faces[bestIndex];
    const SimplexVertex w = minkowskiSupport(a, b, best.normal);
    const float upper = glm::dot(w.w, best.normal);
    if (upper < tightestUpper) {
      tightestUpper = upper;
      tightest = best;
    }
    const float gap = upper - best.distance;
    if (gap <= std::max(absoluteTolerance, kRelativeTolerance * std::abs(best.distance))) {
      converged = true;
      break;
    }
    if (polytope.vertexCount == kMaxVertices) break;
    // A support point already in the polytope cannot lie beyond one of its faces unless rounding
    // folded the polytope there: that face is not on the hull of the polytope's vertices, so it
    // bounds nothing. Adding the point again would only make slivers, so the face is retired
    // (treated like a sliver: never the nearest, removed by the next expansion that reaches it)
    // and the search goes on with the next nearest face: ending it at a folded face would leave the
    // depth short, as on cylinder rims.
    bool known = false;
    for (int i = 0; i < polytope.vertexCount && !known; ++i) {
      const Vec3 d = polytope.vertices[i].w - w.w;
      known = glm::dot(d, d) <= 1e-12f * scaleSquared;
    }
    if (known) {
      polytope.faces[bestIndex].degenerate = true;
      continue;
    }
    polytope.vertices[polytope.vertexCount] = w;
    if (!polytope.expand(polytope.vertexCount++, bestIndex)) break;
  }
  if (converged || !(tightestUpper < std::numeric_limits<float>::infinity())) {
    return resultFromFace(polytope, best, iteration + 1);
  }
  EpaResult result = resultFromFace(polytope, tightest, iteration + 1);
  result.depth = tightestUpper;
  return result;
}

}  // namespace collide::detail
