// World fuzzer: a World with fuzzed settings, driven by a fuzzed sequence of API calls: create
// bodies (every shape type, static, kinematic and dynamic, particles, sensors, ccd), destroy them,
// set their transforms and velocities, apply forces, impulses and torques, wake them, create and
// destroy joints of every type and change their settings, and step with fuzzed dt. Ids are drawn from every
// id handed out so far, so destroyed (stale) ones are used too.
//
// Allowed: every call works or throws collide::Error. A finding: a crash, a sanitizer report,
// another exception, a step with a valid dt that throws, or, after a step, a body whose state is
// not finite without the world reporting it in faultEvents(), or (for input without extreme
// values, FuzzInput::sawExtreme) an event with non-finite values.
#include "fuzz_input.h"

#include <collide/world.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

using namespace collide;
using collide::fuzz::describe;
using collide::fuzz::FuzzInput;

// Bounds on one input's cost: the fuzzer should try many short stories, not a few long ones.
constexpr int kMaxCalls = 96;
constexpr int kMaxBodies = 24;
constexpr int kMaxSteps = 12;

WorldDef decodeWorldDef(FuzzInput& in) {
  WorldDef def;
  if (in.flag()) def.gravity = in.vec(-20.0f, 20.0f);
  def.substeps = 1 + in.choice(8);
  if (in.byte() >= 248) def.substeps = -in.choice(2);  // refused
  def.broadPhase.type = static_cast<BroadPhaseType>(in.choice(kBroadPhaseTypeCount));
  if (in.flag()) def.broadPhase.gridCellSize = in.value(0.0f, 4.0f);
  if (in.flag()) def.broadPhase.treeMargin = in.value(0.0f, 0.5f);
  def.bouncinessCombine = static_cast<CombineRule>(in.choice(4));
  def.frictionCombine = static_cast<CombineRule>(in.choice(4));
  def.impactModel = static_cast<ImpactModel>(in.choice(2));
  def.frictionModel = static_cast<FrictionModel>(in.choice(4));
  def.penetrationResponse = static_cast<PenetrationResponse>(in.choice(3));
  def.sleeping = in.flag();
  def.ccd = in.flag();
  if (in.byte() >= 240) {
    def.contact.hertz = in.value(1.0f, 200.0f);
    def.contact.dampingRatio = in.value(0.0f, 10.0f);
    def.contact.pushOutSpeed = in.value(0.1f, 10.0f);
    def.contact.linearSlop = in.value(0.0f, 0.05f);
    def.contact.speculativeDistance = in.value(0.0f, 0.1f);
  }
  return def;
}

// A part, now and then one no body can have (a plane, a negative density, a bad material).
PartDef decodePartDef(FuzzInput& in) {
  PartDef part;
  part.shape = collide::fuzz::decodeShape(in, /*allowPlane=*/in.byte() >= 248);
  part.position = in.vec(-1.5f, 1.5f);
  part.rotation = in.rotation();
  part.material = {in.range(0.0f, 1.0f), in.range(0.0f, 1.0f), 0.0f};
  if (in.byte() >= 240) part.material.friction = in.value(-1.0f, 2.0f);
  part.density = in.byte() >= 232 ? in.value(-10.0f, 10000.0f) : 1000.0f;
  part.sensor = in.byte() >= 232;
  if (in.byte() >= 224) {
    part.layer = in.byte();
    part.mask = in.byte();
    part.group = static_cast<std::int8_t>(in.byte());
  }
  return part;
}

BodyDef decodeBodyDef(FuzzInput& in) {
  BodyDef def;
  def.type = static_cast<BodyType>(in.choice(3));
  def.particle = def.type == BodyType::Dynamic && in.byte() >= 208;
  // A particle must be a sphere; now and then it is not, and the world must refuse it.
  def.shape = def.particle && in.byte() < 240 ? Shape(Sphere{in.value(0.05f, 1.0f)})
                                              : collide::fuzz::decodeShape(in, /*allowPlane=*/true);
  def.position = in.vec(-6.0f, 6.0f);
  def.rotation = in.rotation();
  if (in.byte() >= 224) def.scale = in.value(0.25f, 4.0f);
  if (in.flag()) def.linearVelocity = in.vec(-20.0f, 20.0f);
  if (!def.particle && in.flag()) def.angularVelocity = in.vec(-20.0f, 20.0f);
  if (in.byte() >= 192) def.mass = in.value(0.01f, 100.0f);
  if (in.byte() >= 224) def.density = in.value(1.0f, 10000.0f);
  def.bounciness = in.byte() >= 224 ? in.value(0.0f, 1.0f) : in.range(0.0f, 1.0f);
  def.friction = in.byte() >= 224 ? in.value(0.0f, 2.0f) : in.range(0.0f, 1.0f);
  if (in.byte() >= 224) {
    def.layer = in.byte();
    def.mask = in.byte();
  }
  def.sensor = in.byte() >= 224;
  def.ccd = in.flag();
  if (!def.particle && in.byte() >= 216) {
    const int count = 1 + in.choice(3);
    for (int k = 0; k < count; ++k) def.parts.push_back(decodePartDef(in));
  }
  return def;
}

std::string describe(BodyId id) {
  return "body(" + std::to_string(id.index) + ", " + std::to_string(id.generation) + ")";
}
std::string describe(JointId id) {
  return "joint(" + std::to_string(id.index) + ", " + std::to_string(id.generation) + ")";
}

std::string describe(const WorldDef& d) {
  return "WorldDef{gravity " + describe(d.gravity) + ", substeps " + std::to_string(d.substeps) +
         ", broad phase " + std::to_string(int(d.broadPhase.type)) + " (cell " +
         describe(d.broadPhase.gridCellSize) + ", margin " + describe(d.broadPhase.treeMargin) +
         "), combine " + std::to_string(int(d.bouncinessCombine)) + "/" +
         std::to_string(int(d.frictionCombine)) + ", impact " + std::to_string(int(d.impactModel)) +
         ", friction " + std::to_string(int(d.frictionModel)) + ", penetration " +
         std::to_string(int(d.penetrationResponse)) + ", sleeping " + std::to_string(d.sleeping) + ", ccd " +
         std::to_string(d.ccd) + ", contact hertz " + describe(d.contact.hertz) + " damping " +
         describe(d.contact.dampingRatio) + " pushOut " + describe(d.contact.pushOutSpeed) + " slop " +
         describe(d.contact.linearSlop) + " speculative " + describe(d.contact.speculativeDistance) + "}";
}

std::string describe(const BodyDef& d) {
  return "BodyDef{type " + std::string(toString(d.type)) + ", shape " + describe(d.shape) + ", position " +
         describe(d.position) + ", rotation " + describe(d.rotation) + ", scale " + describe(d.scale) +
         ", linearVelocity " + describe(d.linearVelocity) + ", angularVelocity " +
         describe(d.angularVelocity) + ", mass " + (d.mass ? describe(*d.mass) : std::string("unset")) +
         ", density " + describe(d.density) + ", bounciness " + describe(d.bounciness) + ", friction " +
         describe(d.friction) + ", layer " + std::to_string(d.layer) + ", mask " + std::to_string(d.mask) +
         ", sensor " + std::to_string(d.sensor) + ", particle " + std::to_string(d.particle) + ", ccd " +
         std::to_string(d.ccd) + ", parts " + std::to_string(d.parts.size()) + "}";
}

void trace(const std::string& line) {
  if (collide::fuzz::tracing()) std::fprintf(stderr, "%s\n", line.c_str());
}

struct Story {
  World& world;
  FuzzInput& in;
  std::vector<BodyId> bodies;  // every id handed out, stale ones included
  std::vector<JointId> joints;

  BodyId anyBody() {
    if (bodies.empty() || in.byte() >= 248) return BodyId{in.byte(), in.byte()};  // never handed out
    return bodies[in.choice(int(bodies.size()))];
  }
  JointId anyJoint() {
    if (joints.empty() || in.byte() >= 248) return JointId{in.byte(), in.byte()};
    return joints[in.choice(int(joints.size()))];
  }
  std::size_t live() const {
    return std::count_if(bodies.begin(), bodies.end(), [&](BodyId id) { return world.isValid(id); });
  }

  // One body's pose and velocities, as a trace line.
  void traceState(BodyId id, const char* suffix) const {
    trace("  " + describe(id) + " at " + describe(world.transform(id)) + " v " +
          describe(world.linearVelocity(id)) + " w " + describe(world.angularVelocity(id)) + suffix);
  }

  // Every live body's state is finite or reported (the fault guard resets a reported body to its
  // start-of-step pose, so in practice every state must be finite); every event is finite.
  void checkAfterStep() const {
    const auto faults = world.faultEvents();
    for (const BodyId id : bodies) {
      if (!world.isValid(id)) continue;
      const Transform t = world.transform(id);
      const bool finite = isFinite(t.position) && isFinite(t.rotation) &&
                          isFinite(world.linearVelocity(id)) && isFinite(world.angularVelocity(id)) &&
                          isFinite(world.centerOfMass(id));
      const bool reported =
          std::any_of(faults.begin(), faults.end(), [&](const FaultEvent& f) { return f.body == id; });
      if (collide::fuzz::tracing()) traceState(id, reported ? " (fault reported)" : "");
      if (!finite && !reported) std::abort();
    }
    // Events only for sane input: a pair far outside float's working range (a 1e30 m sphere
    // against a body spinning at 1e9 rad/s) has an approach speed that overflows, with every state
    // still finite (docs/reliability.md, "Limits").
    for (const ContactEvent& e : world.contactEvents()) {
      trace(std::string("  contact ") + (e.type == ContactEvent::Type::Begin ? "begin " : "end ") +
            describe(e.a) + " " + describe(e.b) + " point " + describe(e.point) + " normal " +
            describe(e.normal) + " impulse " + describe(e.impulse) + " speed " + describe(e.speed));
      const bool finiteEvent =
          isFinite(e.point) && isFinite(e.normal) && std::isfinite(e.impulse) && std::isfinite(e.speed);
      if (!finiteEvent && !in.sawExtreme()) std::abort();
    }
  }

  // A step with a valid dt never throws: whatever the bodies' states, the world contains them (a
  // step that threw half-way would leave the world half-stepped).
  void stepChecked(float dt) {
    try {
      world.step(dt);
    } catch (const Error& e) {
      trace(std::string("  step threw: ") + e.what());
      // The states the step left, to tell which body went wrong.
      for (const BodyId id : bodies) {
        if (world.isValid(id)) traceState(id, "");
      }
      std::abort();
    }
    checkAfterStep();
  }

  void call(int& steps) {
    switch (in.choice(16)) {
      case 0:
      case 1: {
        if (live() >= kMaxBodies) break;
        const BodyDef def = decodeBodyDef(in);
        trace("createBody(" + describe(def) + ")");
        bodies.push_back(world.createBody(def));
        trace("  -> " + describe(bodies.back()));
        break;
      }
      case 2: {
        const BodyId id = anyBody();
        trace("destroyBody(" + describe(id) + ")");
        world.destroyBody(id);
        break;
      }
      case 3: {
        const BodyId id = anyBody();
        const Vec3 position = in.vec(-6.0f, 6.0f);
        const Quat rotation = in.rotation();
        trace("setTransform(" + describe(id) + ", " + describe(position) + ", " + describe(rotation) + ")");
        world.setTransform(id, position, rotation);
        break;
      }
      case 4: {
        const BodyId id = anyBody();
        const Vec3 velocity = in.vec(-30.0f, 30.0f);
        trace("setLinearVelocity(" + describe(id) + ", " + describe(velocity) + ")");
        world.setLinearVelocity(id, velocity);
        break;
      }
      case 5: {
        const BodyId id = anyBody();
        const Vec3 velocity = in.vec(-30.0f, 30.0f);
        trace("setAngularVelocity(" + describe(id) + ", " + describe(velocity) + ")");
        world.setAngularVelocity(id, velocity);
        break;
      }
      case 6: {
        const BodyId id = anyBody();
        const Vec3 impulse = in.vec(-50.0f, 50.0f);
        const Vec3 point = in.vec(-6.0f, 6.0f);
        trace("applyImpulse(" + describe(id) + ", " + describe(impulse) + ", " + describe(point) + ")");
        world.applyImpulse(id, impulse, point);
        break;
      }
      case 7: {
        const BodyId id = anyBody();
        const Vec3 force = in.vec(-1000.0f, 1000.0f);
        const Vec3 point = in.vec(-6.0f, 6.0f);
        trace("applyForce(" + describe(id) + ", " + describe(force) + ", " + describe(point) + ")");
        world.applyForce(id, force, point);
        if (in.flag()) {
          const Vec3 torque = in.vec(-100.0f, 100.0f);
          trace("applyTorque(" + describe(id) + ", " + describe(torque) + ")");
          world.applyTorque(id, torque);
        }
        break;
      }
      case 8: {
        // Every joint type, with every field fuzzed (out-of-range values are refused naming the field).
        const int type = in.choice(6);
        const BodyId a = anyBody();
        const BodyId b = anyBody();
        const Vec3 anchor = in.vec(-6.0f, 6.0f);
        const Vec3 axis = in.vec(-1.0f, 1.0f);
        const JointLimits limits{in.flag(), in.value(-4.0f, 4.0f), in.value(-4.0f, 4.0f)};
        const JointMotor motor{in.flag(), in.value(-20.0f, 20.0f), in.value(-10.0f, 500.0f)};
        const JointSpring spring{in.flag(), in.value(0.0f, 30.0f), in.value(0.0f, 2.0f),
                                 in.value(-2.0f, 2.0f)};
        const JointSoftness softness{in.flag() ? in.value(0.0f, 60.0f) : 0.0f, in.value(0.0f, 2.0f)};
        const float breakForce = in.flag() ? in.value(-10.0f, 2000.0f) : kUnbreakable;
        const float breakTorque = in.flag() ? in.value(-10.0f, 2000.0f) : kUnbreakable;
        const bool collide = in.flag();
        const float friction = in.flag() ? in.value(-1.0f, 50.0f) : 0.0f;
        trace("create joint type " + std::to_string(type) + " (" + describe(a) + ", " + describe(b) +
              ", anchor " + describe(anchor) + ", axis " + describe(axis) + ", limits " +
              describe(limits.lower) + " " + describe(limits.upper) + (limits.enabled ? " on" : " off") +
              ", motor " + describe(motor.speed) + " " + describe(motor.maxForce) +
              (motor.enabled ? " on" : " off") + ", spring " + describe(spring.hertz) +
              (spring.enabled ? " on" : " off") + ", softness " + describe(softness.hertz) + ", break " +
              describe(breakForce) + " " + describe(breakTorque) + ", friction " + describe(friction) + ")");
        switch (type) {
          case 0: {
            DistanceConstraintDef def{.a = a, .b = b};
            if (in.flag()) def.localAnchorA = in.vec(-1.0f, 1.0f);
            if (in.flag()) def.localAnchorB = in.vec(-1.0f, 1.0f);
            if (in.flag()) def.length = in.value(0.0f, 4.0f);
            if (in.flag()) def.compliance = in.value(0.0f, 0.01f);
            if (in.flag()) def.dampingRatio = in.value(0.0f, 2.0f);
            if (in.flag()) def.spring = spring;
            if (in.flag()) def.limits = limits;
            def.collideConnected = collide;
            def.breakForce = breakForce;
            joints.push_back(world.createDistanceConstraint(def));
            break;
          }
          case 1:
            joints.push_back(world.createBallJoint({a, b, anchor, collide, softness, breakForce, friction}));
            break;
          case 2:
            joints.push_back(world.createHingeJoint({a, b, anchor, axis, limits, motor, spring, collide,
                                                     softness, breakForce, breakTorque, friction}));
            break;
          case 3:
            joints.push_back(world.createSliderJoint({a, b, anchor, axis, limits, motor, spring, collide,
                                                      softness, breakForce, breakTorque, friction}));
            break;
          case 4:
            joints.push_back(world.createFixedJoint({a, b, in.flag() ? std::optional(anchor) : std::nullopt,
                                                     collide, softness, softness, breakForce, breakTorque}));
            break;
          default:
            joints.push_back(world.createConeJoint({a, b, anchor, axis, in.value(-1.0f, 4.0f), limits,
                                                    collide, softness, breakForce, breakTorque, friction}));
            break;
        }
        trace("  -> " + describe(joints.back()));
        break;
      }
      case 9: {
        const JointId id = anyJoint();
        trace("destroyConstraint(" + describe(id) + ")");
        world.destroyConstraint(id);
        break;
      }
      case 10: {
        const BodyId id = anyBody();
        trace("wakeBody(" + describe(id) + "), isAwake, mass, constraintCurrentLength");
        world.wakeBody(id);
        (void)world.isAwake(id);
        (void)world.mass(id);
        const JointId joint = anyJoint();
        (void)world.constraintCurrentLength(joint);
        // The joint's readings are finite; its settings change as a game changes them (refused
        // where out of range or not of its type).
        const float readings[] = {world.jointPosition(joint), world.jointSpeed(joint),
                                  world.jointForce(joint), world.jointTorque(joint),
                                  world.jointMotorForce(joint)};
        for (const float r : readings) {
          if (!std::isfinite(r) && !in.sawExtreme()) std::abort();
        }
        const int what = in.choice(7);
        trace("  joint setting " + std::to_string(what));
        if (what == 0) world.setJointLimits(joint, {in.flag(), in.value(-4.0f, 4.0f), in.value(-4.0f, 4.0f)});
        if (what == 1)
          world.setJointMotor(joint, {in.flag(), in.value(-20.0f, 20.0f), in.value(-10.0f, 500.0f)});
        if (what == 2)
          world.setJointSpring(
              joint, {in.flag(), in.value(0.0f, 30.0f), in.value(0.0f, 2.0f), in.value(-2.0f, 2.0f)});
        if (what == 3) world.setJointSoftness(joint, {in.value(0.0f, 60.0f), in.value(0.0f, 2.0f)});
        if (what == 4) world.setJointBreakForce(joint, in.value(-10.0f, 2000.0f));
        if (what == 5) world.setJointCollideConnected(joint, in.flag());
        if (what == 6) world.setJointFriction(joint, in.value(-1.0f, 50.0f));
        break;
      }
      case 11: {
        // What a game changes after creation (extreme and non-finite values included: refused).
        const BodyId id = anyBody();
        const BodyMaterial material{in.value(0.0f, 2.0f), in.value(0.0f, 1.0f), in.value(0.0f, 0.1f)};
        const float gravityScale = in.value(-2.0f, 2.0f);
        const float linear = in.value(0.0f, 5.0f), angular = in.value(0.0f, 5.0f);
        const Vec3 position = in.vec(-6.0f, 6.0f);
        const Quat rotation = in.rotation();
        trace("setMaterial(" + describe(id) + ", " + describe(material.friction) + ", " +
              describe(material.bounciness) + ", " + describe(material.rollingResistance) +
              "), setGravityScale(" + describe(gravityScale) + "), setDamping(" + describe(linear) + ", " +
              describe(angular) + "), setTransform without waking (" + describe(position) + ", " +
              describe(rotation) + ")");
        const auto attempt = [&](auto&& change) {
          try {
            change();
          } catch (const Error& e) {
            trace(std::string("  refused: ") + e.what());
          }
        };
        attempt([&] { world.setMaterial(id, material); });
        attempt([&] { world.setGravityScale(id, gravityScale); });
        attempt([&] { world.setDamping(id, linear, angular); });
        attempt([&] { world.setTransform(id, position, rotation, /*wake=*/false); });
        (void)world.bodies();
        break;
      }
      case 12: {
        // Parts at run time: added, removed, their material and filter changed (bad ones refused).
        const BodyId id = anyBody();
        const int what = in.choice(4);
        const auto part = static_cast<std::uint32_t>(in.choice(4));
        trace("part call " + std::to_string(what) + " on " + describe(id) + ", part " + std::to_string(part));
        try {
          if (what == 0) {
            world.addPart(id, decodePartDef(in));
          } else if (what == 1) {
            world.removePart(id, part);
          } else if (what == 2) {
            world.setPartMaterial(id, part, {in.value(0.0f, 2.0f), in.range(0.0f, 1.0f), 0.0f});
          } else {
            world.setPartFilter(id, part, {in.byte(), in.byte(), static_cast<std::int8_t>(in.byte())});
          }
          (void)world.partCount(id);
        } catch (const Error& e) {
          trace(std::string("  refused: ") + e.what());
        }
        break;
      }
      case 13: {
        const BodyId id = anyBody();
        const bool typeChange = in.flag();
        const auto type = static_cast<BodyType>(in.choice(3));
        const bool enabled = in.flag();
        trace((typeChange ? "setType(" + describe(id) + ", " + std::string(toString(type)) + ")"
                          : "setEnabled(" + describe(id) + ", " + std::to_string(enabled) + ")"));
        try {
          if (typeChange) {
            world.setType(id, type);
          } else {
            world.setEnabled(id, enabled);
          }
        } catch (const Error& e) {
          trace(std::string("  refused: ") + e.what());
        }
        break;
      }
      case 14: {
        // Queries and debug drawing between steps. Their answers must agree with each other: the
        // closest ray hit is the first of all hits, which are sorted and within reach.
        Ray ray{in.vec(-8.0f, 8.0f), in.vec(-1.0f, 1.0f), in.flag() ? in.value(0.0f, 20.0f) : 1e30f};
        const Vec3 point = in.vec(-8.0f, 8.0f);
        const Shape probe = collide::fuzz::decodeShape(in, /*allowPlane=*/false);
        trace("queries: ray " + describe(ray.origin) + " " + describe(ray.direction) + ", probe " +
              describe(probe) + " at " + describe(point));
        try {
          const auto closest = world.castRay(ray);
          const auto all = world.castRayAll(ray);
          for (std::size_t k = 1; k < all.size(); ++k) {
            if (all[k - 1].distance > all[k].distance) std::abort();
          }
          if (closest.has_value() != !all.empty()) std::abort();
          if (closest && closest->distance != all.front().distance) {
            trace("  closest " + describe(closest->distance) + " body " + describe(closest->body) + ", all:");
            for (const RayCastResult& hit : all)
              trace("    " + describe(hit.distance) + " " + describe(hit.body));
            std::abort();
          }
          (void)world.hasLineOfSight(ray.origin, point);
        } catch (const Error& e) {
          trace(std::string("  refused: ") + e.what());
        }
        const auto attempt = [&](auto&& query) {
          try {
            query();
          } catch (const Error& e) {
            trace(std::string("  refused: ") + e.what());
          }
        };
        attempt([&] { (void)world.overlapShape(probe, Transform{point}); });
        attempt([&] { (void)world.overlapPoint(point); });
        attempt([&] { (void)world.castShape(probe, Transform{point}, ray.direction); });
        attempt([&] {
          int handed = 0;
          world.castShapeCollect(probe, Transform{point}, ray.direction, [&](const ShapeCastResult& hit) {
            return ++handed < 3 ? hit.fraction : -1.0f;
          });
        });
        struct CountingDraw : DebugDraw {
          std::size_t lines = 0;
          void drawLine(const Vec3&, const Vec3&, const DebugColor&) override { ++lines; }
        } draw;
        DebugDrawOptions everything;
        everything.bounds = everything.broadPhase = everything.contacts = everything.joints = true;
        everything.centersOfMass = everything.solidMeshes = everything.names = everything.staticTree = true;
        world.draw(draw, everything);
        break;
      }
      default: {
        if (steps >= kMaxSteps) break;
        ++steps;
        const float dt = in.byte() >= 224 ? in.value(1e-3f, 0.05f) : 1.0f / 60.0f;
        trace("step(" + describe(dt) + ")");
        if (!(std::isfinite(dt) && dt > 0.0f)) {
          world.step(dt);  // must throw Error
          std::abort();
        }
        stepChecked(dt);
        break;
      }
    }
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzInput in(data, size);
  try {
    const WorldDef def = decodeWorldDef(in);
    trace("World(" + describe(def) + ")");
    World world(def);
    // Some stories disable contacts in the pre-solve callback (one-way platforms do).
    if (in.flag()) {
      world.setPreSolveCallback(
          [](BodyId a, BodyId b, const Manifold&) { return (a.index + b.index) % 3 != 0; });
    }
    Story story{world, in, {}, {}};
    int steps = 0;
    for (int i = 0; i < kMaxCalls && !in.empty(); ++i) {
      try {
        story.call(steps);
      } catch (const Error& e) {
        trace(std::string("  Error: ") + e.what());
        // Refused: a bad argument, a stale id, a shape the API does not take. The world must be
        // as usable afterwards as before, so the story goes on.
      }
    }
    // The story always ends with a step, so that every input exercises the solver.
    trace("step(1/60)");
    story.stepChecked(1.0f / 60.0f);
  } catch (const Error&) {
  }
  return 0;
}
