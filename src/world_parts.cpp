// The world's API for the parts of a body (docs/parts.md): reading them, changing a part's material
// and filter, adding and removing parts at run time.
#include "base/fail.h"
#include "world_impl.h"

#include "base/format.h"
#include "bodies/body_bounds.h"
#include "bodies/body_def.h"
#include "bodies/body_parts.h"

#include <algorithm>
#include <string>
#include <vector>

namespace collide {

using detail::ApartPair;
using detail::BodyRecord;
using detail::BodyState;
using detail::Contact;
using detail::PartRecord;

namespace {

bool partInRange(const BodyRecord& r, std::uint32_t part, const char* operation) {
  const std::uint32_t count = detail::partCount(r);
  if (part >= count) {
    COLLIDE_FAIL(std::string("world: ") + operation + ": part " + std::to_string(part) +
                     " out of range (the body has " + std::to_string(count) +
                     (count == 1 ? " part)" : " parts)"),
                 false);
  }
  return true;
}

// The part a getter reads: `part`, or after an Error without exceptions part 0, which every body has.
std::uint32_t checkPart(const BodyRecord& r, std::uint32_t part, const char* operation) {
  return partInRange(r, part, operation) ? part : 0;
}

bool validMaterial(const BodyMaterial& material, const char* operation) {
  const std::string where = std::string("world: ") + operation + ": ";
  if (!isFinite(material.friction) || material.friction < 0.0f)
    COLLIDE_FAIL(where + "friction must be finite and >= 0, got " + detail::formatFloat(material.friction),
                 false);
  if (!isFinite(material.bounciness) || material.bounciness < 0.0f || material.bounciness > 1.0f)
    COLLIDE_FAIL(where + "bounciness must be in [0, 1], got " + detail::formatFloat(material.bounciness),
                 false);
  if (!isFinite(material.rollingResistance) || material.rollingResistance < 0.0f) {
    COLLIDE_FAIL(where + "rollingResistance must be finite and >= 0, got " +
                     detail::formatFloat(material.rollingResistance),
                 false);
  }
  return true;
}

// The record's summaries of its parts (BodyRecord::parts) after a part's material or filter changed.
void summariseParts(BodyRecord& r) {
  r.layer = r.mask = 0;
  r.group = 0;
  for (const PartRecord& p : r.parts) {
    r.layer |= p.layer;
    r.mask |= p.mask;
  }
  r.friction = r.parts[0].material.friction;
  r.bounciness = r.parts[0].material.bounciness;
  r.rollingResistance = r.parts[0].material.rollingResistance;
}

}  // namespace

std::uint32_t World::partCount(BodyId id) const {
  return detail::partCount(impl_->recordOf(id, "partCount"));
}

const Shape& World::partShape(BodyId id, std::uint32_t part) const {
  const detail::ErrorScope scope;  // a stale id: one message, not one more for the part
  const BodyRecord& r = impl_->recordOf(id, "partShape");
  return detail::partShape(r, checkPart(r, part, "partShape"));
}

Transform World::partLocalPose(BodyId id, std::uint32_t part) const {
  const detail::ErrorScope scope;  // a stale id: one message, not one more for the part
  const BodyRecord& r = impl_->recordOf(id, "partLocalPose");
  return detail::partLocalPose(r, checkPart(r, part, "partLocalPose"));
}

bool World::partIsSensor(BodyId id, std::uint32_t part) const {
  const detail::ErrorScope scope;  // a stale id: one message, not one more for the part
  const BodyRecord& r = impl_->recordOf(id, "partIsSensor");
  return detail::partIsSensor(r, checkPart(r, part, "partIsSensor"));
}

std::uint64_t World::partUserData(BodyId id, std::uint32_t part) const {
  const detail::ErrorScope scope;  // a stale id: one message, not one more for the part
  const BodyRecord& r = impl_->recordOf(id, "partUserData");
  return detail::partUserData(r, checkPart(r, part, "partUserData"));
}

BodyMaterial World::partMaterial(BodyId id, std::uint32_t part) const {
  const detail::ErrorScope scope;  // a stale id: one message, not one more for the part
  const BodyRecord& r = impl_->recordOf(id, "partMaterial");
  return detail::partMaterial(r, checkPart(r, part, "partMaterial"));
}

void World::setPartMaterial(BodyId id, std::uint32_t part, const BodyMaterial& material) {
  Impl& w = *impl_;
  const std::uint32_t i = w.resolve(id, "setPartMaterial");
  if (i == Impl::kBadSlot) return;
  BodyRecord& r = w.bodies.records[i];
  if (!partInRange(r, part, "setPartMaterial") || !validMaterial(material, "setPartMaterial")) return;
  if (!detail::hasParts(r)) {
    setMaterial(id, material);
    return;
  }
  w.bodies.tally(r, -1);
  r.parts[part].material = material;
  summariseParts(r);
  w.bodies.tally(r, +1);
  detail::wakeIsland(w.bodies, i);
}

CollisionFilter World::partFilter(BodyId id, std::uint32_t part) const {
  const detail::ErrorScope scope;  // a stale id: one message, not one more for the part
  const BodyRecord& r = impl_->recordOf(id, "partFilter");
  const detail::PartFilter f = detail::partFilter(r, checkPart(r, part, "partFilter"));
  return {f.layer, f.mask, f.group};
}

void World::setPartFilter(BodyId id, std::uint32_t part, const CollisionFilter& filter) {
  Impl& w = *impl_;
  const std::uint32_t i = w.resolve(id, "setPartFilter");
  if (i == Impl::kBadSlot) return;
  BodyRecord& r = w.bodies.records[i];
  if (!partInRange(r, part, "setPartFilter")) return;
  if (!detail::hasParts(r)) {
    setCollisionFilter(id, filter.layer, filter.mask, filter.group);
    return;
  }
  r.parts[part].layer = filter.layer;
  r.parts[part].mask = filter.mask;
  r.parts[part].group = filter.group;
  summariseParts(r);
  if (r.enabled) {
    w.broadPhase->setLayer(r.proxy, r.layer);
    w.broadPhase->setMask(r.proxy, detail::proxyMask(r));
  }
  detail::wakeIsland(w.bodies, i);
}

void World::Impl::replaceParts(std::uint32_t index, Array<Compound::Child> children,
                               Array<PartRecord> parts) {
  BodyRecord& r = bodies.records[index];
  BodyState& s = bodies.states[index];
  const Vec3 oldLocalCenter = r.localCenterOfMass;
  BodyRecord before = r;
  detail::setBodyParts(r, s, std::move(children), std::move(parts));  // fails before any change
  COLLIDE_RETURN_IF_FAILED();
  bodies.tally(before, -1);
  bodies.tally(r, +1);
  centerMoved(index, r.localCenterOfMass - oldLocalCenter);
  updateProxy(index);
  detail::wakeByUser(bodies, index);
}

std::uint32_t World::addPart(BodyId id, const PartDef& part) {
  Impl& w = *impl_;
  const detail::ErrorScope scope;
  const std::uint32_t i = w.resolve(id, "addPart");
  if (i == Impl::kBadSlot) return kNoPart;
  const BodyRecord& r = w.bodies.records[i];
  if (r.particle)
    COLLIDE_FAIL("world: addPart: a particle is a point mass of one sphere and has no parts", kNoPart);
  if (r.shape.type() == ShapeType::Plane)
    COLLIDE_FAIL("world: addPart: a body of one plane cannot have parts; make the part a body of its own",
                 kNoPart);
  detail::validatePartDef(part, r.type, "world: addPart");
  COLLIDE_RETURN_IF_FAILED(kNoPart);
  Array<Compound::Child> children;
  Array<PartRecord> parts;
  if (detail::hasParts(r)) {
    const auto current = r.shape.compound().children();
    children.assign(current.begin(), current.end());
    parts = r.parts;
  } else {
    // The body's one shape becomes part 0, with the body's material, density, sensor flag and filter.
    children.push_back({r.shape, Transform{}});
    parts.push_back(
        {{r.friction, r.bounciness, r.rollingResistance}, r.density, r.sensor, r.layer, r.mask, r.group, 0});
  }
  children.push_back(detail::makePartChild(part));
  parts.push_back(detail::makePartRecord(part));
  const auto index = static_cast<std::uint32_t>(parts.size() - 1);
  detail::withErrorContext("world: addPart: ",
                           [&] { w.replaceParts(i, std::move(children), std::move(parts)); });
  COLLIDE_RETURN_IF_FAILED(kNoPart);
  return index;
}

void World::removePart(BodyId id, std::uint32_t part) {
  Impl& w = *impl_;
  const detail::ErrorScope scope;
  const std::uint32_t i = w.resolve(id, "removePart");
  if (i == Impl::kBadSlot) return;
  const BodyRecord& r = w.bodies.records[i];
  if (!partInRange(r, part, "removePart")) return;
  if (detail::partCount(r) == 1) COLLIDE_FAIL("world: removePart: a body keeps at least one part");
  const auto current = r.shape.compound().children();
  Array<Compound::Child> children(current.begin(), current.end());
  Array<PartRecord> parts = r.parts;
  children.erase(children.begin() + part);
  parts.erase(parts.begin() + part);
  detail::withErrorContext("world: removePart: ",
                           [&] { w.replaceParts(i, std::move(children), std::move(parts)); });
  COLLIDE_RETURN_IF_FAILED();
  // The removed part's contacts end (with the next step's events); the later parts' move down.
  const auto ofRemoved = [&](const Contact& c) {
    return (c.bodyA == i && c.partA == part) || (c.bodyB == i && c.partB == part);
  };
  for (const Contact& c : w.contacts) {
    if (!ofRemoved(c)) continue;
    detail::wakeIsland(w.bodies, c.bodyA == i ? c.bodyB : c.bodyA);
    w.events.endWithDestroyedBody(w.bodies, c);
  }
  std::erase_if(w.contacts, ofRemoved);
  // A pair apart is of a body of one shape, its part 0.
  if (part == 0) {
    for (const ApartPair& p : w.apartPairs) {
      if (p.bodyA == i || p.bodyB == i) detail::wakeIsland(w.bodies, p.bodyA == i ? p.bodyB : p.bodyA);
    }
    std::erase_if(w.apartPairs, [&](const ApartPair& p) { return p.bodyA == i || p.bodyB == i; });
  }
  for (Contact& c : w.contacts) {
    if (c.bodyA == i && c.partA > part) --c.partA;
    if (c.bodyB == i && c.partB > part) --c.partB;
  }
}

}  // namespace collide
