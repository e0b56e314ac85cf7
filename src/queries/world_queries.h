// The world's queries between steps (lecture: the same proxies serve picking, visibility and sound
// occlusion): the broad phase's boxes find the candidates, each candidate's shape answers exactly.
#pragma once

#include <collide/broadphase.h>
#include <collide/queries.h>

#include "bodies/body_storage.h"

#include <optional>
#include <span>
#include <vector>

namespace collide::detail {

// The closest non-sensor body whose shape the ray hits within ray.maxDistance, among the bodies whose
// layer passes the mask; equal distances go to the lower body index, so every broad-phase type gives
// the same answer. Throws Error for a non-finite origin, a zero or non-finite direction, or a NaN or
// negative maxDistance.
std::optional<RayCastResult> castRayClosest(const BodyStorage& bodies, const BroadPhase& broadPhase,
                                            const Ray& ray, LayerMask mask);

// The bodies of the proxy pairs the broad phase kept, leaving out pairs with a body destroyed since.
std::vector<BodyPair> bodyPairs(const BodyStorage& bodies, const BroadPhase& broadPhase,
                                std::span<const ProxyPair> pairs);

}  // namespace collide::detail
