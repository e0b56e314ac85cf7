// The world's queries over the broad phase: the closest ray hit, the kept pairs (world_queries.h).
#include "queries/world_queries.h"

#include <collide/error.h>
#include <collide/shapes.h>

#include "base/format.h"

#include <cmath>

namespace collide::detail {

std::optional<RayCastResult> castRayClosest(const BodyStorage& bodies, const BroadPhase& broadPhase,
                                            const Ray& ray, LayerMask mask) {
  if (!isFinite(ray.origin))
    throw Error("world: castRay: origin must be finite, got " + formatVec(ray.origin));
  const float length = glm::length(ray.direction);
  if (!isFinite(ray.direction) || !(length > 0.0f) || !std::isfinite(length)) {
    throw Error("world: castRay: direction must be finite and non-zero, got " + formatVec(ray.direction));
  }
  if (std::isnan(ray.maxDistance) || ray.maxDistance < 0.0f) {
    throw Error("world: castRay: maxDistance must be >= 0, got " + formatFloat(ray.maxDistance));
  }
  Ray unit = ray;
  unit.direction = ray.direction / length;
  std::optional<RayCastResult> best;
  std::uint32_t bestIndex = 0;
  // Each candidate's shape is cast over the whole ray (not clipped to the best so far), so that an
  // equal distance is seen and the tie goes to the lower index whatever order the boxes come in;
  // the broad phase still prunes every box entered beyond the best hit.
  broadPhase.rayCast(unit, mask, [&](ProxyId proxy, float) {
    const auto index = static_cast<std::uint32_t>(broadPhase.userValue(proxy));
    const BodyRecord& r = bodies.records[index];
    if (!r.sensor) {
      const std::optional<RayHit> hit = rayCast(r.shape, bodyTransform(r, bodies.states[index]), unit);
      if (hit && (!best || hit->distance < best->distance ||
                  (hit->distance == best->distance && index < bestIndex))) {
        best = RayCastResult{bodies.idOf(index), hit->distance, hit->point, hit->normal, hit->subShape};
        bestIndex = index;
      }
    }
    return best ? best->distance : unit.maxDistance;
  });
  return best;
}

std::vector<BodyPair> bodyPairs(const BodyStorage& bodies, const BroadPhase& broadPhase,
                                std::span<const ProxyPair> pairs) {
  std::vector<BodyPair> out;
  out.reserve(pairs.size());
  for (const ProxyPair& pair : pairs) {
    if (!broadPhase.contains(pair.a) || !broadPhase.contains(pair.b)) continue;  // destroyed since
    out.push_back({bodies.idOf(static_cast<std::uint32_t>(broadPhase.userValue(pair.a))),
                   bodies.idOf(static_cast<std::uint32_t>(broadPhase.userValue(pair.b)))});
  }
  return out;
}

}  // namespace collide::detail
