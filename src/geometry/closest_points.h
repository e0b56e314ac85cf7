// Closest points between simple primitives: point–segment and segment–segment. Shared by the narrow
// phase (capsule pairs, the lecture's capsule–capsule test, slide 61) and by later continuous
// detection.
#pragma once

#include <collide/math.h>

namespace collide::detail {

// The parameter t in [0, 1] of the point of segment [a, b] nearest to p. A degenerate segment
// (a == b) gives t = 0.
float closestParameterOnSegment(const Vec3& p, const Vec3& a, const Vec3& b);

struct SegmentPair {
  float s = 0.0f;  // parameter on the first segment, in [0, 1]
  float t = 0.0f;  // parameter on the second segment, in [0, 1]
  Vec3 pointOnFirst{0.0f};
  Vec3 pointOnSecond{0.0f};
  float distanceSquared = 0.0f;
};

// The closest points of segments [p1, q1] and [p2, q2] (Ericson, "Real-Time Collision Detection",
// 5.1.9), robust for degenerate (point) segments. For parallel segments, whose closest pairs form a
// whole interval, it returns one of them (s at an end of the overlap).
SegmentPair closestPointsSegmentSegment(const Vec3& p1, const Vec3& q1, const Vec3& p2, const Vec3& q2);

}  // namespace collide::detail
