// The answers of the world's queries (World::castRay and its variants, World::castShape,
// World::overlapShape, World::overlapPoint, World::broadPhasePairs) and the filter they all take.
// docs/queries.md describes each query and what it reports.
#pragma once

#include <collide/body.h>
#include <collide/broadphase.h>
#include <collide/math.h>

#include <cstdint>
#include <functional>

namespace collide {

// Which bodies a query sees. A body takes part when its layer passes the mask ((layer & mask) != 0),
// it is not a sensor (unless includeSensors) and `accept`, when set, returns true for it. For a body
// made of parts the layer and sensor tests are each part's. Sensors are
// left out by default: they are trigger volumes without a surface, so a picking ray or a character's
// sweep should pass through them; set includeSensors to ask which sensors a ray or shape reaches.
// An unset `accept` costs nothing (no allocation, no call).
struct QueryFilter {
  LayerMask mask = kAllLayers;
  bool includeSensors = false;
  std::function<bool(BodyId body)> accept{};
};

// A ray's hit of one body (World::castRay, castRayAny, castRayAll, castRayCollect).
struct RayCastResult {
  BodyId body;
  float distance = 0.0f;  // along the ray (its direction normalised)
  Vec3 point{0.0f};
  Vec3 normal{0.0f};           // unit, the surface normal at the hit, facing the ray's origin side
  std::uint32_t subShape = 0;  // within the part hit: triangle index for a mesh, child index for a compound
  float fraction = 0.0f;       // distance / ray.maxDistance; 0 for an infinite or zero maxDistance
  std::uint32_t part = 0;      // the body's part hit (BodyDef::parts; 0 for a body of one shape)
};

// Called by World::castRayCollect for each body the ray hits, in no particular order (the broad
// phase's, deterministic for a given world). Return the new maximum distance: hit.distance to clip
// the ray there (only nearer hits follow), a larger value (e.g. infinity) to keep going, or a
// negative number to stop.
using RayHitCollector = std::function<float(const RayCastResult& hit)>;

// A swept shape's first contact with one body (World::castShape, castShapeAll).
struct ShapeCastResult {
  BodyId body;
  float fraction = 0.0f;       // the time of impact in [0, 1] along the translation
  float distance = 0.0f;       // fraction * |translation|
  Vec3 point{0.0f};            // on the contact, midway between the two surfaces
  Vec3 normal{0.0f};           // unit, from the hit body's surface towards the cast shape
  std::uint32_t subShape = 0;  // the compound child hit within the part (0 for other shapes)
  std::uint32_t part = 0;      // the body's part hit (0 for a body of one shape)
  // The shape already overlaps the body at the start of the cast: fraction 0, and normal is the
  // direction that separates the cast shape from the body.
  bool initiallyOverlapping = false;
};

// A body that a shape placed in the world overlaps (World::overlapShape).
struct OverlapResult {
  BodyId body;
  std::uint32_t subShape = 0;  // the first compound child overlapped within the part (0 for other shapes)
  std::uint32_t part = 0;      // the part overlapped: a body made of parts has a result per part touched
  friend bool operator==(const OverlapResult&, const OverlapResult&) = default;
};

// Called by World::castShapeCollect for each body the swept shape reaches, by body index: return the
// new largest fraction (hit.fraction to keep only hits no later than this one, a larger value such as
// 1 to keep going) or a negative number to stop. Hits beyond the clip are not handed out.
using ShapeCastCollector = std::function<float(const ShapeCastResult& hit)>;
// Called by World::overlapShapeCollect for each part touched, and by World::overlapPointCollect for
// each body holding the point, by body index: return false to stop.
using OverlapCollector = std::function<bool(const OverlapResult& overlap)>;
using PointCollector = std::function<bool(BodyId body)>;

// Two bodies, as World::broadPhasePairs hands them out.
struct BodyPair {
  BodyId a;
  BodyId b;
  friend bool operator==(const BodyPair&, const BodyPair&) = default;
};

}  // namespace collide
