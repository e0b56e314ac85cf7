// EPA penetration depth (see epa.h). Fixed-size storage on the stack: no allocation per query.
#include "narrowphase/epa.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace collide::detail {

namespace {

constexpr int kMaxVertices = 256;
constexpr int kMaxFaces = 2 * kMaxVertices + 16;  // a closed triangulated polytope has 2V - 4 faces
// Converged when the support along the nearest face's normal is within this of the face: the depth
// is then bracketed to kRelativeTolerance of itself, or kAbsoluteTolerance of the shapes' size.
constexpr float kRelativeTolerance = 1e-5f;
constexpr float kAbsoluteTolerance = 1e-6f;

struct Face {
  std::uint16_t v[3];
  Vec3 normal;     // outward; unit unless degenerate
  float distance;  // of the face's plane from the origin
  bool degenerate;
};

struct Edge {
  std::uint16_t from, to;
};

class Polytope {
 public:
  SimplexVertex vertices[kMaxVertices];
  int vertexCount = 0;
  Face faces[kMaxFaces];
  int faceCount = 0;

  void setFace(Face& face, int i, int j, int k) const {
    face.v[0] = static_cast<std::uint16_t>(i);
    face.v[1] = static_cast<std::uint16_t>(j);
    face.v[2] = static_cast<std::uint16_t>(k);
    const Vec3& a = vertices[i].w;
    const Vec3 n = glm::cross(vertices[j].w - a, vertices[k].w - a);
    const float length = glm::length(n);
    face.degenerate = !(length > 1e-10f * scaleSquared);
    face.normal = face.degenerate ? n : n / length;
    face.distance = face.degenerate ? 1e30f : glm::dot(face.normal, a);
  }

  bool addFace(int i, int j, int k) {
    if (faceCount == kMaxFaces) return false;
    setFace(faces[faceCount++], i, j, k);
    return true;
  }

  // Adds the face oriented away from `inner`, a point strictly inside the polytope.
  void addOrientedFace(int i, int j, int k, const Vec3& inner) {
    const Vec3 n = glm::cross(vertices[j].w - vertices[i].w, vertices[k].w - vertices[i].w);
    if (glm::dot(n, vertices[i].w - inner) < 0.0f) std::swap(j, k);
    addFace(i, j, k);
  }

  // Adds vertex `index` to the hull: removes the faces it sees and fans new faces from it to the
  // horizon, the boundary of the removed region. Returns false when storage runs out.
  bool expand(int index) {
    const Vec3 w = vertices[index].w;
    Edge horizon[3 * kMaxFaces];
    int edgeCount = 0;
    int kept = 0;
    for (int f = 0; f < faceCount; ++f) {
      const Face& face = faces[f];
      if (glm::dot(face.normal, w - vertices[face.v[0]].w) <= 0.0f) {
        faces[kept++] = face;
        continue;
      }
      // An edge shared by two visible faces is walked once in each direction: both copies cancel,
      // and what is left is the horizon.
      for (int e = 0; e < 3; ++e) {
        const std::uint16_t from = face.v[e];
        const std::uint16_t to = face.v[(e + 1) % 3];
        bool cancelled = false;
        for (int h = 0; h < edgeCount; ++h) {
          if (horizon[h].from == to && horizon[h].to == from) {
            horizon[h] = horizon[--edgeCount];
            cancelled = true;
            break;
          }
        }
        if (!cancelled) horizon[edgeCount++] = {from, to};
      }
    }
    faceCount = kept;
    if (faceCount + edgeCount > kMaxFaces) return false;
    for (int h = 0; h < edgeCount; ++h) addFace(horizon[h].from, horizon[h].to, index);
    return edgeCount >= 3;
  }

  float scaleSquared = 1.0f;
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

}  // namespace

EpaResult epaPenetration(const ConvexSupport& a, const ConvexSupport& b, const Simplex& simplex) {
  Polytope polytope;
  float scaleSquared = 1e-30f;
  for (int i = 0; i < simplex.count; ++i) {
    polytope.vertices[polytope.vertexCount++] = simplex.vertices[i];
    scaleSquared = std::max(scaleSquared, glm::dot(simplex.vertices[i].w, simplex.vertices[i].w));
  }
  // Grow the simplex to a solid tetrahedron. GJK ends with the origin on (or within rounding of)
  // its simplex, so adding vertices off the simplex's span keeps the origin in the closed polytope;
  // EPA works with the origin on the boundary, where the nearest face has distance 0.
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
      EpaResult touching;
      touching.depth = 0.0f;
      touching.normal = candidates[0];
      touching.pointOnA = polytope.vertices[0].a;
      touching.pointOnB = polytope.vertices[0].b;
      return touching;
    }
    polytope.vertices[polytope.vertexCount++] = best;
    scaleSquared = std::max(scaleSquared, glm::dot(best.w, best.w));
  }
  polytope.scaleSquared = scaleSquared;
  const Vec3 inner = 0.25f * (polytope.vertices[0].w + polytope.vertices[1].w + polytope.vertices[2].w +
                              polytope.vertices[3].w);
  polytope.addOrientedFace(0, 1, 2, inner);
  polytope.addOrientedFace(0, 3, 1, inner);
  polytope.addOrientedFace(0, 2, 3, inner);
  polytope.addOrientedFace(1, 3, 2, inner);

  const float absoluteTolerance = kAbsoluteTolerance * std::sqrt(scaleSquared);
  Face best = polytope.faces[0];
  int iteration = 0;
  for (; iteration < kMaxVertices; ++iteration) {
    int bestIndex = -1;
    for (int f = 0; f < polytope.faceCount; ++f) {
      const Face& face = polytope.faces[f];
      if (!face.degenerate && (bestIndex < 0 || face.distance < polytope.faces[bestIndex].distance))
        bestIndex = f;
    }
    if (bestIndex < 0) break;
    best = polytope.faces[bestIndex];
    const SimplexVertex w = minkowskiSupport(a, b, best.normal);
    const float gap = glm::dot(w.w, best.normal) - best.distance;
    if (gap <= std::max(absoluteTolerance, kRelativeTolerance * std::abs(best.distance))) break;
    if (polytope.vertexCount == kMaxVertices) break;
    polytope.vertices[polytope.vertexCount] = w;
    if (!polytope.expand(polytope.vertexCount++)) break;
  }
  return resultFromFace(polytope, best, iteration + 1);
}

}  // namespace collide::detail
