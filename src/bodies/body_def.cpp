// Bodies made from their definitions: validation, mass properties, the record and state (body_def.h).
#include "bodies/body_def.h"

#include <collide/error.h>

#include "base/format.h"

#include <algorithm>
#include <cmath>

namespace collide::detail {

namespace {

bool isFiniteMatrix(const Mat3& m) {
  for (int column = 0; column < 3; ++column) {
    if (!collide::isFinite(m[column])) return false;
  }
  return true;
}

void validateParticle(const BodyDef& def, const std::string& who) {
  const auto fail = [&](const std::string& message) { throw Error(who + ": " + message); };
  if (def.type != BodyType::Dynamic)
    fail("particle: a particle must be a dynamic body, got type " + std::string(toString(def.type)));
  if (def.shape.type() != ShapeType::Sphere) {
    fail("particle: a particle's shape must be a sphere, got " + std::string(toString(def.shape.type())));
  }
  if (def.angularVelocity != Vec3(0.0f)) {
    fail("particle: a particle has no angular velocity, got angularVelocity " +
         formatVec(def.angularVelocity));
  }
}

// Mass, centre of mass and inertia of a dynamic body; a particle is a point mass (zero inverse
// inertia, so no impulse ever turns it). Errors start with the field to blame: "shape: " or, for a
// given mass that the shape's inertia cannot carry in float, "mass: ".
void initMass(const BodyDef& def, BodyRecord& r, BodyState& s) {
  MassProperties props;
  try {
    props = massProperties(def.shape, def.mass ? 1.0f : def.density, def.scale);
  } catch (const Error& e) {
    throw Error(std::string("shape: ") + e.what());
  }
  float massScale = 1.0f;
  if (def.mass) massScale = *def.mass / props.mass;
  r.mass = props.mass * massScale;
  r.localCenterOfMass = props.centerOfMass;
  if (!def.particle) {
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
    if (def.mass && shapeFits) {
      throw Error("mass: mass properties not representable in float with mass " + formatFloat(*def.mass) +
                  ": the mass is too large or too small for this shape at this scale");
    }
    throw Error("shape: mass properties not representable in float (mass " + formatFloat(r.mass) +
                "): the shape is too large or too small at this scale");
  }
}

// The radii and extent that the speculative margin, the manifold cache and continuous collision
// read.
void initShapeExtents(const BodyDef& def, BodyRecord& r) {
  if (def.type != BodyType::Static) {
    const Vec3 half = localBounds(def.shape).halfExtents() * def.scale;
    r.minExtent = std::min({half.x, half.y, half.z});
    const BoundingSphere sphere = localBoundingSphere(def.shape);
    r.boundingRadius =
        glm::length(sphere.center * def.scale - r.localCenterOfMass) + sphere.radius * def.scale;
  }
  const BoundingSphere sphere = localBoundingSphere(def.shape);
  r.originRadius = (glm::length(sphere.center) + sphere.radius) * def.scale;
}

// What the shape's size gives the record: mass (dynamic bodies), radii and extent.
void initShapeMeasures(const BodyDef& def, BodyRecord& r, BodyState& s) {
  if (def.type == BodyType::Dynamic) initMass(def, r, s);  // its errors name their field
  try {
    initShapeExtents(def, r);
  } catch (const Error& e) {
    throw Error(std::string("shape: ") + e.what());
  }
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
  const auto fail = [&](const std::string& message) { throw Error(who + ": " + message); };
  if (static_cast<int>(def.type) > static_cast<int>(BodyType::Dynamic)) fail("type: unknown body type");
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
  if (!isFinite(def.bounciness) || def.bounciness < 0.0f || def.bounciness > 1.0f) {
    fail("bounciness must be in [0, 1], got " + formatFloat(def.bounciness));
  }
  if (!isFinite(def.friction) || def.friction < 0.0f)
    fail("friction must be finite and >= 0, got " + formatFloat(def.friction));
  if (!isFinite(def.rollingResistance) || def.rollingResistance < 0.0f)
    fail("rollingResistance must be finite and >= 0, got " + formatFloat(def.rollingResistance));
  if (!isFinite(def.gravityScale)) fail("gravityScale must be finite, got " + formatFloat(def.gravityScale));
  if (!isFinite(def.linearDamping) || def.linearDamping < 0.0f)
    fail("linearDamping must be finite and >= 0, got " + formatFloat(def.linearDamping));
  if (!isFinite(def.angularDamping) || def.angularDamping < 0.0f)
    fail("angularDamping must be finite and >= 0, got " + formatFloat(def.angularDamping));
  if (def.shape.type() == ShapeType::Plane && def.type != BodyType::Static) {
    fail("shape: a plane is an infinite half-space and can only be on a static body");
  }
  if (def.type == BodyType::Dynamic && !def.sensor && def.shape.type() == ShapeType::Mesh &&
      !def.shape.mesh().isClosed()) {
    fail("shape: an open triangle mesh has no mass; make the body static or kinematic");
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
  try {
    initShapeMeasures(def, r, s);
  } catch (const Error& e) {
    throw Error(who + ": " + e.what());  // "shape: ..." or "mass: ..."
  }
  s.rotation = glm::normalize(def.rotation);
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

  // Refused before the broad phase sees it: a shape whose box at this place is not representable
  // (or whose parts cannot be placed: a compound's child scales can multiply down to zero).
  Aabb bounds;
  try {
    bounds = worldBounds(r.shape, bodyTransform(r, s));
  } catch (const Error& e) {
    throw Error(who + ": shape: " + e.what());
  }
  if (!isFinite(bounds.min) || !isFinite(bounds.max) || !std::isfinite(r.boundingRadius)) {
    throw Error(who + ": shape: its bounds are not finite at this position and scale (min " +
                formatVec(bounds.min) + ", max " + formatVec(bounds.max) + "): the shape is too large");
  }
}

}  // namespace collide::detail
