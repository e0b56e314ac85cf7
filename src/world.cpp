// The world's API bookkeeping: creating, destroying, reading and changing bodies and joints behind
// their generation-checked ids, and the world's settings. The step itself is in step.cpp, a stage per
// call; what a stage does is in the folder of its layer.
#include "base/fail.h"
#include "world_impl.h"

#include "base/format.h"
#include "bodies/body_bounds.h"
#include "bodies/body_def.h"
#include "bodies/body_parts.h"
#include "dynamics/fault_guard.h"
#include "memory/heap_bytes.h"
#include "queries/world_queries.h"
#include "response/revert.h"

#include <algorithm>
#include <cmath>

namespace collide {

using detail::ApartPair;
using detail::BodyRecord;
using detail::BodyState;
using detail::Contact;
using detail::formatFloat;
using detail::formatVec;
using detail::Joint;

bool World::Impl::isLive(BodyId id) const {
  return id.index < bodies.records.size() && bodies.records[id.index].alive &&
         bodies.records[id.index].generation == id.generation;
}

std::uint32_t World::Impl::resolve(BodyId id, const char* operation) const {
  if (!isLive(id)) {
    COLLIDE_FAIL(std::string("world: ") + operation + ": invalid or stale body id (index " +
                     std::to_string(id.index) + ", generation " + std::to_string(id.generation) + ")",
                 kBadSlot);
  }
  return id.index;
}

std::uint32_t World::Impl::resolve(JointId id, const char* operation) const {
  if (id.index >= joints.size() || !joints[id.index].alive || joints[id.index].generation != id.generation) {
    COLLIDE_FAIL(std::string("world: ") + operation + ": invalid or stale constraint id (index " +
                     std::to_string(id.index) + ", generation " + std::to_string(id.generation) + ")",
                 kBadSlot);
  }
  return id.index;
}

namespace {
const BodyRecord& noRecord() {
  static const BodyRecord record;
  return record;
}
const BodyState& noState() {
  static const BodyState state;
  return state;
}
const Joint& noJoint() {
  static const Joint joint;
  return joint;
}
}  // namespace

const BodyRecord& World::Impl::recordOf(BodyId id, const char* operation) const {
  const std::uint32_t i = resolve(id, operation);
  return i == kBadSlot ? noRecord() : bodies.records[i];
}

const BodyState& World::Impl::stateOf(BodyId id, const char* operation) const {
  const std::uint32_t i = resolve(id, operation);
  return i == kBadSlot ? noState() : bodies.states[i];
}

const Joint& World::Impl::jointOf(JointId id, const char* operation) const {
  const std::uint32_t i = resolve(id, operation);
  return i == kBadSlot ? noJoint() : joints[i];
}

void World::Impl::freeJoint(std::uint32_t index) {
  const detail::Joint& joint = joints[index];
  if (!joint.collideConnected) {
    const auto it = jointedApart.find(detail::bodyPairKey(joint.bodyA, joint.bodyB));
    if (it != jointedApart.end() && --it->second == 0) jointedApart.erase(it);
  }
  joints[index].alive = false;
  ++joints[index].generation;
  freeJoints.push_back(index);
  --jointCount;
}

Vec3 World::Impl::anchorWorld(std::uint32_t body, const Vec3& localAnchor) const {
  const BodyState& s = bodies.states[body];
  return s.centerOfMass + s.rotation * localAnchor;
}

World::World(const WorldDef& def) : impl_(std::make_unique<Impl>()) {
  const detail::ErrorScope scope;
  // Without exceptions a refused definition leaves the world with the default one (World::create
  // returns null instead).
  const bool valid = validateWorldDef(def);
  impl_->def = valid ? def : WorldDef{};
  impl_->broadPhase = createBroadPhase(impl_->def.broadPhase);
  impl_->tasks.configure(impl_->def.workerCount, impl_->def.enqueueTask, impl_->def.finishTask,
                         impl_->def.userTaskContext);
}

std::unique_ptr<World> World::create(const WorldDef& def) {
  const detail::ErrorScope scope;
  if (!validateWorldDef(def)) return nullptr;
  return std::make_unique<World>(def);
}

World::~World() = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;

const WorldDef& World::def() const { return impl_->def; }

void World::setDef(const WorldDef& def) {
  const detail::ErrorScope scope;
  if (!validateWorldDef(def)) return;
  Impl& w = *impl_;
  if (def.broadPhase != w.def.broadPhase) {
    std::unique_ptr<BroadPhase> next = createBroadPhase(def.broadPhase);  // may fail: nothing changed yet
    COLLIDE_RETURN_IF_FAILED();
    next->adoptProxies(*w.broadPhase);
    COLLIDE_RETURN_IF_FAILED();
    w.broadPhase = std::move(next);
  }
  if (w.def.sleeping && !def.sleeping) {
    for (std::uint32_t i = 0; i < w.bodies.records.size(); ++i) detail::wakeIsland(w.bodies, i);
  }
  if (def.penetrationResponse == PenetrationResponse::Revert &&
      w.def.penetrationResponse != PenetrationResponse::Revert) {
    detail::takeCurrentPosesAsValid(w.bodies);  // revert goes back no further than this switch
  }
  w.tasks.configure(def.workerCount, def.enqueueTask, def.finishTask, def.userTaskContext);
  w.def = def;
}

void World::reserveBodies(std::size_t count) {
  if (count > kMaxReservedBodies)
    COLLIDE_FAIL("world: reserveBodies: " + std::to_string(count) + " bodies, more than the " +
                 std::to_string(kMaxReservedBodies) + " a world reserves room for");
  Impl& w = *impl_;
  w.bodies.records.reserve(count);
  w.bodies.states.reserve(count);
  w.broadPhase->reserveProxies(count);
  w.proxyUpdate.reserve(count);
}

BodyId World::createBody(const BodyDef& def) {
  const detail::ErrorScope scope;
  detail::validateBodyDef(def);
  COLLIDE_RETURN_IF_FAILED(BodyId{});
  Impl& w = *impl_;
  const std::uint32_t index = w.bodies.allocate();
  // Any Error from here on frees the slot again: a body left allocated without a proxy in the broad
  // phase would make every later step fail.
  struct FreeSlotUnlessKept {
    detail::BodyStorage& bodies;
    std::uint32_t index;
    bool keep = false;
    ~FreeSlotUnlessKept() {
      if (!keep) bodies.free(index);
    }
  } slot{w.bodies, index};
  BodyRecord& r = w.bodies.records[index];
  detail::initBody(def, r, w.bodies.states[index]);
  COLLIDE_RETURN_IF_FAILED(BodyId{});
  detail::withErrorContext(detail::bodyLabel(def) + ": ", [&] { w.addProxy(index); });
  COLLIDE_RETURN_IF_FAILED(BodyId{});
  slot.keep = true;
  w.bodies.tally(r, +1);
  return w.bodies.idOf(index);
}

void World::destroyBody(BodyId id) {
  Impl& w = *impl_;
  const std::uint32_t index = w.resolve(id, "destroyBody");
  if (index == Impl::kBadSlot) return;
  if (w.bodies.records[index].enabled) w.broadPhase->remove(w.bodies.records[index].proxy);
  for (std::uint32_t j = 0; j < w.joints.size(); ++j) {
    if (w.joints[j].alive && (w.joints[j].bodyA == index || w.joints[j].bodyB == index)) {
      detail::wakeIsland(w.bodies, w.joints[j].bodyA == index ? w.joints[j].bodyB : w.joints[j].bodyA);
      w.freeJoint(j);
    }
  }
  detail::wakeIsland(w.bodies, index);
  w.endBodyContacts(index);
  w.bodies.tally(w.bodies.records[index], -1);
  w.bodies.free(index);
}

bool World::isValid(BodyId id) const { return impl_->isLive(id); }
std::size_t World::bodyCount() const { return impl_->bodies.aliveCount; }

BodyType World::type(BodyId id) const { return impl_->recordOf(id, "type").type; }
bool World::isParticle(BodyId id) const { return impl_->recordOf(id, "isParticle").particle; }

Transform World::transform(BodyId id) const {
  const std::uint32_t i = impl_->resolve(id, "transform");
  if (i == Impl::kBadSlot) return {};
  return detail::bodyTransform(impl_->bodies.records[i], impl_->bodies.states[i]);
}

void World::setTransform(BodyId id, const Vec3& position, const Quat& rotation) {
  setTransform(id, position, rotation, true);
}

void World::setTransform(BodyId id, const Vec3& position, const Quat& rotation, bool wake) {
  Impl& w = *impl_;
  const std::uint32_t i = w.resolve(id, "setTransform");
  if (i == Impl::kBadSlot) return;
  if (!isFinite(position))
    COLLIDE_FAIL("world: setTransform: position must be finite, got " + formatVec(position));
  if (!isFinite(rotation) || std::abs(glm::length(rotation) - 1.0f) > 1e-3f) {
    COLLIDE_FAIL("world: setTransform: rotation must be a finite unit quaternion");
  }
  BodyRecord& r = w.bodies.records[i];
  BodyState& s = w.bodies.states[i];
  BodyState placed = s;
  placed.rotation = glm::normalize(rotation);
  placed.centerOfMass = position + placed.rotation * r.localCenterOfMass;
  const detail::ErrorScope scope;
  detail::requireRepresentableBounds(r, placed, "world: setTransform");
  COLLIDE_RETURN_IF_FAILED();
  s.rotation = placed.rotation;
  s.centerOfMass = placed.centerOfMass;
  s.inverseInertiaWorld = detail::worldInverseInertia(r.inverseInertiaLocal, s.rotation);
  r.validCenterOfMass = s.centerOfMass;  // placed by the user: where revert goes back to from now
  r.validRotation = s.rotation;
  w.updateProxy(i);
  if (wake) {
    detail::wakeByUser(w.bodies, i);
  } else {
    detail::unfreezeBody(r, s);
  }
}

void World::Impl::endBodyContacts(std::uint32_t index) {
  // Touching contacts end now, reported with the next step's events (the step's event lists are
  // "what happened in the last step", so they are not changed in between).
  for (const Contact& c : contacts) {
    if (c.bodyA != index && c.bodyB != index) continue;
    detail::wakeIsland(bodies, c.bodyA == index ? c.bodyB : c.bodyA);  // what rested on it must fall
    events.endWithDestroyedBody(bodies, c);
  }
  std::erase_if(contacts, [&](const Contact& c) { return c.bodyA == index || c.bodyB == index; });
  // Its pairs apart are forgotten too (a disabled body comes back with its pairs tested anew), and
  // what was near it wakes.
  for (const ApartPair& p : apartPairs) {
    if (p.bodyA == index || p.bodyB == index)
      detail::wakeIsland(bodies, p.bodyA == index ? p.bodyB : p.bodyA);
  }
  std::erase_if(apartPairs, [&](const ApartPair& p) { return p.bodyA == index || p.bodyB == index; });
}

void World::Impl::addProxy(std::uint32_t index) {
  BodyRecord& r = bodies.records[index];
  ProxyDef proxy;
  proxy.bounds = detail::proxyBounds(bodies, index, 0.0f, def.contact.speculativeDistance);
  proxy.motion = r.type == BodyType::Static ? MotionType::Static : MotionType::Movable;
  proxy.userValue = index;
  proxy.layer = r.layer;  // a body made of parts: the union of its parts' layers
  proxy.mask = detail::proxyMask(r);
  r.proxy = broadPhase->add(proxy);
}

void World::Impl::updateProxy(std::uint32_t index) {
  const BodyRecord& r = bodies.records[index];
  if (!r.enabled) return;  // a disabled body has none; enabling it computes its box
  broadPhase->setLayer(r.proxy, r.layer);
  broadPhase->setMask(r.proxy, detail::proxyMask(r));
  broadPhase->update(r.proxy, detail::proxyBounds(bodies, index, 0.0f, def.contact.speculativeDistance));
}

void World::setEnabled(BodyId id, bool enabled) {
  Impl& w = *impl_;
  const std::uint32_t i = w.resolve(id, "setEnabled");
  if (i == Impl::kBadSlot) return;
  BodyRecord& r = w.bodies.records[i];
  if (r.enabled == enabled) return;
  if (!enabled) {
    detail::wakeIsland(w.bodies, i);  // its island goes on without it
    w.endBodyContacts(i);
    w.broadPhase->remove(r.proxy);
    r.proxy = ProxyId{};
    r.enabled = false;
    r.awake = false;
    r.sleepTime = 0.0f;
    return;
  }
  r.enabled = true;
  const detail::ErrorScope scope;
  detail::withErrorContext("world: setEnabled: ", [&] { w.addProxy(i); });
  if (detail::errorPending()) {
    r.enabled = false;
    return;
  }
  r.awake = true;
  detail::wakeByUser(w.bodies, i);
}

bool World::isEnabled(BodyId id) const { return impl_->recordOf(id, "isEnabled").enabled; }

void World::Impl::centerMoved(std::uint32_t index, const Vec3& shift) {
  if (shift == Vec3(0.0f)) return;
  for (Joint& joint : joints) {
    if (!joint.alive) continue;
    if (joint.bodyA == index) joint.localAnchorA -= shift;
    if (joint.bodyB == index) joint.localAnchorB -= shift;
  }
  for (Contact& c : contacts) {
    if (c.bodyA == index || c.bodyB == index) c.stuck = false;  // its friction anchors were from the centre
  }
}

void World::setType(BodyId id, BodyType type) {
  Impl& w = *impl_;
  const std::uint32_t i = w.resolve(id, "setType");
  if (i == Impl::kBadSlot) return;
  BodyRecord& r = w.bodies.records[i];
  if (type == r.type) return;
  const Vec3 oldLocalCenter = r.localCenterOfMass;
  const bool wasStatic = r.type == BodyType::Static;
  const detail::ErrorScope scope;
  detail::withErrorContext("world: setType: ", [&] { detail::setBodyType(r, w.bodies.states[i], type); });
  COLLIDE_RETURN_IF_FAILED();
  w.centerMoved(i, r.localCenterOfMass - oldLocalCenter);
  if (r.enabled && (wasStatic || type == BodyType::Static)) {
    // The broad phase keeps static and movable proxies apart: the proxy moves to the other side (its
    // slot is reused, so the contacts' pair keys stay).
    w.broadPhase->remove(r.proxy);
    w.addProxy(i);
  } else {
    w.updateProxy(i);
  }
  r.faulted = false;  // its mass properties are new
  r.sleepTime = 0.0f;
  r.awake = r.enabled;
  detail::wakeIsland(w.bodies, i);
  for (const Contact& c : w.contacts) {  // what rested on it, or was near it, must feel the change
    if (c.bodyA == i || c.bodyB == i) detail::wakeIsland(w.bodies, c.bodyA == i ? c.bodyB : c.bodyA);
  }
  for (const ApartPair& p : w.apartPairs) {
    if (p.bodyA == i || p.bodyB == i) detail::wakeIsland(w.bodies, p.bodyA == i ? p.bodyB : p.bodyA);
  }
}

Vec3 World::linearVelocity(BodyId id) const { return impl_->stateOf(id, "linearVelocity").linearVelocity; }
Vec3 World::angularVelocity(BodyId id) const { return impl_->stateOf(id, "angularVelocity").angularVelocity; }

void World::setLinearVelocity(BodyId id, const Vec3& velocity) {
  const std::uint32_t i = impl_->resolve(id, "setLinearVelocity");
  if (i == Impl::kBadSlot) return;
  if (!isFinite(velocity))
    COLLIDE_FAIL("world: setLinearVelocity: velocity must be finite, got " + formatVec(velocity));
  if (impl_->bodies.records[i].type == BodyType::Static) return;  // static bodies never move
  detail::wakeByUser(impl_->bodies, i);
  impl_->bodies.states[i].linearVelocity = velocity;
}

void World::setAngularVelocity(BodyId id, const Vec3& velocity) {
  const std::uint32_t i = impl_->resolve(id, "setAngularVelocity");
  if (i == Impl::kBadSlot) return;
  if (!isFinite(velocity))
    COLLIDE_FAIL("world: setAngularVelocity: velocity must be finite, got " + formatVec(velocity));
  if (impl_->bodies.records[i].type == BodyType::Static) return;
  if (impl_->bodies.records[i].particle) {
    if (velocity != Vec3(0.0f))
      COLLIDE_FAIL("world: setAngularVelocity: a particle has no angular velocity, got " +
                   formatVec(velocity));
    return;
  }
  detail::wakeByUser(impl_->bodies, i);
  impl_->bodies.states[i].angularVelocity = velocity;
}

void World::applyImpulse(BodyId id, const Vec3& impulse, const Vec3& worldPoint) {
  const std::uint32_t i = impl_->resolve(id, "applyImpulse");
  if (i == Impl::kBadSlot) return;
  if (!isFinite(impulse) || !isFinite(worldPoint))
    COLLIDE_FAIL("world: applyImpulse: impulse and point must be finite");
  if (impl_->bodies.records[i].type != BodyType::Dynamic) return;
  detail::wakeIsland(impl_->bodies, i);
  BodyState& s = impl_->bodies.states[i];
  s.linearVelocity += s.inverseMass * impulse;
  s.angularVelocity += s.inverseInertiaWorld * glm::cross(worldPoint - s.centerOfMass, impulse);
}

void World::applyForce(BodyId id, const Vec3& force, const Vec3& worldPoint) {
  const std::uint32_t i = impl_->resolve(id, "applyForce");
  if (i == Impl::kBadSlot) return;
  if (!isFinite(force) || !isFinite(worldPoint))
    COLLIDE_FAIL("world: applyForce: force and point must be finite");
  BodyRecord& r = impl_->bodies.records[i];
  if (r.type != BodyType::Dynamic) return;
  detail::wakeIsland(impl_->bodies, i);
  r.force += force;
  if (!r.particle) r.torque += glm::cross(worldPoint - impl_->bodies.states[i].centerOfMass, force);
}

void World::applyTorque(BodyId id, const Vec3& torque) {
  const std::uint32_t i = impl_->resolve(id, "applyTorque");
  if (i == Impl::kBadSlot) return;
  if (!isFinite(torque)) COLLIDE_FAIL("world: applyTorque: torque must be finite, got " + formatVec(torque));
  if (impl_->bodies.records[i].type != BodyType::Dynamic || impl_->bodies.records[i].particle) return;
  detail::wakeIsland(impl_->bodies, i);
  impl_->bodies.records[i].torque += torque;
}

bool World::isAwake(BodyId id) const {
  const std::uint32_t i = impl_->resolve(id, "isAwake");
  if (i == Impl::kBadSlot) return false;
  const BodyRecord& r = impl_->bodies.records[i];
  return r.type != BodyType::Static && r.awake;
}

void World::wakeBody(BodyId id) {
  const std::uint32_t i = impl_->resolve(id, "wakeBody");
  if (i != Impl::kBadSlot) detail::wakeByUser(impl_->bodies, i);
}

float World::mass(BodyId id) const { return impl_->recordOf(id, "mass").mass; }
Vec3 World::centerOfMass(BodyId id) const { return impl_->stateOf(id, "centerOfMass").centerOfMass; }
const Shape& World::shape(BodyId id) const { return impl_->recordOf(id, "shape").shape; }
std::uint64_t World::userData(BodyId id) const { return impl_->recordOf(id, "userData").userData; }
const std::string& World::name(BodyId id) const { return impl_->recordOf(id, "name").name; }

BodyMaterial World::material(BodyId id) const {
  const BodyRecord& r = impl_->recordOf(id, "material");
  return {r.friction, r.bounciness, r.rollingResistance};
}

void World::setMaterial(BodyId id, const BodyMaterial& material) {
  Impl& w = *impl_;
  const std::uint32_t i = w.resolve(id, "setMaterial");
  if (i == Impl::kBadSlot) return;
  if (!isFinite(material.friction) || material.friction < 0.0f)
    COLLIDE_FAIL("world: setMaterial: friction must be finite and >= 0, got " +
                 formatFloat(material.friction));
  if (!isFinite(material.bounciness) || material.bounciness < 0.0f || material.bounciness > 1.0f)
    COLLIDE_FAIL("world: setMaterial: bounciness must be in [0, 1], got " + formatFloat(material.bounciness));
  if (!isFinite(material.rollingResistance) || material.rollingResistance < 0.0f) {
    COLLIDE_FAIL("world: setMaterial: rollingResistance must be finite and >= 0, got " +
                 formatFloat(material.rollingResistance));
  }
  BodyRecord& r = w.bodies.records[i];
  w.bodies.tally(r, -1);
  r.friction = material.friction;
  r.bounciness = material.bounciness;
  r.rollingResistance = material.rollingResistance;
  for (detail::PartRecord& part : r.parts) part.material = material;
  w.bodies.tally(r, +1);
  detail::wakeIsland(w.bodies, i);
}

float World::gravityScale(BodyId id) const { return impl_->recordOf(id, "gravityScale").gravityScale; }

void World::setGravityScale(BodyId id, float scale) {
  const std::uint32_t i = impl_->resolve(id, "setGravityScale");
  if (i == Impl::kBadSlot) return;
  if (!isFinite(scale))
    COLLIDE_FAIL("world: setGravityScale: scale must be finite, got " + formatFloat(scale));
  impl_->bodies.records[i].gravityScale = scale;
  detail::wakeIsland(impl_->bodies, i);
}

float World::linearDamping(BodyId id) const { return impl_->recordOf(id, "linearDamping").linearDamping; }
float World::angularDamping(BodyId id) const { return impl_->recordOf(id, "angularDamping").angularDamping; }

void World::setDamping(BodyId id, float linear, float angular) {
  const std::uint32_t i = impl_->resolve(id, "setDamping");
  if (i == Impl::kBadSlot) return;
  if (!isFinite(linear) || linear < 0.0f)
    COLLIDE_FAIL("world: setDamping: linear damping must be finite and >= 0, got " + formatFloat(linear));
  if (!isFinite(angular) || angular < 0.0f)
    COLLIDE_FAIL("world: setDamping: angular damping must be finite and >= 0, got " + formatFloat(angular));
  BodyRecord& r = impl_->bodies.records[i];
  r.linearDamping = linear;
  r.angularDamping = angular;
  detail::wakeIsland(impl_->bodies, i);
}

std::vector<BodyId> World::bodies() const {
  std::vector<BodyId> ids;
  ids.reserve(impl_->bodies.aliveCount);
  for (std::uint32_t i = 0; i < impl_->bodies.records.size(); ++i) {
    if (impl_->bodies.records[i].alive) ids.push_back(impl_->bodies.idOf(i));
  }
  return ids;
}

void World::setPreSolveCallback(PreSolveCallback callback) { impl_->preSolve = std::move(callback); }
void World::setPreSolveCallback(PreSolveFilter filter) {
  if (!filter) {
    impl_->preSolve = nullptr;
    return;
  }
  impl_->preSolve = [filter = std::move(filter)](BodyId a, BodyId b, const Manifold& manifold,
                                                 ContactSettings&) { return filter(a, b, manifold); };
}

void World::setContactListener(ContactListener* listener) { impl_->contactListener = listener; }
void World::setPairFilter(PairFilter filter) { impl_->pairFilter = std::move(filter); }

void World::setCollisionFilter(BodyId id, std::uint32_t layer, std::uint32_t mask, std::int32_t group) {
  Impl& w = *impl_;
  const std::uint32_t index = w.resolve(id, "setCollisionFilter");
  if (index == Impl::kBadSlot) return;
  BodyRecord& r = w.bodies.records[index];
  r.layer = layer;
  r.mask = mask;
  r.group = detail::hasParts(r) ? 0 : group;  // a body made of parts: every part's, the summary 0
  for (detail::PartRecord& part : r.parts) {
    part.layer = layer;
    part.mask = mask;
    part.group = group;
  }
  if (r.enabled) {
    w.broadPhase->setLayer(r.proxy, layer);
    w.broadPhase->setMask(r.proxy, detail::proxyMask(r));
  }
  detail::wakeIsland(w.bodies, index);
}

std::uint32_t World::layer(BodyId id) const { return impl_->recordOf(id, "layer").layer; }
std::uint32_t World::mask(BodyId id) const { return impl_->recordOf(id, "mask").mask; }
std::int32_t World::group(BodyId id) const { return impl_->recordOf(id, "group").group; }

void World::step(float dt) {
  if (!isFinite(dt) || dt <= 0.0f)
    COLLIDE_FAIL("world: step: dt must be finite and > 0, got " + formatFloat(dt));
  impl_->callbackError.clear();
  impl_->step(dt);
  if (!impl_->callbackError.empty()) COLLIDE_FAIL(impl_->callbackError);
  if (impl_->contactListener != nullptr)
    detail::tellContactListener(impl_->events, impl_->bodies, impl_->contacts, *impl_->contactListener);
}

void World::visitContacts(const std::function<void(const ContactData&)>& visitor) const {
  for (const detail::Contact& c : impl_->contacts) {
    if (c.touching && !c.sensor) visitor(detail::makeContactData(impl_->bodies, c));
  }
}

void World::visitContacts(BodyId body, const std::function<void(const ContactData&)>& visitor) const {
  const std::uint32_t index = impl_->resolve(body, "visitContacts");
  if (index == Impl::kBadSlot) return;
  for (const detail::Contact& c : impl_->contacts) {
    if (c.touching && !c.sensor && (c.bodyA == index || c.bodyB == index))
      visitor(detail::makeContactData(impl_->bodies, c));
  }
}

const StepStats& World::lastStats() const { return impl_->lastStats; }
const StepStats& World::totalStats() const { return impl_->totalStats; }

WorldMemory World::memoryUse() const { return impl_->memoryUse(); }

WorldMemory World::Impl::memoryUse() const {
  using detail::heapBytes;
  const Impl& w = *this;
  WorldMemory memory;
  memory.bodies = w.bodies.memoryBytes() + w.proxyUpdate.memoryBytes();
  memory.broadPhase = w.broadPhase->memoryBytes() + heapBytes(w.pairs);
  memory.contacts = heapBytes(w.contacts) + heapBytes(w.apartPairs) + w.contactUpdate.memoryBytes() +
                    w.events.memoryBytes();
  memory.solver = w.stepSolver.memoryBytes() + w.impacts.memoryBytes() + w.revert.memoryBytes();
  memory.joints = heapBytes(w.joints) + heapBytes(w.jointGroups) + heapBytes(w.freeJoints) +
                  heapBytes(w.jointedApart) + w.stepSolver.jointMemoryBytes();
  memory.islands = w.islands.memoryBytes();
  return memory;
}
std::span<const ContactEvent> World::contactEvents() const { return impl_->events.contacts; }
std::span<const SensorEvent> World::sensorEvents() const { return impl_->events.sensors; }
std::span<const FaultEvent> World::faultEvents() const { return impl_->events.faults; }
std::size_t World::touchingContactCount() const { return impl_->touchingCount; }

std::optional<RayCastResult> World::castRay(const Ray& ray, LayerMask mask) const {
  return detail::castRayClosest(impl_->bodies, *impl_->broadPhase, ray, QueryFilter{mask, false, {}});
}

std::optional<RayCastResult> World::castRay(const Ray& ray, const QueryFilter& filter) const {
  return detail::castRayClosest(impl_->bodies, *impl_->broadPhase, ray, filter);
}

std::optional<RayCastResult> World::castRayAny(const Ray& ray, const QueryFilter& filter) const {
  return detail::castRayAny(impl_->bodies, *impl_->broadPhase, ray, filter);
}

std::vector<RayCastResult> World::castRayAll(const Ray& ray, const QueryFilter& filter) const {
  return detail::castRayAll(impl_->bodies, *impl_->broadPhase, ray, filter);
}

void World::castRayCollect(const Ray& ray, const RayHitCollector& collector,
                           const QueryFilter& filter) const {
  detail::castRayCollect(impl_->bodies, *impl_->broadPhase, ray, collector, filter);
}

std::optional<ShapeCastResult> World::castShape(const Shape& shape, const Transform& pose,
                                                const Vec3& translation, const QueryFilter& filter) const {
  return detail::castShapeClosest(impl_->bodies, *impl_->broadPhase, shape, pose, translation, filter);
}

std::vector<ShapeCastResult> World::castShapeAll(const Shape& shape, const Transform& pose,
                                                 const Vec3& translation, const QueryFilter& filter) const {
  return detail::castShapeAll(impl_->bodies, *impl_->broadPhase, shape, pose, translation, filter);
}

std::vector<OverlapResult> World::overlapShape(const Shape& shape, const Transform& pose,
                                               const QueryFilter& filter) const {
  return detail::overlapShape(impl_->bodies, *impl_->broadPhase, shape, pose, filter);
}

std::vector<BodyId> World::overlapPoint(const Vec3& point, const QueryFilter& filter) const {
  return detail::overlapPoint(impl_->bodies, *impl_->broadPhase, point, filter);
}

void World::castShapeCollect(const Shape& shape, const Transform& pose, const Vec3& translation,
                             const ShapeCastCollector& collector, const QueryFilter& filter) const {
  detail::castShapeCollect(impl_->bodies, *impl_->broadPhase, shape, pose, translation, collector, filter);
}

void World::overlapShapeCollect(const Shape& shape, const Transform& pose, const OverlapCollector& collector,
                                const QueryFilter& filter) const {
  detail::overlapShapeCollect(impl_->bodies, *impl_->broadPhase, shape, pose, collector, filter);
}

void World::overlapPointCollect(const Vec3& point, const PointCollector& collector,
                                const QueryFilter& filter) const {
  detail::overlapPointCollect(impl_->bodies, *impl_->broadPhase, point, collector, filter);
}

bool World::hasLineOfSight(const Vec3& from, const Vec3& to, const QueryFilter& filter) const {
  return detail::hasLineOfSight(impl_->bodies, *impl_->broadPhase, from, to, filter);
}

std::vector<BodyPair> World::broadPhasePairs() const {
  return detail::bodyPairs(impl_->bodies, *impl_->broadPhase, impl_->pairs);
}

const BroadPhase& World::broadPhase() const { return *impl_->broadPhase; }

Vec3 World::linearMomentum() const {
  Vec3 p(0.0f);
  for (std::size_t i = 0; i < impl_->bodies.records.size(); ++i) {
    const BodyRecord& r = impl_->bodies.records[i];
    if (r.alive && r.type == BodyType::Dynamic) p += r.mass * impl_->bodies.states[i].linearVelocity;
  }
  return p;
}

float World::kineticEnergy() const {
  float energy = 0.0f;
  for (std::size_t i = 0; i < impl_->bodies.records.size(); ++i) {
    const BodyRecord& r = impl_->bodies.records[i];
    if (!r.alive || r.type != BodyType::Dynamic) continue;
    const BodyState& s = impl_->bodies.states[i];
    // I_world w from the local inertia (a particle has none).
    const Vec3 localOmega = glm::conjugate(s.rotation) * s.angularVelocity;
    energy += 0.5f * r.mass * glm::dot(s.linearVelocity, s.linearVelocity) +
              0.5f * glm::dot(localOmega, r.inertiaLocal * localOmega);
  }
  return energy;
}

}  // namespace collide
