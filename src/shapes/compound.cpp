// Compound proxy: child shapes placed by local transforms, the union of their solids (lecture,
// slide 51). Queries go through the public per-shape queries with each child's transform, so any
// proxy (a nested compound too) can be a child.
#include "shapes/shape_functions.h"

#include "base/fail.h"

#include <limits>
#include <sstream>
#include <string>

namespace collide {

Compound Compound::fromChildren(std::vector<Child> children) {
  const detail::ErrorScope scope;
  if (children.empty()) COLLIDE_FAIL("compound: needs at least one child, got 0", {});
  Compound compound;
  for (std::size_t i = 0; i < children.size(); ++i) {
    const Child& child = children[i];
    detail::withErrorContext("compound: child " + std::to_string(i) + ": ",
                             [&] { detail::validateShape(child.shape); });
    COLLIDE_RETURN_IF_FAILED({});
    if (child.shape.type() == ShapeType::Plane) {
      COLLIDE_FAIL(
          "compound: child " + std::to_string(i) + " is a plane; a half-space cannot be part of a compound",
          {});
    }
    if (!isValid(child.transform)) {
      const Transform& t = child.transform;
      std::ostringstream message;
      message << "compound: child " << i
              << " has an invalid transform (needs a finite position, a unit rotation and a finite "
                 "scale > 0), got position ["
              << t.position.x << ", " << t.position.y << ", " << t.position.z << "], rotation [w "
              << t.rotation.w << ", " << t.rotation.x << ", " << t.rotation.y << ", " << t.rotation.z
              << "], scale " << t.scale;
      COLLIDE_FAIL(message.str(), {});
    }
    compound.bounds_.grow(worldBounds(child.shape, child.transform));
  }
  compound.children_.assign(children.begin(), children.end());
  return compound;
}

}  // namespace collide

namespace collide::detail {

Aabb computeLocalBounds(const Compound& s) { return s.bounds(); }

// The union of the children's own world bounds: tighter than transforming the compound's local box,
// since each child keeps its exact (or its own conservative) bound.
Aabb computeWorldBounds(const Compound& s, const Transform& t) {
  Aabb box;
  for (const Compound::Child& child : s.children()) {
    box.grow(worldBounds(child.shape, t * child.transform));
    COLLIDE_RETURN_IF_FAILED({});
  }
  return box;
}

// The sum of the children's mass properties: each child is taken at its own scale, its centre of
// mass placed and its inertia rotated (R I R^T) into the compound frame, then all inertias moved to
// the common centre of mass (parallel-axis theorem). Children are assumed not to overlap: an
// overlap is counted twice, as in every engine that sums child masses.
MassProperties computeMassProperties(const Compound& s, float density) {
  struct Placed {
    float mass;
    Vec3 center;
    Mat3 inertia;
  };
  Array<Placed> placed;
  placed.reserve(s.children().size());
  MassProperties total;
  Vec3 weightedCenter(0.0f);
  for (std::size_t i = 0; i < s.children().size(); ++i) {
    const Compound::Child& child = s.children()[i];
    const MassProperties m =
        withErrorContext("compound: child " + std::to_string(i) + " has no mass properties: ",
                         [&] { return massProperties(child.shape, density, child.transform.scale); });
    COLLIDE_RETURN_IF_FAILED({});
    const Mat3 rotation = glm::mat3_cast(child.transform.rotation);
    // massProperties already scaled the centre of mass; only rotation and offset remain.
    const Vec3 center = child.transform.position + rotation * m.centerOfMass;
    placed.push_back({m.mass, center, rotation * m.inertia * glm::transpose(rotation)});
    total.mass += m.mass;
    total.volume += m.volume;
    weightedCenter += m.mass * center;
  }
  total.centerOfMass = weightedCenter / total.mass;
  total.inertia = Mat3(0.0f);
  for (const Placed& p : placed) {
    total.inertia += shiftInertia(p.inertia, p.mass, p.center - total.centerOfMass);
  }
  return total;
}

bool localContains(const Compound& s, const Vec3& p) {
  for (const Compound::Child& child : s.children()) {
    if (containsPoint(child.shape, child.transform, p)) return true;
  }
  return false;
}

// Outside every child, the nearest child surface point is exact: the distance to a union is the
// smallest distance to its members. Inside, we return the child surface point of smallest signed
// distance (the deepest penetration into one child). That point may lie inside another child, so
// for overlapping children it is a bound, not the union's true surface: the true depth is at least
// this deep, since the ball of that radius around p lies in one child and hence in the union.
SurfacePoint localClosestPoint(const Compound& s, const Vec3& p) {
  SurfacePoint best;
  best.signedDistance = std::numeric_limits<float>::infinity();
  for (const Compound::Child& child : s.children()) {
    if (best.signedDistance >= 0.0f) {
      // Skip children whose box is farther than the best surface so far.
      const Aabb bounds = worldBounds(child.shape, child.transform);
      const Vec3 gap = glm::max(glm::max(bounds.min - p, p - bounds.max), Vec3(0.0f));
      if (glm::dot(gap, gap) > best.signedDistance * best.signedDistance) continue;
    }
    const SurfacePoint candidate = closestPoint(child.shape, child.transform, p);
    if (candidate.signedDistance < best.signedDistance) best = candidate;
  }
  return best;
}

// The nearest hit over the children; subShape is the child index. A solid child that contains the
// origin answers distance 0 with normal -direction, which no other hit can beat.
std::optional<RayHit> localRayCast(const Compound& s, const Ray& ray) {
  std::optional<RayHit> best;
  Ray search = ray;
  for (std::size_t i = 0; i < s.children().size(); ++i) {
    const Compound::Child& child = s.children()[i];
    if (rayAabbEntry(search, worldBounds(child.shape, child.transform)) < 0.0f) continue;
    std::optional<RayHit> hit = rayCast(child.shape, child.transform, search);
    if (hit && (!best || hit->distance < best->distance)) {
      best = hit;
      best->subShape = static_cast<std::uint32_t>(i);
      search.maxDistance = hit->distance;
      if (hit->distance == 0.0f) break;
    }
  }
  return best;
}

}  // namespace collide::detail
