// The world's queries between steps (lecture: the same proxies serve picking, visibility and sound
// occlusion): the broad phase's boxes find the candidates, each candidate's shape answers exactly.
// Every query skips bodies the filter refuses (QueryFilter), validates its input with an Error naming
// the query, and is deterministic: sorted answers are ordered by (distance, body index) or body
// index, and a closest answer's ties go to the lower body index, whatever the broad-phase type.
#pragma once

#include <collide/broadphase.h>
#include <collide/queries.h>

#include "bodies/body_storage.h"

#include <optional>
#include <span>
#include <vector>

namespace collide::detail {

// The closest body whose shape the ray hits within ray.maxDistance; equal distances go to the lower
// body index. Throws Error for a non-finite origin, a zero or non-finite direction, or a NaN or
// negative maxDistance (as every ray query below).
std::optional<RayCastResult> castRayClosest(const BodyStorage& bodies, const BroadPhase& broadPhase,
                                            const Ray& ray, const QueryFilter& filter);
// The first hit found, the cheapest: the broad phase stops at the first body whose shape is hit.
std::optional<RayCastResult> castRayAny(const BodyStorage& bodies, const BroadPhase& broadPhase,
                                        const Ray& ray, const QueryFilter& filter);
// Every body hit, sorted by (distance, body index).
std::vector<RayCastResult> castRayAll(const BodyStorage& bodies, const BroadPhase& broadPhase, const Ray& ray,
                                      const QueryFilter& filter);
// Each body hit, handed to the collector, which clips or stops the ray (RayHitCollector).
void castRayCollect(const BodyStorage& bodies, const BroadPhase& broadPhase, const Ray& ray,
                    const RayHitCollector& collector, const QueryFilter& filter);

// The convex shape at `pose` swept along `translation` (no turning): the earliest contact over the
// candidates of the swept box, ties to the lower body index. Throws Error for a shape that is not
// convex, an invalid pose or a non-finite translation.
std::optional<ShapeCastResult> castShapeClosest(const BodyStorage& bodies, const BroadPhase& broadPhase,
                                                const Shape& shape, const Transform& pose,
                                                const Vec3& translation, const QueryFilter& filter);
// Every body the swept shape reaches, sorted by (fraction, body index).
std::vector<ShapeCastResult> castShapeAll(const BodyStorage& bodies, const BroadPhase& broadPhase,
                                          const Shape& shape, const Transform& pose, const Vec3& translation,
                                          const QueryFilter& filter);

// Every body whose shape the shape at `pose` overlaps (collide() reports a contact of depth >= 0),
// sorted by body index. Throws Error for a plane (no finite extent) or an invalid pose.
std::vector<OverlapResult> overlapShape(const BodyStorage& bodies, const BroadPhase& broadPhase,
                                        const Shape& shape, const Transform& pose, const QueryFilter& filter);
// Every body whose solid holds the point (containsPoint: boundary included, a plane's half-space, a
// closed mesh's inside, never an open mesh), sorted by body index. Throws Error for a non-finite point.
std::vector<BodyId> overlapPoint(const BodyStorage& bodies, const BroadPhase& broadPhase, const Vec3& point,
                                 const QueryFilter& filter);

// The queries above, each answer handed to a collector as it is found (by body index, then part),
// which may stop the query (collide/queries.h: ShapeCastCollector, OverlapCollector,
// PointCollector). Throws Error for an unset collector and as the queries above.
void castShapeCollect(const BodyStorage& bodies, const BroadPhase& broadPhase, const Shape& shape,
                      const Transform& pose, const Vec3& translation, const ShapeCastCollector& collector,
                      const QueryFilter& filter);
void overlapShapeCollect(const BodyStorage& bodies, const BroadPhase& broadPhase, const Shape& shape,
                         const Transform& pose, const OverlapCollector& collector, const QueryFilter& filter);
void overlapPointCollect(const BodyStorage& bodies, const BroadPhase& broadPhase, const Vec3& point,
                         const PointCollector& collector, const QueryFilter& filter);

// Exact line of sight: no shape the filter sees touches the segment (a ray cast, the first hit
// stops it); a zero-length segment: no solid holds the point.
bool hasLineOfSight(const BodyStorage& bodies, const BroadPhase& broadPhase, const Vec3& from, const Vec3& to,
                    const QueryFilter& filter);

// The bodies of the proxy pairs the broad phase kept, leaving out pairs with a body destroyed since.
std::vector<BodyPair> bodyPairs(const BodyStorage& bodies, const BroadPhase& broadPhase,
                                std::span<const ProxyPair> pairs);

}  // namespace collide::detail
