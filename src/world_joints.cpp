// The world's joints: creating them from their definitions (checked field by field), reading and
// changing them behind their generation-checked ids. The solver's side is src/dynamics/joints/.
#include "base/fail.h"
#include "world_impl.h"

#include "base/format.h"

#include <cmath>

namespace collide {

using detail::BodyRecord;
using detail::BodyState;
using detail::formatFloat;
using detail::formatVec;
using detail::Joint;

namespace {

// Reports Error (`who: message`); false, for the checks' returns.
bool fail(const std::string& who, const std::string& message) {
  detail::raiseError(who + ": " + message);
  return false;
}

Vec3 checkedAxis(const Vec3& axis, const std::string& who) {
  const float length = glm::length(axis);
  if (!isFinite(axis) || !(length > 1e-6f) || !std::isfinite(length)) {
    fail(who, "axis must be finite and non-zero, got " + formatVec(axis));
    return Vec3(1.0f, 0.0f, 0.0f);
  }
  return axis / length;
}

bool checkSoftness(const JointSoftness& s, const std::string& who, const char* field) {
  if (!isFinite(s.hertz) || s.hertz < 0.0f)
    return fail(who, std::string(field) + ".hertz must be finite and >= 0, got " + formatFloat(s.hertz));
  if (!isFinite(s.dampingRatio) || s.dampingRatio < 0.0f)
    return fail(who, std::string(field) + ".dampingRatio must be finite and >= 0, got " +
                         formatFloat(s.dampingRatio));
  return true;
}

// Angles within [-pi, pi]; lengths >= 0.
enum class Coordinate { Angle, Offset, Length };

bool checkLimits(const JointLimits& l, Coordinate coordinate, const std::string& who, const char* field) {
  if (!isFinite(l.lower) || !isFinite(l.upper) || !(l.lower <= l.upper)) {
    return fail(who, std::string(field) + ": lower and upper must be finite with lower <= upper, got [" +
                         formatFloat(l.lower) + ", " + formatFloat(l.upper) + "]");
  }
  if (coordinate == Coordinate::Angle && (l.lower < -kPi || l.upper > kPi)) {
    return fail(who, std::string(field) + ": angles must be within [-pi, pi], got [" + formatFloat(l.lower) +
                         ", " + formatFloat(l.upper) + "]");
  }
  if (coordinate == Coordinate::Length && l.lower < 0.0f)
    return fail(who, std::string(field) + ": lengths must be >= 0, got lower " + formatFloat(l.lower));
  return true;
}

bool checkMotor(const JointMotor& m, const std::string& who) {
  if (!isFinite(m.speed)) return fail(who, "motor.speed must be finite, got " + formatFloat(m.speed));
  if (!isFinite(m.maxForce) || m.maxForce < 0.0f)
    return fail(who, "motor.maxForce must be finite and >= 0, got " + formatFloat(m.maxForce));
  return true;
}

bool checkSpring(const JointSpring& s, const std::string& who) {
  if (!isFinite(s.hertz) || s.hertz < 0.0f)
    return fail(who, "spring.hertz must be finite and >= 0, got " + formatFloat(s.hertz));
  if (!isFinite(s.dampingRatio) || s.dampingRatio < 0.0f)
    return fail(who, "spring.dampingRatio must be finite and >= 0, got " + formatFloat(s.dampingRatio));
  if (!isFinite(s.target)) return fail(who, "spring.target must be finite, got " + formatFloat(s.target));
  return true;
}

bool checkBreak(float value, const std::string& who, const char* field) {
  if (!(value > 0.0f))
    return fail(who, std::string(field) + " must be > 0 (kUnbreakable for none), got " + formatFloat(value));
  return true;
}

bool checkFriction(float value, const std::string& who, const char* field) {
  if (!isFinite(value) || value < 0.0f)
    return fail(who, std::string(field) + " must be finite and >= 0, got " + formatFloat(value));
  return true;
}

bool checkSwing(float swing, const std::string& who) {
  if (!isFinite(swing) || swing < 0.0f || swing > kPi)
    return fail(who, "swingLimit must be within [0, pi], got " + formatFloat(swing));
  return true;
}

// The rotation that takes x to the unit axis: the joint frame in the world at creation.
Quat frameOfAxis(const Vec3& axis) {
  const Vec3 x(1.0f, 0.0f, 0.0f);
  const float c = glm::dot(x, axis);
  if (c < -0.9999f) return Quat(0.0f, 0.0f, 1.0f, 0.0f);  // half a turn about y
  return glm::normalize(Quat(1.0f + c, glm::cross(x, axis)));
}

}  // namespace

JointId World::Impl::addJoint(Joint joint) {
  if (!joint.collideConnected) ++jointedApart[detail::bodyPairKey(joint.bodyA, joint.bodyB)];
  joint.alive = true;
  std::uint32_t index;
  if (!freeJoints.empty()) {
    index = freeJoints.back();
    freeJoints.pop_back();
    joint.generation = joints[index].generation;
    joints[index] = joint;
  } else {
    index = static_cast<std::uint32_t>(joints.size());
    joints.push_back(joint);
  }
  ++jointCount;
  detail::wakeIsland(bodies, joint.bodyA);
  detail::wakeIsland(bodies, joint.bodyB);
  return {index, joints[index].generation};
}

bool World::Impl::requireJointBodies(BodyId a, BodyId b, const std::string& who) const {
  if (!isLive(a)) return fail(who, "a: invalid or stale body id (index " + std::to_string(a.index) + ")");
  if (!isLive(b)) return fail(who, "b: invalid or stale body id (index " + std::to_string(b.index) + ")");
  if (a == b) return fail(who, "a and b are the same body (index " + std::to_string(a.index) + ")");
  const BodyRecord& ra = bodies.records[a.index];
  const BodyRecord& rb = bodies.records[b.index];
  if (ra.type != BodyType::Dynamic && rb.type != BodyType::Dynamic) {
    return fail(who, "a and b: at least one body must be dynamic, got " + std::string(toString(ra.type)) +
                         " and " + std::string(toString(rb.type)));
  }
  return true;
}

Joint World::Impl::jointAt(BodyId a, BodyId b, const Vec3& anchor, const std::optional<Vec3>& axis,
                           JointType type, bool turns) const {
  const std::string who = std::string(toString(type)) + " joint";
  if (!requireJointBodies(a, b, who)) return {};
  if (!isFinite(anchor)) fail(who, "anchor must be finite, got " + formatVec(anchor));
  const Quat frame = axis ? frameOfAxis(checkedAxis(*axis, who)) : Quat(1.0f, 0.0f, 0.0f, 0.0f);
  Joint joint;
  joint.type = type;
  joint.bodyA = a.index;
  joint.bodyB = b.index;
  // Each body's local point under the world anchor, from its centre of mass. A particle has no
  // orientation to carry an offset: its anchor must be its centre, and only joints that leave it
  // free to turn may hold it.
  const auto local = [&](std::uint32_t body, const char* field, Vec3& localAnchor, Quat& localFrame) {
    const BodyState& s = bodies.states[body];
    const Vec3 offset = anchor - s.centerOfMass;
    if (bodies.records[body].particle) {
      if (turns)
        fail(who, std::string(field) + ": a particle cannot turn; hold it with a ball or distance joint");
      if (glm::length(offset) > 1e-6f) {
        fail(who, std::string(field) + ": a particle's anchor must be its centre " +
                      formatVec(s.centerOfMass) + ", got " + formatVec(anchor));
      }
    }
    localAnchor = glm::conjugate(s.rotation) * offset;
    localFrame = glm::conjugate(s.rotation) * frame;
  };
  local(joint.bodyA, "a", joint.localAnchorA, joint.localFrameA);
  local(joint.bodyB, "b", joint.localAnchorB, joint.localFrameB);
  return joint;
}

JointId World::createDistanceConstraint(const DistanceConstraintDef& def) {
  Impl& w = *impl_;
  const std::string who = "distance constraint";
  const detail::ErrorScope scope;
  if (!w.requireJointBodies(def.a, def.b, who)) return {};
  const BodyRecord& ra = w.bodies.records[def.a.index];
  const BodyRecord& rb = w.bodies.records[def.b.index];
  const auto localAnchor = [&](const std::optional<Vec3>& anchor, const BodyRecord& r, const char* field) {
    if (!anchor) return Vec3(0.0f);
    if (!isFinite(*anchor)) fail(who, std::string(field) + " must be finite, got " + formatVec(*anchor));
    if (r.particle && *anchor != Vec3(0.0f)) {
      fail(who, std::string(field) + ": a particle's anchor must be its centre (0, 0, 0), got " +
                    formatVec(*anchor));
    }
    return r.scale * *anchor - r.localCenterOfMass;
  };
  Joint joint;
  joint.type = JointType::Distance;
  joint.bodyA = def.a.index;
  joint.bodyB = def.b.index;
  joint.localAnchorA = localAnchor(def.localAnchorA, ra, "localAnchorA");
  joint.localAnchorB = localAnchor(def.localAnchorB, rb, "localAnchorB");
  const Vec3 d =
      w.anchorWorld(joint.bodyB, joint.localAnchorB) - w.anchorWorld(joint.bodyA, joint.localAnchorA);
  joint.length = glm::length(d);
  if (def.length) {
    if (!isFinite(*def.length) || *def.length < 0.0f)
      fail(who, "length must be finite and >= 0, got " + formatFloat(*def.length));
    joint.length = *def.length;
  }
  if (!isFinite(def.compliance) || def.compliance < 0.0f)
    fail(who, "compliance must be finite and >= 0, got " + formatFloat(def.compliance));
  if (!isFinite(def.dampingRatio) || def.dampingRatio < 0.0f)
    fail(who, "dampingRatio must be finite and >= 0, got " + formatFloat(def.dampingRatio));
  checkSpring(def.spring, who);
  if (def.spring.enabled && def.compliance > 0.0f)
    fail(who, "spring and compliance: a distance constraint has one spring, got both");
  checkLimits(def.limits, Coordinate::Length, who, "limits");
  checkBreak(def.breakForce, who, "breakForce");
  joint.compliance = def.compliance;
  joint.dampingRatio = def.dampingRatio;
  joint.spring = def.spring;
  joint.limits = def.limits;
  joint.breakForce = def.breakForce;
  joint.collideConnected = def.collideConnected;
  if (glm::length(d) > 1e-6f) joint.axis = d / glm::length(d);
  COLLIDE_RETURN_IF_FAILED(JointId{});
  return w.addJoint(joint);
}

JointId World::createBallJoint(const BallJointDef& def) {
  Impl& w = *impl_;
  const detail::ErrorScope scope;
  Joint joint = w.jointAt(def.a, def.b, def.anchor, std::nullopt, JointType::Ball, false);
  checkSoftness(def.softness, "ball joint", "softness");
  checkBreak(def.breakForce, "ball joint", "breakForce");
  checkFriction(def.frictionTorque, "ball joint", "frictionTorque");
  joint.softness = def.softness;
  joint.friction = def.frictionTorque;
  joint.breakForce = def.breakForce;
  joint.collideConnected = def.collideConnected;
  COLLIDE_RETURN_IF_FAILED(JointId{});
  return w.addJoint(joint);
}

// Hinge and slider share their fields: one free coordinate along an axis (an angle, an offset).
template <typename Def>
JointId World::Impl::addAxialJoint(const Def& def, JointType type) {
  const std::string who = std::string(toString(type)) + " joint";
  const detail::ErrorScope scope;
  Joint joint = jointAt(def.a, def.b, def.anchor, def.axis, type, true);
  checkLimits(def.limits, type == JointType::Hinge ? Coordinate::Angle : Coordinate::Offset, who, "limits");
  checkMotor(def.motor, who);
  checkSpring(def.spring, who);
  checkSoftness(def.softness, who, "softness");
  checkBreak(def.breakForce, who, "breakForce");
  checkBreak(def.breakTorque, who, "breakTorque");
  if constexpr (requires { def.frictionTorque; }) {
    checkFriction(def.frictionTorque, who, "frictionTorque");
    joint.friction = def.frictionTorque;
  } else {
    checkFriction(def.frictionForce, who, "frictionForce");
    joint.friction = def.frictionForce;
  }
  joint.limits = def.limits;
  joint.motor = def.motor;
  joint.spring = def.spring;
  joint.softness = def.softness;
  joint.breakForce = def.breakForce;
  joint.breakTorque = def.breakTorque;
  joint.collideConnected = def.collideConnected;
  COLLIDE_RETURN_IF_FAILED(JointId{});
  return addJoint(joint);
}

JointId World::createHingeJoint(const HingeJointDef& def) {
  return impl_->addAxialJoint(def, JointType::Hinge);
}
JointId World::createSliderJoint(const SliderJointDef& def) {
  return impl_->addAxialJoint(def, JointType::Slider);
}

JointId World::createFixedJoint(const FixedJointDef& def) {
  Impl& w = *impl_;
  const std::string who = "fixed joint";
  const detail::ErrorScope scope;
  if (!w.isLive(def.b)) {
    w.requireJointBodies(def.a, def.b, who);
    return {};
  }
  const Vec3 anchor = def.anchor ? *def.anchor : w.bodies.states[def.b.index].centerOfMass;
  Joint joint = w.jointAt(def.a, def.b, anchor, std::nullopt, JointType::Fixed, true);
  checkSoftness(def.linearSoftness, who, "linearSoftness");
  checkSoftness(def.angularSoftness, who, "angularSoftness");
  checkBreak(def.breakForce, who, "breakForce");
  checkBreak(def.breakTorque, who, "breakTorque");
  joint.softness = def.linearSoftness;
  joint.angularSoftness = def.angularSoftness;
  joint.breakForce = def.breakForce;
  joint.breakTorque = def.breakTorque;
  joint.collideConnected = def.collideConnected;
  COLLIDE_RETURN_IF_FAILED(JointId{});
  return w.addJoint(joint);
}

JointId World::createConeJoint(const ConeJointDef& def) {
  Impl& w = *impl_;
  const std::string who = "cone joint";
  const detail::ErrorScope scope;
  Joint joint = w.jointAt(def.a, def.b, def.anchor, def.axis, JointType::Cone, true);
  checkSwing(def.swingLimit, who);
  checkLimits(def.twistLimits, Coordinate::Angle, who, "twistLimits");
  checkFriction(def.frictionTorque, who, "frictionTorque");
  joint.friction = def.frictionTorque;
  checkSoftness(def.softness, who, "softness");
  checkBreak(def.breakForce, who, "breakForce");
  checkBreak(def.breakTorque, who, "breakTorque");
  joint.swingLimit = def.swingLimit;
  joint.limits = def.twistLimits;
  joint.softness = def.softness;
  joint.breakForce = def.breakForce;
  joint.breakTorque = def.breakTorque;
  joint.collideConnected = def.collideConnected;
  COLLIDE_RETURN_IF_FAILED(JointId{});
  return w.addJoint(joint);
}

void World::destroyConstraint(JointId id) {
  Impl& w = *impl_;
  const std::uint32_t index = w.resolve(id, "destroyConstraint");
  if (index == Impl::kBadSlot) return;
  detail::wakeIsland(w.bodies, w.joints[index].bodyA);
  detail::wakeIsland(w.bodies, w.joints[index].bodyB);
  w.freeJoint(index);
}

bool World::isValid(JointId id) const {
  return id.index < impl_->joints.size() && impl_->joints[id.index].alive &&
         impl_->joints[id.index].generation == id.generation;
}
std::size_t World::constraintCount() const { return impl_->jointCount; }
JointType World::jointType(JointId id) const { return impl_->jointOf(id, "jointType").type; }
// The getters that read the joint's bodies: nothing to read for a stale id (Error; without
// exceptions a default value).
BodyId World::jointBodyA(JointId id) const {
  const std::uint32_t i = impl_->resolve(id, "jointBodyA");
  return i == Impl::kBadSlot ? BodyId{} : impl_->bodies.idOf(impl_->joints[i].bodyA);
}
BodyId World::jointBodyB(JointId id) const {
  const std::uint32_t i = impl_->resolve(id, "jointBodyB");
  return i == Impl::kBadSlot ? BodyId{} : impl_->bodies.idOf(impl_->joints[i].bodyB);
}

float World::constraintLength(JointId id) const {
  const Joint& j = impl_->jointOf(id, "constraintLength");
  return j.type == JointType::Distance ? j.length : 0.0f;
}
float World::constraintCurrentLength(JointId id) const {
  const std::uint32_t i = impl_->resolve(id, "constraintCurrentLength");
  if (i == Impl::kBadSlot) return 0.0f;
  const Joint& j = impl_->joints[i];
  return glm::length(impl_->anchorWorld(j.bodyB, j.localAnchorB) -
                     impl_->anchorWorld(j.bodyA, j.localAnchorA));
}

Vec3 World::jointAnchorA(JointId id) const {
  const std::uint32_t i = impl_->resolve(id, "jointAnchorA");
  return i == Impl::kBadSlot ? Vec3(0.0f) : detail::jointPose(impl_->bodies, impl_->joints[i]).anchorA;
}
Vec3 World::jointAnchorB(JointId id) const {
  const std::uint32_t i = impl_->resolve(id, "jointAnchorB");
  return i == Impl::kBadSlot ? Vec3(0.0f) : detail::jointPose(impl_->bodies, impl_->joints[i]).anchorB;
}
Vec3 World::jointAxis(JointId id) const {
  const std::uint32_t i = impl_->resolve(id, "jointAxis");
  return i == Impl::kBadSlot ? Vec3(0.0f) : detail::jointPose(impl_->bodies, impl_->joints[i]).axisA;
}
float World::jointPosition(JointId id) const {
  const std::uint32_t i = impl_->resolve(id, "jointPosition");
  return i == Impl::kBadSlot ? 0.0f : detail::jointPose(impl_->bodies, impl_->joints[i]).position;
}

float World::jointSpeed(JointId id) const {
  const std::uint32_t i = impl_->resolve(id, "jointSpeed");
  if (i == Impl::kBadSlot) return 0.0f;
  const Joint& j = impl_->joints[i];
  const detail::JointPose pose = detail::jointPose(impl_->bodies, j);
  const BodyState& a = impl_->bodies.states[j.bodyA];
  const BodyState& b = impl_->bodies.states[j.bodyB];
  const Vec3 turn = b.angularVelocity - a.angularVelocity;
  switch (j.type) {
    case JointType::Hinge:
      return glm::dot(pose.axisA, turn);
    case JointType::Cone: {
      const Vec3 mean = pose.axisA + pose.axisB;
      return glm::length(mean) > 1e-6f ? glm::dot(mean / glm::length(mean), turn) : 0.0f;
    }
    case JointType::Slider:
    case JointType::Distance: {
      // The slider's line is a's: its point under anchor B moves with a.
      const Vec3 pointA = j.type == JointType::Slider ? pose.anchorB : pose.anchorA;
      const Vec3 vA = a.linearVelocity + glm::cross(a.angularVelocity, pointA - a.centerOfMass);
      const Vec3 vB = b.linearVelocity + glm::cross(b.angularVelocity, pose.anchorB - b.centerOfMass);
      const Vec3 d = pose.anchorB - pose.anchorA;
      const Vec3 axis = j.type == JointType::Slider ? pose.axisA
                        : glm::length(d) > 1e-6f    ? d / glm::length(d)
                                                    : j.axis;
      return glm::dot(axis, vB - vA);
    }
    case JointType::Ball:
    case JointType::Fixed:
      return 0.0f;
  }
  return 0.0f;
}

float World::jointForce(JointId id) const {
  const Joint& j = impl_->jointOf(id, "jointForce");
  return impl_->lastSubstep > 0.0f ? detail::jointLoad(j, impl_->lastSubstep).force : 0.0f;
}
float World::jointTorque(JointId id) const {
  const Joint& j = impl_->jointOf(id, "jointTorque");
  return impl_->lastSubstep > 0.0f ? detail::jointLoad(j, impl_->lastSubstep).torque : 0.0f;
}
float World::jointMotorForce(JointId id) const {
  const Joint& j = impl_->jointOf(id, "jointMotorForce");
  return impl_->lastSubstep > 0.0f ? j.motorImpulse / impl_->lastSubstep : 0.0f;
}

Joint* World::Impl::jointFor(JointId id, const char* operation, std::initializer_list<JointType> types) {
  const std::uint32_t index = resolve(id, operation);
  if (index == kBadSlot) return nullptr;
  Joint& j = joints[index];
  for (JointType t : types) {
    if (j.type == t) return &j;
  }
  fail(std::string("world: ") + operation, "does not apply to a " + std::string(toString(j.type)) + " joint");
  return nullptr;
}

void World::Impl::wakeJoint(const Joint& joint) {
  detail::wakeIsland(bodies, joint.bodyA);
  detail::wakeIsland(bodies, joint.bodyB);
}

namespace {
constexpr std::initializer_list<JointType> kAllTypes = {JointType::Distance, JointType::Ball,
                                                        JointType::Hinge,    JointType::Slider,
                                                        JointType::Fixed,    JointType::Cone};
constexpr std::initializer_list<JointType> kFrictionTypes = {JointType::Ball, JointType::Cone,
                                                             JointType::Hinge, JointType::Slider};
}  // namespace

JointLimits World::jointLimits(JointId id) const { return impl_->jointOf(id, "jointLimits").limits; }
void World::setJointLimits(JointId id, const JointLimits& limits) {
  Joint* const found = impl_->jointFor(
      id, "setJointLimits", {JointType::Distance, JointType::Hinge, JointType::Slider, JointType::Cone});
  if (!found) return;
  Joint& j = *found;
  const Coordinate coordinate = j.type == JointType::Slider     ? Coordinate::Offset
                                : j.type == JointType::Distance ? Coordinate::Length
                                                                : Coordinate::Angle;
  if (!checkLimits(limits, coordinate, "world: setJointLimits", "limits")) return;
  if (!limits.enabled) j.lowerImpulse = j.upperImpulse = 0.0f;
  j.limits = limits;
  impl_->wakeJoint(j);
}

JointMotor World::jointMotor(JointId id) const { return impl_->jointOf(id, "jointMotor").motor; }
void World::setJointMotor(JointId id, const JointMotor& motor) {
  Joint* const found = impl_->jointFor(id, "setJointMotor", {JointType::Hinge, JointType::Slider});
  if (!found) return;
  Joint& j = *found;
  if (!checkMotor(motor, "world: setJointMotor")) return;
  if (!motor.enabled) j.motorImpulse = 0.0f;
  j.motor = motor;
  impl_->wakeJoint(j);
}

JointSpring World::jointSpring(JointId id) const { return impl_->jointOf(id, "jointSpring").spring; }
void World::setJointSpring(JointId id, const JointSpring& spring) {
  Joint* const found =
      impl_->jointFor(id, "setJointSpring", {JointType::Distance, JointType::Hinge, JointType::Slider});
  if (!found) return;
  Joint& j = *found;
  if (!checkSpring(spring, "world: setJointSpring")) return;
  if (j.type == JointType::Distance && spring.enabled && j.compliance > 0.0f)
    return static_cast<void>(
        fail("world: setJointSpring", "the distance constraint has a compliance spring already"));
  if (!spring.enabled) j.springImpulse = 0.0f;
  j.spring = spring;
  impl_->wakeJoint(j);
}

JointSoftness World::jointSoftness(JointId id) const { return impl_->jointOf(id, "jointSoftness").softness; }
void World::setJointSoftness(JointId id, const JointSoftness& softness) {
  Joint* const found = impl_->jointFor(id, "setJointSoftness", kAllTypes);
  if (!found) return;
  Joint& j = *found;
  if (!checkSoftness(softness, "world: setJointSoftness", "softness")) return;
  j.softness = softness;
  impl_->wakeJoint(j);
}
JointSoftness World::jointAngularSoftness(JointId id) const {
  const Joint* j = impl_->jointFor(id, "jointAngularSoftness", {JointType::Fixed});
  return j ? j->angularSoftness : decltype(j->angularSoftness){};
}
void World::setJointAngularSoftness(JointId id, const JointSoftness& softness) {
  Joint* const found = impl_->jointFor(id, "setJointAngularSoftness", {JointType::Fixed});
  if (!found) return;
  Joint& j = *found;
  if (!checkSoftness(softness, "world: setJointAngularSoftness", "softness")) return;
  j.angularSoftness = softness;
  impl_->wakeJoint(j);
}

float World::coneSwingLimit(JointId id) const {
  const Joint* j = impl_->jointFor(id, "coneSwingLimit", {JointType::Cone});
  return j ? j->swingLimit : decltype(j->swingLimit){};
}
void World::setConeSwingLimit(JointId id, float swingLimit) {
  Joint* const found = impl_->jointFor(id, "setConeSwingLimit", {JointType::Cone});
  if (!found) return;
  Joint& j = *found;
  if (!checkSwing(swingLimit, "world: setConeSwingLimit")) return;
  j.swingLimit = swingLimit;
  impl_->wakeJoint(j);
}

float World::jointBreakForce(JointId id) const { return impl_->jointOf(id, "jointBreakForce").breakForce; }
void World::setJointBreakForce(JointId id, float force) {
  Joint* const found = impl_->jointFor(id, "setJointBreakForce", kAllTypes);
  if (!found) return;
  Joint& j = *found;
  if (!checkBreak(force, "world: setJointBreakForce", "force")) return;
  j.breakForce = force;
}
float World::jointBreakTorque(JointId id) const { return impl_->jointOf(id, "jointBreakTorque").breakTorque; }
void World::setJointBreakTorque(JointId id, float torque) {
  // A distance or ball joint carries no torque.
  Joint* const found = impl_->jointFor(
      id, "setJointBreakTorque", {JointType::Hinge, JointType::Slider, JointType::Fixed, JointType::Cone});
  if (!found) return;
  Joint& j = *found;
  if (!checkBreak(torque, "world: setJointBreakTorque", "torque")) return;
  j.breakTorque = torque;
}

float World::jointFriction(JointId id) const {
  const Joint* j = impl_->jointFor(id, "jointFriction", kFrictionTypes);
  return j ? j->friction : decltype(j->friction){};
}
void World::setJointFriction(JointId id, float friction) {
  Joint* const found = impl_->jointFor(id, "setJointFriction", kFrictionTypes);
  if (!found) return;
  Joint& j = *found;
  if (!checkFriction(friction, "world: setJointFriction", "friction")) return;
  j.friction = friction;
  impl_->wakeJoint(j);
}

bool World::jointInTree(JointId id) const { return impl_->jointOf(id, "jointInTree").inTree; }

bool World::jointCollideConnected(JointId id) const {
  return impl_->jointOf(id, "jointCollideConnected").collideConnected;
}
void World::setJointCollideConnected(JointId id, bool collide) {
  Impl& w = *impl_;
  const std::uint32_t index = w.resolve(id, "setJointCollideConnected");
  if (index == Impl::kBadSlot) return;
  Joint& j = w.joints[index];
  if (j.collideConnected == collide) return;
  const std::uint64_t key = detail::bodyPairKey(j.bodyA, j.bodyB);
  if (collide) {
    const auto it = w.jointedApart.find(key);
    if (it != w.jointedApart.end() && --it->second == 0) w.jointedApart.erase(it);
  } else {
    ++w.jointedApart[key];
  }
  j.collideConnected = collide;
  w.wakeJoint(j);
}

std::span<const JointBreakEvent> World::jointBreakEvents() const { return impl_->events.jointBreaks; }

}  // namespace collide
