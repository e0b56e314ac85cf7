// Bodies made from their definitions: validation, mass properties, the record and state (body_def.h).
#include "bodies/body_def.h"

#include <collide/error.h>

#include "base/fail.h"
#include "base/format.h"
#include "bodies/body_parts.h"
#include "shapes/shape_functions.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <vector>

namespace collide::detail {

namespace {

bool isFiniteMatrix(const Mat3& m) {
  for (int column = 0; column < 3; ++column) {
    if (!collide::isFinite(m[column])) return false;
  }
  return true;
}

void validateParticle(const BodyDef& def, const std::string& who) {
  const auto fail = [&](const std::string& message) { raiseError(who + ": " + message); };
  if (def.type != BodyType::Dynamic)
    return fail("particle: a particle must be a dynamic body, got type " + std::string(toString(def.type)));
  if (def.shape.type() != ShapeType::Sphere) {
    return fail("particle: a particle's shape must be a sphere, got " +
                std::string(toString(def.shape.type())));
  }
  if (def.angularVelocity != Vec3(0.0f)) {
    fail("particle: a particle has no angular velocity, got angularVelocity " +
         formatVec(def.angularVelocity));
  }
}

// The parts' mass properties in the body frame at the body's scale: each part of density > 0 at
// its pose (centre placed, inertia rotated R I R^T), then every inertia moved to the common centre
// (parallel-axis theorem). Parts are taken not to overlap, as compound children.
MassProperties partsMassProperties(const Compound& compound, const Array<PartRecord>& parts, float scale) {
  struct Placed {
    float mass;
    Vec3 center;
    Mat3 inertia;
  };
  Array<Placed> placed;
  MassProperties total;
  Vec3 weighted(0.0f);
  for (std::size_t i = 0; i < parts.size(); ++i) {
    if (parts[i].density == 0.0f) continue;
    const Compound::Child& child = compound.children()[i];
    const MassProperties m = withErrorContext("parts[" + std::to_string(i) + "]: shape: ", [&] {
      return massProperties(child.shape, parts[i].density, scale);
    });
    COLLIDE_RETURN_IF_FAILED(total);
    const Mat3 rotation = glm::mat3_cast(child.transform.rotation);
    const Vec3 center = scale * child.transform.position + rotation * m.centerOfMass;
    placed.push_back({m.mass, center, rotation * m.inertia * glm::transpose(rotation)});
    total.mass += m.mass;
    total.volume += m.volume;
    weighted += m.mass * center;
  }
  if (placed.empty()) COLLIDE_FAIL("parts: a dynamic body needs a part with density > 0", total);
  total.centerOfMass = weighted / total.mass;
  for (const Placed& p : placed)
    total.inertia += shiftInertia(p.inertia, p.mass, p.center - total.centerOfMass);
  return total;
}

// Mass, centre of mass and inertia of a dynamic body from its shape's (or parts') mass properties
// at density 1 when the mass is given, else at the body's densities; a particle is a point mass
// (zero inverse inertia, so no impulse ever turns it). Errors start with the field to blame:
// "shape: " (or "parts..."), or, for a given mass that the shape's inertia cannot carry in float,
// "mass: ".
void initMass(const MassProperties& props, const std::optional<float>& givenMass, bool particle,
              BodyRecord& r, BodyState& s) {
  float massScale = 1.0f;
  if (givenMass) massScale = *givenMass / props.mass;
  r.mass = props.mass * massScale;
  r.localCenterOfMass = props.centerOfMass;
  r.inertiaLocal = Mat3(0.0f);
  r.inverseInertiaLocal = Mat3(0.0f);
  if (!particle) {
    r.inertiaLocal = props.inertia * massScale;
    r.inverseInertiaLocal = glm::inverse(r.inertiaLocal);
    r.isotropicInertia = isIsotropic(r.inertiaLocal);
  }
  s.inverseMass = 1.0f / r.mass;
  // Every number of the shape was valid, yet its mass may not be representable: a 1e30 m box
  // weighs infinitely much, a 1e-20 m one nothing (an infinite inverse mass). A given mass can be
  // too large or too small for the shape in the same way (3e38 kg on a 1 m sphere: its inertia
  // matrix cannot be inverted in float).
  if (!(std::isfinite(r.mass) && r.mass > 0.0f && std::isfinite(s.inverseMass) &&
        isFinite(r.localCenterOfMass) && isFiniteMatrix(r.inverseInertiaLocal))) {
    const bool shapeFits = std::isfinite(props.mass) && props.mass > 0.0f && isFinite(props.centerOfMass);
    if (givenMass && shapeFits) {
      COLLIDE_FAIL("mass: mass properties not representable in float with mass " + formatFloat(*givenMass) +
                   ": the mass is too large or too small for this shape at this scale");
    }
    COLLIDE_FAIL("shape: mass properties not representable in float (mass " + formatFloat(r.mass) +
                 "): the shape is too large or too small at this scale");
  }
}

// The radii and extent that the speculative margin, the manifold cache and continuous collision
// read.
void initShapeExtents(BodyRecord& r) {
  if (r.type != BodyType::Static) {
    const Vec3 half = localBounds(r.shape).halfExtents() * r.scale;
    r.minExtent = std::min({half.x, half.y, half.z});
    const BoundingSphere sphere = localBoundingSphere(r.shape);
    r.boundingRadius = glm::length(sphere.center * r.scale - r.localCenterOfMass) + sphere.radius * r.scale;
  }
  const BoundingSphere sphere = localBoundingSphere(r.shape);
  r.originRadius = (glm::length(sphere.center) + sphere.radius) * r.scale;
}

// What the shape's size gives the record: mass (dynamic bodies), radii and extent.
void initShapeMeasures(const BodyDef& def, BodyRecord& r, BodyState& s) {
  if (def.type == BodyType::Dynamic) {
    const MassProperties props = withErrorContext(
        "shape: ", [&] { return massProperties(def.shape, def.mass ? 1.0f : def.density, def.scale); });
    COLLIDE_RETURN_IF_FAILED();
    initMass(props, def.mass, def.particle, r, s);  // its errors name their field
    COLLIDE_RETURN_IF_FAILED();
  }
  withErrorContext("shape: ", [&] { initShapeExtents(r); });
}

void validateMaterial(const BodyMaterial& m, const std::function<void(const std::string&)>& fail) {
  if (!isFinite(m.bounciness) || m.bounciness < 0.0f || m.bounciness > 1.0f) {
    fail("bounciness must be in [0, 1], got " + formatFloat(m.bounciness));
  }
  if (!isFinite(m.friction) || m.friction < 0.0f)
    fail("friction must be finite and >= 0, got " + formatFloat(m.friction));
  if (!isFinite(m.rollingResistance) || m.rollingResistance < 0.0f)
    fail("rollingResistance must be finite and >= 0, got " + formatFloat(m.rollingResistance));
}

}  // namespace

bool isIsotropic(const Mat3& inertia) {
  const float scale = std::max({std::abs(inertia[0][0]), std::abs(inertia[1][1]), std::abs(inertia[2][2])});
  const float tolerance = 1e-6f * scale;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const float expected = i == j ? inertia[0][0] : 0.0f;
      if (std::abs(inertia[i][j] - expected) > tolerance) return false;
    }
  return true;
}

std::string bodyLabel(const BodyDef& def) {
  return def.name.empty() ? std::string("body") : "body \"" + def.name + "\"";
}

void validateBodyDef(const BodyDef& def) {
  const std::string who = bodyLabel(def);
  const auto fail = [&](const std::string& message) { raiseError(who + ": " + message); };
  if (static_cast<int>(def.type) > static_cast<int>(BodyType::Dynamic))
    return fail("type: unknown body type");
  // The shape first: a Shape made from a bad primitive without exceptions carries its bad value.
  withErrorContext(who + ": shape: ", [&] { validateShape(def.shape); });
  COLLIDE_RETURN_IF_FAILED();
  if (!isFinite(def.position)) fail("position must be finite, got " + formatVec(def.position));
  if (!isFinite(def.rotation) || std::abs(glm::length(def.rotation) - 1.0f) > 1e-3f) {
    fail("rotation must be a finite unit quaternion, got length " + formatFloat(glm::length(def.rotation)));
  }
  if (!isFinite(def.scale) || def.scale <= 0.0f)
    fail("scale must be finite and > 0, got " + formatFloat(def.scale));
  if (!isFinite(def.linearVelocity))
    fail("linearVelocity must be finite, got " + formatVec(def.linearVelocity));
  if (!isFinite(def.angularVelocity)) {
    fail("angularVelocity must be finite, got " + formatVec(def.angularVelocity));
  }
  validateMaterial({def.friction, def.bounciness, def.rollingResistance}, fail);
  if (!isFinite(def.gravityScale)) fail("gravityScale must be finite, got " + formatFloat(def.gravityScale));
  if (!isFinite(def.linearDamping) || def.linearDamping < 0.0f)
    fail("linearDamping must be finite and >= 0, got " + formatFloat(def.linearDamping));
  if (!isFinite(def.angularDamping) || def.angularDamping < 0.0f)
    fail("angularDamping must be finite and >= 0, got " + formatFloat(def.angularDamping));
  if (!def.parts.empty()) {
    if (def.particle) return fail("parts: a particle is a point mass of one sphere and has no parts");
    if (def.type == BodyType::Dynamic && def.mass && (!isFinite(*def.mass) || *def.mass <= 0.0f))
      fail("mass must be finite and > 0, got " + formatFloat(*def.mass));
    bool anyMass = false;
    for (std::size_t i = 0; i < def.parts.size(); ++i) {
      validatePartDef(def.parts[i], def.type, who + ": parts[" + std::to_string(i) + "]");
      COLLIDE_RETURN_IF_FAILED();
      anyMass = anyMass || def.parts[i].density > 0.0f;
    }
    if (def.type == BodyType::Dynamic && !anyMass)
      fail("parts: a dynamic body needs a part with density > 0");
    return;  // the single-part fields are not read
  }
  if (def.shape.type() == ShapeType::Plane && def.type != BodyType::Static) {
    return fail("shape: a plane is an infinite half-space and can only be on a static body");
  }
  if (def.type == BodyType::Dynamic && !def.sensor && def.shape.type() == ShapeType::Mesh &&
      !def.shape.mesh().isClosed()) {
    return fail("shape: an open triangle mesh has no mass; make the body static or kinematic");
  }
  if (def.particle) validateParticle(def, who);
  if (def.type == BodyType::Dynamic) {
    if (def.mass && (!isFinite(*def.mass) || *def.mass <= 0.0f)) {
      fail("mass must be finite and > 0, got " + formatFloat(*def.mass));
    }
    if (!def.mass && (!isFinite(def.density) || def.density <= 0.0f)) {
      fail("density must be finite and > 0, got " + formatFloat(def.density));
    }
  }
}

void validatePartDef(const PartDef& part, BodyType type, const std::string& who) {
  const auto fail = [&](const std::string& message) { raiseError(who + ": " + message); };
  withErrorContext(who + ": shape: ", [&] { validateShape(part.shape); });
  COLLIDE_RETURN_IF_FAILED();
  if (part.shape.type() == ShapeType::Plane)
    return fail("shape: a plane is an infinite half-space and cannot be a part; make it a body of its own");
  if (part.shape.type() == ShapeType::Mesh && type == BodyType::Dynamic)
    return fail("shape: a triangle mesh part is for static and kinematic bodies");
  if (!isFinite(part.position)) fail("position must be finite, got " + formatVec(part.position));
  if (!isFinite(part.rotation) || std::abs(glm::length(part.rotation) - 1.0f) > 1e-3f) {
    fail("rotation must be a finite unit quaternion, got length " + formatFloat(glm::length(part.rotation)));
  }
  validateMaterial(part.material, fail);
  if (!isFinite(part.density) || part.density < 0.0f)
    fail("density must be finite and >= 0, got " + formatFloat(part.density));
}

PartRecord makePartRecord(const PartDef& part) {
  return {part.material, part.density, part.sensor, part.layer, part.mask, part.group, part.userData};
}

Compound::Child makePartChild(const PartDef& part) {
  return {part.shape, Transform{part.position, glm::normalize(part.rotation), 1.0f}};
}

namespace {

// The mass properties (a dynamic body: from its shape or parts; else none, its centre at its
// origin), radii and extent of `next`, and its state placed with the body origin at `origin` and the
// velocity field it had (`oldCenter` moved at nextState's velocities). Throws Error before writing
// anything the caller keeps (next and nextState are the caller's copies).
void remeasure(BodyRecord& next, BodyState& nextState, const Vec3& origin, const Vec3& oldCenter) {
  next.mass = 0.0f;
  next.localCenterOfMass = Vec3(0.0f);
  next.inertiaLocal = next.inverseInertiaLocal = Mat3(0.0f);
  next.isotropicInertia = true;
  nextState.inverseMass = 0.0f;
  if (next.type == BodyType::Dynamic) {
    MassProperties props;
    if (hasParts(next)) {
      props = partsMassProperties(next.shape.compound(), next.parts, next.scale);
    } else {
      props = withErrorContext("shape: ", [&] {
        return massProperties(next.shape, next.givenMass ? 1.0f : next.density, next.scale);
      });
    }
    COLLIDE_RETURN_IF_FAILED();
    initMass(props, next.givenMass, next.particle, next, nextState);
    COLLIDE_RETURN_IF_FAILED();
  }
  withErrorContext("shape: ", [&] { initShapeExtents(next); });
  COLLIDE_RETURN_IF_FAILED();
  const Quat rotation = nextState.rotation;
  nextState.centerOfMass = origin + rotation * next.localCenterOfMass;
  nextState.centerOfMass0 = nextState.centerOfMass;
  nextState.rotation0 = rotation;
  // The velocity field of the body is kept: its new centre moves as that point of the body did.
  nextState.linearVelocity += glm::cross(nextState.angularVelocity, nextState.centerOfMass - oldCenter);
  nextState.inverseInertiaWorld = worldInverseInertia(next.inverseInertiaLocal, rotation);
  next.validCenterOfMass = nextState.centerOfMass;
  next.validRotation = rotation;
  next.boundsValid = false;
}

}  // namespace

void setBodyParts(BodyRecord& r, BodyState& s, Array<Compound::Child> children, Array<PartRecord> parts) {
  Compound compound = Compound::fromChildren(std::vector<Compound::Child>(children.begin(), children.end()));
  COLLIDE_RETURN_IF_FAILED();
  Shape shape = std::move(compound);
  BodyRecord next = r;  // the record changes only once everything below has succeeded
  next.shape = std::move(shape);
  next.parts = std::move(parts);
  next.sensor = true;
  next.layer = next.mask = 0;
  next.group = 0;
  for (const PartRecord& p : next.parts) {
    next.sensor = next.sensor && p.sensor;
    next.layer |= p.layer;
    next.mask |= p.mask;
  }
  next.friction = next.parts[0].material.friction;
  next.bounciness = next.parts[0].material.bounciness;
  next.rollingResistance = next.parts[0].material.rollingResistance;
  next.ccd = next.ccd && !next.sensor;
  BodyState nextState = s;
  remeasure(next, nextState, bodyOrigin(r, s), s.centerOfMass);
  COLLIDE_RETURN_IF_FAILED();
  requireRepresentableBounds(next, nextState, "parts");
  COLLIDE_RETURN_IF_FAILED();
  r = std::move(next);
  s = nextState;
}

void setBodyType(BodyRecord& r, BodyState& s, BodyType type) {
  if (static_cast<int>(type) > static_cast<int>(BodyType::Dynamic)) COLLIDE_FAIL("type: unknown body type");
  if (r.particle && type != BodyType::Dynamic) COLLIDE_FAIL("type: a particle is a dynamic body");
  if (type != BodyType::Static && r.shape.type() == ShapeType::Plane)
    COLLIDE_FAIL("type: a plane is an infinite half-space and can only be on a static body");
  if (type == BodyType::Dynamic) {
    if (!hasParts(r) && !r.sensor && r.shape.type() == ShapeType::Mesh && !r.shape.mesh().isClosed())
      COLLIDE_FAIL("type: an open triangle mesh has no mass; it can be static or kinematic");
    for (std::uint32_t k = 0; k < r.parts.size(); ++k) {
      if (partShape(r, k).type() == ShapeType::Mesh)
        COLLIDE_FAIL("type: part " + std::to_string(k) +
                     " is a triangle mesh, which is for static and kinematic bodies");
    }
  }
  BodyRecord next = r;
  next.type = type;
  BodyState nextState = s;
  if (type == BodyType::Static) nextState.linearVelocity = nextState.angularVelocity = Vec3(0.0f);
  remeasure(next, nextState, bodyOrigin(r, s), s.centerOfMass);
  COLLIDE_RETURN_IF_FAILED();
  r = std::move(next);
  s = nextState;
}

void initBody(const BodyDef& def, BodyRecord& r, BodyState& s) {
  const std::string who = bodyLabel(def);
  r.shape = def.shape;
  r.name = def.name;
  r.userData = def.userData;
  r.type = def.type;
  r.scale = def.scale;
  r.bounciness = def.bounciness;
  r.friction = def.friction;
  r.rollingResistance = def.rollingResistance;
  r.gravityScale = def.gravityScale;
  r.linearDamping = def.linearDamping;
  r.angularDamping = def.angularDamping;
  r.layer = def.layer;
  r.mask = def.mask;
  r.group = def.group;
  r.sensor = def.sensor;
  r.particle = def.particle;
  r.ccd = def.ccd && !def.sensor;
  r.givenMass = def.mass;
  r.density = def.density;
  s.rotation = glm::normalize(def.rotation);
  if (def.parts.empty()) {
    withErrorContext(who + ": ", [&] { initShapeMeasures(def, r, s); });  // "shape: ..." or "mass: ..."
    COLLIDE_RETURN_IF_FAILED();
  } else {
    Array<Compound::Child> children;
    Array<PartRecord> parts;
    for (const PartDef& part : def.parts) {
      children.push_back(makePartChild(part));
      parts.push_back(makePartRecord(part));
    }
    r.ccd = def.ccd;
    s.centerOfMass = def.position;  // the origin, until the parts' centre of mass is known
    r.localCenterOfMass = Vec3(0.0f);
    withErrorContext(who + ": ", [&] { setBodyParts(r, s, std::move(children), std::move(parts)); });
    COLLIDE_RETURN_IF_FAILED();
  }
  s.centerOfMass = def.position + s.rotation * r.localCenterOfMass;
  s.centerOfMass0 = s.centerOfMass;
  s.rotation0 = s.rotation;
  r.validCenterOfMass = s.centerOfMass;
  r.validRotation = s.rotation;
  if (def.type != BodyType::Static) {
    s.linearVelocity = def.linearVelocity;
    s.angularVelocity = def.angularVelocity;
  }
  s.inverseInertiaWorld = worldInverseInertia(r.inverseInertiaLocal, s.rotation);

  requireRepresentableBounds(r, s, who);
}

void requireRepresentableBounds(const BodyRecord& r, const BodyState& s, const std::string& who) {
  // Refused before the broad phase sees it: a shape whose box at this place is not representable
  // (or whose parts cannot be placed: a compound's child scales can multiply down to zero, a part
  // near float's limit from the body's origin lands beyond it).
  const Aabb bounds =
      withErrorContext(who + ": shape: ", [&] { return worldBounds(r.shape, bodyTransform(r, s)); });
  COLLIDE_RETURN_IF_FAILED();
  if (!isFinite(bounds.min) || !isFinite(bounds.max) || !std::isfinite(r.boundingRadius)) {
    COLLIDE_FAIL(who + ": shape: its bounds are not finite at this position and scale (min " +
                 formatVec(bounds.min) + ", max " + formatVec(bounds.max) + "): the shape is too large");
  }
}

}  // namespace collide::detail
