// The parts of a body (BodyDef::parts, docs/parts.md), read the same way whether the body has one
// shape or several parts: a body of one shape is its part 0, with the record's own material, sensor
// flag and filter; a body made of parts has a compound shape, whose child k is part k's shape and
// local pose, and a PartRecord per part for the rest.
#pragma once

#include <collide/body.h>
#include <collide/narrowphase.h>
#include <collide/shapes.h>

#include "bodies/body_storage.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace collide::detail {

inline bool hasParts(const BodyRecord& r) { return !r.parts.empty(); }

inline std::uint32_t partCount(const BodyRecord& r) {
  return hasParts(r) ? static_cast<std::uint32_t>(r.parts.size()) : 1u;
}

inline const Shape& partShape(const BodyRecord& r, std::uint32_t part) {
  return hasParts(r) ? r.shape.compound().children()[part].shape : r.shape;
}

// The part's pose in the body frame (unscaled: the body transform's scale applies to it).
inline Transform partLocalPose(const BodyRecord& r, std::uint32_t part) {
  return hasParts(r) ? r.shape.compound().children()[part].transform : Transform{};
}

inline bool partIsSensor(const BodyRecord& r, std::uint32_t part) {
  return hasParts(r) ? r.parts[part].sensor : r.sensor;
}

inline BodyMaterial partMaterial(const BodyRecord& r, std::uint32_t part) {
  return hasParts(r) ? r.parts[part].material : BodyMaterial{r.friction, r.bounciness, r.rollingResistance};
}

inline std::uint64_t partUserData(const BodyRecord& r, std::uint32_t part) {
  return hasParts(r) ? r.parts[part].userData : r.userData;
}

struct PartFilter {
  std::uint32_t layer = 1;
  std::uint32_t mask = kAllLayers;
  std::int32_t group = 0;
};

inline PartFilter partFilter(const BodyRecord& r, std::uint32_t part) {
  if (!hasParts(r)) return {r.layer, r.mask, r.group};
  const PartRecord& p = r.parts[part];
  return {p.layer, p.mask, p.group};
}

// Groups first (the same non-zero group: positive always, negative never), then each part's layer in
// the other's mask.
inline bool filtersAllow(const PartFilter& a, const PartFilter& b) {
  if (a.group != 0 && a.group == b.group) return a.group > 0;
  return (a.layer & b.mask) != 0 && (b.layer & a.mask) != 0;
}

// The mask the body's broad-phase proxy pairs by (ProxyDef::mask): its parts' masks together, or
// every layer when a part has a positive group, which collides whatever the masks say.
inline std::uint32_t proxyMask(const BodyRecord& r) {
  if (!hasParts(r)) return r.group > 0 ? kAllLayers : r.mask;
  for (const PartRecord& p : r.parts)
    if (p.group > 0) return kAllLayers;
  return r.mask;
}

// The sweep of a part over its body's sweep: the part turns with the body about the body's centre of
// mass. (Rotations multiplied on the right keep the angle between them, so the part's slerp is the
// body's slerp times the part's rotation.)
inline Sweep partSweep(const Sweep& body, const Transform& local) {
  Sweep sweep = body;
  const Quat turn = local.rotation;
  sweep.rotation0 = body.rotation0 * turn;
  sweep.rotation1 = body.rotation1 * turn;
  sweep.localCenter = glm::conjugate(turn) * (body.localCenter - body.scale * local.position);
  return sweep;
}

// Whether every placement along the sweep is finite in float: Sweep::at computes
// center0 + t (center1 - center0) - q localCenter, and this bounds each of its terms and the steps
// in between. glm turns a vector v by a unit quaternion (w, u) as v + 2 (w (u x v) + u x (u x v)),
// whose parts reach 13 times v's largest component before they cancel: an offset within float's
// range once turned can overflow on the way. A part placed near float's limit from its body's
// centre, or a body near that limit, has no such sweep: the continuous pass and the sensor sweeps
// leave the pair (its contact still acts).
inline bool sweepStaysFinite(const Sweep& s) {
  // The sum of the components' sizes bounds the largest, and a NaN carries through it.
  const auto size = [](const Vec3& v) { return std::abs(v.x) + std::abs(v.y) + std::abs(v.z); };
  const float reach = size(s.center0) + size(s.center1) + 13.0f * size(s.localCenter);
  return std::isfinite(reach);
}

// Calls visit(partA, partB) for each pair of a part of ra and a part of rb that the parts' filters
// allow, in order (a's parts, then b's).
template <typename Visit>
void forEachAllowedPartPair(const BodyRecord& ra, const BodyRecord& rb, Visit&& visit) {
  const std::uint32_t na = partCount(ra), nb = partCount(rb);
  for (std::uint32_t i = 0; i < na; ++i) {
    const PartFilter fa = partFilter(ra, i);
    for (std::uint32_t j = 0; j < nb; ++j) {
      if (filtersAllow(fa, partFilter(rb, j))) visit(i, j);
    }
  }
}

// Whether any part of ra may collide with any part of rb by their filters (for two bodies of one
// shape each, the bodies' own filters).
inline bool anyPartPairAllowed(const BodyRecord& ra, const BodyRecord& rb) {
  if (!hasParts(ra) && !hasParts(rb)) return filtersAllow(partFilter(ra, 0), partFilter(rb, 0));
  bool any = false;
  const std::uint32_t na = partCount(ra), nb = partCount(rb);
  for (std::uint32_t i = 0; i < na && !any; ++i) {
    const PartFilter fa = partFilter(ra, i);
    for (std::uint32_t j = 0; j < nb && !any; ++j) any = filtersAllow(fa, partFilter(rb, j));
  }
  return any;
}

// The deepest manifold between the solid parts (not sensors) of two bodies at these poses, over the
// pairs of parts the filters allow and `skip(partA, partB)` does not rule out; false when no such pair
// touches within the margin. For two bodies of one shape each: collide() of their shapes.
template <typename Skip>
bool collideSolidParts(const BodyRecord& ra, const Transform& ta, const BodyRecord& rb, const Transform& tb,
                       float margin, Manifold& out, Skip&& skip) {
  if (!hasParts(ra) && !hasParts(rb))
    return !skip(0u, 0u) && collide::collide(ra.shape, ta, rb.shape, tb, out, margin);
  bool found = false;
  forEachAllowedPartPair(ra, rb, [&](std::uint32_t i, std::uint32_t j) {
    if (partIsSensor(ra, i) || partIsSensor(rb, j) || skip(i, j)) return;
    Manifold m;
    if (!collide::collide(partShape(ra, i), ta * partLocalPose(ra, i), partShape(rb, j),
                          tb * partLocalPose(rb, j), m, margin))
      return;
    if (!found || m.maxDepth() > out.maxDepth()) out = m;
    found = true;
  });
  return found;
}

}  // namespace collide::detail
