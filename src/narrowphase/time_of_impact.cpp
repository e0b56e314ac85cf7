// Time of impact: when two moving shapes first come within a target gap (docs/ccd.md).
//
// Two methods. A sphere whose centre moves in a straight line relative to a shape that does not
// turn sweeps a capsule (the lecture): its time of impact is a segment cast against the other shape
// grown by the sphere's radius, the Minkowski sum, answered exactly for planes, boxes, triangles,
// spheres and capsules. Every other pair goes by conservative advancement (Mirtich, "Impulse-based
// Dynamic Simulation of Rigid Body Systems", 1996; Catto, "Continuous Collision", GDC 2013): at the
// current time take the distance d, bound how fast any point of one shape can approach the other,
// and advance by (d - target) / bound, which can never step past the contact. Meshes and compounds
// are taken apart into triangles and children, and the earliest hit wins.
#include <collide/narrowphase.h>

#include "base/fail.h"
#include "narrowphase/convex_distance.h"
#include "narrowphase/convex_support.h"
#include "narrowphase/pair_functions.h"
#include "shapes/shape_functions.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>

namespace collide {

Sweep Sweep::fixed(const Transform& transform) { return between(transform, transform); }

Sweep Sweep::between(const Transform& start, const Transform& end, const Vec3& localCenter) {
  Sweep sweep;
  sweep.localCenter = localCenter;
  sweep.rotation0 = start.rotation;
  sweep.rotation1 = end.rotation;
  sweep.center0 = start.position + start.rotation * localCenter;
  sweep.center1 = end.position + end.rotation * localCenter;
  sweep.scale = start.scale;
  return sweep;
}

Transform Sweep::at(float t) const {
  const Quat q =
      t <= 0.0f ? rotation0 : (t >= 1.0f ? rotation1 : glm::normalize(glm::slerp(rotation0, rotation1, t)));
  const Vec3 c = center0 + t * (center1 - center0);
  return {c - q * localCenter, q, scale};
}

float Sweep::angle() const {
  // From the relative rotation's vector and scalar parts: atan2 keeps small angles accurate where
  // acos of the dot product would turn float noise into milliradians.
  const Quat relative = rotation1 * glm::conjugate(rotation0);
  const float sinHalf = glm::length(Vec3(relative.x, relative.y, relative.z));
  return 2.0f * std::atan2(sinHalf, std::abs(relative.w));
}

namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

// A convex piece of a shape: the shape itself, one triangle of a mesh, or a plane.
struct Piece {
  enum class Kind : std::uint8_t { Convex, Triangle, Plane };
  Kind kind = Kind::Convex;
  const Shape* shape = nullptr;    // Convex, Plane
  std::array<Vec3, 3> triangle{};  // Triangle: local vertices
  Sweep sweep;

  detail::ConvexSupport support(const Transform& transform) const {
    return kind == Kind::Triangle ? detail::makePointsSupport(triangle.data(), 3, transform)
                                  : detail::makeConvexSupport(*shape, transform);
  }
};

// The farthest a point of the piece's core lies from its centre of rotation: the lever arm of
// Catto's bound |delta x| + angle * r_max. The rounded part (a sphere's or capsule's radius) does
// not count, since turning does not move it relative to the core.
float coreReach(const Piece& piece) {
  const Sweep& s = piece.sweep;
  if (piece.kind == Piece::Kind::Triangle) {
    float reach = 0.0f;
    for (const Vec3& v : piece.triangle) reach = std::max(reach, glm::length(s.scale * v - s.localCenter));
    return reach;
  }
  if (piece.kind == Piece::Kind::Plane) return kInfinity;
  const Shape& shape = *piece.shape;
  float extent = 0.0f;
  switch (shape.type()) {
    case ShapeType::Sphere:
      extent = 0.0f;
      break;
    case ShapeType::Capsule:
      extent = shape.capsule().halfHeight;
      break;
    default: {
      const BoundingSphere bound = localBoundingSphere(shape);
      extent = glm::length(bound.center) + bound.radius;
    }
  }
  return glm::length(s.localCenter) + s.scale * extent;
}

// The combined answer over several pieces: the earliest hit; "overlapping" only when nothing hits.
void keepEarliest(ToiResult& best, const ToiResult& candidate) {
  best.iterations += candidate.iterations;
  const int iterations = best.iterations;
  if (candidate.hit()) {
    if (!best.hit() || candidate.t < best.t) best = candidate;
  } else if (candidate.state == ToiResult::State::Overlapping && !best.hit() &&
             (best.state != ToiResult::State::Overlapping || candidate.separation < best.separation)) {
    best = candidate;  // the deepest of the pieces touching at the start
  }
  best.iterations = iterations;
}

ToiResult mirrored(ToiResult result) {
  result.normal = -result.normal;
  return result;
}

// ---- Exact sphere sweeps: a segment p + t d, t in [0, 1], against a shape grown by radius R. ----
// All in the other shape's local frame (divided by its scale), where t keeps its meaning.

std::optional<float> segmentSphere(const Vec3& p, const Vec3& d, const Vec3& center, float radius) {
  const Vec3 m = p - center;
  const float c = glm::dot(m, m) - radius * radius;
  if (c <= 0.0f) return 0.0f;
  const float a = glm::dot(d, d);
  const float b = glm::dot(m, d);
  if (b >= 0.0f || a <= 0.0f) return std::nullopt;  // moving away or not moving
  const float discriminant = b * b - a * c;
  if (discriminant < 0.0f) return std::nullopt;
  // The smaller root written as c / q (Numerical Recipes' stable form) to avoid cancellation.
  const float t = c / (-b + std::sqrt(discriminant));
  return t <= 1.0f ? std::optional<float>(t) : std::nullopt;
}

// The capsule is the finite cylinder around segment ab and the two end spheres.
std::optional<float> segmentCapsule(const Vec3& p, const Vec3& d, const Vec3& a, const Vec3& b,
                                    float radius) {
  std::optional<float> best;
  const auto keep = [&](std::optional<float> t) {
    if (t && (!best || *t < *best)) best = t;
  };
  keep(segmentSphere(p, d, a, radius));
  keep(segmentSphere(p, d, b, radius));
  const Vec3 axis = b - a;
  const float length = glm::length(axis);
  if (length <= 0.0f) return best;
  const Vec3 u = axis / length;
  const Vec3 m = p - a;
  const Vec3 mPerp = m - glm::dot(m, u) * u;
  const Vec3 dPerp = d - glm::dot(d, u) * u;
  const float qa = glm::dot(dPerp, dPerp);
  const float qb = glm::dot(mPerp, dPerp);
  const float qc = glm::dot(mPerp, mPerp) - radius * radius;
  float t = 0.0f;
  if (qc > 0.0f) {
    if (qa <= 0.0f || qb >= 0.0f) return best;
    const float discriminant = qb * qb - qa * qc;
    if (discriminant < 0.0f) return best;
    t = qc / (-qb + std::sqrt(discriminant));
    if (t > 1.0f) return best;
  }
  const float along = glm::dot(m + t * d, u);
  if (along >= 0.0f && along <= length) keep(t);
  return best;
}

// Segment against an axis-aligned box [-e, e] (slabs); the entry time, 0 when starting inside.
std::optional<float> segmentBox(const Vec3& p, const Vec3& d, const Vec3& e) {
  float enter = 0.0f, leave = 1.0f;
  for (int i = 0; i < 3; ++i) {
    if (std::abs(d[i]) < 1e-30f) {
      if (p[i] < -e[i] || p[i] > e[i]) return std::nullopt;
      continue;
    }
    float t0 = (-e[i] - p[i]) / d[i];
    float t1 = (e[i] - p[i]) / d[i];
    if (t0 > t1) std::swap(t0, t1);
    enter = std::max(enter, t0);
    leave = std::min(leave, t1);
    if (enter > leave) return std::nullopt;
  }
  return enter;
}

// The rounded box (box of half extents e grown by R) is the union of three boxes each grown along
// one axis and the twelve edge capsules. The entry into the box grown by R along all axes is the
// answer when it lies on a face (outside the box along at most one axis); otherwise it is in an
// edge or corner region, and the union gives the first entry exactly.
std::optional<float> segmentRoundedBox(const Vec3& p, const Vec3& d, const Vec3& e, float radius) {
  const std::optional<float> outer = segmentBox(p, d, e + Vec3(radius));
  if (!outer) return std::nullopt;
  const Vec3 q = p + *outer * d;
  int outside = 0;
  for (int i = 0; i < 3; ++i) outside += std::abs(q[i]) > e[i] ? 1 : 0;
  if (outside <= 1) return outer;
  std::optional<float> best;
  const auto keep = [&](std::optional<float> t) {
    if (t && (!best || *t < *best)) best = t;
  };
  for (int i = 0; i < 3; ++i) {
    Vec3 grown = e;
    grown[i] += radius;
    keep(segmentBox(p, d, grown));
  }
  for (int axis = 0; axis < 3; ++axis) {
    const int j = (axis + 1) % 3, k = (axis + 2) % 3;
    for (int sj = -1; sj <= 1; sj += 2) {
      for (int sk = -1; sk <= 1; sk += 2) {
        Vec3 a(0.0f);
        a[j] = static_cast<float>(sj) * e[j];
        a[k] = static_cast<float>(sk) * e[k];
        Vec3 b = a;
        a[axis] = -e[axis];
        b[axis] = e[axis];
        keep(segmentCapsule(p, d, a, b, radius));
      }
    }
  }
  return best;
}

// Triangle grown by R (two-sided): the prism between the triangle shifted by ±R along its normal,
// whose side walls lie inside the three edge capsules, and those capsules.
std::optional<float> segmentRoundedTriangle(const Vec3& p, const Vec3& d, const std::array<Vec3, 3>& tri,
                                            float radius) {
  std::optional<float> best;
  const auto keep = [&](std::optional<float> t) {
    if (t && (!best || *t < *best)) best = t;
  };
  const Vec3 areaNormal = glm::cross(tri[1] - tri[0], tri[2] - tri[0]);
  const float area2 = glm::length(areaNormal);
  if (area2 > 0.0f) {
    const Vec3 n = areaNormal / area2;
    const float height = glm::dot(p - tri[0], n);
    const float rate = glm::dot(d, n);
    // Inside test by the signs of the sub-triangle areas along n, for a point on the plane.
    const auto inside = [&](const Vec3& q) {
      return glm::dot(glm::cross(tri[1] - tri[0], q - tri[0]), n) >= 0.0f &&
             glm::dot(glm::cross(tri[2] - tri[1], q - tri[1]), n) >= 0.0f &&
             glm::dot(glm::cross(tri[0] - tri[2], q - tri[2]), n) >= 0.0f;
    };
    const float side = height >= 0.0f ? 1.0f : -1.0f;
    if (std::abs(height) < radius) {
      // Within the slab: inside the prism already when over the triangle (else only the edge
      // capsules, which hold the prism's side walls, can be entered).
      if (inside(p - height * n)) return 0.0f;
    } else if (rate * side < 0.0f) {
      // The face of the prism on the segment's side, reached when the height falls to ±R.
      const float t = (height - side * radius) / -rate;
      if (t <= 1.0f && inside(p + t * d - (height + t * rate) * n)) keep(t);
    }
  }
  for (int i = 0; i < 3; ++i) keep(segmentCapsule(p, d, tri[i], tri[(i + 1) % 3], radius));
  return best;
}

bool isSphere(const Piece& piece) {
  return piece.kind == Piece::Kind::Convex && piece.shape->type() == ShapeType::Sphere;
}

// The sphere's world centre moves in a straight line when it does not turn or turns about itself.
bool movesStraight(const Piece& sphere) {
  return sphere.sweep.angle() == 0.0f || glm::length(sphere.sweep.localCenter) <= 1e-6f * sphere.sweep.scale;
}

// Exact sweep of sphere A against B (plane, box, triangle, sphere, capsule) that does not turn;
// nullopt when this pair has no exact path.
std::optional<ToiResult> sphereSweep(const Piece& sphere, const Piece& other, const ToiSettings& settings) {
  if (!isSphere(sphere) || !movesStraight(sphere) || other.sweep.angle() != 0.0f) return std::nullopt;
  ShapeType otherType = ShapeType::Mesh;
  if (other.kind != Piece::Kind::Triangle) {
    otherType = other.shape->type();
    if (otherType != ShapeType::Plane && otherType != ShapeType::Box && otherType != ShapeType::Sphere &&
        otherType != ShapeType::Capsule)
      return std::nullopt;
  }
  const float radius = sphere.shape->sphere().radius * sphere.sweep.scale;
  const Transform frame0 = other.sweep.at(0.0f);
  const Transform frame1 = other.sweep.at(1.0f);
  // The sphere's centre in B's frame at 0 and 1: a straight segment, since B only translates.
  const Vec3 p = frame0.inverseApplyToPoint(sphere.sweep.at(0.0f).position);
  const Vec3 p1 = frame1.inverseApplyToPoint(sphere.sweep.at(1.0f).position);
  const Vec3 d = p1 - p;
  const float scale = frame0.scale;
  // Grown by the radius and the target gap, in B's unscaled frame.
  // (A negative target shrinks the radius; kept above zero so the sum stays a sphere.)
  const float grown = std::max(radius + settings.targetSeparation, 1e-6f * radius) / scale;
  const float touching =
      std::max(radius + settings.targetSeparation + settings.tolerance, 1e-6f * radius) / scale;

  std::optional<float> t;
  std::optional<float> atStart;  // overlap at t = 0 (grown by the tolerance too)
  const Vec3 zero(0.0f);
  switch (otherType) {
    case ShapeType::Plane: {
      const Plane& plane = other.shape->plane();
      const float height = plane.signedDistance(p);
      const float rate = glm::dot(plane.normal, d);
      if (height <= touching) {
        atStart = 0.0f;
      } else if (rate < 0.0f && height + rate <= grown) {
        t = (height - grown) / -rate;
      }
      break;
    }
    case ShapeType::Box:
      atStart = segmentRoundedBox(p, zero, other.shape->box().halfExtents, touching);
      if (!atStart) t = segmentRoundedBox(p, d, other.shape->box().halfExtents, grown);
      break;
    case ShapeType::Sphere:
      atStart = segmentSphere(p, zero, Vec3(0.0f), other.shape->sphere().radius + touching);
      if (!atStart) t = segmentSphere(p, d, Vec3(0.0f), other.shape->sphere().radius + grown);
      break;
    case ShapeType::Capsule: {
      const Capsule& c = other.shape->capsule();
      const Vec3 a(0.0f, -c.halfHeight, 0.0f), b(0.0f, c.halfHeight, 0.0f);
      atStart = segmentCapsule(p, zero, a, b, c.radius + touching);
      if (!atStart) t = segmentCapsule(p, d, a, b, c.radius + grown);
      break;
    }
    default:  // a triangle
      atStart = segmentRoundedTriangle(p, zero, other.triangle, touching);
      if (!atStart) t = segmentRoundedTriangle(p, d, other.triangle, grown);
      break;
  }

  ToiResult result;
  result.iterations = 1;
  if (!atStart && !t) return result;  // Separated, t = 1
  result.t = atStart ? 0.0f : *t;
  result.state = atStart ? ToiResult::State::Overlapping : ToiResult::State::Hit;
  // Normal and point from the distance query at t (cheap, and the same answer the contact gets).
  const Transform sphereAt = sphere.sweep.at(result.t);
  const Transform otherAt = other.sweep.at(result.t);
  DistanceResult gap;
  if (other.kind == Piece::Kind::Plane) {
    gap = distance(*sphere.shape, sphereAt, *other.shape, otherAt);
  } else {
    detail::convexSignedDistance(sphere.support(sphereAt), other.support(otherAt), kInfinity, gap);
  }
  result.normal = gap.normal;
  result.point = 0.5f * (gap.pointOnA + gap.pointOnB);
  result.separation = gap.distance;
  return result;
}

// ---- Conservative advancement ----

DistanceResult pieceDistance(const Piece& a, const Piece& b, float t) {
  const Transform ta = a.sweep.at(t);
  const Transform tb = b.sweep.at(t);
  if (a.kind == Piece::Kind::Plane || b.kind == Piece::Kind::Plane) {
    // The plane against a convex piece: the lowest point of the piece's support along -normal.
    const bool planeIsA = a.kind == Piece::Kind::Plane;
    const Piece& planePiece = planeIsA ? a : b;
    const Piece& convex = planeIsA ? b : a;
    const Plane surface = detail::worldPlane(planePiece.shape->plane(), planeIsA ? ta : tb);
    const detail::ConvexSupport support = convex.support(planeIsA ? tb : ta);
    const Vec3 lowest = support.supportCore(-surface.normal) - support.radius * surface.normal;
    DistanceResult result;
    result.distance = surface.signedDistance(lowest);
    result.pointOnB = lowest;
    result.pointOnA = lowest - result.distance * surface.normal;
    result.normal = surface.normal;
    if (!planeIsA) {
      std::swap(result.pointOnA, result.pointOnB);
      result.normal = -result.normal;
    }
    return result;
  }
  DistanceResult result;
  detail::convexSignedDistance(a.support(ta), b.support(tb), kInfinity, result);
  return result;
}

ToiResult advance(const Piece& a, const Piece& b, const ToiSettings& settings) {
  const Vec3 linear = (b.sweep.center1 - b.sweep.center0) - (a.sweep.center1 - a.sweep.center0);
  const float angleA = a.sweep.angle(), angleB = b.sweep.angle();
  const float angular =
      (angleA > 0.0f ? angleA * coreReach(a) : 0.0f) + (angleB > 0.0f ? angleB * coreReach(b) : 0.0f);
  const float target = settings.targetSeparation;
  ToiResult result;
  float t = 0.0f;
  bool apart = false;  // proven not to reach the target within [0, 1]
  for (int i = 0; i < settings.maxIterations && !apart; ++i) {
    const DistanceResult gap = pieceDistance(a, b, t);
    ++result.iterations;
    if (gap.distance < target + settings.tolerance) {
      result.state = i == 0 ? ToiResult::State::Overlapping : ToiResult::State::Hit;
      result.t = t;
      result.normal = gap.normal;
      result.point = 0.5f * (gap.pointOnA + gap.pointOnB);
      result.separation = gap.distance;
      return result;
    }
    // How fast the gap can close, per unit of t. Without turning, the distance of two convex sets
    // is a convex function of t along a straight relative motion, so its tangent (the approach
    // along the current normal) bounds it from below: advancing to where the tangent meets the
    // target never overshoots. With turning, the speed of any point: |delta x| + angle * r_max.
    const float speed = angular > 0.0f ? glm::length(linear) + angular : -glm::dot(linear, gap.normal);
    if (!(speed > 0.0f)) {
      apart = true;
    } else {
      t += (gap.distance - target) / speed;
      apart = t >= 1.0f;
    }
  }
  if (!apart) {
    result.state = ToiResult::State::MaxIterations;
    result.t = t;
    const DistanceResult gap = pieceDistance(a, b, t);
    result.normal = gap.normal;
    result.point = 0.5f * (gap.pointOnA + gap.pointOnB);
    result.separation = gap.distance;
    return result;
  }
  result.state = ToiResult::State::Separated;
  result.t = 1.0f;
  return result;
}

ToiResult piecesToi(const Piece& a, const Piece& b, const ToiSettings& settings) {
  if (std::optional<ToiResult> exact = sphereSweep(a, b, settings)) return *exact;
  if (std::optional<ToiResult> exact = sphereSweep(b, a, settings)) return mirrored(*exact);
  return advance(a, b, settings);
}

// ---- Taking shapes apart ----

// A child's sweep: the parent's sweep composed with the child's fixed placement (slerp commutes
// with multiplying both ends by the same rotation on the right).
Sweep childSweep(const Sweep& parent, const Transform& child) {
  Sweep sweep;
  sweep.center0 = parent.center0;
  sweep.center1 = parent.center1;
  sweep.rotation0 = glm::normalize(parent.rotation0 * child.rotation);
  sweep.rotation1 = glm::normalize(parent.rotation1 * child.rotation);
  sweep.scale = parent.scale * child.scale;
  sweep.localCenter = glm::conjugate(child.rotation) * (parent.localCenter - parent.scale * child.position);
  return sweep;
}

// The first fraction in [0, 1] at which `box` moved by `move` touches `target`, or -1 if it never
// does: the slab test of the box's centre against the target grown by the box's half extents.
float movingBoxEntry(const Aabb& box, const Vec3& move, const Aabb& target) {
  const Vec3 c = box.center(), h = box.halfExtents();
  float t0 = 0.0f, t1 = 1.0f;
  for (int i = 0; i < 3; ++i) {
    const float lo = target.min[i] - h[i], hi = target.max[i] + h[i];
    if (move[i] == 0.0f) {
      if (c[i] < lo || c[i] > hi) return -1.0f;
      continue;
    }
    float a = (lo - c[i]) / move[i], b = (hi - c[i]) / move[i];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
    if (t0 > t1) return -1.0f;
  }
  return t0;
}

// The box, in the local frame of `frame` (a mesh's sweep), that the other shape covers over its
// sweep relative to the mesh: its bounds at both ends, grown by what turning can add.
Aabb sweptBoundsInFrame(const Shape& shape, const Sweep& sweep, const Sweep& frame) {
  Aabb box;
  float farthest = 0.0f;
  for (float t : {0.0f, 1.0f}) {
    const Transform placed = sweep.at(t);
    const Transform frameAt = frame.at(t);
    box.grow(transformAabb(localBounds(shape), frameAt.inverse() * placed));
    const Vec3 c = t == 0.0f ? sweep.center0 : sweep.center1;
    const Vec3 fc = t == 0.0f ? frame.center0 : frame.center1;
    farthest = std::max(farthest, glm::length(c - fc));
  }
  const BoundingSphere bound = localBoundingSphere(shape);
  const float reach =
      glm::length(sweep.localCenter) + sweep.scale * (glm::length(bound.center) + bound.radius);
  // Between the ends, a turning body sweeps at most angle * reach beyond them, and a turning
  // frame moves the other shape by at most its angle times their distance.
  const float grow = sweep.angle() * reach + frame.angle() * (farthest + reach);
  return box.expanded(grow / frame.scale);
}

Piece convexPiece(const Shape& shape, const Sweep& sweep) {
  Piece piece;
  piece.kind = shape.type() == ShapeType::Plane ? Piece::Kind::Plane : Piece::Kind::Convex;
  piece.shape = &shape;
  piece.sweep = sweep;
  return piece;
}

Piece trianglePiece(const TriangleMesh& mesh, std::uint32_t index, const Sweep& sweep) {
  Piece piece;
  piece.kind = Piece::Kind::Triangle;
  piece.triangle = mesh.triangle(index);
  piece.sweep = sweep;
  return piece;
}

ToiResult shapesToi(const Shape& a, const Sweep& sa, const Shape& b, const Sweep& sb,
                    const ToiSettings& settings);

// Mesh A against any non-compound B, per triangle of A near B's swept box.
ToiResult meshToi(const Shape& mesh, const Sweep& meshSweep, const Shape& other, const Sweep& otherSweep,
                  const ToiSettings& settings) {
  ToiResult best;
  const TriangleMesh& triangles = mesh.mesh();
  const float margin = (settings.targetSeparation + settings.tolerance) / meshSweep.scale;
  if (other.type() == ShapeType::Mesh) {
    const TriangleMesh& otherTriangles = other.mesh();
    triangles.forEachTriangleOverlapping(
        sweptBoundsInFrame(other, otherSweep, meshSweep).expanded(margin), [&](std::uint32_t i) {
          const Piece pieceA = trianglePiece(triangles, i, meshSweep);
          Aabb local;
          for (const Vec3& v : pieceA.triangle) local.grow(v);
          // The triangle's swept box in the other mesh's frame, from its ends and turning.
          Aabb inOther;
          for (float t : {0.0f, 1.0f}) {
            inOther.grow(transformAabb(local, otherSweep.at(t).inverse() * meshSweep.at(t)));
          }
          const float turn = (meshSweep.angle() + otherSweep.angle()) *
                             (coreReach(pieceA) + glm::length(meshSweep.center0 - otherSweep.center0) +
                              glm::length(meshSweep.center1 - otherSweep.center1));
          otherTriangles.forEachTriangleOverlapping(
              inOther.expanded((turn + settings.targetSeparation + settings.tolerance) / otherSweep.scale),
              [&](std::uint32_t j) {
                keepEarliest(best, piecesToi(pieceA, trianglePiece(otherTriangles, j, otherSweep), settings));
              });
        });
    return best;
  }
  const Piece otherPiece = convexPiece(other, otherSweep);
  const bool turning =
      meshSweep.rotation0 != meshSweep.rotation1 || otherSweep.rotation0 != otherSweep.rotation1;
  if (turning) {
    triangles.forEachTriangleOverlapping(
        sweptBoundsInFrame(other, otherSweep, meshSweep).expanded(margin), [&](std::uint32_t i) {
          keepEarliest(best, piecesToi(trianglePiece(triangles, i, meshSweep), otherPiece, settings));
        });
    return best;
  }
  // Neither turns (a shape cast against a level): in the mesh's frame the other's box moves along a
  // line, so a triangle whose box that moving box does not touch, or touches only after the earliest
  // contact so far, cannot be hit first (the box, grown by the target and the tolerance, is touched
  // no later than the contact is reported). A long sweep over a terrain passes most of the triangles
  // its swept box holds by this test.
  const Transform startFrame = meshSweep.at(0.0f).inverse() * otherSweep.at(0.0f);
  const Transform endFrame = meshSweep.at(1.0f).inverse() * otherSweep.at(1.0f);
  const Aabb start = transformAabb(localBounds(other), startFrame).expanded(margin);
  const Vec3 move = endFrame.position - startFrame.position;
  const auto vertices = triangles.vertices();
  triangles.forEachTriangleOverlapping(
      sweptBoundsInFrame(other, otherSweep, meshSweep).expanded(margin), [&](std::uint32_t i) {
        const MeshTriangle& tri = triangles.triangles()[i];
        Aabb box;
        for (const std::uint32_t v : tri.v) box.grow(vertices[v]);
        const float entry = movingBoxEntry(start, move, box);
        if (entry < 0.0f || (best.state != ToiResult::State::Separated && entry > best.t)) return;
        keepEarliest(best, piecesToi(trianglePiece(triangles, i, meshSweep), otherPiece, settings));
      });
  return best;
}

ToiResult shapesToi(const Shape& a, const Sweep& sa, const Shape& b, const Sweep& sb,
                    const ToiSettings& settings) {
  if (a.type() == ShapeType::Compound) {
    ToiResult best;
    for (const Compound::Child& child : a.compound().children())
      keepEarliest(best, shapesToi(child.shape, childSweep(sa, child.transform), b, sb, settings));
    return best;
  }
  if (b.type() == ShapeType::Compound) {
    ToiResult best;
    for (const Compound::Child& child : b.compound().children())
      keepEarliest(best, shapesToi(a, sa, child.shape, childSweep(sb, child.transform), settings));
    return best;
  }
  if (a.type() == ShapeType::Mesh) {
    if (b.type() == ShapeType::Plane) return mirrored(shapesToi(b, sb, a, sa, settings));
    return meshToi(a, sa, b, sb, settings);
  }
  if (b.type() == ShapeType::Mesh) {
    if (a.type() == ShapeType::Plane) {
      // A plane against a mesh: every triangle (a mesh flying at a floor), through the pieces.
      ToiResult best;
      const Piece plane = convexPiece(a, sa);
      for (std::uint32_t i = 0; i < b.mesh().triangles().size(); ++i)
        keepEarliest(best, piecesToi(plane, trianglePiece(b.mesh(), i, sb), settings));
      return best;
    }
    return mirrored(meshToi(b, sb, a, sa, settings));
  }
  return piecesToi(convexPiece(a, sa), convexPiece(b, sb), settings);
}

std::string describe(float value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

bool validSweep(const Sweep& sweep, const char* which) {
  const auto bad = [&](const std::string& what) {
    detail::raiseError(std::string("timeOfImpact: sweep ") + which + ": " + what);
    return false;
  };
  if (!isFinite(sweep.localCenter) || !isFinite(sweep.center0) || !isFinite(sweep.center1))
    return bad("centres must be finite");
  // The same test as a Transform's (isValid): |q|^2 within 1e-3 of 1.
  const auto unit = [](const Quat& q) { return isFinite(q) && std::abs(glm::dot(q, q) - 1.0f) < 1e-3f; };
  if (!unit(sweep.rotation0))
    return bad("rotation0 must be a finite unit quaternion, got length " +
               describe(glm::length(sweep.rotation0)));
  if (!unit(sweep.rotation1))
    return bad("rotation1 must be a finite unit quaternion, got length " +
               describe(glm::length(sweep.rotation1)));
  if (!isFinite(sweep.scale) || sweep.scale <= 0.0f)
    return bad("scale must be finite and > 0, got " + describe(sweep.scale));
  return true;
}

}  // namespace

ToiResult timeOfImpact(const Shape& shapeA, const Sweep& sweepA, const Shape& shapeB, const Sweep& sweepB,
                       const ToiSettings& settings) {
  const ToiResult refused;  // without exceptions, what a refused query returns: separated, t = 1
  if (!detail::usableShape(shapeA) || !detail::usableShape(shapeB) || !validSweep(sweepA, "A") ||
      !validSweep(sweepB, "B"))
    return refused;
  if (!isFinite(settings.targetSeparation))
    COLLIDE_FAIL("timeOfImpact: targetSeparation must be finite, got " + describe(settings.targetSeparation),
                 refused);
  if (!isFinite(settings.tolerance) || settings.tolerance <= 0.0f)
    COLLIDE_FAIL("timeOfImpact: tolerance must be finite and > 0, got " + describe(settings.tolerance),
                 refused);
  if (settings.maxIterations < 1)
    COLLIDE_FAIL("timeOfImpact: maxIterations must be >= 1, got " + std::to_string(settings.maxIterations),
                 refused);
  const bool planeA = shapeA.type() == ShapeType::Plane, planeB = shapeB.type() == ShapeType::Plane;
  if (planeA && planeB)
    COLLIDE_FAIL("timeOfImpact: two planes (infinite static half-spaces) cannot meet", refused);
  if ((planeA && sweepA.angle() > 0.0f) || (planeB && sweepB.angle() > 0.0f)) {
    COLLIDE_FAIL(std::string("timeOfImpact: the plane ") + (planeA ? "A" : "B") +
                     " turns during its sweep; a plane may only translate (its far points have no bound)",
                 refused);
  }
  return shapesToi(shapeA, sweepA, shapeB, sweepB, settings);
}

}  // namespace collide
