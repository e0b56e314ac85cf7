// The answers of the world's queries (World::castRay, World::broadPhasePairs).
#pragma once

#include <collide/body.h>
#include <collide/math.h>

#include <cstdint>

namespace collide {

// The hit of World::castRay: the body and where its shape was hit.
struct RayCastResult {
  BodyId body;
  float distance = 0.0f;  // along the ray (its direction normalised)
  Vec3 point{0.0f};
  Vec3 normal{0.0f};           // unit, the surface normal at the hit, facing the ray's origin side
  std::uint32_t subShape = 0;  // triangle index for a mesh, child index for a compound
};

// Two bodies, as World::broadPhasePairs hands them out.
struct BodyPair {
  BodyId a;
  BodyId b;
  friend bool operator==(const BodyPair&, const BodyPair&) = default;
};

}  // namespace collide
