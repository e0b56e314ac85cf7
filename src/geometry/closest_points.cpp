// Point–segment and segment–segment closest points.
#include "geometry/closest_points.h"

#include <algorithm>

namespace collide::detail {

float closestParameterOnSegment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const float lengthSquared = glm::dot(ab, ab);
  if (lengthSquared <= 1e-30f) return 0.0f;
  return std::clamp(glm::dot(p - a, ab) / lengthSquared, 0.0f, 1.0f);
}

SegmentPair closestPointsSegmentSegment(const Vec3& p1, const Vec3& q1, const Vec3& p2, const Vec3& q2) {
  // Minimise |p1 + s d1 - p2 - t d2|² over the unit square. The unconstrained minimum on one line
  // is clamped, the other parameter is recomputed for it and clamped in turn; that pair is the
  // constrained minimum because the function is convex (Ericson 5.1.9).
  const Vec3 d1 = q1 - p1;
  const Vec3 d2 = q2 - p2;
  const Vec3 r = p1 - p2;
  const float a = glm::dot(d1, d1);
  const float e = glm::dot(d2, d2);
  const float f = glm::dot(d2, r);
  constexpr float kDegenerate = 1e-30f;
  float s = 0.0f;
  float t = 0.0f;
  if (a <= kDegenerate && e <= kDegenerate) {
    s = t = 0.0f;
  } else if (a <= kDegenerate) {
    t = std::clamp(f / e, 0.0f, 1.0f);
  } else {
    const float c = glm::dot(d1, r);
    if (e <= kDegenerate) {
      s = std::clamp(-c / a, 0.0f, 1.0f);
    } else {
      const float b = glm::dot(d1, d2);
      const float denominator = a * e - b * b;  // |d1 × d2|², >= 0
      // Parallel lines: any s is a closest pair on the lines; start from s = 0 and let the clamping
      // below pick the matching t (and move s if t had to be clamped).
      s = denominator > 1e-12f * a * e ? std::clamp((b * f - c * e) / denominator, 0.0f, 1.0f) : 0.0f;
      t = (b * s + f) / e;
      if (t < 0.0f) {
        t = 0.0f;
        s = std::clamp(-c / a, 0.0f, 1.0f);
      } else if (t > 1.0f) {
        t = 1.0f;
        s = std::clamp((b - c) / a, 0.0f, 1.0f);
      }
    }
  }
  SegmentPair result;
  result.s = s;
  result.t = t;
  result.pointOnFirst = p1 + s * d1;
  result.pointOnSecond = p2 + t * d2;
  const Vec3 gap = result.pointOnFirst - result.pointOnSecond;
  result.distanceSquared = glm::dot(gap, gap);
  return result;
}

}  // namespace collide::detail
