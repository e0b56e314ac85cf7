// GJK + radii + EPA (see convex_distance.h).
#include "narrowphase/convex_distance.h"
#include "base/fail.h"

#include "narrowphase/epa.h"
#include "narrowphase/gjk.h"

#include <algorithm>
#include <cmath>

namespace collide::detail {

bool convexSignedDistance(const ConvexSupport& a, const ConvexSupport& b, float maxDistance,
                          DistanceResult& out) {
  const float radii = a.radius + b.radius;
  const GjkResult gjk = gjkDistance(a, b, maxDistance + radii);
  if (gjk.status == GjkResult::Status::BeyondBound) return false;

  // Cores apart by a clear margin: the direction between the closest points is well defined and
  // the rounded shapes' answer follows exactly (the radius offsets both points along it).
  const float coreDistance = gjk.distance;
  const float size = std::max(
      {glm::length(gjk.pointOnA - a.center()), glm::length(gjk.pointOnB - b.center()), radii, 1e-20f});
  if (gjk.status == GjkResult::Status::Separated && coreDistance > (radii > 0.0f ? 1e-4f : 1e-5f) * size) {
    const Vec3 normal = gjk.normal;
    out.distance = coreDistance - radii;
    out.normal = normal;
    out.pointOnA = gjk.pointOnA + a.radius * normal;
    out.pointOnB = gjk.pointOnB - b.radius * normal;
    out.overlapping = out.distance < 0.0f;
    return out.distance <= maxDistance;
  }
  if (radii > 0.0f && gjk.status == GjkResult::Status::Separated) {
    // The cores nearly touch but the rounded shapes overlap deeply. The direction between the
    // cores is reliable for some cores (a point: the depth varies only as d cos θ around it) and
    // lost in rounding for others (two nearly crossing segments: tilting it by θ costs their length
    // times θ), so two candidates are weighed by their directional depth, the translation along
    // the normal that separates the shapes (an upper bound of the depth; the smaller the better):
    // the cores' direction, and EPA on the whole rounded shapes, whose difference holds the origin
    // well inside (Jolt runs EPA on the rounded shapes the same way).
    const Vec3 coreNormal = gjk.normal;
    const float coreDepth = radii - coreDistance;
    const float coreDirectional =
        glm::dot(a.supportCore(coreNormal) - b.supportCore(-coreNormal), coreNormal) + radii;
    out.distance = -coreDepth;
    out.normal = coreNormal;
    out.pointOnA = gjk.pointOnA + a.radius * coreNormal;
    out.pointOnB = gjk.pointOnB - b.radius * coreNormal;
    ConvexSupport wholeA = a, wholeB = b;
    wholeA.inflated = wholeB.inflated = true;
    const GjkResult whole = gjkDistance(wholeA, wholeB);
    if (whole.status == GjkResult::Status::Overlapping) {
      const EpaResult epa = epaPenetration(wholeA, wholeB, whole.simplex);
      const float epaDirectional =
          glm::dot(wholeA.supportCore(epa.normal) - wholeB.supportCore(-epa.normal), epa.normal);
      if (epaDirectional < coreDirectional) {
        out.distance = -epa.depth;
        out.normal = epa.normal;
        out.pointOnA = epa.pointOnA;
        out.pointOnB = epa.pointOnB;
      }
    }
    out.overlapping = out.distance < 0.0f;
    return out.distance <= maxDistance;
  }
  // The cores touch or overlap: EPA gives their penetration; the radii add to it.
  const EpaResult epa = epaPenetration(a, b, gjk.simplex);
  out.distance = -(epa.depth + radii);
  out.normal = epa.normal;
  out.pointOnA = epa.pointOnA + a.radius * epa.normal;
  out.pointOnB = epa.pointOnB - b.radius * epa.normal;
  out.overlapping = out.distance < 0.0f;
  return out.distance <= maxDistance;
}

}  // namespace collide::detail

// ---- The generic table entry for every convex pair ----

#include "narrowphase/pair_functions.h"
#include "shapes/shape_functions.h"

namespace collide::detail {

bool collideConvexGeneric(const Shape& shapeA, const Transform& transformA, const Shape& shapeB,
                          const Transform& transformB, float margin, Manifold& out) {
  const ConvexSupport a = makeConvexSupport(shapeA, transformA);
  const ConvexSupport b = makeConvexSupport(shapeB, transformB);
  DistanceResult distance;
  if (!convexSignedDistance(a, b, margin, distance)) {
    out.count = 0;
    return false;
  }
  // One point: the generic path knows the closest features only through GJK's simplex, which is
  // not stable enough to name them; id 0 lets the cache match the single point by position.
  return manifoldFromDistance(distance, 0, margin, out);
}

}  // namespace collide::detail

// ---- The public distance query ----

namespace collide {

namespace {

// Plane (A) and convex shape (B): the signed height of B's lowest point above the surface.
DistanceResult planeConvexDistance(const Shape& plane, const Transform& planeTransform, const Shape& convex,
                                   const Transform& convexTransform) {
  const Plane surface = detail::worldPlane(plane.plane(), planeTransform);
  const detail::ConvexSupport support = detail::makeConvexSupport(convex, convexTransform);
  const Vec3 lowest = support.supportCore(-surface.normal) - support.radius * surface.normal;
  const float height = surface.signedDistance(lowest);
  DistanceResult result;
  result.distance = height;
  result.pointOnB = lowest;
  result.pointOnA = lowest - height * surface.normal;
  result.normal = surface.normal;
  result.overlapping = height < 0.0f;
  return result;
}

DistanceResult mirrored(DistanceResult result) {
  std::swap(result.pointOnA, result.pointOnB);
  result.normal = -result.normal;
  return result;
}

}  // namespace

DistanceResult distance(const Shape& shapeA, const Transform& givenA, const Shape& shapeB,
                        const Transform& givenB) {
  if (!detail::usableShape(shapeA) || !detail::usableShape(shapeB) ||
      !detail::requireValidTransform(givenA, "distance", "A") ||
      !detail::requireValidTransform(givenB, "distance", "B"))
    return {};
  const Transform transformA = detail::withUnitRotation(givenA);
  const Transform transformB = detail::withUnitRotation(givenB);
  const bool planeA = shapeA.type() == ShapeType::Plane;
  const bool planeB = shapeB.type() == ShapeType::Plane;
  if ((!planeA && !shapeA.isConvex()) || (!planeB && !shapeB.isConvex()) || (planeA && planeB)) {
    COLLIDE_FAIL("distance: needs two convex shapes or a plane and a convex shape, got " +
                     std::string(toString(shapeA.type())) + " and " + std::string(toString(shapeB.type())),
                 {});
  }
  if (planeA) return planeConvexDistance(shapeA, transformA, shapeB, transformB);
  if (planeB) return mirrored(planeConvexDistance(shapeB, transformB, shapeA, transformA));
  DistanceResult result;
  detail::convexSignedDistance(detail::makeConvexSupport(shapeA, transformA),
                               detail::makeConvexSupport(shapeB, transformB), 1e30f, result);
  return result;
}

}  // namespace collide
