// The world: rigid bodies, their contacts and the collision response (lecture: "collision handling").
// One step runs broad phase -> narrow phase -> contact persistence -> solver -> events; see
// docs/architecture.md ("World and solver") for the walk through the code.
//
// Bodies are created from a BodyDef and named by a BodyId (slot index + generation, as Box2D v3),
// so a stale id is reported with collide::Error instead of aliasing a new body.
#pragma once

#include <collide/broadphase.h>
#include <collide/error.h>
#include <collide/math.h>
#include <collide/narrowphase.h>
#include <collide/shapes.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace collide {

// How the two bodies' bounciness (or friction) make the pair's value.
enum class CombineRule : std::uint8_t { Average, Min, Max, Multiply };
// Newton: restitution on the normal relative velocity, friction handles the tangent.
// Interpolated: the lecture's blend of the elastic and the inelastic impact (src/response/).
enum class ImpactModel : std::uint8_t { Newton, Interpolated };
enum class FrictionModel : std::uint8_t { Coulomb, Viscous, Damping, None };
// Project: push bodies apart (mass-weighted, by the soft contact). Revert: put a penetrating body
// back where it was at the start of the step.
enum class PenetrationResponse : std::uint8_t { Project, Revert };

// Scene-file names ("average", "newton", ...); parse functions throw Error on unknown names.
std::string_view toString(CombineRule rule);
std::string_view toString(ImpactModel model);
std::string_view toString(FrictionModel model);
std::string_view toString(PenetrationResponse response);
CombineRule parseCombineRule(std::string_view name);
ImpactModel parseImpactModel(std::string_view name);
FrictionModel parseFrictionModel(std::string_view name);
PenetrationResponse parsePenetrationResponse(std::string_view name);
// The pair's value from the two bodies' values (bounciness, friction) under `rule`.
float combine(CombineRule rule, float a, float b);

// The contact constraint's tuning (Catto, "Solver2D" 2024 / Box2D v3 soft step). Box2D's defaults
// are 30 Hz and damping ratio 10 at 4 substeps; ours are stiffer so stacks stand (see below).
struct ContactTuning {
  // Stiffness of the soft contact, capped at a quarter of the substep rate (90 Hz at 6 substeps of
  // 1/360 s). A resting point carrying force F sits F / (m_eff omega^2) deep, so the stiffness sets
  // how far a stack sags (docs/architecture.md, "Stacking").
  float hertz = 90.0f;
  // Under-damped spring, but the softness per iteration it gives (mass scale 0.80) keeps stiff
  // stacks from shivering; over-damped (10) shivers at this stiffness. Impacts do not bounce.
  float dampingRatio = 0.5f;
  float pushOutSpeed = 3.0f;          // m/s, the most the position correction may add
  float restitutionThreshold = 1.0f;  // m/s: slower impacts do not bounce (resting contacts stay quiet)
  float linearSlop = 0.005f;          // m: the penetration allowed (and the "touching" tolerance of events)
  float speculativeDistance = 0.02f;  // m: contacts are created this far apart (plus the step's motion)
  // Passes without the position bias after each substep's position update (Box2D v3's relax), so
  // that push-out does not turn into bounce.
  int relaxPasses = 1;
  // A sticking friction patch holds its place (a point fixed in each body); when the two points
  // drift apart farther than this (m) along the surface, the anchor is taken again where the patch is.
  float frictionAnchorReach = 0.02f;
  // A pair of which no point of either body moved more than this (m) relative to the other since
  // its manifold was computed gets that manifold placed at the new poses instead of a new
  // narrow-phase query (Jolt's body pair cache), and a pair found apart stays apart: resting bodies
  // cost almost nothing. Kept well under the linear slop (what a feature the cached manifold lacks
  // could sink by) and the speculative distance (what a pair found apart could close). 0 turns the
  // cache off.
  float manifoldCacheDistance = 0.002f;
};

// When a body counts as resting (Box2D's sleep tolerances and time to sleep).
struct SleepTuning {
  float linearSpeed = 0.05f;   // m/s, of the centre of mass
  float angularSpeed = 0.05f;  // rad/s
  float timeToSleep = 0.5f;    // s every body of an island must rest before the island sleeps
};

struct WorldDef {
  Vec3 gravity{0.0f, -9.81f, 0.0f};
  int substeps = 6;  // the contact stiffness cap is a quarter of the substep rate
  BroadPhaseSettings broadPhase{};
  CombineRule bouncinessCombine = CombineRule::Max;
  CombineRule frictionCombine = CombineRule::Average;
  ImpactModel impactModel = ImpactModel::Newton;
  FrictionModel frictionModel = FrictionModel::Coulomb;
  PenetrationResponse penetrationResponse = PenetrationResponse::Project;
  // Resting islands sleep (docs/architecture.md, "Islands and sleeping").
  bool sleeping = false;
  // Continuous collision: bodies with BodyDef::ccd get a time-of-impact pass after the solve
  // (docs/ccd.md). Off, every body relies on speculative contacts alone.
  bool ccd = true;
  // ContactEvent::Type::Persist every step for every contact that goes on touching (lecture: the
  // prolonged contact). Off by default: a resting pile of 4,096 boxes would report 10,000 a step.
  bool persistEvents = false;
  SleepTuning sleep{};
  ContactTuning contact{};
};

enum class BodyType : std::uint8_t { Static, Kinematic, Dynamic };
std::string_view toString(BodyType type);

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
  float bounciness = 0.0f;          // [0, 1]
  float friction = 0.5f;            // >= 0
  std::uint32_t layer = 1;          // the body's bits
  std::uint32_t mask = kAllLayers;  // the layers it collides with; both must agree
  bool sensor = false;              // reports overlap events, takes no response
  // A point mass: a dynamic body whose shape must be a Sphere (it collides as a sphere of that
  // radius times scale) but that has no inertia, no angular velocity and a rotation that never
  // changes. Cheap links for chains, ropes and cloth-like meshes of distance constraints.
  bool particle = false;
  // Continuous collision (docs/ccd.md): when WorldDef::ccd is on and the body moves more than half
  // its smallest extent in a step, it is stopped at its first time of impact against any other
  // body (static, kinematic or dynamic) instead of passing through thin or turning obstacles that
  // the speculative contacts miss. Costs a broad-phase query and a time of impact per candidate
  // for each such fast body; nothing for a slow one. Ignored for sensors.
  bool ccd = false;
  std::uint64_t userData = 0;
  std::string name;
};

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

// Keeps an anchor on body a at `length` from an anchor on body b (a rope that also pushes: a rod).
// Any two bodies, at least one dynamic. Anchors are points in each body's local frame (scaled with
// the body, like its shape); unset, they are the centres of mass. A particle's anchor must be its
// centre (it cannot turn, so an offset anchor would have no lever).
struct DistanceConstraintDef {
  BodyId a;
  BodyId b;
  std::optional<Vec3> localAnchorA;
  std::optional<Vec3> localAnchorB;
  std::optional<float> length;  // >= 0; unset: the anchors' distance at creation
  // m/N, >= 0. 0 is rigid; otherwise a spring of stiffness 1/compliance (XPBD's compliance), see
  // docs/architecture.md ("Distance constraints").
  float compliance = 0.0f;
  float dampingRatio = 0.0f;  // of the spring (compliance > 0), >= 0; 1 is critical
};

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
  Vec3 point{0.0f};
  Vec3 normal{0.0f, 1.0f, 0.0f};
  float impulse = 0.0f;
  float speed = 0.0f;
};

struct SensorEvent {
  enum class Type : std::uint8_t { Begin, End };
  Type type = Type::Begin;
  BodyId sensor;
  BodyId visitor;
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

// The hit of World::castRay: the body and where its shape was hit.
struct RayCastResult {
  BodyId body;
  float distance = 0.0f;  // along the ray (its direction normalised)
  Vec3 point{0.0f};
  Vec3 normal{0.0f};           // unit, the surface normal at the hit, facing the ray's origin side
  std::uint32_t subShape = 0;  // triangle index for a mesh, child index for a compound
};

// Two bodies, as World::broadPhasePairs hands them out.
struct BodyPair {
  BodyId a;
  BodyId b;
  friend bool operator==(const BodyPair&, const BodyPair&) = default;
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
};

// Called for each contact before the solve (normal from a to b); return false to disable it for
// this step (one-way platforms), or change its settings (gameplay surfaces: ice, bumpers, belts).
// Settings out of range (negative or non-finite friction, bounciness outside [0, 1], a non-finite
// surface velocity) are not applied: the step completes with the contact's own values and then
// World::step throws Error naming the bodies. The narrow phase takes every body's pose once, before
// the first pair: a pose set from inside the callback counts from the next step.
using PreSolveCallback =
    std::function<bool(BodyId a, BodyId b, const Manifold& manifold, ContactSettings& settings)>;
// The same without settings, for callbacks that only look or disable.
using PreSolveFilter = std::function<bool(BodyId a, BodyId b, const Manifold& manifold)>;

class World {
 public:
  // Throws Error on invalid settings (substeps < 1, non-finite gravity, bad tuning) and on
  // settings not implemented yet.
  explicit World(const WorldDef& def = {});
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;
  World(World&&) noexcept;
  World& operator=(World&&) noexcept;

  const WorldDef& def() const;
  // Changes the world's settings between steps; each takes effect from the next step (the
  // viewer's live settings, a game's slow motion or low-gravity zone). Bodies, contacts and their
  // warm start are kept; a new broad-phase type or setting moves every proxy to a new broad phase
  // with the same boxes; turning sleeping off wakes every sleeping body. Throws Error as the
  // constructor does, and then changes nothing.
  void setDef(const WorldDef& def);

  // Throws Error naming the field for a bad definition.
  BodyId createBody(const BodyDef& def);
  // Also destroys the body's constraints and wakes what it touched. Its touching contacts and
  // sensor overlaps end: their End events (with the now stale id) open the next step's events.
  void destroyBody(BodyId id);
  bool isValid(BodyId id) const;
  std::size_t bodyCount() const;

  // ---- Between steps. Stale ids throw Error. ----
  BodyType type(BodyId id) const;
  bool isParticle(BodyId id) const;
  Transform transform(BodyId id) const;
  void setTransform(BodyId id, const Vec3& position, const Quat& rotation);
  Vec3 linearVelocity(BodyId id) const;
  Vec3 angularVelocity(BodyId id) const;
  void setLinearVelocity(BodyId id, const Vec3& velocity);
  // A particle has no angular velocity: a non-zero one is an Error.
  void setAngularVelocity(BodyId id, const Vec3& velocity);
  // At a world point; changes the velocity immediately (dynamic bodies only; a particle takes the
  // linear part only, as does applyForce, and ignores applyTorque).
  void applyImpulse(BodyId id, const Vec3& impulse, const Vec3& worldPoint);
  // Accumulated until the next step, then cleared (dynamic bodies only).
  void applyForce(BodyId id, const Vec3& force, const Vec3& worldPoint);
  void applyTorque(BodyId id, const Vec3& torque);
  // The setters and applyImpulse/Force/Torque above wake the body's island (WorldDef::sleeping).
  // Static bodies are never awake; kinematic bodies always are; with sleeping off every dynamic
  // body is. wakeBody wakes the body's whole island (no effect on static bodies).
  bool isAwake(BodyId id) const;
  void wakeBody(BodyId id);
  float mass(BodyId id) const;         // 0 for static and kinematic bodies
  Vec3 centerOfMass(BodyId id) const;  // world frame
  const Shape& shape(BodyId id) const;
  std::uint64_t userData(BodyId id) const;
  const std::string& name(BodyId id) const;

  // ---- Constraints. Stale ids throw Error; destroying a body destroys its constraints. ----
  // Throws Error naming the field for a bad definition (stale body, a == b, no dynamic body, ...).
  JointId createDistanceConstraint(const DistanceConstraintDef& def);
  void destroyConstraint(JointId id);
  bool isValid(JointId id) const;
  std::size_t constraintCount() const;
  float constraintLength(JointId id) const;         // the rest length
  float constraintCurrentLength(JointId id) const;  // the anchors' distance now

  void setPreSolveCallback(PreSolveCallback callback);
  void setPreSolveCallback(PreSolveFilter filter);

  // Advances by dt > 0 (finite); throws Error otherwise.
  void step(float dt);

  // The funnel of the last step: the broad phase's counters plus narrow-phase tests and pairs in
  // contact. Totals sum them over all steps.
  const BroadPhaseStats& lastStats() const;
  const BroadPhaseStats& totalStats() const;
  // Events of the last step, in a deterministic order.
  std::span<const ContactEvent> contactEvents() const;
  std::span<const SensorEvent> sensorEvents() const;
  // Bodies frozen by the last step because their state became non-finite (see FaultEvent).
  std::span<const FaultEvent> faultEvents() const;
  // The number of touching (non-sensor) contact pairs after the last step.
  std::size_t touchingContactCount() const;

  // ---- Queries between steps, through the broad phase. ----
  // The closest body whose shape the ray hits within ray.maxDistance (the lecture's picking: the
  // broad phase's boxes find the candidates, each candidate's shape is cast exactly). Only bodies
  // whose layer passes the mask ((layer & mask) != 0); sensors are skipped, having no surface to
  // hit. Equal distances go to the lower body index, so every broad-phase type gives the same
  // answer. The direction is normalised here; a non-finite origin, a zero or non-finite direction
  // or a NaN or negative maxDistance throws Error. A ray that starts inside a solid shape hits it
  // at distance 0 with normal -direction (as collide::rayCast).
  std::optional<RayCastResult> castRay(const Ray& ray, LayerMask mask = kAllLayers) const;
  // The pairs the broad phase kept in the last step (proxy boxes overlapping, static-static never),
  // in its order (by proxy index); pairs with a body destroyed since are left out. For drawing and
  // inspection: it allocates.
  std::vector<BodyPair> broadPhasePairs() const;
  // The broad phase, read-only: its box queries, and visitNodes for drawing its structure. A body's
  // proxy box holds its shape grown by the contact tuning's speculative distance (by the step's
  // predicted motion too, from the start of a step), so between steps it holds where the body is.
  const BroadPhase& broadPhase() const;

  // Sum over dynamic bodies.
  Vec3 linearMomentum() const;
  float kineticEnergy() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace collide
