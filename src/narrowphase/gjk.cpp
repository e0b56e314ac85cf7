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

// The closest point kept in double precision: near convergence on curved shapes an iteration turns v
// by ~1e-4 while |v|² changes below float resolution, and a float v would stall there.
bool closestPointOfSimplexD(Simplex& simplex, DVec3& outClosest) {
  switch (simplex.count) {
    case 1:
      simplex.lambda[0] = 1.0;
      break;
    case 2: {
      const DVec3 l =
          closestBarycentricOnSegment(DVec3(simplex.vertices[0].w), DVec3(simplex.vertices[1].w), DVec3(0.0));
      const double lambda[2] = {l.x, l.y};
      compact(simplex, lambda, 2);
      break;
    }
    case 3: {
      const DVec3 l =
          closestBarycentricOnTriangleD(DVec3(simplex.vertices[0].w), DVec3(simplex.vertices[1].w),
                                        DVec3(simplex.vertices[2].w), DVec3(0.0));
      const double lambda[3] = {l.x, l.y, l.z};
      compact(simplex, lambda, 3);
      break;
    }
    case 4: {
      // Inside when the origin is on the inner side of all four faces. A nearly flat tetrahedron
      // gives those signs no meaning, so it never counts as enclosing the origin (GJK then goes
      // on, or ends on its other tests). Outside, the closest point of the solid is the closest
      // of its four faces' closest points: all four are evaluated rather than trusting the signs.
      static constexpr int kFaces[4][4] = {{0, 1, 2, 3}, {0, 3, 1, 2}, {0, 2, 3, 1}, {1, 3, 2, 0}};
      const DVec3 w[4] = {DVec3(simplex.vertices[0].w), DVec3(simplex.vertices[1].w),
                          DVec3(simplex.vertices[2].w), DVec3(simplex.vertices[3].w)};
      const DVec3 e1 = w[1] - w[0], e2 = w[2] - w[0], e3 = w[3] - w[0];
      const double volume = glm::dot(e3, glm::cross(e1, e2));
      const bool flat = std::abs(volume) <= 1e-6 * glm::length(e1) * glm::length(e2) * glm::length(e3);
      bool inside = !flat;
      for (const auto& face : kFaces) {
        if (!inside) break;
        const DVec3& a = w[face[0]];
        const DVec3 n = glm::cross(w[face[1]] - a, w[face[2]] - a);
        if (-glm::dot(n, a) * glm::dot(n, w[face[3]] - a) < 0.0) inside = false;
      }
      if (inside) {
        outClosest = DVec3(0.0);
        return false;
      }
      double bestDistance = 1e300;
      double bestLambda[4] = {0, 0, 0, 0};
      for (const auto& face : kFaces) {
        const DVec3& a = w[face[0]];
        const DVec3& b = w[face[1]];
        const DVec3& c = w[face[2]];
        const DVec3 l = closestBarycentricOnTriangleD(a, b, c, DVec3(0.0));
        const DVec3 q = l.x * a + l.y * b + l.z * c;
        const double distance = glm::dot(q, q);
        if (distance < bestDistance) {
          bestDistance = distance;
          std::fill(bestLambda, bestLambda + 4, 0.0);
          bestLambda[face[0]] = l.x;
          bestLambda[face[1]] = l.y;
          bestLambda[face[2]] = l.z;
        }
      }
      compact(simplex, bestLambda, 4);
      break;
    }
    default:
      break;
  }
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

void saveCache(const ConvexSupport& a, const ConvexSupport& b, const Simplex& simplex, GjkCache* cache) {
  if (cache == nullptr) return;
  cache->count = simplex.count;
  for (int i = 0; i < simplex.count; ++i) {
    cache->localA[i] = a.toLocal(simplex.vertices[i].a);
    cache->localB[i] = b.toLocal(simplex.vertices[i].b);
  }
}

}  // namespace

GjkResult gjkDistance(const ConvexSupport& a, const ConvexSupport& b, float bound, GjkCache* cache) {
  GjkResult result;
  Simplex& simplex = result.simplex;
  if (cache != nullptr && cache->count > 0 && !a.inflated && !b.inflated) {
    // Warm start: last query's simplex placed by the current transforms.
    simplex.count = std::min(cache->count, 4);
    for (int i = 0; i < simplex.count; ++i) {
      SimplexVertex& vertex = simplex.vertices[i];
      vertex.a = a.toWorld(cache->localA[i]);
      vertex.b = b.toWorld(cache->localB[i]);
      vertex.w = vertex.a - vertex.b;
    }
    DVec3 closest;
    if (!closestPointOfSimplexD(simplex, closest)) {
      // The cached tetrahedron still encloses the origin: overlapping, and EPA can start from it.
      result.status = GjkResult::Status::Overlapping;
      result.iterations = 0;
      DVec3 pointOnA(0.0), pointOnB(0.0);
      for (int i = 0; i < simplex.count; ++i) {
        pointOnA += simplex.lambda[i] * DVec3(simplex.vertices[i].a);
        pointOnB += simplex.lambda[i] * DVec3(simplex.vertices[i].b);
      }
      result.pointOnA = Vec3(pointOnA);
      result.pointOnB = Vec3(pointOnB);
      saveCache(a, b, simplex, cache);
      return result;
    }
  } else {
    // A - B contains a.center() - b.center(); the origin lies in direction b.center() - a.center()
    // from it.
    Vec3 direction = b.center() - a.center();
    if (glm::dot(direction, direction) < 1e-20f) direction = Vec3(1.0f, 0.0f, 0.0f);
    simplex.vertices[0] = minkowskiSupport(a, b, direction);
    simplex.lambda[0] = 1.0;
    simplex.count = 1;
  }
  DVec3 v = pointOf(simplex);
  double maxVertexSquared = 0.0;
  for (int i = 0; i < simplex.count; ++i) {
    maxVertexSquared =
        std::max(maxVertexSquared, glm::dot(DVec3(simplex.vertices[i].w), DVec3(simplex.vertices[i].w)));
  }
  const double boundSquared = bound < 1e15f ? double(bound) * double(bound) : 1e30;
  bool overlapping = false;

  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    result.iterations = iteration + 1;
    const double vv = glm::dot(v, v);
    if (vv <= kTouchingSquared * std::max(maxVertexSquared, 1e-30)) {
      overlapping = true;
      break;
    }
    const SimplexVertex next = minkowskiSupport(a, b, Vec3(-v));
    const double vw = glm::dot(v, DVec3(next.w));
    // v·w / |v| is a lower bound of the distance (the plane through w normal to v separates the
    // origin from A - B): once it exceeds the bound the caller does not care about the rest.
    if (vw > 0.0 && vw * vw > boundSquared * vv) {
      result.status = GjkResult::Status::BeyondBound;
      saveCache(a, b, simplex, cache);
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
    maxVertexSquared = 0.0;
    for (int i = 0; i < simplex.count; ++i) {
      maxVertexSquared =
          std::max(maxVertexSquared, glm::dot(DVec3(simplex.vertices[i].w), DVec3(simplex.vertices[i].w)));
    }
  }

  DVec3 pointOnA(0.0), pointOnB(0.0);
  for (int i = 0; i < simplex.count; ++i) {
    pointOnA += simplex.lambda[i] * DVec3(simplex.vertices[i].a);
    pointOnB += simplex.lambda[i] * DVec3(simplex.vertices[i].b);
  }
  result.pointOnA = Vec3(pointOnA);
  result.pointOnB = Vec3(pointOnB);
  saveCache(a, b, simplex, cache);
  if (overlapping) {
    result.status = GjkResult::Status::Overlapping;
    result.distance = 0.0f;
  } else {
    result.status = GjkResult::Status::Separated;
    const double length = std::sqrt(glm::dot(v, v));
    result.distance = static_cast<float>(length);
    result.normal = Vec3(-v / length);
  }
  return result;
}

}  // namespace collide::detail
