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

Vec3 closestBarycentricOnSegment(const Vec3& a, const Vec3& b, const Vec3& p) {
  const Vec3 ab = b - a;
  const float lengthSquared = glm::dot(ab, ab);
  if (lengthSquared <= 0.0f) return {1.0f, 0.0f, 0.0f};
  const float t = std::clamp(glm::dot(p - a, ab) / lengthSquared, 0.0f, 1.0f);
  if (t == 0.0f) return {1.0f, 0.0f, 0.0f};
  if (t == 1.0f) return {0.0f, 1.0f, 0.0f};
  return {1.0f - t, t, 0.0f};
}

}  // namespace

Vec3 closestBarycentricOnTriangle(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& p) {
  // Voronoi regions of the vertices, then the edges, then the face (Ericson 5.1.5).
  const Vec3 ab = b - a;
  const Vec3 ac = c - a;
  const Vec3 ap = p - a;
  const float d1 = glm::dot(ab, ap);
  const float d2 = glm::dot(ac, ap);
  if (d1 <= 0.0f && d2 <= 0.0f) return {1.0f, 0.0f, 0.0f};
  const Vec3 bp = p - b;
  const float d3 = glm::dot(ab, bp);
  const float d4 = glm::dot(ac, bp);
  if (d3 >= 0.0f && d4 <= d3) return {0.0f, 1.0f, 0.0f};
  const float vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) {
    const float v = d1 / (d1 - d3);
    return {1.0f - v, v, 0.0f};
  }
  const Vec3 cp = p - c;
  const float d5 = glm::dot(ab, cp);
  const float d6 = glm::dot(ac, cp);
  if (d6 >= 0.0f && d5 <= d6) return {0.0f, 0.0f, 1.0f};
  const float vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) {
    const float w = d2 / (d2 - d6);
    return {1.0f - w, 0.0f, w};
  }
  const float va = d3 * d6 - d5 * d4;
  if (va <= 0.0f && d4 - d3 >= 0.0f && d5 - d6 >= 0.0f) {
    const float w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0.0f, 1.0f - w, w};
  }
  const float sum = va + vb + vc;  // |ab × ac|², the squared double area
  const float scale = glm::dot(ab, ab) * glm::dot(ac, ac);
  if (!(sum > 1e-12f * scale)) {
    // A sliver triangle: the face region is numerically meaningless; take the best edge.
    const Vec3 eab = closestBarycentricOnSegment(a, b, p);
    const Vec3 eac = closestBarycentricOnSegment(a, c, p);
    const Vec3 ebc = closestBarycentricOnSegment(b, c, p);
    const Vec3 candidates[3] = {{eab.x, eab.y, 0.0f}, {eac.x, 0.0f, eac.y}, {0.0f, ebc.x, ebc.y}};
    Vec3 best = candidates[0];
    float bestDistance = 1e30f;
    for (const Vec3& candidate : candidates) {
      const Vec3 q = candidate.x * a + candidate.y * b + candidate.z * c - p;
      const float distance = glm::dot(q, q);
      if (distance < bestDistance) {
        bestDistance = distance;
        best = candidate;
      }
    }
    return best;
  }
  const float v = vb / sum;
  const float w = vc / sum;
  return {1.0f - v - w, v, w};
}

namespace {

// Keeps the vertices with a non-zero coordinate, in order.
void compact(Simplex& simplex, const float* lambda, int count) {
  int kept = 0;
  for (int i = 0; i < count; ++i) {
    if (lambda[i] > 0.0f) {
      simplex.vertices[kept] = simplex.vertices[i];
      simplex.lambda[kept] = lambda[i];
      ++kept;
    }
  }
  if (kept == 0) {  // cannot happen for coordinates summing to 1; keep the first vertex to be safe
    simplex.lambda[0] = 1.0f;
    kept = 1;
  }
  simplex.count = kept;
}

Vec3 pointOf(const Simplex& simplex) {
  Vec3 p(0.0f);
  for (int i = 0; i < simplex.count; ++i) p += simplex.lambda[i] * simplex.vertices[i].w;
  return p;
}

}  // namespace

bool closestPointOfSimplex(Simplex& simplex, Vec3& outClosest) {
  const Vec3 origin(0.0f);
  switch (simplex.count) {
    case 1:
      simplex.lambda[0] = 1.0f;
      break;
    case 2: {
      const Vec3 l = closestBarycentricOnSegment(simplex.vertices[0].w, simplex.vertices[1].w, origin);
      const float lambda[2] = {l.x, l.y};
      compact(simplex, lambda, 2);
      break;
    }
    case 3: {
      const Vec3 l = closestBarycentricOnTriangle(simplex.vertices[0].w, simplex.vertices[1].w,
                                                  simplex.vertices[2].w, origin);
      const float lambda[3] = {l.x, l.y, l.z};
      compact(simplex, lambda, 3);
      break;
    }
    case 4: {
      // The origin is inside unless it lies beyond one of the four faces; then the closest point is
      // on the nearest such face.
      static constexpr int kFaces[4][4] = {{0, 1, 2, 3}, {0, 3, 1, 2}, {0, 2, 3, 1}, {1, 3, 2, 0}};
      const Vec3* w[4] = {&simplex.vertices[0].w, &simplex.vertices[1].w, &simplex.vertices[2].w,
                          &simplex.vertices[3].w};
      const Vec3 e1 = *w[1] - *w[0], e2 = *w[2] - *w[0], e3 = *w[3] - *w[0];
      const float volume = glm::dot(e3, glm::cross(e1, e2));
      const bool flat = std::abs(volume) <= 1e-6f * glm::length(e1) * glm::length(e2) * glm::length(e3);
      float bestDistance = 1e30f;
      float bestLambda[4] = {0, 0, 0, 0};
      bool outside = false;
      for (const auto& face : kFaces) {
        const Vec3& a = *w[face[0]];
        const Vec3& b = *w[face[1]];
        const Vec3& c = *w[face[2]];
        const Vec3& d = *w[face[3]];
        const Vec3 n = glm::cross(b - a, c - a);
        const float originSide = -glm::dot(n, a);
        const float oppositeSide = glm::dot(n, d - a);
        if (!flat && originSide * oppositeSide >= 0.0f) continue;  // origin on the inner side
        outside = true;
        const Vec3 l = closestBarycentricOnTriangle(a, b, c, origin);
        const Vec3 q = l.x * a + l.y * b + l.z * c;
        const float distance = glm::dot(q, q);
        if (distance < bestDistance) {
          bestDistance = distance;
          std::fill(bestLambda, bestLambda + 4, 0.0f);
          bestLambda[face[0]] = l.x;
          bestLambda[face[1]] = l.y;
          bestLambda[face[2]] = l.z;
        }
      }
      if (!outside) {
        outClosest = origin;
        return false;
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

GjkResult gjkDistance(const ConvexSupport& a, const ConvexSupport& b, float bound) {
  GjkResult result;
  Simplex& simplex = result.simplex;
  // A - B contains a.center() - b.center(); the origin lies in direction b.center() - a.center() from it.
  Vec3 direction = b.center() - a.center();
  if (glm::dot(direction, direction) < 1e-20f) direction = Vec3(1.0f, 0.0f, 0.0f);
  simplex.vertices[0] = minkowskiSupport(a, b, direction);
  simplex.lambda[0] = 1.0f;
  simplex.count = 1;
  Vec3 v = simplex.vertices[0].w;
  float maxVertexSquared = glm::dot(v, v);
  const float boundSquared = bound < 1e15f ? bound * bound : 1e30f;
  bool overlapping = false;

  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    result.iterations = iteration + 1;
    const float vv = glm::dot(v, v);
    if (vv <= kTouchingSquared * std::max(maxVertexSquared, 1e-30f)) {
      overlapping = true;
      break;
    }
    const SimplexVertex next = minkowskiSupport(a, b, -v);
    const float vw = glm::dot(v, next.w);
    // v·w / |v| is a lower bound of the distance (the plane through w normal to v separates the
    // origin from A - B): once it exceeds the bound the caller does not care about the rest.
    if (vw > 0.0f && vw * vw > boundSquared * vv) {
      result.status = GjkResult::Status::BeyondBound;
      return result;
    }
    // No progress beyond the relative tolerance: v is the closest point (van den Bergen 1999).
    if (vv - vw <= kRelativeGap * vv) break;
    // A repeated vertex means the support cannot get any closer either (rounding).
    bool repeated = false;
    for (int i = 0; i < simplex.count; ++i) {
      if (simplex.vertices[i].w == next.w) repeated = true;
    }
    if (repeated) break;

    const Simplex previous = simplex;
    simplex.vertices[simplex.count++] = next;
    Vec3 closest;
    if (!closestPointOfSimplex(simplex, closest)) {
      overlapping = true;
      break;
    }
    const float closestSquared = glm::dot(closest, closest);
    if (closestSquared >= vv) {
      // Rounding made the new simplex no better: keep the previous answer and stop.
      simplex = previous;
      break;
    }
    v = closest;
    maxVertexSquared = 0.0f;
    for (int i = 0; i < simplex.count; ++i) {
      maxVertexSquared = std::max(maxVertexSquared, glm::dot(simplex.vertices[i].w, simplex.vertices[i].w));
    }
  }

  Vec3 pointOnA(0.0f), pointOnB(0.0f);
  for (int i = 0; i < simplex.count; ++i) {
    pointOnA += simplex.lambda[i] * simplex.vertices[i].a;
    pointOnB += simplex.lambda[i] * simplex.vertices[i].b;
  }
  result.pointOnA = pointOnA;
  result.pointOnB = pointOnB;
  if (overlapping) {
    result.status = GjkResult::Status::Overlapping;
    result.distance = 0.0f;
  } else {
    result.status = GjkResult::Status::Separated;
    result.distance = std::sqrt(glm::dot(v, v));
  }
  return result;
}

}  // namespace collide::detail
