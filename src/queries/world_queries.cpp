// The world's queries over the broad phase: rays, shape casts, overlaps and points (world_queries.h).
#include "queries/world_queries.h"
#include "base/fail.h"

#include <collide/error.h>
#include <collide/narrowphase.h>
#include <collide/shapes.h>

#include "base/format.h"
#include "bodies/body_parts.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace collide::detail {

namespace {

// The filter's verdict beyond the layer mask, which the broad phase applies itself.
bool passes(const QueryFilter& filter, const BodyStorage& bodies, std::uint32_t index) {
  if (bodies.records[index].sensor && !filter.includeSensors) return false;
  return !filter.accept || filter.accept(bodies.idOf(index));
}

// A part of a body made of parts is seen when its own layer passes the mask and it is not a sensor
// (unless includeSensors); a body of one shape is its only part, which `passes` judged.
bool partPasses(const QueryFilter& filter, const BodyRecord& r, std::uint32_t part) {
  if (!hasParts(r)) return true;
  const PartRecord& p = r.parts[part];
  return (p.layer & filter.mask) != 0 && (!p.sensor || filter.includeSensors);
}

std::uint32_t bodyIndex(const BroadPhase& broadPhase, ProxyId proxy) {
  return static_cast<std::uint32_t>(broadPhase.userValue(proxy));
}

// The ray with a unit direction, or Error naming the query (and without exceptions nothing).
std::optional<Ray> checkedUnitRay(const Ray& ray, const char* query) {
  const std::string where = std::string("world: ") + query + ": ";
  if (!isFinite(ray.origin))
    COLLIDE_FAIL(where + "origin must be finite, got " + formatVec(ray.origin), std::nullopt);
  const float length = glm::length(ray.direction);
  if (!isFinite(ray.direction) || !(length > 0.0f) || !std::isfinite(length)) {
    COLLIDE_FAIL(where + "direction must be finite and non-zero, got " + formatVec(ray.direction),
                 std::nullopt);
  }
  if (std::isnan(ray.maxDistance) || ray.maxDistance < 0.0f) {
    COLLIDE_FAIL(where + "maxDistance must be >= 0, got " + formatFloat(ray.maxDistance), std::nullopt);
  }
  Ray unit = ray;
  unit.direction = ray.direction / length;
  return unit;
}

float fractionOf(float distance, float maxDistance) {
  return maxDistance > 0.0f && std::isfinite(maxDistance) ? distance / maxDistance : 0.0f;
}

RayCastResult rayResult(const BodyStorage& bodies, std::uint32_t index, const RayHit& hit, float maxDistance,
                        std::uint32_t part) {
  return {bodies.idOf(index),
          hit.distance,
          hit.point,
          hit.normal,
          hit.subShape,
          fractionOf(hit.distance, maxDistance),
          part};
}

// Body `index`'s hit by `ray` if the filter lets the body through; the fraction is of `reach`, the
// query's whole length (the ray cast may be a clipped part of it).
std::optional<RayCastResult> bodyRayHit(const BodyStorage& bodies, std::uint32_t index, const Ray& ray,
                                        float reach, const QueryFilter& filter) {
  if (!passes(filter, bodies, index)) return std::nullopt;
  const BodyRecord& r = bodies.records[index];
  const Transform pose = bodyTransform(r, bodies.states[index]);
  if (!hasParts(r)) {
    const std::optional<RayHit> hit = rayCast(r.shape, pose, ray);
    if (!hit) return std::nullopt;
    return rayResult(bodies, index, *hit, reach, 0);
  }
  // The nearest part the filter sees (ties to the lower part).
  std::optional<RayCastResult> best;
  for (std::uint32_t part = 0; part < partCount(r); ++part) {
    if (!partPasses(filter, r, part)) continue;
    const std::optional<RayHit> hit = rayCast(partShape(r, part), pose * partLocalPose(r, part), ray);
    if (hit && (!best || hit->distance < best->distance)) best = rayResult(bodies, index, *hit, reach, part);
  }
  return best;
}

bool nearerRay(const RayCastResult& a, const RayCastResult& b) {
  return a.distance < b.distance || (a.distance == b.distance && a.body.index < b.body.index);
}

bool checkPose(const Transform& pose, const char* query) {
  if (!isValid(pose)) {
    COLLIDE_FAIL(std::string("world: ") + query +
                     ": pose must have a finite position, a unit rotation and a positive finite scale, got "
                     "position " +
                     formatVec(pose.position) + ", scale " + formatFloat(pose.scale),
                 false);
  }
  return true;
}

// The candidates whose proxy box touches `box`, by body index (the broad phase's order varies by type).
std::vector<std::uint32_t> candidates(const BroadPhase& broadPhase, const Aabb& box, LayerMask mask) {
  std::vector<std::uint32_t> out;
  broadPhase.queryAabb(box, mask, [&](ProxyId proxy) {
    out.push_back(bodyIndex(broadPhase, proxy));
    return true;
  });
  std::sort(out.begin(), out.end());
  return out;
}

// The cast's contact is within this gap (ToiSettings::tolerance): touching, not a speculative margin.
ToiSettings castSettings() {
  ToiSettings settings;
  settings.targetSeparation = 0.0f;
  return settings;
}

// The sweep's first contact with one shape of body `index` placed at `target`.
std::optional<ShapeCastResult> castAgainstShape(const BodyStorage& bodies, std::uint32_t index,
                                                const Shape& shape, const Sweep& sweep,
                                                const Vec3& translation, const Shape& targetShape,
                                                const Transform& target) {
  const ToiResult toi = timeOfImpact(shape, sweep, targetShape, Sweep::fixed(target), castSettings());
  if (toi.state == ToiResult::State::Separated) return std::nullopt;
  ShapeCastResult hit;
  hit.body = bodies.idOf(index);
  hit.initiallyOverlapping = toi.state == ToiResult::State::Overlapping;
  hit.fraction = hit.initiallyOverlapping ? 0.0f : toi.t;
  hit.distance = hit.fraction * glm::length(translation);
  hit.point = toi.point;
  hit.normal = -toi.normal;  // ToiResult's normal points from the cast shape (A) to the body (B)
  if (targetShape.type() == ShapeType::Compound) {
    // The child reached first (ties to the lower child), as the compound's own sweep takes the earliest.
    float earliest = std::numeric_limits<float>::infinity();
    const auto children = targetShape.compound().children();
    for (std::size_t c = 0; c < children.size(); ++c) {
      const ToiResult child = timeOfImpact(shape, sweep, children[c].shape,
                                           Sweep::fixed(target * children[c].transform), castSettings());
      if (child.state != ToiResult::State::Separated && child.t < earliest) {
        earliest = child.t;
        hit.subShape = static_cast<std::uint32_t>(c);
      }
    }
  }
  return hit;
}

// The sweep's first contact with body `index`: its shape, or the earliest of the parts the filter
// sees (ties to the lower part).
std::optional<ShapeCastResult> castAgainst(const BodyStorage& bodies, std::uint32_t index, const Shape& shape,
                                           const Sweep& sweep, const Vec3& translation,
                                           const QueryFilter& filter) {
  const BodyRecord& r = bodies.records[index];
  const Transform bodyPose = bodyTransform(r, bodies.states[index]);
  if (!hasParts(r)) return castAgainstShape(bodies, index, shape, sweep, translation, r.shape, bodyPose);
  std::optional<ShapeCastResult> best;
  for (std::uint32_t part = 0; part < partCount(r); ++part) {
    if (!partPasses(filter, r, part)) continue;
    std::optional<ShapeCastResult> hit = castAgainstShape(
        bodies, index, shape, sweep, translation, partShape(r, part), bodyPose * partLocalPose(r, part));
    if (hit && (!best || hit->fraction < best->fraction)) {
      best = hit;
      best->part = part;
    }
  }
  return best;
}

// The query shape: without exceptions a Shape can carry a bad value (collide/error.h).
bool checkQueryShape(const Shape& shape, const char* query) {
  return withErrorContext(std::string("world: ") + query + ": shape: ", [&] { return validateShape(shape); });
}

bool checkCast(const Shape& shape, const Transform& pose, const Vec3& translation, const char* query) {
  if (!shape.isConvex()) {
    COLLIDE_FAIL(
        std::string("world: ") + query +
            ": the cast shape must be convex (sphere, capsule, box, k-DOP, ellipsoid, cylinder or convex "
            "hull), got " +
            std::string(toString(shape.type())),
        false);
  }
  if (!checkQueryShape(shape, query) || !checkPose(pose, query)) return false;
  if (!isFinite(translation)) {
    COLLIDE_FAIL(
        std::string("world: ") + query + ": translation must be finite, got " + formatVec(translation),
        false);
  }
  return true;
}

// The cast's broad phase: the proxies the shape's box meets on its way (BroadPhase::boxCast: the
// shape does not turn, so its box at any time is the start box moved), grown by the cast's
// tolerance, each with the distance the box has moved when it first touches.
template <typename Visit>
void castCandidates(const BroadPhase& broadPhase, const Shape& shape, const Transform& pose,
                    const Vec3& translation, LayerMask mask, Visit&& visit) {
  broadPhase.boxCast(worldBounds(shape, pose).expanded(castSettings().tolerance), translation, mask,
                     [&](ProxyId proxy, float entry) { return visit(bodyIndex(broadPhase, proxy), entry); });
}

Sweep castSweep(const Transform& pose, const Vec3& translation) {
  Transform end = pose;
  end.position += translation;
  return Sweep::between(pose, end);
}

// Each body the swept shape reaches, by body index, handed to `visit` until it returns false.
template <typename Visit>
void visitShapeCast(const BodyStorage& bodies, const BroadPhase& broadPhase, const Shape& shape,
                    const Transform& pose, const Vec3& translation, const QueryFilter& filter,
                    const char* query, Visit&& visit) {
  if (!checkCast(shape, pose, translation, query)) return;
  const Sweep sweep = castSweep(pose, translation);
  std::vector<std::uint32_t> indices;
  castCandidates(broadPhase, shape, pose, translation, filter.mask, [&](std::uint32_t index, float) {
    indices.push_back(index);
    return std::numeric_limits<float>::infinity();
  });
  std::sort(indices.begin(), indices.end());
  for (const std::uint32_t index : indices) {
    if (!passes(filter, bodies, index)) continue;
    if (std::optional<ShapeCastResult> hit = castAgainst(bodies, index, shape, sweep, translation, filter)) {
      if (!visit(*hit)) return;
    }
  }
}

std::vector<ShapeCastResult> castShapeCandidates(const BodyStorage& bodies, const BroadPhase& broadPhase,
                                                 const Shape& shape, const Transform& pose,
                                                 const Vec3& translation, const QueryFilter& filter,
                                                 const char* query) {
  std::vector<ShapeCastResult> hits;
  visitShapeCast(bodies, broadPhase, shape, pose, translation, filter, query,
                 [&](const ShapeCastResult& hit) {
                   hits.push_back(hit);
                   return true;
                 });
  return hits;
}

bool earlierCast(const ShapeCastResult& a, const ShapeCastResult& b) {
  return a.fraction < b.fraction || (a.fraction == b.fraction && a.body.index < b.body.index);
}

// Exact overlap: collide() reports a contact of depth >= 0 (touching counts).
bool touches(const Shape& a, const Transform& poseA, const Shape& b, const Transform& poseB) {
  Manifold manifold;
  return collide(a, poseA, b, poseB, manifold) && manifold.maxDepth() >= 0.0f;
}

}  // namespace

std::optional<RayCastResult> castRayClosest(const BodyStorage& bodies, const BroadPhase& broadPhase,
                                            const Ray& ray, const QueryFilter& filter) {
  const std::optional<Ray> checked = checkedUnitRay(ray, "castRay");
  if (!checked) return std::nullopt;
  const Ray unit = *checked;
  std::optional<RayCastResult> best;
  // Each candidate's shape is cast over the whole ray (not clipped to the best so far), so that an
  // equal distance is seen and the tie goes to the lower index whatever order the boxes come in;
  // the broad phase still prunes every box entered beyond the best hit.
  broadPhase.rayCast(unit, filter.mask, [&](ProxyId proxy, float) {
    const auto hit = bodyRayHit(bodies, bodyIndex(broadPhase, proxy), unit, unit.maxDistance, filter);
    if (hit && (!best || nearerRay(*hit, *best))) best = hit;
    return best ? best->distance : unit.maxDistance;
  });
  return best;
}

void castRayCollect(const BodyStorage& bodies, const BroadPhase& broadPhase, const Ray& ray,
                    const RayHitCollector& collector, const QueryFilter& filter) {
  const std::optional<Ray> checked = checkedUnitRay(ray, "castRayCollect");
  if (!checked) return;
  const Ray unit = *checked;
  if (!collector) COLLIDE_FAIL("world: castRayCollect: the collector must be set");
  float reach = unit.maxDistance;
  broadPhase.rayCast(unit, filter.mask, [&](ProxyId proxy, float) {
    const auto hit = bodyRayHit(bodies, bodyIndex(broadPhase, proxy), Ray{unit.origin, unit.direction, reach},
                                unit.maxDistance, filter);
    if (!hit) return reach;
    const float answer = collector(*hit);
    if (answer < 0.0f) return -1.0f;                           // stop
    if (!std::isnan(answer)) reach = std::min(answer, reach);  // clip; never beyond the reach so far
    return reach;
  });
}

std::optional<RayCastResult> castRayAny(const BodyStorage& bodies, const BroadPhase& broadPhase,
                                        const Ray& ray, const QueryFilter& filter) {
  const std::optional<Ray> checked = checkedUnitRay(ray, "castRayAny");
  if (!checked) return std::nullopt;
  const Ray unit = *checked;
  std::optional<RayCastResult> found;
  broadPhase.rayCast(unit, filter.mask, [&](ProxyId proxy, float) {
    found = bodyRayHit(bodies, bodyIndex(broadPhase, proxy), unit, unit.maxDistance, filter);
    return found ? -1.0f : unit.maxDistance;  // the first hit stops the cast
  });
  return found;
}

std::vector<RayCastResult> castRayAll(const BodyStorage& bodies, const BroadPhase& broadPhase, const Ray& ray,
                                      const QueryFilter& filter) {
  const std::optional<Ray> checked = checkedUnitRay(ray, "castRayAll");
  if (!checked) return {};
  const Ray unit = *checked;
  std::vector<RayCastResult> hits;
  broadPhase.rayCast(unit, filter.mask, [&](ProxyId proxy, float) {
    if (const auto hit = bodyRayHit(bodies, bodyIndex(broadPhase, proxy), unit, unit.maxDistance, filter))
      hits.push_back(*hit);
    return unit.maxDistance;
  });
  std::sort(hits.begin(), hits.end(), nearerRay);
  return hits;
}

std::optional<ShapeCastResult> castShapeClosest(const BodyStorage& bodies, const BroadPhase& broadPhase,
                                                const Shape& shape, const Transform& pose,
                                                const Vec3& translation, const QueryFilter& filter) {
  if (!checkCast(shape, pose, translation, "castShape")) return std::nullopt;
  const Sweep sweep = castSweep(pose, translation);
  const float length = glm::length(translation);
  // Twice the time of impact's tolerance: a contact it reports that much early must not hide a body
  // whose box the moving box meets just beyond it.
  const float slack = 2.0f * castSettings().tolerance;
  std::optional<ShapeCastResult> best;
  castCandidates(broadPhase, shape, pose, translation, filter.mask, [&](std::uint32_t index, float) {
    if (passes(filter, bodies, index)) {
      const std::optional<ShapeCastResult> hit =
          castAgainst(bodies, index, shape, sweep, translation, filter);
      if (hit && (!best || earlierCast(*hit, *best))) best = hit;
    }
    // The broad phase passes by every box the moving box meets beyond the earliest contact so far.
    return best ? best->fraction * length + slack : std::numeric_limits<float>::infinity();
  });
  return best;
}

std::vector<ShapeCastResult> castShapeAll(const BodyStorage& bodies, const BroadPhase& broadPhase,
                                          const Shape& shape, const Transform& pose, const Vec3& translation,
                                          const QueryFilter& filter) {
  std::vector<ShapeCastResult> hits =
      castShapeCandidates(bodies, broadPhase, shape, pose, translation, filter, "castShapeAll");
  std::sort(hits.begin(), hits.end(), earlierCast);
  return hits;
}

namespace {

// Each part the shape touches, by body index and part, handed to `visit` until it returns false.
template <typename Visit>
void visitOverlaps(const BodyStorage& bodies, const BroadPhase& broadPhase, const Shape& shape,
                   const Transform& pose, const QueryFilter& filter, const char* query, Visit&& visit) {
  if (shape.type() == ShapeType::Plane) {
    COLLIDE_FAIL(std::string("world: ") + query + ": a plane has no finite extent to query with; use a box");
  }
  if (!checkQueryShape(shape, query) || !checkPose(pose, query)) return;
  for (const std::uint32_t index : candidates(broadPhase, worldBounds(shape, pose), filter.mask)) {
    if (!passes(filter, bodies, index)) continue;
    const BodyRecord& r = bodies.records[index];
    const Transform bodyPose = bodyTransform(r, bodies.states[index]);
    if (hasParts(r)) {
      // Every part the shape touches.
      for (std::uint32_t part = 0; part < partCount(r); ++part) {
        if (partPasses(filter, r, part) &&
            touches(shape, pose, partShape(r, part), bodyPose * partLocalPose(r, part)) &&
            !visit(OverlapResult{bodies.idOf(index), 0, part}))
          return;
      }
    } else if (r.shape.type() == ShapeType::Compound) {
      // Child by child, so that the part overlapped is known; a compound's collide() is their union.
      const auto children = r.shape.compound().children();
      for (std::size_t c = 0; c < children.size(); ++c) {
        if (touches(shape, pose, children[c].shape, bodyPose * children[c].transform)) {
          if (!visit(OverlapResult{bodies.idOf(index), static_cast<std::uint32_t>(c), 0})) return;
          break;
        }
      }
    } else if (touches(shape, pose, r.shape, bodyPose)) {
      if (!visit(OverlapResult{bodies.idOf(index), 0, 0})) return;
    }
  }
}

// Each body whose solid holds the point, by body index, handed to `visit` until it returns false.
template <typename Visit>
void visitPoint(const BodyStorage& bodies, const BroadPhase& broadPhase, const Vec3& point,
                const QueryFilter& filter, const char* query, Visit&& visit) {
  if (!isFinite(point))
    COLLIDE_FAIL(std::string("world: ") + query + ": point must be finite, got " + formatVec(point));
  for (const std::uint32_t index : candidates(broadPhase, Aabb{point, point}, filter.mask)) {
    if (!passes(filter, bodies, index)) continue;
    const BodyRecord& r = bodies.records[index];
    const Transform pose = bodyTransform(r, bodies.states[index]);
    bool inside = false;
    for (std::uint32_t part = 0; part < partCount(r) && !inside; ++part) {
      inside = partPasses(filter, r, part) &&
               containsPoint(partShape(r, part), pose * partLocalPose(r, part), point);
    }
    if (inside && !visit(bodies.idOf(index))) return;
  }
}

}  // namespace

std::vector<OverlapResult> overlapShape(const BodyStorage& bodies, const BroadPhase& broadPhase,
                                        const Shape& shape, const Transform& pose,
                                        const QueryFilter& filter) {
  std::vector<OverlapResult> out;
  visitOverlaps(bodies, broadPhase, shape, pose, filter, "overlapShape", [&](const OverlapResult& o) {
    out.push_back(o);
    return true;
  });
  return out;
}

void overlapShapeCollect(const BodyStorage& bodies, const BroadPhase& broadPhase, const Shape& shape,
                         const Transform& pose, const OverlapCollector& collector,
                         const QueryFilter& filter) {
  if (!collector) COLLIDE_FAIL("world: overlapShapeCollect: the collector must be set");
  visitOverlaps(bodies, broadPhase, shape, pose, filter, "overlapShapeCollect", collector);
}

std::vector<BodyId> overlapPoint(const BodyStorage& bodies, const BroadPhase& broadPhase, const Vec3& point,
                                 const QueryFilter& filter) {
  std::vector<BodyId> out;
  visitPoint(bodies, broadPhase, point, filter, "overlapPoint", [&](BodyId id) {
    out.push_back(id);
    return true;
  });
  return out;
}

void overlapPointCollect(const BodyStorage& bodies, const BroadPhase& broadPhase, const Vec3& point,
                         const PointCollector& collector, const QueryFilter& filter) {
  if (!collector) COLLIDE_FAIL("world: overlapPointCollect: the collector must be set");
  visitPoint(bodies, broadPhase, point, filter, "overlapPointCollect", collector);
}

void castShapeCollect(const BodyStorage& bodies, const BroadPhase& broadPhase, const Shape& shape,
                      const Transform& pose, const Vec3& translation, const ShapeCastCollector& collector,
                      const QueryFilter& filter) {
  if (!collector) COLLIDE_FAIL("world: castShapeCollect: the collector must be set");
  float reach = 1.0f;
  visitShapeCast(bodies, broadPhase, shape, pose, translation, filter, "castShapeCollect",
                 [&](const ShapeCastResult& hit) {
                   if (hit.fraction > reach) return true;  // beyond the clip: not handed out
                   const float answer = collector(hit);
                   if (answer < 0.0f) return false;
                   if (!std::isnan(answer)) reach = std::min(answer, reach);
                   return true;
                 });
}

bool hasLineOfSight(const BodyStorage& bodies, const BroadPhase& broadPhase, const Vec3& from, const Vec3& to,
                    const QueryFilter& filter) {
  if (!isFinite(from) || !isFinite(to))
    COLLIDE_FAIL(
        "world: hasLineOfSight: from and to must be finite, got " + formatVec(from) + " and " + formatVec(to),
        false);
  const Vec3 d = to - from;
  const float length = glm::length(d);
  if (!std::isfinite(length)) COLLIDE_FAIL("world: hasLineOfSight: the segment is too long for float", false);
  if (length == 0.0f) return overlapPoint(bodies, broadPhase, from, filter).empty();
  return !castRayAny(bodies, broadPhase, Ray{from, d / length, length}, filter).has_value();
}

std::vector<BodyPair> bodyPairs(const BodyStorage& bodies, const BroadPhase& broadPhase,
                                std::span<const ProxyPair> pairs) {
  std::vector<BodyPair> out;
  out.reserve(pairs.size());
  for (const ProxyPair& pair : pairs) {
    if (!broadPhase.contains(pair.a) || !broadPhase.contains(pair.b)) continue;  // destroyed since
    out.push_back({bodies.idOf(bodyIndex(broadPhase, pair.a)), bodies.idOf(bodyIndex(broadPhase, pair.b))});
  }
  return out;
}

}  // namespace collide::detail
