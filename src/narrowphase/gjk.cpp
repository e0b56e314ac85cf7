// GJK distance between convex cores (see gjk.h).
#include "narrowphase/gjk.h"

#include <algorithm>
#include <cmath>

namespace collide::detail {

namespace {

// Relative tolerances, chosen for single precision: the distance converges to 1e-6 of itself, and
// a closest point within 1e-6 of the shapes' size from the origin counts as touching.
constexpr float kRelativeGap = 1e-6f;
constexpr float kTouchingSquared = 1e-12f;
constexpr int kMaxIterations = 64;

// The simplex is solved in double precision: its vertices are single-precision support points,
// but the solve subtracts nearly equal products (a thin triangle far from the origin), and in
// single precision that misplaces the closest point enough for GJK to stall or cycle.
using DVec3 = glm::dvec3;

DVec3 closestBarycentricOnSegment(const DVec3& a, const DVec3& b, const DVec3& p) {
  const DVec3 ab = b - a;
  const double lengthSquared = glm::dot(ab, ab);
  if (lengthSquared <= 0.0) return {1.0, 0.0, 0.0};
  const double t = std::clamp(glm::dot(p - a, ab) / lengthSquared, 0.0, 1.0);
  return {1.0 - t, t, 0.0};
}

DVec3 closestBarycentricOnTriangleD(const DVec3& a, const DVec3& b, const DVec3& c, const DVec3& p) {
  // The projection onto the plane, with barycentric coordinates as ratios of signed areas; if one
  // is negative the answer lies on an edge, and the nearest of the three edges is it.
  const DVec3 n = glm::cross(b - a, c - a);
  const double nn = glm::dot(n, n);
  const double scale = glm::dot(b - a, b - a) * glm::dot(c - a, c - a);
  if (nn > 1e-20 * scale) {
    const DVec3 q = p - (glm::dot(p - a, n) / nn) * n;
    const double u = glm::dot(glm::cross(b - q, c - q), n) / nn;
    const double v = glm::dot(glm::cross(c - q, a - q), n) / nn;
    const double w = 1.0 - u - v;
    if (u >= 0.0 && v >= 0.0 && w >= 0.0) return {u, v, w};
  }
  const DVec3 eab = closestBarycentricOnSegment(a, b, p);
  const DVec3 eac = closestBarycentricOnSegment(a, c, p);
  const DVec3 ebc = closestBarycentricOnSegment(b, c, p);
  const DVec3 candidates[3] = {{eab.x, eab.y, 0.0}, {eac.x, 0.0, eac.y}, {0.0, ebc.x, ebc.y}};
  DVec3 best = candidates[0];
  double bestDistance = 1e300;
  for (const DVec3& candidate : candidates) {
    const DVec3 r = candidate.x * a + candidate.y * b + candidate.z * c - p;
    const double distance = glm::dot(r, r);
    if (distance < bestDistance) {
      bestDistance = distance;
      best = candidate;
    }
  }
  return best;
}

}  // namespace

Vec3 closestBarycentricOnTriangle(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& p) {
  return Vec3(closestBarycentricOnTriangleD(DVec3(a), DVec3(b), DVec3(c), DVec3(p)));
}

namespace {

// Keeps the vertices with a non-zero coordinate, in order.
void compact(Simplex& simplex, const double* lambda, int count) {
  int kept = 0;
  for (int i = 0; i < count; ++i) {
    if (lambda[i] > 0.0) {
      simplex.vertices[kept] = simplex.vertices[i];
      simplex.lambda[kept] = lambda[i];
      ++kept;
    }
  }
  if (kept == 0) {  // cannot happen for coordinates summing to 1; keep the first vertex to be safe
    simplex.lambda[0] = 1.0;
    kept = 1;
  }
  simplex.count = kept;
}

DVec3 pointOf(const Simplex& simplex) {
  DVec3 p(0.0);
  for (int i = 0; i < simplex.count; ++i) p += simplex.lambda[i] * DVec3(simplex.vertices[i].w);
  return p;
}

// ---- The sub-simplex solver: signed volumes (Montanari, Petrinic and Barbieri, "Improving the GJK
// algorithm for faster and more reliable distance queries between convex objects", ACM TOG 2017).
// The barycentric coordinates of the origin's projection are ratios of signed lengths, areas and
// volumes; where one is not positive the origin lies beyond the opposite face, and only those faces
// can hold the closest point, so only they are searched (Johnson's sub-simplices without the full
// enumeration). Double precision from single-precision points: the areas subtract nearly equal
// products (a thin triangle far from the origin), and in single precision that misplaces the
// closest point enough for GJK to stall or cycle; on x86-64 a scalar double costs what a float does.

bool sameSign(double a, double b) { return (a > 0.0 && b > 0.0) || (a < 0.0 && b < 0.0); }

double squaredLength(const DVec3& v) { return glm::dot(v, v); }

// The segment [w0, w1]: coordinates of its point nearest the origin.
void solveSegment(const DVec3& w0, const DVec3& w1, double* lambda) {
  const DVec3 edge = w1 - w0;
  const double lengthSquared = glm::dot(edge, edge);
  const double t = lengthSquared > 0.0 ? std::clamp(-glm::dot(w0, edge) / lengthSquared, 0.0, 1.0) : 0.0;
  lambda[0] = 1.0 - t;
  lambda[1] = t;
}

// The triangle (w0, w1, w2): the origin projected onto its plane, then the signed areas of the
// sub-triangles in the coordinate plane where the triangle's shadow is largest (Montanari's S2D).
void solveTriangle(const DVec3* w, double* lambda) {
  const DVec3 normal = glm::cross(w[1] - w[0], w[2] - w[0]);
  const double normalSquared = glm::dot(normal, normal);
  // Every edge faces the origin of a degenerate triangle (no plane to project on).
  bool facing[3] = {true, true, true};
  if (normalSquared > 1e-20 * squaredLength(w[1] - w[0]) * squaredLength(w[2] - w[0])) {
    const DVec3 p = (glm::dot(w[0], normal) / normalSquared) * normal;
    const DVec3 magnitude = glm::abs(normal);
    const int k = magnitude.x >= magnitude.y ? (magnitude.x >= magnitude.z ? 0 : 2)
                                             : (magnitude.y >= magnitude.z ? 1 : 2);
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    // Twice the signed area of (a, b, c) projected on the (i, j) plane: positive counter-clockwise
    // about +k, like the k component of the normal.
    auto area = [&](const DVec3& a, const DVec3& b, const DVec3& c) {
      return (b[i] - a[i]) * (c[j] - a[j]) - (b[j] - a[j]) * (c[i] - a[i]);
    };
    const double coordinates[3] = {area(p, w[1], w[2]), area(w[0], p, w[2]), area(w[0], w[1], p)};
    const double total = normal[k];
    for (int m = 0; m < 3; ++m) facing[m] = !sameSign(coordinates[m], total);
    if (!facing[0] && !facing[1] && !facing[2]) {
      const double sum = coordinates[0] + coordinates[1] + coordinates[2];
      for (int m = 0; m < 3; ++m) lambda[m] = coordinates[m] / sum;
      return;
    }
  }
  // The nearest point of the edges facing the origin (the edge opposite m faces it when the
  // origin's coordinate m is not positive).
  double best = 1e300;
  for (int m = 0; m < 3; ++m) {
    if (!facing[m]) continue;
    const int first = (m + 1) % 3, second = (m + 2) % 3;
    double edge[2];
    solveSegment(w[first], w[second], edge);
    const double distance = squaredLength(edge[0] * w[first] + edge[1] * w[second]);
    if (distance < best) {
      best = distance;
      lambda[m] = 0.0;
      lambda[first] = edge[0];
      lambda[second] = edge[1];
    }
  }
}

// The tetrahedron (w0..w3): signed volumes with the origin in place of each vertex (Montanari's
// S3D). Returns true when the origin lies inside; a nearly flat tetrahedron never counts as
// enclosing it (the signs mean nothing there), and then all four faces are searched.
bool solveTetrahedron(const DVec3* w, double* lambda) {
  const DVec3 e1 = w[1] - w[0], e2 = w[2] - w[0], e3 = w[3] - w[0];
  const double volume = glm::dot(e1, glm::cross(e2, e3));
  const bool flat =
      std::abs(volume) <= 1e-6 * std::sqrt(squaredLength(e1) * squaredLength(e2) * squaredLength(e3));
  double coordinates[4];
  coordinates[0] = glm::dot(w[1], glm::cross(w[2], w[3]));
  coordinates[1] = -glm::dot(w[0], glm::cross(e2, e3));
  coordinates[2] = -glm::dot(e1, glm::cross(w[0], e3));
  coordinates[3] = -glm::dot(e1, glm::cross(e2, w[0]));
  bool visible[4];
  bool inside = !flat;
  for (int m = 0; m < 4; ++m) {
    visible[m] = flat || !sameSign(coordinates[m], volume);
    inside = inside && !visible[m];
  }
  if (inside) {
    const double sum = coordinates[0] + coordinates[1] + coordinates[2] + coordinates[3];
    for (int m = 0; m < 4; ++m) lambda[m] = coordinates[m] / sum;
    return true;
  }
  // The nearest point of the faces that see the origin (the face opposite m sees it when the
  // origin's coordinate m is not positive).
  static constexpr int kFaces[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
  double best = 1e300;
  for (int m = 0; m < 4; ++m) {
    if (!visible[m]) continue;
    const DVec3 face[3] = {w[kFaces[m][0]], w[kFaces[m][1]], w[kFaces[m][2]]};
    double faceLambda[3];
    solveTriangle(face, faceLambda);
    const double distance =
        squaredLength(faceLambda[0] * face[0] + faceLambda[1] * face[1] + faceLambda[2] * face[2]);
    if (distance < best) {
      best = distance;
      lambda[m] = 0.0;
      for (int n = 0; n < 3; ++n) lambda[kFaces[m][n]] = faceLambda[n];
    }
  }
  return false;
}

// The closest point kept in double precision: near convergence on curved shapes an iteration turns v
// by ~1e-4 while |v|² changes below float resolution, and a float v would stall there.
bool closestPointOfSimplexD(Simplex& simplex, DVec3& outClosest) {
  DVec3 w[4];
  for (int i = 0; i < simplex.count; ++i) w[i] = DVec3(simplex.vertices[i].w);
  double lambda[4] = {1.0, 0.0, 0.0, 0.0};
  switch (simplex.count) {
    case 1:
      break;
    case 2:
      solveSegment(w[0], w[1], lambda);
      break;
    case 3:
      solveTriangle(w, lambda);
      break;
    case 4:
      if (solveTetrahedron(w, lambda)) {
        for (int i = 0; i < 4; ++i) simplex.lambda[i] = lambda[i];
        outClosest = DVec3(0.0);
        return false;
      }
      break;
    default:
      break;
  }
  compact(simplex, lambda, simplex.count);
  outClosest = pointOf(simplex);
  return true;
}

}  // namespace

bool closestPointOfSimplex(Simplex& simplex, Vec3& outClosest) {
  DVec3 closest;
  const bool outside = closestPointOfSimplexD(simplex, closest);
  outClosest = Vec3(closest);
  return outside;
}

namespace {

// GJK runs in A's frame (A's rotation, origin at A's position, world units): A's support then needs
// no transform, and B's one rotation of the direction in and one of the point out, where a support
// in world coordinates rotates both ways for both shapes. The answers are rotated back at the end.
struct PairFrame {
  const ConvexSupport& a;
  const ConvexSupport& b;
  Mat3 rotationB;  // B's axes in A's frame: RAᵀ RB
  Vec3 positionB;  // B's origin in A's frame

  PairFrame(const ConvexSupport& shapeA, const ConvexSupport& shapeB)
      : a(shapeA),
        b(shapeB),
        rotationB(glm::transpose(shapeA.rotation) * shapeB.rotation),
        positionB((shapeB.position - shapeA.position) * shapeA.rotation) {}

  static Vec3 inflate(const ConvexSupport& shape, const Vec3& point, const Vec3& direction) {
    if (!shape.inflated) return point;
    const float length = glm::length(direction);
    return length > 0.0f ? point + (shape.radius / length) * direction : point;
  }
  Vec3 supportA(const Vec3& direction) const {
    return inflate(a, a.scale * a.localSupportCore(direction), direction);
  }
  Vec3 supportB(const Vec3& direction) const {
    const Vec3 local = direction * rotationB;  // RBᵀ d
    return inflate(b, positionB + rotationB * (b.scale * b.localSupportCore(local)), direction);
  }
  SimplexVertex support(const Vec3& direction) const {
    SimplexVertex v;
    v.a = supportA(direction);
    v.b = supportB(-direction);
    v.w = v.a - v.b;
    return v;
  }

  // Between the frame and the shapes' local frames (the warm-start cache) and the world.
  Vec3 fromLocalA(const Vec3& local) const { return a.scale * local; }
  Vec3 fromLocalB(const Vec3& local) const { return positionB + rotationB * (b.scale * local); }
  Vec3 toLocalA(const Vec3& p) const { return p / a.scale; }
  Vec3 toLocalB(const Vec3& p) const { return ((p - positionB) * rotationB) / b.scale; }
  Vec3 toWorld(const Vec3& p) const { return a.position + a.rotation * p; }
};

void saveCache(const PairFrame& frame, const Simplex& simplex, GjkCache* cache) {
  if (cache == nullptr) return;
  cache->count = simplex.count;
  for (int i = 0; i < simplex.count; ++i) {
    cache->localA[i] = frame.toLocalA(simplex.vertices[i].a);
    cache->localB[i] = frame.toLocalB(simplex.vertices[i].b);
  }
}

// The result's points, normal and simplex from A's frame into the world (EPA goes on from the
// simplex in world coordinates).
void finishInWorld(const PairFrame& frame, GjkResult& result) {
  result.pointOnA = frame.toWorld(result.pointOnA);
  result.pointOnB = frame.toWorld(result.pointOnB);
  // Renormalised: a rotation within the accepted 1e-3 of unit length scales what it turns, so the
  // normal would be off unit length by as much.
  if (result.status == GjkResult::Status::Separated)
    result.normal = glm::normalize(frame.a.rotation * result.normal);
  for (int i = 0; i < result.simplex.count; ++i) {
    SimplexVertex& vertex = result.simplex.vertices[i];
    vertex.a = frame.toWorld(vertex.a);
    vertex.b = frame.toWorld(vertex.b);
    vertex.w = vertex.a - vertex.b;
  }
}

// The closest points on A and B from the simplex's coordinates, summed in double precision like the
// closest point; the warm start's early answer and the end of the loop both need them.
void witnessPoints(GjkResult& result) {
  const Simplex& simplex = result.simplex;
  DVec3 pointOnA(0.0), pointOnB(0.0);
  for (int i = 0; i < simplex.count; ++i) {
    pointOnA += simplex.lambda[i] * DVec3(simplex.vertices[i].a);
    pointOnB += simplex.lambda[i] * DVec3(simplex.vertices[i].b);
  }
  result.pointOnA = Vec3(pointOnA);
  result.pointOnB = Vec3(pointOnB);
}

// The first simplex: the cached one placed by the current transforms (a warm start, for shapes
// without an inflated radius), else one support point towards the origin. Apart from the loop,
// which starts from either alike. True when the cached tetrahedron still encloses the origin: the
// pair overlaps, EPA can start from it, and `result` holds the answer in A's frame.
bool startSimplex(const PairFrame& frame, const GjkCache* cache, GjkResult& result) {
  Simplex& simplex = result.simplex;
  if (cache != nullptr && cache->count > 0 && !frame.a.inflated && !frame.b.inflated) {
    simplex.count = std::min(cache->count, 4);
    for (int i = 0; i < simplex.count; ++i) {
      SimplexVertex& vertex = simplex.vertices[i];
      vertex.a = frame.fromLocalA(cache->localA[i]);
      vertex.b = frame.fromLocalB(cache->localB[i]);
      vertex.w = vertex.a - vertex.b;
    }
    DVec3 closest;
    if (!closestPointOfSimplexD(simplex, closest)) {
      result.status = GjkResult::Status::Overlapping;
      result.iterations = 0;
      witnessPoints(result);
      return true;
    }
  } else {
    // A - B contains a.center() - b.center() (the origins); the origin lies in direction
    // b.center() - a.center() from it.
    Vec3 direction = frame.positionB;
    if (glm::dot(direction, direction) < 1e-20f) direction = Vec3(1.0f, 0.0f, 0.0f);
    simplex.vertices[0] = frame.support(direction);
    simplex.lambda[0] = 1.0;
    simplex.count = 1;
  }
  return false;
}

double largestSquared(const Simplex& simplex) {
  double largest = 0.0;
  for (int i = 0; i < simplex.count; ++i)
    largest = std::max(largest, squaredLength(DVec3(simplex.vertices[i].w)));
  return largest;
}

}  // namespace

GjkResult gjkDistance(const ConvexSupport& a, const ConvexSupport& b, float bound, GjkCache* cache) {
  const PairFrame frame(a, b);
  GjkResult result;
  Simplex& simplex = result.simplex;
  if (startSimplex(frame, cache, result)) {
    // The cached tetrahedron still encloses the origin: overlapping, and EPA can start from it.
    saveCache(frame, simplex, cache);
    finishInWorld(frame, result);
    return result;
  }
  DVec3 v = pointOf(simplex);
  double maxVertexSquared = largestSquared(simplex);
  const double boundSquared = bound < 1e15f ? double(bound) * double(bound) : 1e30;
  bool overlapping = false;

  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    result.iterations = iteration + 1;
    const double vv = glm::dot(v, v);
    if (vv <= kTouchingSquared * std::max(maxVertexSquared, 1e-30)) {
      overlapping = true;
      break;
    }
    const SimplexVertex next = frame.support(Vec3(-v));
    const double vw = glm::dot(v, DVec3(next.w));
    // v·w / |v| is a lower bound of the distance (the plane through w normal to v separates the
    // origin from A - B): once it exceeds the bound the caller does not care about the rest.
    if (vw > 0.0 && vw * vw > boundSquared * vv) {
      result.status = GjkResult::Status::BeyondBound;
      saveCache(frame, simplex, cache);
      return result;
    }
    // No progress beyond the relative tolerance: v is the closest point (van den Bergen 1999).
    // The |v| |w| term is single precision's floor: the support points are floats, so a small
    // distance between large shapes cannot converge relative to itself alone.
    if (vv - vw <= kRelativeGap * (vv + std::sqrt(vv * maxVertexSquared))) break;
    // A repeated vertex means the support cannot get any closer either (rounding).
    bool repeated = false;
    for (int i = 0; i < simplex.count; ++i) {
      if (simplex.vertices[i].w == next.w) repeated = true;
    }
    if (repeated) break;

    const Simplex previous = simplex;
    simplex.vertices[simplex.count++] = next;
    DVec3 closest;
    if (!closestPointOfSimplexD(simplex, closest)) {
      overlapping = true;
      break;
    }
    const double closestSquared = glm::dot(closest, closest);
    if (closestSquared >= vv) {
      // No progress (rounding in the solve): keep the previous answer and stop.
      simplex = previous;
      break;
    }
    v = closest;
    maxVertexSquared = largestSquared(simplex);
  }

  witnessPoints(result);
  saveCache(frame, simplex, cache);
  if (overlapping) {
    result.status = GjkResult::Status::Overlapping;
    result.distance = 0.0f;
  } else {
    result.status = GjkResult::Status::Separated;
    const double length = std::sqrt(glm::dot(v, v));
    result.distance = static_cast<float>(length);
    result.normal = Vec3(-v / length);
  }
  finishInWorld(frame, result);
  return result;
}

}  // namespace collide::detail
