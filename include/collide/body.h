// Bodies as the API names them: the type, the ids handed out for bodies and joints (slot index +
// generation, as Box2D v3: a stale id is detected, never dereferenced) and the definition a body is
// created from.
#pragma once

#include <collide/broadphase.h>
#include <collide/math.h>
#include <collide/shapes.h>

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace collide {

enum class BodyType : std::uint8_t { Static, Kinematic, Dynamic };
std::string_view toString(BodyType type);

struct BodyId {
  static constexpr std::uint32_t kNullIndex = 0xFFFFFFFFu;
  std::uint32_t index = kNullIndex;
  std::uint32_t generation = 0;
  bool isNull() const { return index == kNullIndex; }
  friend bool operator==(const BodyId&, const BodyId&) = default;
};

struct JointId {
  static constexpr std::uint32_t kNullIndex = 0xFFFFFFFFu;
  std::uint32_t index = kNullIndex;
  std::uint32_t generation = 0;
  bool isNull() const { return index == kNullIndex; }
  friend bool operator==(const JointId&, const JointId&) = default;
};

// The kinds of joint (collide/joints.h, docs/joints.md).
enum class JointType : std::uint8_t {
  Distance,  // the anchors keep a distance (rigid, a spring, or within [min, max])
  Ball,      // the anchors coincide; the bodies turn freely about them (spherical)
  Hinge,     // the anchors coincide; the bodies turn about one axis (revolute)
  Slider,    // the bodies keep their relative rotation and slide along one axis (prismatic)
  Fixed,     // the bodies keep their relative pose (weld)
  Cone,      // a ball joint whose axis stays in a cone and twists within limits (swing-twist)
};
std::string_view toString(JointType type);

// What a body's contacts combine with their partner's (BodyDef's fields of the same names).
struct BodyMaterial {
  float friction = 0.5f;           // >= 0
  float bounciness = 0.0f;         // [0, 1]
  float rollingResistance = 0.0f;  // m, >= 0
  friend bool operator==(const BodyMaterial&, const BodyMaterial&) = default;
};

// Which parts a part collides with (BodyDef::layer, mask and group, per part): two parts of the same
// non-zero group always collide (positive) or never do (negative); otherwise each one's layer must be
// in the other's mask.
struct CollisionFilter {
  std::uint32_t layer = 1;
  std::uint32_t mask = kAllLayers;
  std::int32_t group = 0;
  friend bool operator==(const CollisionFilter&, const CollisionFilter&) = default;
};

// One collision part of a body made of several (BodyDef::parts, World::addPart): a shape placed in
// the body's frame, with its own material, density, sensor flag, collision filter and user data.
// The body's mass, centre of mass and inertia are the sum of its parts' (each of uniform density);
// its contacts are kept per pair of parts, each with the two parts' materials combined; contacts,
// events and query hits name the part by its index in the body (docs/parts.md).
struct PartDef {
  Shape shape{Sphere{0.5f}};  // any shape but a plane; a mesh only on a static or kinematic body
  Vec3 position{0.0f};        // in the body frame, before the body's scale
  Quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
  BodyMaterial material{};
  // kg/m^3, >= 0. A part of density 0 has no mass (a sensor, a decoration); a dynamic body needs
  // one part with mass unless BodyDef::mass is given (the densities then weigh the parts).
  float density = 1000.0f;
  bool sensor = false;  // reports overlaps of this part, takes no response
  std::uint32_t layer = 1;
  std::uint32_t mask = kAllLayers;
  std::int32_t group = 0;
  std::uint64_t userData = 0;
};

struct BodyDef {
  BodyType type = BodyType::Dynamic;
  Shape shape{Sphere{0.5f}};
  Vec3 position{0.0f};
  Quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
  float scale = 1.0f;
  Vec3 linearVelocity{0.0f};   // world frame, of the centre of mass
  Vec3 angularVelocity{0.0f};  // world frame, rad/s
  // Dynamic bodies: mass > 0 if given (inertia scaled from the shape's), else density > 0.
  std::optional<float> mass;
  float density = 1000.0f;
  float bounciness = 0.0f;  // [0, 1]
  float friction = 0.5f;    // >= 0
  // Rolling resistance (m, >= 0): the lever of the torque that resists rolling (and pivoting) on a
  // contact, at most this length times the normal force (a ball of radius r on a surface with
  // rolling coefficient c: c r). 0 rolls freely; a pair takes the larger of its two bodies' values.
  float rollingResistance = 0.0f;
  // Dynamic bodies: the share of the world's gravity the body feels (0 floats, -1 rises, 2 falls
  // twice as fast; finite), and the damping of its linear and angular velocity (1/s, >= 0): each
  // substep of length h multiplies the velocity by 1 / (1 + h damping), so a velocity decays by
  // about e^(-damping t) (air drag in a game's sense, a wheel's bearing, a body under water).
  float gravityScale = 1.0f;
  float linearDamping = 0.0f;
  float angularDamping = 0.0f;
  // Which bodies it collides with (docs/architecture.md, "Filtering"): two bodies of the same
  // non-zero group always collide (positive) or never do (negative); otherwise each body's layer must
  // be in the other's mask. Then a world's pair filter (World::setPairFilter), if set, has the last
  // word. Sensors use the same rules for their overlaps.
  std::uint32_t layer = 1;          // the body's bits
  std::uint32_t mask = kAllLayers;  // the layers it collides with; both must agree
  std::int32_t group = 0;
  bool sensor = false;  // reports overlap events, takes no response
  // A point mass: a dynamic body whose shape must be a Sphere (it collides as a sphere of that
  // radius times scale) but that has no inertia, no angular velocity and a rotation that never
  // changes. Cheap links for chains, ropes and cloth-like meshes of distance constraints.
  bool particle = false;
  // A bullet (docs/ccd.md): with WorldDef::ccd on, every dynamic body that moves more than half its
  // smallest extent in a step is stopped at its first time of impact with static geometry; a body
  // flagged ccd is stopped at its first impact with anything (static, kinematic or dynamic), so it
  // does not pass through thin or turning moving bodies that the speculative contacts miss. Costs a
  // broad-phase query and a time of impact per candidate for each such fast body; nothing for a slow
  // one. Ignored for sensors.
  bool ccd = false;
  std::uint64_t userData = 0;
  std::string name;
  // A body made of parts: when not empty, the body is these parts (in this order: part i is index i)
  // and the single-part fields above (shape, density, bounciness, friction, rollingResistance,
  // sensor, layer, mask, group) are not read; position, rotation, scale, velocities, mass and the
  // rest still are. A particle has no parts.
  std::vector<PartDef> parts;
};

}  // namespace collide
