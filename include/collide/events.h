// What the step tells gameplay code: contact and sensor events, bodies the fault guard froze, and the
// pre-solve callback that sees (and may change or disable) each contact before the solve.
#pragma once

#include <collide/body.h>
#include <collide/math.h>
#include <collide/narrowphase.h>

#include <array>
#include <cstdint>
#include <functional>

namespace collide {

// A touching contact that began or ended this step. For begin events, point/normal are the
// deepest point and the normal (from a to b), impulse the total normal impulse of the step, and
// speed the normal approach speed before the solve (>= 0). End events carry the last known values.
// Begin: the bodies started touching this step; Persist: they touched last step and still do
// (only with WorldDef::persistEvents); End: they stopped touching (or a body was destroyed).
// point and normal are the deepest point and the manifold's normal, from a to b; impulse the normal
// impulse of the step (0 for End); speed the normal approach speed before the solve.
struct ContactEvent {
  enum class Type : std::uint8_t { Begin, Persist, End };
  Type type = Type::Begin;
  BodyId a;
  BodyId b;
  // The parts in contact (World::partCount; 0 for a body of one shape): a body made of parts has a
  // contact, and events, per pair of parts that touch.
  std::uint32_t partA = 0;
  std::uint32_t partB = 0;
  Vec3 point{0.0f};
  Vec3 normal{0.0f, 1.0f, 0.0f};
  float impulse = 0.0f;
  float speed = 0.0f;
};

// A touching contact as the last step left it, whole: the two bodies, the manifold (its points with
// their depths, the normal from a to b), the normal impulse the solver gave each point over the
// step, the impulse of an impact resolved before the solve (the impact stage's, at the manifold's
// deepest points), and the friction patch's impulse (a world vector, on b), all in N s. The data of
// World::visitContacts and of a ContactListener's begin and persist calls.
struct ContactData {
  BodyId a;
  BodyId b;
  std::uint32_t partA = 0;  // as ContactEvent
  std::uint32_t partB = 0;
  Manifold manifold;
  std::array<float, Manifold::kMaxPoints> normalImpulses{};
  float impactImpulse = 0.0f;
  Vec3 frictionImpulse{0.0f};
  // The step's whole normal impulse on the pair (what the begin event reports).
  float totalNormalImpulse() const {
    float sum = impactImpulse;
    for (int i = 0; i < manifold.count; ++i) sum += normalImpulses[i];
    return sum;
  }
};

// Told of every contact event of a step with the whole contact (World::setContactListener), once
// the step is done, in the order of World::contactEvents(): begin when a contact starts touching,
// persist while it goes on touching (only with WorldDef::persistEvents, as the events), end when it
// stops (its manifold is gone by then: the end event's last known point and normal). The world is
// not to be changed from inside a call; a call that throws ends the dispatch and World::step
// rethrows it.
class ContactListener {
 public:
  virtual ~ContactListener() = default;
  virtual void onBegin(const ContactData&) {}
  virtual void onPersist(const ContactData&) {}
  virtual void onEnd(const ContactEvent&) {}
};

struct SensorEvent {
  enum class Type : std::uint8_t { Begin, End };
  Type type = Type::Begin;
  BodyId sensor;
  BodyId visitor;
  // The sensor part and the part of the visitor that crossed it (0 for a body of one shape).
  std::uint32_t sensorPart = 0;
  std::uint32_t visitorPart = 0;
};

// A body whose state stopped being finite during the last step (an accumulated force that
// overflowed, a NaN from a degenerate contact). The world does not let it spread to what it
// touches: the body is put back where it was at the start of the step, stopped, and frozen as an
// immovable obstacle (isAwake() false, forces and impulses ignored) until setTransform,
// setLinearVelocity, setAngularVelocity or wakeBody gives it a new state.
struct FaultEvent {
  static constexpr std::uint8_t kPosition = 1, kRotation = 2, kLinearVelocity = 4, kAngularVelocity = 8;
  BodyId body;
  // The parts of the state that were non-finite (bits above); kRotation also for a finite rotation
  // that is no longer a unit quaternion (an overflowing angular velocity integrates to zero).
  std::uint8_t fields = 0;
};

// A joint that broke this step: its constraint force (or torque) exceeded the break force (torque)
// of its definition. The joint is destroyed at the end of the step that broke it (the id is stale
// from then on); its bodies are kept.
struct JointBreakEvent {
  JointId joint;
  BodyId a;
  BodyId b;
  float force = 0.0f;   // N: the force the joint carried in the step's last substep
  float torque = 0.0f;  // N m
};

// What a pre-solve callback may change of one contact for this step. friction and bounciness start
// as the world's combined values for the pair. surfaceVelocity is the velocity B's surface is to keep
// relative to A's along the contact plane (its normal part is ignored): friction drives the bodies'
// relative sliding towards it, a conveyor belt (Box2D's tangent speed). A contact with a surface
// velocity has no static anchor: it is meant to slide.
struct ContactSettings {
  float friction = 0.0f;
  float bounciness = 0.0f;
  Vec3 surfaceVelocity{0.0f};
  // The parts in contact (0 for a body of one shape), for the callback to read: a one-way platform
  // that is one part of a level body. What the callback writes here is ignored.
  std::uint32_t partA = 0;
  std::uint32_t partB = 0;
};

// Called for each contact before the solve (normal from a to b); return false to disable it for
// this step (one-way platforms), or change its settings (gameplay surfaces: ice, bumpers, belts).
// Settings out of range (negative or non-finite friction, bounciness outside [0, 1], a non-finite
// surface velocity) are not applied: the step completes with the contact's own values and then
// World::step throws Error naming the bodies. The narrow phase takes every body's pose once, before
// the first pair: a pose set from inside the callback counts from the next step.
using PreSolveCallback =
    std::function<bool(BodyId a, BodyId b, const Manifold& manifold, ContactSettings& settings)>;
// A world's last word on a pair of bodies that passed their groups, layers and masks (and the
// constraints' collideConnected): return false to keep them from colliding (or a sensor from
// reporting them). Called for each candidate pair in every stage that pairs bodies (contacts, sensor
// crossings, continuous collision, revert), from inside the step: it must not change the world.
using PairFilter = std::function<bool(BodyId a, BodyId b)>;

// The same without settings, for callbacks that only look or disable.
using PreSolveFilter = std::function<bool(BodyId a, BodyId b, const Manifold& manifold)>;

}  // namespace collide
