// Compound pairs: each child (placed by the compound's transform times its own) against the other
// shape through the table, children whose box misses the other's skipped, and the children's
// manifolds merged into one. The compound is A; the mirroring wrapper serves compound as B.
#include <vector>

#include "narrowphase/pair_functions.h"

namespace collide::detail {

namespace {
// Mixes the child index into A's half of a feature id, so that two children's points differ.
std::uint32_t childFeature(std::uint32_t featureId, std::size_t child) {
  const std::uint32_t a = (featureId & 0xffffu) * 0x9E37u + static_cast<std::uint32_t>(child) * 0x7F4Bu + 1u;
  return (featureId & 0xffff0000u) | (a & 0xffffu);
}
}  // namespace

bool collideChildrenAny(std::span<const Compound::Child> children, const Transform& compoundTransform,
                        const Shape& other, const Transform& otherTransform, float margin, Manifold& out) {
  const bool otherIsPlane = other.type() == ShapeType::Plane;
  const Aabb otherBounds = otherIsPlane ? Aabb{} : worldBounds(other, otherTransform).expanded(margin);
  Array<NormalContact> contacts;
  for (std::size_t i = 0; i < children.size(); ++i) {
    const Compound::Child& child = children[i];
    const Transform placed = compoundTransform * child.transform;
    if (!otherIsPlane && !worldBounds(child.shape, placed).overlaps(otherBounds)) continue;
    Manifold manifold;
    if (!collidePair(child.shape, placed, other, otherTransform, margin, manifold)) continue;
    for (int p = 0; p < manifold.count; ++p) {
      NormalContact contact;
      contact.point = manifold.points[p];
      contact.point.featureId = childFeature(contact.point.featureId, i);
      contact.normal = manifold.normal;
      contacts.push_back(contact);
    }
  }
  return mergeContacts(contacts, margin, out);
}

bool collideCompoundAny(const Shape& shapeA, const Transform& transformA, const Shape& shapeB,
                        const Transform& transformB, float margin, Manifold& out) {
  return collideChildrenAny(shapeA.compound().children(), transformA, shapeB, transformB, margin, out);
}

}  // namespace collide::detail
