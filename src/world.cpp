// The step: broad phase -> narrow phase -> persist -> solve -> ccd -> (revert) -> events.
//   1. proxies: every movable body's box, grown by the speculative distance and the step's motion;
//   2. broad phase (src/broadphase/): sorted pairs, static-static never produced;
//   3. narrow phase (src/narrowphase/) per pair that can respond: kinematic/static partners of a
//      kinematic body are skipped, layers filtered, then collide() with a speculative margin;
//   4. persist (src/contacts/): last step's contacts merged by pair key, points matched by feature
//      id for warm starting; the pre-solve callback may disable a contact;
//   5. solve (src/dynamics/): the soft step over all bodies and enabled contacts; then the
//      lecture's interpolated impact on new contacts and viscous/damping friction on prolonged ones
//      (src/response/contact_response.h), when the WorldDef asks for them;
//   6. ccd (src/dynamics/continuous.cpp, WorldDef::ccd): fast ccd bodies go back to their first
//      time of impact (docs/ccd.md); then revert (PenetrationResponse::Revert): bodies still
//      penetrating go back to the step's start;
//   7. events: begin/end contacts and sensor overlaps, in pair order.
#include <collide/world.h>

#include "contacts/contact_cache.h"
#include "bodies/body_storage.h"
#include "dynamics/continuous.h"
#include "dynamics/fault_guard.h"
#include "dynamics/integrate.h"
#include "dynamics/joint_solver.h"
#include "dynamics/solver.h"
#include "memory/prefetch.h"
#include "response/contact_response.h"
#include "shapes/shape_functions.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>

namespace collide {

using detail::BodyRecord;
using detail::BodyState;
using detail::Contact;
using detail::DistanceJoint;

namespace {

// A separating axis is kept for pairs apart where the collider test is costly: polyhedra (k-DOP,
// hull) against any convex shape. Two support points decide whether the pair is still apart.
bool separatingAxisPays(const Shape& a, const Shape& b) {
  const auto polyhedron = [](const Shape& s) {
    return s.type() == ShapeType::ConvexHull || s.type() == ShapeType::Kdop;
  };
  return a.isConvex() && b.isConvex() && (polyhedron(a) || polyhedron(b));
}

// How far B lies beyond A along the unit world direction: B's farthest point against it minus A's
// farthest point along it; > 0 is apart.
float separationAlong(const Shape& a, const Transform& ta, const Shape& b, const Transform& tb,
                      const Vec3& axis) {
  const Vec3 pa = ta.applyToPoint(support(a, ta.inverseApplyToDirection(axis)));
  const Vec3 pb = tb.applyToPoint(support(b, tb.inverseApplyToDirection(-axis)));
  return glm::dot(pb - pa, axis);
}

// A body's world box is recomputed once any of its points may have moved this far (m) since the box
// was computed; until then the old box grown by the possible motion stands in (conservative).
constexpr float kBoundsReuseDistance = 0.002f;
// The unit of how far ahead the loops that place shapes ask for their data (prefetchShapeHeader,
// prefetchShapeArrays): the pair loop looks up to three times this many pairs ahead, the bounds
// loop four times this many bodies.
constexpr std::uint32_t kPrefetchAhead = 4;

bool isFinite(const Mat3& m) {
  for (int column = 0; column < 3; ++column) {
    if (!collide::isFinite(m[column])) return false;
  }
  return true;
}

std::string formatVec(const Vec3& v) {
  std::ostringstream out;
  out << "(" << v.x << ", " << v.y << ", " << v.z << ")";
  return out.str();
}

std::string formatFloat(float value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

}  // namespace

struct World::Impl {
  WorldDef def;
  detail::BodyStorage bodies;
  std::unique_ptr<BroadPhase> broadPhase;
  std::vector<ProxyPair> pairs;
  // Each body's pose, spin reach and velocity, taken once per narrow phase rather than once per pair.
  std::vector<Transform> poses;
  std::vector<Mat3> scaledRotations;  // mat3_cast(rotation) * scale
  std::vector<float> spinReaches;
  std::vector<Vec3> velocities;            // linear, for the speculative margins
  std::vector<std::uint8_t> likelyPlaced;  // moves beyond the manifold cache's tolerance this step
  std::vector<std::uint32_t> proxyBodies;  // the body of each broad-phase proxy slot (its user value)
  std::vector<Contact> contacts;
  std::vector<Contact> previousContacts;
  detail::StepSolver stepSolver;
  std::vector<DistanceJoint> joints;
  std::vector<std::uint32_t> freeJoints;
  std::size_t jointCount = 0;
  std::vector<ContactEvent> contactEvents;
  std::vector<SensorEvent> sensorEvents;
  std::vector<FaultEvent> faultEvents;
  // End events of destroyed bodies' contacts, handed out with the next step's events.
  std::vector<ContactEvent> pendingContactEvents;
  std::vector<SensorEvent> pendingSensorEvents;
  std::vector<std::uint32_t> islandParent;  // union-find scratch (sleeping)
  std::vector<float> islandSleepTime;
  BroadPhaseStats lastStats;
  BroadPhaseStats totalStats;
  PreSolveCallback preSolve;
  std::string callbackError;  // reported by step() once the step is complete
  std::size_t touchingCount = 0;

  std::uint32_t resolve(BodyId id, const char* operation) const {
    if (id.index >= bodies.records.size() || !bodies.records[id.index].alive ||
        bodies.records[id.index].generation != id.generation) {
      throw Error(std::string("world: ") + operation + ": invalid or stale body id (index " +
                  std::to_string(id.index) + ", generation " + std::to_string(id.generation) + ")");
    }
    return id.index;
  }

  bool isAwakeDynamic(std::uint32_t index) const {
    const BodyRecord& r = bodies.records[index];
    return r.alive && r.type == BodyType::Dynamic && r.awake;
  }
  bool isSleeping(std::uint32_t index) const {
    const BodyRecord& r = bodies.records[index];
    return r.alive && r.type == BodyType::Dynamic && !r.awake;
  }
  bool isMovingKinematic(std::uint32_t index) const {
    const BodyRecord& r = bodies.records[index];
    const BodyState& s = bodies.states[index];
    return r.type == BodyType::Kinematic &&
           (s.linearVelocity != Vec3(0.0f) || s.angularVelocity != Vec3(0.0f));
  }

  // Wakes the island the body fell asleep with (all of it: an island sleeps and wakes as one, so
  // a stack never has half its boxes frozen), and restarts an awake body's rest timer. Returns
  // whether a sleeping body woke (a body frozen by the fault guard does not: it only looks asleep).
  bool wake(std::uint32_t index) {
    BodyRecord& r = bodies.records[index];
    if (!r.alive || r.type != BodyType::Dynamic || r.faulted) return false;
    r.sleepTime = 0.0f;
    if (r.awake) return false;
    const std::uint32_t root = r.island;
    for (BodyRecord& other : bodies.records) {
      if (other.alive && other.type == BodyType::Dynamic && !other.awake && !other.faulted &&
          other.island == root) {
        other.awake = true;
        other.sleepTime = 0.0f;
      }
    }
    return true;
  }

  // The user gave the body a new state: a body frozen by the fault guard comes back.
  void wakeByUser(std::uint32_t index) {
    detail::unfreezeBody(bodies.records[index], bodies.states[index]);
    wake(index);
  }

  std::uint32_t findRoot(std::uint32_t i) {
    while (islandParent[i] != i) {
      islandParent[i] = islandParent[islandParent[i]];  // path halving
      i = islandParent[i];
    }
    return i;
  }
  // The smaller index becomes the root: the islands do not depend on the order of the unions.
  void unite(std::uint32_t a, std::uint32_t b) {
    a = findRoot(a);
    b = findRoot(b);
    if (a < b) islandParent[b] = a;
    if (b < a) islandParent[a] = b;
  }

  BodyId idOf(std::uint32_t index) const { return {index, bodies.records[index].generation}; }

  std::uint32_t resolve(JointId id, const char* operation) const {
    if (id.index >= joints.size() || !joints[id.index].alive ||
        joints[id.index].generation != id.generation) {
      throw Error(std::string("world: ") + operation + ": invalid or stale constraint id (index " +
                  std::to_string(id.index) + ", generation " + std::to_string(id.generation) + ")");
    }
    return id.index;
  }

  void freeJoint(std::uint32_t index) {
    joints[index].alive = false;
    ++joints[index].generation;
    freeJoints.push_back(index);
    --jointCount;
  }

  Vec3 anchorWorld(std::uint32_t body, const Vec3& localAnchor) const {
    const BodyState& s = bodies.states[body];
    return s.centerOfMass + s.rotation * localAnchor;
  }

  // How far any point of the body can have moved between two poses: the centre's move plus the turn
  // angle times the radius about the centre. The turn angle is 2 asin |vector part of the turn|,
  // at most pi times that |vector part|.
  static float pointMotionBound(const BodyRecord& r, const Vec3& com0, const Quat& q0, const Vec3& com1,
                                const Quat& q1) {
    const Quat turn = q1 * glm::conjugate(q0);
    return glm::length(com1 - com0) + kPi * glm::length(Vec3(turn.x, turn.y, turn.z)) * r.boundingRadius;
  }

  // Whether the body's last box still serves (grown by `moved`, set then): see currentBounds.
  bool boundsReusable(std::uint32_t index, float& moved) const {
    const BodyRecord& r = bodies.records[index];
    if (!r.boundsValid || r.type == BodyType::Static) return false;
    const BodyState& s = bodies.states[index];
    moved = pointMotionBound(r, r.boundsCenter, r.boundsRotation, s.centerOfMass, s.rotation);
    return moved <= kBoundsReuseDistance;
  }

  // The body's world box. A body that barely moved since its box was last computed (a resting hull
  // transforms all its vertices for it) gets the old box grown by how far it can have moved.
  Aabb currentBounds(std::uint32_t index) {
    float moved = 0.0f;
    if (boundsReusable(index, moved)) return bodies.records[index].bounds.expanded(moved);
    return recomputeBounds(index);
  }
  // The body's world box computed anew from its shape and pose, and kept with that pose.
  Aabb recomputeBounds(std::uint32_t index) {
    BodyRecord& r = bodies.records[index];
    const BodyState& s = bodies.states[index];
    r.bounds = worldBounds(r.shape, detail::bodyTransform(r, s));
    r.boundsCenter = s.centerOfMass;
    r.boundsRotation = s.rotation;
    r.boundsValid = true;
    return r.bounds;
  }

  Aabb proxyBounds(std::uint32_t index, float dt) { return grownForStep(index, dt, currentBounds(index)); }
  // The body's current box as its proxy's: grown by the step's motion.
  Aabb grownForStep(std::uint32_t index, float dt, Aabb box) const {
    const BodyRecord& r = bodies.records[index];
    const BodyState& s = bodies.states[index];
    if (r.type == BodyType::Static) return withinFloatRange(box);
    // Speculative contacts need the pair before the bodies meet: grow by the step's motion.
    const Vec3 motion = dt * s.linearVelocity;
    box.min = glm::min(box.min, box.min + motion);
    box.max = glm::max(box.max, box.max + motion);
    const float turn = dt * glm::length(s.angularVelocity) * r.boundingRadius;
    return withinFloatRange(box.expanded(def.contact.speculativeDistance + turn));
  }
  // A finite state can still give an infinite box (a large shape turning fast, a body at 1e38 m
  // moving on), which the broad phase refuses: both sides are kept within the planes' "infinite"
  // extent, +-1e30 (NaN goes to the far side). Nothing that far matters to a contact any more; the
  // broad phase keeps working, and the fault guard contains the body.
  static Aabb withinFloatRange(Aabb box) {
    static constexpr float kFar = 1e30f;
    const auto clampFar = [](float v, float ifNaN) {
      return std::isnan(v) ? ifNaN : std::clamp(v, -kFar, kFar);
    };
    for (int axis = 0; axis < 3; ++axis) {
      box.min[axis] = clampFar(box.min[axis], -kFar);
      box.max[axis] = clampFar(box.max[axis], kFar);
    }
    return box;
  }

  void step(float dt);
  void solve(float dt);
  void narrowPhase(float dt);
  void wakeTouchedIslands(float dt);
  void updateSleep(float dt);
  float speculativeMargin(std::uint32_t ia, std::uint32_t ib, float dt) const;
  // The same from the bodies' linear velocities and spin reaches (|angular velocity| x bounding
  // radius), as the narrow phase keeps them per body.
  float speculativeMargin(const Vec3& velocityA, const Vec3& velocityB, float spinA, float spinB,
                          float dt) const;
  float spinReach(std::uint32_t index) const;
  void revertPenetrating();
  void refreshEscapedProxies();
  void emitEvents();
  ContactEvent makeEvent(const Contact& c, ContactEvent::Type type) const;
};

namespace {

void validateWorldDef(const WorldDef& def) {
  using collide::isFinite;  // not the Mat3 overload above, which would hide it
  if (!isFinite(def.gravity)) throw Error("world: gravity must be finite, got " + formatVec(def.gravity));
  if (def.substeps < 1) throw Error("world: substeps must be >= 1, got " + std::to_string(def.substeps));
  const ContactTuning& t = def.contact;
  const auto check = [](float value, bool ok, const char* field) {
    if (!isFinite(value) || !ok)
      throw Error(std::string("world: contact.") + field + " out of range, got " + formatFloat(value));
  };
  check(t.hertz, t.hertz > 0.0f, "hertz (must be > 0)");
  check(t.dampingRatio, t.dampingRatio >= 0.0f, "dampingRatio (must be >= 0)");
  check(t.pushOutSpeed, t.pushOutSpeed > 0.0f, "pushOutSpeed (must be > 0)");
  check(t.restitutionThreshold, t.restitutionThreshold >= 0.0f, "restitutionThreshold (must be >= 0)");
  check(t.linearSlop, t.linearSlop >= 0.0f, "linearSlop (must be >= 0)");
  check(t.speculativeDistance, t.speculativeDistance >= 0.0f, "speculativeDistance (must be >= 0)");
  check(t.frictionAnchorReach, t.frictionAnchorReach >= 0.0f, "frictionAnchorReach (must be >= 0)");
  check(t.manifoldCacheDistance, t.manifoldCacheDistance >= 0.0f, "manifoldCacheDistance (must be >= 0)");
  if (t.relaxPasses < 0)
    throw Error("world: contact.relaxPasses out of range (must be >= 0), got " +
                std::to_string(t.relaxPasses));
  const SleepTuning& sleep = def.sleep;
  const auto checkSleep = [](float value, bool ok, const char* field) {
    if (!isFinite(value) || !ok)
      throw Error(std::string("world: sleep.") + field + " out of range, got " + formatFloat(value));
  };
  checkSleep(sleep.linearSpeed, sleep.linearSpeed >= 0.0f, "linearSpeed (must be >= 0)");
  checkSleep(sleep.angularSpeed, sleep.angularSpeed >= 0.0f, "angularSpeed (must be >= 0)");
  checkSleep(sleep.timeToSleep, sleep.timeToSleep > 0.0f, "timeToSleep (must be > 0)");
}

}  // namespace

World::World(const WorldDef& def) : impl_(std::make_unique<Impl>()) {
  validateWorldDef(def);
  impl_->def = def;
  impl_->broadPhase = createBroadPhase(def.broadPhase);
}

World::~World() = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;

const WorldDef& World::def() const { return impl_->def; }

void World::setDef(const WorldDef& def) {
  validateWorldDef(def);
  Impl& w = *impl_;
  if (def.broadPhase != w.def.broadPhase) {
    std::unique_ptr<BroadPhase> next = createBroadPhase(def.broadPhase);  // may throw: nothing changed yet
    next->adoptProxies(*w.broadPhase);
    w.broadPhase = std::move(next);
  }
  if (w.def.sleeping && !def.sleeping) {
    for (std::uint32_t i = 0; i < w.bodies.records.size(); ++i) w.wake(i);
  }
  w.def = def;
}

BodyId World::createBody(const BodyDef& def) {
  const std::string who = def.name.empty() ? std::string("body") : "body \"" + def.name + "\"";
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
  if (def.shape.type() == ShapeType::Plane && def.type != BodyType::Static) {
    fail("shape: a plane is an infinite half-space and can only be on a static body");
  }
  if (def.type != BodyType::Static && def.sensor == false && def.shape.type() == ShapeType::Mesh &&
      def.type == BodyType::Dynamic && !def.shape.mesh().isClosed()) {
    fail("shape: an open triangle mesh has no mass; make the body static or kinematic");
  }
  if (def.particle) {
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
  if (def.type == BodyType::Dynamic) {
    if (def.mass && (!isFinite(*def.mass) || *def.mass <= 0.0f)) {
      fail("mass must be finite and > 0, got " + formatFloat(*def.mass));
    }
    if (!def.mass && (!isFinite(def.density) || def.density <= 0.0f)) {
      fail("density must be finite and > 0, got " + formatFloat(def.density));
    }
  }

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
  BodyState& s = w.bodies.states[index];
  r.shape = def.shape;
  r.name = def.name;
  r.userData = def.userData;
  r.type = def.type;
  r.scale = def.scale;
  r.bounciness = def.bounciness;
  r.friction = def.friction;
  r.layer = def.layer;
  r.mask = def.mask;
  r.sensor = def.sensor;
  r.particle = def.particle;
  r.ccd = def.ccd && !def.sensor;
  try {
    if (def.type == BodyType::Dynamic) {
      MassProperties props = massProperties(def.shape, def.mass ? 1.0f : def.density, def.scale);
      float massScale = 1.0f;
      if (def.mass) massScale = *def.mass / props.mass;
      r.mass = props.mass * massScale;
      r.localCenterOfMass = props.centerOfMass;
      // A particle is a point mass: zero inverse inertia, so no impulse ever turns it.
      if (!def.particle) {
        r.inertiaLocal = props.inertia * massScale;
        r.inverseInertiaLocal = glm::inverse(r.inertiaLocal);
        r.isotropicInertia = detail::isIsotropic(r.inertiaLocal);
      }
      s.inverseMass = 1.0f / r.mass;
      // Every number of the shape was valid, yet its mass may not be representable: a 1e30 m box
      // weighs infinitely much, a 1e-20 m one nothing (an infinite inverse mass).
      if (!(std::isfinite(r.mass) && r.mass > 0.0f && std::isfinite(s.inverseMass) &&
            isFinite(r.localCenterOfMass) && isFinite(r.inverseInertiaLocal))) {
        throw Error("mass properties not representable in float (mass " + formatFloat(r.mass) +
                    "): the shape is too large or too small at this scale");
      }
    }
    if (def.type != BodyType::Static) {
      const Vec3 half = localBounds(def.shape).halfExtents() * def.scale;
      r.minExtent = std::min({half.x, half.y, half.z});
      const BoundingSphere sphere = localBoundingSphere(def.shape);
      r.boundingRadius =
          glm::length(sphere.center * def.scale - r.localCenterOfMass) + sphere.radius * def.scale;
    }
    const BoundingSphere sphere = localBoundingSphere(def.shape);
    r.originRadius = (glm::length(sphere.center) + sphere.radius) * def.scale;
  } catch (const Error& e) {
    fail(std::string("shape: ") + e.what());
  }
  s.rotation = glm::normalize(def.rotation);
  s.centerOfMass = def.position + s.rotation * r.localCenterOfMass;
  s.centerOfMass0 = s.centerOfMass;
  s.rotation0 = s.rotation;
  if (def.type != BodyType::Static) {
    s.linearVelocity = def.linearVelocity;
    s.angularVelocity = def.angularVelocity;
  }
  s.inverseInertiaWorld = detail::worldInverseInertia(r.inverseInertiaLocal, s.rotation);

  // Refused before the broad phase sees it: a shape whose box at this place is not representable
  // (or whose parts cannot be placed: a compound's child scales can multiply down to zero).
  Aabb bounds;
  try {
    bounds = worldBounds(r.shape, detail::bodyTransform(r, s));
  } catch (const Error& e) {
    fail(std::string("shape: ") + e.what());
  }
  if (!isFinite(bounds.min) || !isFinite(bounds.max) || !std::isfinite(r.boundingRadius)) {
    fail("shape: its bounds are not finite at this position and scale (min " + formatVec(bounds.min) +
         ", max " + formatVec(bounds.max) + "): the shape is too large");
  }
  ProxyDef proxy;
  proxy.bounds = w.proxyBounds(index, 0.0f);
  proxy.motion = def.type == BodyType::Static ? MotionType::Static : MotionType::Movable;
  proxy.userValue = index;
  proxy.layer = def.layer;
  try {
    r.proxy = w.broadPhase->add(proxy);
  } catch (const Error& e) {
    fail(e.what());
  }
  slot.keep = true;
  return w.idOf(index);
}

void World::destroyBody(BodyId id) {
  Impl& w = *impl_;
  const std::uint32_t index = w.resolve(id, "destroyBody");
  w.broadPhase->remove(w.bodies.records[index].proxy);
  for (std::uint32_t j = 0; j < w.joints.size(); ++j) {
    if (w.joints[j].alive && (w.joints[j].bodyA == index || w.joints[j].bodyB == index)) {
      w.wake(w.joints[j].bodyA == index ? w.joints[j].bodyB : w.joints[j].bodyA);
      w.freeJoint(j);
    }
  }
  w.wake(index);
  // Its contacts go with it: touching ones end now, reported with the next step's events (the
  // step's event lists are "what happened in the last step", so they are not changed in between).
  for (const Contact& c : w.contacts) {
    if (c.bodyA != index && c.bodyB != index) continue;
    w.wake(c.bodyA == index ? c.bodyB : c.bodyA);  // what rested on it must fall
    if (!c.touching) continue;
    if (c.sensor) {
      const bool aIsSensor = w.bodies.records[c.bodyA].sensor;
      w.pendingSensorEvents.push_back({SensorEvent::Type::End, w.idOf(aIsSensor ? c.bodyA : c.bodyB),
                                       w.idOf(aIsSensor ? c.bodyB : c.bodyA)});
    } else {
      w.pendingContactEvents.push_back(w.makeEvent(c, ContactEvent::Type::End));
    }
  }
  std::erase_if(w.contacts, [&](const Contact& c) { return c.bodyA == index || c.bodyB == index; });
  w.bodies.free(index);
}

bool World::isValid(BodyId id) const {
  return id.index < impl_->bodies.records.size() && impl_->bodies.records[id.index].alive &&
         impl_->bodies.records[id.index].generation == id.generation;
}
std::size_t World::bodyCount() const { return impl_->bodies.aliveCount; }

BodyType World::type(BodyId id) const { return impl_->bodies.records[impl_->resolve(id, "type")].type; }
bool World::isParticle(BodyId id) const {
  return impl_->bodies.records[impl_->resolve(id, "isParticle")].particle;
}

Transform World::transform(BodyId id) const {
  const std::uint32_t i = impl_->resolve(id, "transform");
  return detail::bodyTransform(impl_->bodies.records[i], impl_->bodies.states[i]);
}

void World::setTransform(BodyId id, const Vec3& position, const Quat& rotation) {
  Impl& w = *impl_;
  const std::uint32_t i = w.resolve(id, "setTransform");
  if (!isFinite(position))
    throw Error("world: setTransform: position must be finite, got " + formatVec(position));
  if (!isFinite(rotation) || std::abs(glm::length(rotation) - 1.0f) > 1e-3f) {
    throw Error("world: setTransform: rotation must be a finite unit quaternion");
  }
  BodyRecord& r = w.bodies.records[i];
  BodyState& s = w.bodies.states[i];
  s.rotation = glm::normalize(rotation);
  s.centerOfMass = position + s.rotation * r.localCenterOfMass;
  s.inverseInertiaWorld = detail::worldInverseInertia(r.inverseInertiaLocal, s.rotation);
  w.broadPhase->update(r.proxy, w.proxyBounds(i, 0.0f));
  w.wakeByUser(i);
}

Vec3 World::linearVelocity(BodyId id) const {
  return impl_->bodies.states[impl_->resolve(id, "linearVelocity")].linearVelocity;
}
Vec3 World::angularVelocity(BodyId id) const {
  return impl_->bodies.states[impl_->resolve(id, "angularVelocity")].angularVelocity;
}

void World::setLinearVelocity(BodyId id, const Vec3& velocity) {
  const std::uint32_t i = impl_->resolve(id, "setLinearVelocity");
  if (!isFinite(velocity))
    throw Error("world: setLinearVelocity: velocity must be finite, got " + formatVec(velocity));
  if (impl_->bodies.records[i].type == BodyType::Static) return;  // static bodies never move
  impl_->wakeByUser(i);
  impl_->bodies.states[i].linearVelocity = velocity;
}

void World::setAngularVelocity(BodyId id, const Vec3& velocity) {
  const std::uint32_t i = impl_->resolve(id, "setAngularVelocity");
  if (!isFinite(velocity))
    throw Error("world: setAngularVelocity: velocity must be finite, got " + formatVec(velocity));
  if (impl_->bodies.records[i].type == BodyType::Static) return;
  if (impl_->bodies.records[i].particle) {
    if (velocity != Vec3(0.0f))
      throw Error("world: setAngularVelocity: a particle has no angular velocity, got " +
                  formatVec(velocity));
    return;
  }
  impl_->wakeByUser(i);
  impl_->bodies.states[i].angularVelocity = velocity;
}

void World::applyImpulse(BodyId id, const Vec3& impulse, const Vec3& worldPoint) {
  const std::uint32_t i = impl_->resolve(id, "applyImpulse");
  if (!isFinite(impulse) || !isFinite(worldPoint))
    throw Error("world: applyImpulse: impulse and point must be finite");
  if (impl_->bodies.records[i].type != BodyType::Dynamic) return;
  impl_->wake(i);
  BodyState& s = impl_->bodies.states[i];
  s.linearVelocity += s.inverseMass * impulse;
  s.angularVelocity += s.inverseInertiaWorld * glm::cross(worldPoint - s.centerOfMass, impulse);
}

void World::applyForce(BodyId id, const Vec3& force, const Vec3& worldPoint) {
  const std::uint32_t i = impl_->resolve(id, "applyForce");
  if (!isFinite(force) || !isFinite(worldPoint))
    throw Error("world: applyForce: force and point must be finite");
  BodyRecord& r = impl_->bodies.records[i];
  if (r.type != BodyType::Dynamic) return;
  impl_->wake(i);
  r.force += force;
  if (!r.particle) r.torque += glm::cross(worldPoint - impl_->bodies.states[i].centerOfMass, force);
}

void World::applyTorque(BodyId id, const Vec3& torque) {
  const std::uint32_t i = impl_->resolve(id, "applyTorque");
  if (!isFinite(torque)) throw Error("world: applyTorque: torque must be finite, got " + formatVec(torque));
  if (impl_->bodies.records[i].type != BodyType::Dynamic || impl_->bodies.records[i].particle) return;
  impl_->wake(i);
  impl_->bodies.records[i].torque += torque;
}

bool World::isAwake(BodyId id) const {
  const std::uint32_t i = impl_->resolve(id, "isAwake");
  const BodyRecord& r = impl_->bodies.records[i];
  return r.type != BodyType::Static && r.awake;
}

void World::wakeBody(BodyId id) { impl_->wakeByUser(impl_->resolve(id, "wakeBody")); }

float World::mass(BodyId id) const { return impl_->bodies.records[impl_->resolve(id, "mass")].mass; }
Vec3 World::centerOfMass(BodyId id) const {
  return impl_->bodies.states[impl_->resolve(id, "centerOfMass")].centerOfMass;
}
const Shape& World::shape(BodyId id) const {
  return impl_->bodies.records[impl_->resolve(id, "shape")].shape;
}
std::uint64_t World::userData(BodyId id) const {
  return impl_->bodies.records[impl_->resolve(id, "userData")].userData;
}
const std::string& World::name(BodyId id) const {
  return impl_->bodies.records[impl_->resolve(id, "name")].name;
}

JointId World::createDistanceConstraint(const DistanceConstraintDef& def) {
  Impl& w = *impl_;
  const auto fail = [](const std::string& message) { throw Error("distance constraint: " + message); };
  if (!isValid(def.a)) fail("a: invalid or stale body id (index " + std::to_string(def.a.index) + ")");
  if (!isValid(def.b)) fail("b: invalid or stale body id (index " + std::to_string(def.b.index) + ")");
  if (def.a == def.b) fail("a and b are the same body (index " + std::to_string(def.a.index) + ")");
  const BodyRecord& ra = w.bodies.records[def.a.index];
  const BodyRecord& rb = w.bodies.records[def.b.index];
  if (ra.type != BodyType::Dynamic && rb.type != BodyType::Dynamic) {
    fail("a and b: at least one body must be dynamic, got " + std::string(toString(ra.type)) + " and " +
         std::string(toString(rb.type)));
  }
  const auto localAnchor = [&](const std::optional<Vec3>& anchor, const BodyRecord& r, const char* field) {
    if (!anchor) return Vec3(0.0f);
    if (!isFinite(*anchor)) fail(std::string(field) + " must be finite, got " + formatVec(*anchor));
    if (r.particle && *anchor != Vec3(0.0f)) {
      fail(std::string(field) + ": a particle's anchor must be its centre (0, 0, 0), got " +
           formatVec(*anchor));
    }
    return r.scale * *anchor - r.localCenterOfMass;
  };
  DistanceJoint joint;
  joint.bodyA = def.a.index;
  joint.bodyB = def.b.index;
  joint.localAnchorA = localAnchor(def.localAnchorA, ra, "localAnchorA");
  joint.localAnchorB = localAnchor(def.localAnchorB, rb, "localAnchorB");
  const Vec3 d =
      w.anchorWorld(joint.bodyB, joint.localAnchorB) - w.anchorWorld(joint.bodyA, joint.localAnchorA);
  joint.length = glm::length(d);
  if (def.length) {
    if (!isFinite(*def.length) || *def.length < 0.0f)
      fail("length must be finite and >= 0, got " + formatFloat(*def.length));
    joint.length = *def.length;
  }
  if (!isFinite(def.compliance) || def.compliance < 0.0f)
    fail("compliance must be finite and >= 0, got " + formatFloat(def.compliance));
  if (!isFinite(def.dampingRatio) || def.dampingRatio < 0.0f)
    fail("dampingRatio must be finite and >= 0, got " + formatFloat(def.dampingRatio));
  joint.compliance = def.compliance;
  joint.dampingRatio = def.dampingRatio;
  if (glm::length(d) > 1e-6f) joint.axis = d / glm::length(d);
  joint.alive = true;

  std::uint32_t index;
  if (!w.freeJoints.empty()) {
    index = w.freeJoints.back();
    w.freeJoints.pop_back();
    joint.generation = w.joints[index].generation;
    w.joints[index] = joint;
  } else {
    index = static_cast<std::uint32_t>(w.joints.size());
    w.joints.push_back(joint);
  }
  ++w.jointCount;
  w.wake(joint.bodyA);
  w.wake(joint.bodyB);
  return {index, w.joints[index].generation};
}

void World::destroyConstraint(JointId id) {
  Impl& w = *impl_;
  const std::uint32_t index = w.resolve(id, "destroyConstraint");
  w.wake(w.joints[index].bodyA);
  w.wake(w.joints[index].bodyB);
  w.freeJoint(index);
}

bool World::isValid(JointId id) const {
  return id.index < impl_->joints.size() && impl_->joints[id.index].alive &&
         impl_->joints[id.index].generation == id.generation;
}
std::size_t World::constraintCount() const { return impl_->jointCount; }
float World::constraintLength(JointId id) const {
  return impl_->joints[impl_->resolve(id, "constraintLength")].length;
}
float World::constraintCurrentLength(JointId id) const {
  const DistanceJoint& j = impl_->joints[impl_->resolve(id, "constraintCurrentLength")];
  return glm::length(impl_->anchorWorld(j.bodyB, j.localAnchorB) -
                     impl_->anchorWorld(j.bodyA, j.localAnchorA));
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

void World::step(float dt) {
  if (!isFinite(dt) || dt <= 0.0f)
    throw Error("world: step: dt must be finite and > 0, got " + formatFloat(dt));
  impl_->callbackError.clear();
  impl_->step(dt);
  if (!impl_->callbackError.empty()) throw Error(impl_->callbackError);
}

void World::Impl::step(float dt) {
  contactEvents.assign(pendingContactEvents.begin(), pendingContactEvents.end());
  sensorEvents.assign(pendingSensorEvents.begin(), pendingSensorEvents.end());
  pendingContactEvents.clear();
  pendingSensorEvents.clear();
  faultEvents.clear();
  // Each body's verdict (is its proxy updated; is its box grown by how far it moved, or computed
  // anew) is taken once, kBodiesAhead places ahead, where a box to compute anew has its shape's data
  // asked for (the hull there, its arrays half-way: prefetchShapeHeader), and kept in a ring until
  // the body's turn. A box costs less than a pair, so this looks twice as far as the pair loop.
  struct BoxVerdict {
    bool updated = false;
    bool reusable = false;
    float moved = 0.0f;
  };
  constexpr std::uint32_t kBodiesAhead = 4 * kPrefetchAhead;
  std::array<BoxVerdict, kBodiesAhead> verdicts;
  const auto bodyCount = static_cast<std::uint32_t>(bodies.records.size());
  const auto judge = [&](std::uint32_t i) {
    const BodyRecord& r = bodies.records[i];
    BoxVerdict v;
    v.updated = r.alive && r.type != BodyType::Static && r.awake;
    if (v.updated) v.reusable = boundsReusable(i, v.moved);
    if (v.updated && !v.reusable) detail::prefetchShapeHeader(r.shape);
    verdicts[i % kBodiesAhead] = v;
  };
  for (std::uint32_t i = 0; i < std::min(kBodiesAhead, bodyCount); ++i) judge(i);
  for (std::uint32_t i = 0; i < bodyCount; ++i) {
    const BoxVerdict v = verdicts[i % kBodiesAhead];
    if (i + kBodiesAhead < bodyCount) judge(i + kBodiesAhead);
    if (const std::uint32_t half = i + kBodiesAhead / 2; half < bodyCount) {
      const BoxVerdict& w = verdicts[half % kBodiesAhead];
      if (w.updated && !w.reusable) detail::prefetchShapeArrays(bodies.records[half].shape);
    }
    if (!v.updated) continue;
    const Aabb box = v.reusable ? bodies.records[i].bounds.expanded(v.moved) : recomputeBounds(i);
    broadPhase->update(bodies.records[i].proxy, grownForStep(i, dt, box));
  }
  broadPhase->findPairs(pairs);
  if (def.sleeping) wakeTouchedIslands(dt);
  narrowPhase(dt);

  solve(dt);
  if (def.impactModel == ImpactModel::Interpolated) {
    detail::applyInterpolatedImpacts(bodies, contacts, stepSolver.solvedContacts(),
                                     def.contact.restitutionThreshold, def.contact.linearSlop);
  }
  detail::applyProlongedFriction(bodies, contacts, stepSolver.solvedContacts(), def.frictionModel, dt);
  for (BodyRecord& r : bodies.records) {
    r.force = Vec3(0.0f);
    r.torque = Vec3(0.0f);
  }
  if (def.ccd) detail::solveContinuous(bodies, *broadPhase, def.contact.linearSlop);
  if (def.penetrationResponse == PenetrationResponse::Revert) revertPenetrating();
  detail::guardFiniteStates(bodies, faultEvents);
  if (!faultEvents.empty()) detail::dropFaultedContacts(faultEvents, contacts, joints);
  refreshEscapedProxies();
  emitEvents();
  if (def.sleeping) updateSleep(dt);

  totalStats.proxies = lastStats.proxies;
  totalStats.potentialPairs += lastStats.potentialPairs;
  totalStats.keptPairs += lastStats.keptPairs;
  totalStats.boxTests += lastStats.boxTests;
  totalStats.narrowPhaseTests += lastStats.narrowPhaseTests;
  totalStats.reusedManifolds += lastStats.reusedManifolds;
  totalStats.contactPairs += lastStats.contactPairs;
}

// The soft step (src/dynamics/solver.h): the substep loop over the awake bodies, contacts and joints.
void World::Impl::solve(float dt) {
  detail::StepSettings settings;
  settings.gravity = def.gravity;
  settings.substeps = def.substeps;
  settings.relaxPasses = def.contact.relaxPasses;
  settings.tuning = def.contact;
  // Viscous and damping friction replace the solver's Coulomb friction (applied after the solve).
  settings.friction = def.frictionModel == FrictionModel::Coulomb;
  stepSolver.solve(bodies, contacts, joints, settings, dt, faultEvents);
}

ContactEvent World::Impl::makeEvent(const Contact& c, ContactEvent::Type type) const {
  ContactEvent e;
  e.type = type;
  e.a = idOf(c.bodyA);
  e.b = idOf(c.bodyB);
  e.normal = c.manifold.normal;
  int deepest = 0;
  for (int i = 0; i < c.manifold.count; ++i) {
    if (c.manifold.points[i].depth > c.manifold.points[deepest].depth) deepest = i;
    e.impulse += c.points[i].totalNormalImpulse;
    e.speed = std::max(e.speed, -c.points[i].relativeVelocity);
  }
  if (c.manifold.count > 0) e.point = c.manifold.points[deepest].midpoint();
  if (type == ContactEvent::Type::End) e.impulse = 0.0f;
  return e;
}

void World::Impl::narrowPhase(float dt) {
  poses.resize(bodies.records.size());
  scaledRotations.resize(bodies.records.size());
  spinReaches.resize(bodies.records.size());
  velocities.resize(bodies.records.size());
  likelyPlaced.assign(bodies.records.size(), 0);
  for (std::uint32_t i = 0; i < bodies.records.size(); ++i) {
    if (!bodies.records[i].alive) continue;
    poses[i] = detail::bodyTransform(bodies.records[i], bodies.states[i]);
    scaledRotations[i] = glm::mat3_cast(poses[i].rotation) * poses[i].scale;
    spinReaches[i] = spinReach(i);
    velocities[i] = bodies.states[i].linearVelocity;
    // A body that moves this step by more than the manifold cache's tolerance will likely have its
    // pairs computed, not reused: the pair loop asks ahead for such bodies' shape data.
    const float motion = dt * (glm::length(velocities[i]) + spinReaches[i]);
    likelyPlaced[i] = motion > def.contact.manifoldCacheDistance;
  }
  std::swap(contacts, previousContacts);
  contacts.clear();
  lastStats = broadPhase->lastStats();
  std::uint64_t tests = 0;
  std::uint64_t reused = 0;
  std::size_t j = 0;
  const auto endVanished = [&](const Contact& old) {
    // Contacts of destroyed bodies were erased; a generation mismatch means the slot was reused.
    if (!old.touching || !bodies.records[old.bodyA].alive || !bodies.records[old.bodyB].alive) return;
    if (bodies.records[old.bodyA].generation != old.generationA ||
        bodies.records[old.bodyB].generation != old.generationB)
      return;
    if (old.sensor) {
      const bool aIsSensor = bodies.records[old.bodyA].sensor;
      sensorEvents.push_back({SensorEvent::Type::End, idOf(aIsSensor ? old.bodyA : old.bodyB),
                              idOf(aIsSensor ? old.bodyB : old.bodyA)});
    } else {
      contactEvents.push_back(makeEvent(old, ContactEvent::Type::End));
    }
  };

  // Each proxy's body (its user value), copied once per step into a compact array that the pair
  // loop and its prefetching read twice a pair, instead of the broad phase's 48-byte records.
  const auto& proxies = broadPhase->records();
  proxyBodies.resize(proxies.size());
  for (std::size_t k = 0; k < proxies.size(); ++k)
    proxyBodies[k] = static_cast<std::uint32_t>(proxies[k].userValue);
  const auto bodyOf = [&](ProxyId proxy) { return proxyBodies[proxy.index]; };
  // The record's shape is the first step of the chain: asked for before the shape's own data.
  const auto prefetchRecordShape = [](const Shape& shape) { detail::prefetchLine(&shape); };
  const auto prefetchPairShapes = [&](std::size_t p, void (*prefetch)(const Shape&)) {
    if (p >= pairs.size()) return;
    const std::uint32_t a = bodyOf(pairs[p].a), b = bodyOf(pairs[p].b);
    if (!likelyPlaced[a] && !likelyPlaced[b]) return;
    prefetch(bodies.records[a].shape);
    prefetch(bodies.records[b].shape);
  };
  // Last step's contacts are read, and this step's written, in order, 496 bytes each: both asked
  // for a few contacts ahead (the stride is too long for the hardware to follow it in time).
  constexpr std::size_t kContactsAhead = 4;

  for (std::size_t p = 0; p < pairs.size(); ++p) {
    const ProxyPair& pair = pairs[p];
    if (j + kContactsAhead < previousContacts.size())
      detail::prefetchBytes(&previousContacts[j + kContactsAhead], sizeof(Contact));
    if (contacts.size() + kContactsAhead < contacts.capacity())
      detail::prefetchBytes(contacts.data() + contacts.size() + kContactsAhead, sizeof(Contact));
    // The shapes of the pairs a few places on that will likely be computed, not reused, asked for
    // in three stages: the bodies' records (where the shape is), the hulls, their arrays.
    prefetchPairShapes(p + 3 * kPrefetchAhead, prefetchRecordShape);
    prefetchPairShapes(p + 2 * kPrefetchAhead, detail::prefetchShapeHeader);
    prefetchPairShapes(p + kPrefetchAhead, detail::prefetchShapeArrays);
    const std::uint64_t key = detail::pairKey(pair.a.index, pair.b.index);
    while (j < previousContacts.size() && previousContacts[j].key < key) endVanished(previousContacts[j++]);
    const Contact* previous = nullptr;
    bool reusedManifold = false;

    const std::uint32_t ia = bodyOf(pair.a);
    const std::uint32_t ib = bodyOf(pair.b);
    const BodyRecord& ra = bodies.records[ia];
    const BodyRecord& rb = bodies.records[ib];
    if (j < previousContacts.size() && previousContacts[j].key == key) {
      const Contact& old = previousContacts[j++];
      if (old.bodyA == ia && old.bodyB == ib && old.generationA == ra.generation &&
          old.generationB == rb.generation)
        previous = &old;
    }
    // Only a dynamic body responds: kinematic-kinematic and kinematic-static pairs are never tested
    // (static-static never reaches us: the broad phase does not produce them).
    const bool sensor = ra.sensor || rb.sensor;
    if (ra.type != BodyType::Dynamic && rb.type != BodyType::Dynamic) continue;
    if ((ra.sensor && rb.sensor) || (ra.layer & rb.mask) == 0 || (rb.layer & ra.mask) == 0) {
      if (previous) endVanished(*previous);
      continue;
    }

    if (!isAwakeDynamic(ia) && !isAwakeDynamic(ib)) {
      // Sleeping against static, sleeping or still kinematic: nothing moves, so last step's contact
      // is kept as it was (touching state, impulses for the warm start on waking), unsolved.
      if (previous) {
        Contact& kept = contacts.emplace_back(*previous);
        kept.asleep = true;
        kept.wasTouching = kept.touching;
      }
      continue;
    }
    const Transform& ta = poses[ia];
    const Transform& tb = poses[ib];
    Contact& c = contacts.emplace_back();
    ++tests;
    // A pair that has not moved relative to itself since its manifold was computed (a resting
    // stack, a crate on the terrain) gets that manifold placed again (Jolt's body pair cache).
    const float margin =
        sensor ? 0.0f
               : speculativeMargin(velocities[ia], velocities[ib], spinReaches[ia], spinReaches[ib], dt);
    if (previous && !sensor &&
        detail::reuseManifold(previous->cache, previous->manifold, ta, tb, scaledRotations[ia],
                              scaledRotations[ib], ra.originRadius, rb.originRadius,
                              def.contact.manifoldCacheDistance, c.manifold)) {
      c.cache = previous->cache;
      reusedManifold = true;
      ++reused;
    } else if (glm::length(tb.position - ta.position) > ra.originRadius + rb.originRadius + margin) {
      // The bounding spheres are apart by more than the margin: the lecture's early reject with the
      // cheapest bounding volume, before the proxies' collider test.
      c.manifold.count = 0;
      if (!sensor && margin > 2.0f * def.contact.manifoldCacheDistance)
        detail::storeManifold(c.manifold, ta, tb, c.cache);
    } else if (previous && !sensor && previous->cache.hasAxis && previous->manifold.count == 0 &&
               separationAlong(ra.shape, ta, rb.shape, tb,
                               ta.applyToDirection(previous->cache.separatingAxis)) > margin) {
      // Still apart along the axis that separated them last time: two support points instead of the
      // separating-axis test (the broad phase's fat boxes keep many such pairs, e.g. neighbours in a
      // heap of hulls).
      c.manifold.count = 0;
      if (margin > 2.0f * def.contact.manifoldCacheDistance)
        detail::storeManifold(c.manifold, ta, tb, c.cache);
      c.cache.separatingAxis = previous->cache.separatingAxis;
      c.cache.hasAxis = true;
    } else {
      collide::collide(ra.shape, ta, rb.shape, tb, c.manifold, margin);
      // An empty manifold is cached only if the margin exceeds the cache's tolerance: a pair found
      // apart by more than the margin then cannot touch before it moves beyond the tolerance.
      if (!sensor && (c.manifold.count > 0 || margin > 2.0f * def.contact.manifoldCacheDistance))
        detail::storeManifold(c.manifold, ta, tb, c.cache);
      if (!sensor && c.manifold.count == 0 && separatingAxisPays(ra.shape, rb.shape)) {
        const DistanceResult apart = collide::distance(ra.shape, ta, rb.shape, tb);
        if (!apart.overlapping && apart.distance > margin) {
          c.cache.separatingAxis = ta.inverseApplyToDirection(apart.normal);
          c.cache.hasAxis = true;
        }
      }
    }
    if (c.manifold.count == 0) {
      if (previous) endVanished(*previous);
      if (!c.cache.valid) {
        contacts.pop_back();
        continue;
      }
      // Kept empty, so that next step can take the same "apart" while the pair does not move. It
      // has no points: the solver, the events and the islands pass it by. Only its manifold and
      // cache were written since it was made, and the cache is what it is kept for.
      c.manifold = Manifold{};
      c.key = key;
      c.bodyA = ia;
      c.bodyB = ib;
      c.generationA = ra.generation;
      c.generationB = rb.generation;
      c.enabled = false;
      continue;
    }
    c.key = key;
    c.bodyA = ia;
    c.bodyB = ib;
    c.generationA = ra.generation;
    c.generationB = rb.generation;
    c.sensor = sensor;
    c.friction = combine(def.frictionCombine, ra.friction, rb.friction);
    c.restitution = combine(def.bouncinessCombine, ra.bounciness, rb.bounciness);
    c.impactBounciness = c.restitution;
    c.consecutiveSteps = previous ? previous->consecutiveSteps + 1 : 1;
    c.wasTouching = previous ? previous->touching : false;
    if (def.impactModel == ImpactModel::Interpolated) {
      // The lecture's impact replaces the solver's restitution, and its glued (inelastic) part
      // already handles the tangent, so the impact step gets no solver bounce and no Coulomb
      // friction (friction is for prolonged contacts, lecture slide 12). See contact_response.h.
      c.restitution = 0.0f;
      if (!c.wasTouching) c.friction = 0.0f;
    }
    if (previous) {
      detail::inheritContact(*previous, c, def.contact.linearSlop, reusedManifold);
    } else {
      c.points = {};
    }
    c.enabled = true;
    if (!sensor && preSolve) {
      ContactSettings settings{c.friction, c.impactBounciness, Vec3(0.0f)};
      c.enabled = preSolve(idOf(ia), idOf(ib), c.manifold, settings);
      // A NaN friction would reach every body the contact touches: bad settings are refused (the
      // contact keeps the world's values), the step completes, and then step() reports them.
      if (!isFinite(settings.friction) || settings.friction < 0.0f || !isFinite(settings.bounciness) ||
          settings.bounciness < 0.0f || settings.bounciness > 1.0f || !isFinite(settings.surfaceVelocity)) {
        if (callbackError.empty()) {
          callbackError =
              "world: step: the pre-solve callback set contact settings out of range for bodies " +
              std::to_string(ia) + " and " + std::to_string(ib) + " (friction " +
              formatFloat(settings.friction) + ", bounciness " + formatFloat(settings.bounciness) +
              ", surfaceVelocity " + formatVec(settings.surfaceVelocity) +
              "); the contact kept its own values";
        }
        settings = ContactSettings{c.friction, c.impactBounciness, Vec3(0.0f)};
      }
      c.friction = settings.friction;
      c.impactBounciness = settings.bounciness;
      if (def.impactModel != ImpactModel::Interpolated) c.restitution = settings.bounciness;
      c.surfaceVelocity = settings.surfaceVelocity -
                          glm::dot(settings.surfaceVelocity, c.manifold.normal) * c.manifold.normal;
    }
    const float deepest = c.manifold.maxDepth();
    c.touching = c.enabled && (sensor ? deepest >= 0.0f : deepest >= -def.contact.linearSlop);
    if (!c.enabled) c.points = {};
  }
  while (j < previousContacts.size()) endVanished(previousContacts[j++]);
  lastStats.narrowPhaseTests = tests;
  lastStats.reusedManifolds = reused;
}

// Speculative margin: the gap this pair can close within the step (Catto, GDC 2013).
float World::Impl::speculativeMargin(std::uint32_t ia, std::uint32_t ib, float dt) const {
  return speculativeMargin(bodies.states[ia].linearVelocity, bodies.states[ib].linearVelocity, spinReach(ia),
                           spinReach(ib), dt);
}

float World::Impl::spinReach(std::uint32_t index) const {
  return glm::length(bodies.states[index].angularVelocity) * bodies.records[index].boundingRadius;
}

float World::Impl::speculativeMargin(const Vec3& velocityA, const Vec3& velocityB, float spinA, float spinB,
                                     float dt) const {
  const float approach = glm::length(velocityB - velocityA) + spinA + spinB;
  const float margin = def.contact.speculativeDistance + dt * approach;
  // A finite velocity can still have an infinite length (beyond 1.8e19 m/s the square overflows):
  // capped at the largest float (NaN too), so that collide() takes the margin and the step goes
  // on; the fault guard contains what such a body then does.
  constexpr float kMaxMargin = std::numeric_limits<float>::max();
  return margin < kMaxMargin ? margin : kMaxMargin;
}

// Before the narrow phase: an awake dynamic or moving kinematic body that may reach a sleeping
// one within this step (its speculative manifold has points) wakes the sleeper's island, so the
// island takes part in this step's solve instead of being run into. Repeated until no island
// wakes, because a woken island can reach the next one. Only pairs on the border of a sleeping
// island are tested here.
void World::Impl::wakeTouchedIslands(float dt) {
  bool woke = true;
  while (woke) {
    woke = false;
    for (const ProxyPair& pair : pairs) {
      const auto ia = static_cast<std::uint32_t>(broadPhase->records()[pair.a.index].userValue);
      const auto ib = static_cast<std::uint32_t>(broadPhase->records()[pair.b.index].userValue);
      const bool sleepA = isSleeping(ia);
      const bool sleepB = isSleeping(ib);
      if (sleepA == sleepB) continue;
      const std::uint32_t mover = sleepA ? ib : ia;
      if (!isAwakeDynamic(mover) && !isMovingKinematic(mover)) continue;
      const BodyRecord& ra = bodies.records[ia];
      const BodyRecord& rb = bodies.records[ib];
      if (ra.sensor || rb.sensor || (ra.layer & rb.mask) == 0 || (rb.layer & ra.mask) == 0) continue;
      Manifold manifold;
      collide::collide(ra.shape, detail::bodyTransform(ra, bodies.states[ia]), rb.shape,
                       detail::bodyTransform(rb, bodies.states[ib]), manifold, speculativeMargin(ia, ib, dt));
      if (manifold.count == 0) continue;
      // Only what actually woke repeats the pass: a frozen body touched by a mover never wakes, and
      // counting it would repeat the pass forever.
      if (wake(sleepA ? ia : ib)) woke = true;
    }
  }
}

// Islands (Box2D's union-find over touching contacts and joints) of the awake dynamic bodies, then
// the rest timers: a body below both sleep speeds accumulates rest time, and an island whose every
// body has rested for timeToSleep falls asleep as a whole, velocities zeroed. Static bodies do not
// join islands (a floor would join every pile on it); a moving kinematic body keeps what it touches
// awake.
void World::Impl::updateSleep(float dt) {
  const auto n = static_cast<std::uint32_t>(bodies.records.size());
  islandParent.resize(n);
  islandSleepTime.assign(n, std::numeric_limits<float>::infinity());
  for (std::uint32_t i = 0; i < n; ++i) islandParent[i] = i;
  const auto link = [&](std::uint32_t a, std::uint32_t b) {
    if (isAwakeDynamic(a) && isAwakeDynamic(b)) unite(a, b);
    // -dt: the timer below then restarts from 0 whatever the body's own speed.
    if (isAwakeDynamic(a) && isMovingKinematic(b)) bodies.records[a].sleepTime = -dt;
    if (isAwakeDynamic(b) && isMovingKinematic(a)) bodies.records[b].sleepTime = -dt;
  };
  for (const Contact& c : contacts) {
    if (!c.sensor && c.touching && !c.asleep) link(c.bodyA, c.bodyB);
  }
  for (const DistanceJoint& joint : joints) {
    if (joint.alive) link(joint.bodyA, joint.bodyB);
  }
  const SleepTuning& tuning = def.sleep;
  for (std::uint32_t i = 0; i < n; ++i) {
    if (!isAwakeDynamic(i)) continue;
    BodyRecord& r = bodies.records[i];
    const BodyState& s = bodies.states[i];
    const bool resting = glm::length(s.linearVelocity) <= tuning.linearSpeed &&
                         glm::length(s.angularVelocity) <= tuning.angularSpeed;
    r.sleepTime = resting ? r.sleepTime + dt : 0.0f;
    float& islandTime = islandSleepTime[findRoot(i)];
    islandTime = std::min(islandTime, r.sleepTime);
  }
  for (std::uint32_t i = 0; i < n; ++i) {
    if (!isAwakeDynamic(i)) continue;
    const std::uint32_t root = findRoot(i);
    if (islandSleepTime[root] < tuning.timeToSleep) continue;
    BodyRecord& r = bodies.records[i];
    BodyState& s = bodies.states[i];
    r.awake = false;
    r.island = root;
    s.linearVelocity = Vec3(0.0f);
    s.angularVelocity = Vec3(0.0f);
  }
}

void World::Impl::revertPenetrating() {
  // Simple version of the lecture's "revert": one re-test per solved contact at the new poses.
  for (const std::uint32_t index : stepSolver.solvedContacts()) {
    const Contact& c = contacts[index];
    BodyRecord& ra = bodies.records[c.bodyA];
    BodyRecord& rb = bodies.records[c.bodyB];
    BodyState& sa = bodies.states[c.bodyA];
    BodyState& sb = bodies.states[c.bodyB];
    Manifold now;
    if (!collide::collide(ra.shape, detail::bodyTransform(ra, sa), rb.shape, detail::bodyTransform(rb, sb),
                          now))
      continue;
    if (now.maxDepth() <= def.contact.linearSlop) continue;
    const Vec3 n = now.normal;
    if (ra.type == BodyType::Dynamic && !ra.faulted) {
      sa.centerOfMass = sa.centerOfMass0;
      sa.rotation = sa.rotation0;
      sa.inverseInertiaWorld = detail::worldInverseInertia(ra.inverseInertiaLocal, sa.rotation);
      sa.linearVelocity -= std::max(0.0f, glm::dot(sa.linearVelocity, n)) * n;  // A moving into B
    }
    if (rb.type == BodyType::Dynamic && !rb.faulted) {
      sb.centerOfMass = sb.centerOfMass0;
      sb.rotation = sb.rotation0;
      sb.inverseInertiaWorld = detail::worldInverseInertia(rb.inverseInertiaLocal, sb.rotation);
      sb.linearVelocity -= std::min(0.0f, glm::dot(sb.linearVelocity, n)) * n;  // B moving into A
    }
  }
}

// The proxies were grown by the motion the step predicted; an impulse (a hit, a constraint) can
// carry a body out of its box. Queries between steps (castRay) read these boxes, so a body that
// escaped gets a box where it is now. The next step updates every awake body's box anyway, so the
// pairs it finds do not depend on this.
void World::Impl::refreshEscapedProxies() {
  for (std::uint32_t i = 0; i < bodies.records.size(); ++i) {
    const BodyRecord& r = bodies.records[i];
    if (!r.alive || r.type == BodyType::Static || !r.awake) continue;
    // The step's box was grown by at least the speculative distance all round: a body whose points
    // moved less than that since the step began is still inside it.
    const BodyState& s = bodies.states[i];
    if (pointMotionBound(r, s.centerOfMass0, s.rotation0, s.centerOfMass, s.rotation) <
        def.contact.speculativeDistance)
      continue;
    const Aabb now = currentBounds(i);
    if (!broadPhase->bounds(r.proxy).contains(now)) broadPhase->update(r.proxy, proxyBounds(i, 0.0f));
  }
}

void World::Impl::emitEvents() {
  touchingCount = 0;
  for (Contact& c : contacts) {
    // A speculative contact that stopped the bodies this step touched them, though it was still
    // apart before the solve: count it, so the begin event carries the impact speed and impulse.
    if (!c.sensor && c.enabled && !c.touching) {
      for (int i = 0; i < c.manifold.count; ++i)
        c.touching = c.touching || c.points[i].maxNormalImpulse > 0.0f;
    }
    if (c.sensor) {
      if (c.touching != c.wasTouching) {
        const bool aIsSensor = bodies.records[c.bodyA].sensor;
        sensorEvents.push_back({c.touching ? SensorEvent::Type::Begin : SensorEvent::Type::End,
                                idOf(aIsSensor ? c.bodyA : c.bodyB), idOf(aIsSensor ? c.bodyB : c.bodyA)});
      }
      continue;
    }
    if (c.touching) ++touchingCount;
    if (c.touching && !c.wasTouching) contactEvents.push_back(makeEvent(c, ContactEvent::Type::Begin));
    if (c.touching && c.wasTouching && def.persistEvents && !c.asleep)
      contactEvents.push_back(makeEvent(c, ContactEvent::Type::Persist));
    if (!c.touching && c.wasTouching) contactEvents.push_back(makeEvent(c, ContactEvent::Type::End));
  }
  lastStats.contactPairs = touchingCount;
}

const BroadPhaseStats& World::lastStats() const { return impl_->lastStats; }
const BroadPhaseStats& World::totalStats() const { return impl_->totalStats; }
std::span<const ContactEvent> World::contactEvents() const { return impl_->contactEvents; }
std::span<const SensorEvent> World::sensorEvents() const { return impl_->sensorEvents; }
std::span<const FaultEvent> World::faultEvents() const { return impl_->faultEvents; }
std::size_t World::touchingContactCount() const { return impl_->touchingCount; }

std::optional<RayCastResult> World::castRay(const Ray& ray, LayerMask mask) const {
  const Impl& w = *impl_;
  if (!isFinite(ray.origin))
    throw Error("world: castRay: origin must be finite, got " + formatVec(ray.origin));
  const float length = glm::length(ray.direction);
  if (!isFinite(ray.direction) || !(length > 0.0f) || !std::isfinite(length)) {
    throw Error("world: castRay: direction must be finite and non-zero, got " + formatVec(ray.direction));
  }
  if (std::isnan(ray.maxDistance) || ray.maxDistance < 0.0f) {
    throw Error("world: castRay: maxDistance must be >= 0, got " + formatFloat(ray.maxDistance));
  }
  Ray unit = ray;
  unit.direction = ray.direction / length;
  std::optional<RayCastResult> best;
  std::uint32_t bestIndex = 0;
  // Each candidate's shape is cast over the whole ray (not clipped to the best so far), so that an
  // equal distance is seen and the tie goes to the lower index whatever order the boxes come in;
  // the broad phase still prunes every box entered beyond the best hit.
  w.broadPhase->rayCast(unit, mask, [&](ProxyId proxy, float) {
    const auto index = static_cast<std::uint32_t>(w.broadPhase->userValue(proxy));
    const BodyRecord& r = w.bodies.records[index];
    if (!r.sensor) {
      const std::optional<RayHit> hit =
          rayCast(r.shape, detail::bodyTransform(r, w.bodies.states[index]), unit);
      if (hit && (!best || hit->distance < best->distance ||
                  (hit->distance == best->distance && index < bestIndex))) {
        best = RayCastResult{w.idOf(index), hit->distance, hit->point, hit->normal, hit->subShape};
        bestIndex = index;
      }
    }
    return best ? best->distance : unit.maxDistance;
  });
  return best;
}

std::vector<BodyPair> World::broadPhasePairs() const {
  const Impl& w = *impl_;
  std::vector<BodyPair> out;
  out.reserve(w.pairs.size());
  for (const ProxyPair& pair : w.pairs) {
    if (!w.broadPhase->contains(pair.a) || !w.broadPhase->contains(pair.b)) continue;  // destroyed since
    out.push_back({w.idOf(static_cast<std::uint32_t>(w.broadPhase->userValue(pair.a))),
                   w.idOf(static_cast<std::uint32_t>(w.broadPhase->userValue(pair.b)))});
  }
  return out;
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
