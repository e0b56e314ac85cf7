// The world: rigid bodies, their contacts and the collision response (lecture: "collision handling").
// One step runs broad phase -> narrow phase -> contact persistence -> solver -> events; see
// docs/architecture.md ("World and solver") for the walk through the code.
//
// Bodies are created from a BodyDef and named by a BodyId (slot index + generation, as Box2D v3),
// so a stale id is reported with collide::Error instead of aliasing a new body.
//
// "Throws Error" below means: reports it (collide/error.h). A build with exceptions throws; one
// without (COLLIDE_EXCEPTIONS=OFF) calls the error handler and returns a null id, a default value
// or no hit, having changed nothing, as a thrown Error leaves things.
#pragma once

#include <collide/body.h>
#include <collide/broadphase.h>
#include <collide/debug_draw.h>
#include <collide/error.h>
#include <collide/events.h>
#include <collide/joints.h>
#include <collide/math.h>
#include <collide/narrowphase.h>
#include <collide/queries.h>
#include <collide/settings.h>
#include <collide/shapes.h>
#include <collide/tasks.h>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace collide {

// Where a step's wall time went, in seconds, stage by stage as src/step.cpp runs them (a parallel
// stage counts from its start on the calling thread to the end of its last range). Timings are not
// part of the state: they differ run to run while the results do not.
struct StageTimes {
  double broadPhase = 0.0;   // proxies' bounds, the broad phase's update and pair finding, waking islands
  double narrowPhase = 0.0;  // contacts: the pairs' collider tests, manifold reuse, pre-solve callbacks
  double solve = 0.0;        // impacts, the soft step with its joints, joint breaks, friction models
  double continuous = 0.0;   // the continuous pass and the revert response
  double events = 0.0;       // fault guard, escaped proxies, contact and sensor events
  double islands = 0.0;      // islands and sleeping

  // The stages in step order, with the names reports print (`label`) and write (`key`, snake
  // case): collide run's table and JSON and the viewer's panel all walk this one list.
  struct Stage {
    const char* label;
    const char* key;
    double StageTimes::*seconds;
  };
  static constexpr Stage kStages[] = {
      {"broad phase", "broad_phase", &StageTimes::broadPhase},
      {"narrow phase", "narrow_phase", &StageTimes::narrowPhase},
      {"solve", "solve", &StageTimes::solve},
      {"continuous", "continuous", &StageTimes::continuous},
      {"events", "events", &StageTimes::events},
      {"islands and sleep", "islands", &StageTimes::islands},
  };

  double total() const {
    double sum = 0.0;
    for (const Stage& stage : kStages) sum += this->*stage.seconds;
    return sum;
  }
  StageTimes& operator+=(const StageTimes& step) {
    for (const Stage& stage : kStages) this->*stage.seconds += step.*stage.seconds;
    return *this;
  }
};

// The heap memory a world holds, in bytes, by the stage that holds it: what its arrays have
// reserved (their capacity, which steps reuse rather than free), not what they use this step. The
// shapes are the caller's, shared by value, and not counted; nor is the allocator's own overhead.
struct WorldMemory {
  std::size_t bodies = 0;      // records and states, parts, names, free slots, the proxies' step boxes
  std::size_t broadPhase = 0;  // the proxies, the algorithm's structure, the step's pairs
  std::size_t contacts = 0;    // this and last step's contacts, the narrow phase's scratch, events
  std::size_t solver = 0;      // solver bodies, contact batches and colours, projection, impacts, revert
  std::size_t joints = 0;      // the joints, their trees' systems, the pairs they keep apart
  std::size_t islands = 0;     // islands and sleep timers

  // The categories, with the names reports print (`label`) and write (`key`).
  struct Category {
    const char* label;
    const char* key;
    std::size_t WorldMemory::*bytes;
  };
  static constexpr Category kCategories[] = {
      {"bodies", "bodies", &WorldMemory::bodies},
      {"broad phase", "broad_phase", &WorldMemory::broadPhase},
      {"contacts", "contacts", &WorldMemory::contacts},
      {"solver", "solver", &WorldMemory::solver},
      {"joints", "joints", &WorldMemory::joints},
      {"islands", "islands", &WorldMemory::islands},
  };

  std::size_t total() const {
    std::size_t sum = 0;
    for (const Category& category : kCategories) sum += this->*category.bytes;
    return sum;
  }
};

// The step's funnel (the lecture's argument for a broad phase: almost no pair collides): the
// potential pairs, those the broad phase kept, the narrow-phase tests and the pairs in contact.
struct StepStats {
  std::uint64_t proxies = 0;  // at the end of the step: a count, which += takes rather than adds
  std::uint64_t potentialPairs = 0;
  std::uint64_t keptPairs = 0;
  std::uint64_t boxTests = 0;
  // Of the kept pairs, those the filters ruled out before the narrow phase (groups, parts' filters,
  // constraints' collideConnected, the pair filter). A pair the bodies' layers and masks refuse is
  // not kept: their broad-phase proxies carry them.
  std::uint64_t filteredPairs = 0;
  std::uint64_t narrowPhaseTests = 0;
  // Of those, the pairs whose manifold was placed again from its last computation instead of
  // computed, because the two bodies had not moved relative to each other (the manifold cache).
  std::uint64_t reusedManifolds = 0;
  std::uint64_t contactPairs = 0;  // touching, sensors left out
  StageTimes time;

  StepStats() = default;
  explicit StepStats(const BroadPhaseStats& broadPhase)
      : proxies(broadPhase.proxies),
        potentialPairs(broadPhase.potentialPairs),
        keptPairs(broadPhase.keptPairs),
        boxTests(broadPhase.boxTests) {}
  // Totals over steps.
  StepStats& operator+=(const StepStats& step) {
    proxies = step.proxies;
    potentialPairs += step.potentialPairs;
    keptPairs += step.keptPairs;
    boxTests += step.boxTests;
    filteredPairs += step.filteredPairs;
    narrowPhaseTests += step.narrowPhaseTests;
    reusedManifolds += step.reusedManifolds;
    contactPairs += step.contactPairs;
    time += step.time;
    return *this;
  }
  // The fraction of potential pairs the broad phase kept (0 when there are none).
  double keptFraction() const {
    return potentialPairs == 0 ? 0.0 : static_cast<double>(keptPairs) / static_cast<double>(potentialPairs);
  }
};

// The most substeps a step may take: each costs a full solve, so a setting above this is a mistake
// (or a hostile snapshot or scene file) that would stall the step, and is refused.
inline constexpr int kMaxSubsteps = 64;

struct WorldDef {
  Vec3 gravity{0.0f, -9.81f, 0.0f};
  // 1 to kMaxSubsteps; the contact stiffness cap is a quarter of the substep rate. The substeps are
  // the solver's iterations too: with fewer, tall stacks and loaded joints can give way
  // (docs/architecture.md, "Fewer substeps").
  int substeps = 6;
  BroadPhaseSettings broadPhase{};
  CombineRule bouncinessCombine = CombineRule::Max;
  CombineRule frictionCombine = CombineRule::Average;
  ImpactModel impactModel = ImpactModel::Newton;
  FrictionModel frictionModel = FrictionModel::Coulomb;
  PenetrationResponse penetrationResponse = PenetrationResponse::Soft;
  // Resting islands sleep (docs/architecture.md, "Islands and sleeping").
  bool sleeping = false;
  // Continuous collision after the solve (docs/ccd.md): fast dynamic bodies against static geometry,
  // and bodies with BodyDef::ccd against everything. Off, every body relies on speculative contacts
  // alone.
  bool ccd = true;
  // ContactEvent::Type::Persist every step for every contact that goes on touching (lecture: the
  // prolonged contact). Off by default: a resting pile of 4,096 boxes would report 10,000 a step.
  bool persistEvents = false;
  SleepTuning sleep{};
  ContactTuning contact{};
  // Workers for the step's parallel stages (include/collide/tasks.h, docs/threads.md), 1 to
  // kMaxWorkers. One runs the step on the calling thread and creates no thread. More, without
  // enqueueTask, start workerCount - 1 threads of the world's own; with enqueueTask (and finishTask,
  // both or neither) the engine's job system runs the tasks, userTaskContext passed to both. The
  // result is the same, bit for bit, at every worker count.
  int workerCount = 1;
  EnqueueTaskCallback* enqueueTask = nullptr;
  FinishTaskCallback* finishTask = nullptr;
  void* userTaskContext = nullptr;
};

class World {
 public:
  // Throws Error on invalid settings (substeps outside 1 to kMaxSubsteps, non-finite gravity, bad
  // tuning) and on settings not implemented yet.
  // Without exceptions (collide/error.h) a refused definition is reported and the world takes the
  // default one; create() returns null instead, the result to check.
  explicit World(const WorldDef& def = {});
  static std::unique_ptr<World> create(const WorldDef& def = {});
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

  // Makes room for `count` bodies in all (alive or not), as std::vector::reserve does: a world whose
  // bodies are known before it is built (a level, a scene file) then keeps its body records and
  // broad-phase proxies in arrays of that size, not in arrays that doubled past it, whose freed
  // smaller copies stay in the process (R1's 4,097 bodies: the whole process peaks 1.4 MiB lower).
  // A hint, not a limit: more bodies may be created. A count at or below the room already there
  // changes nothing; a count above kMaxReservedBodies is refused (an Error, nothing changed).
  static constexpr std::size_t kMaxReservedBodies = std::size_t{1} << 24;
  void reserveBodies(std::size_t count);

  // Throws Error naming the field for a bad definition.
  BodyId createBody(const BodyDef& def);
  // Also destroys the body's constraints and wakes what it touched. Its touching contacts and
  // sensor overlaps end: their End events (with the now stale id) open the next step's events.
  void destroyBody(BodyId id);
  bool isValid(BodyId id) const;
  std::size_t bodyCount() const;

  // ---- Between steps. Stale ids throw Error. ----
  BodyType type(BodyId id) const;
  // A new type from the next step (a door unlocked, a crate frozen in place, a platform under script):
  // a dynamic body gets its mass properties from its shape or parts (its density, or BodyDef::mass
  // if it was given), the others none; the body origin stays where it is and the velocity of every
  // point is kept (a static body stops). The body and what touches it wake; contacts go on where
  // the new type still pairs (a body made static loses its contacts with static bodies). Error, and
  // no change, for a plane or an open mesh made movable or dynamic, or a particle made static or
  // kinematic.
  void setType(BodyId id, BodyType type);
  // A disabled body leaves the simulation but keeps its id, state and settings (a pickup in the
  // player's pocket, a piece of a level not streamed in): it has no broad-phase proxy, so no contacts
  // (touching ones end, their End events with the next step's), no query finds it, it does not move
  // and nothing wakes it; its constraints rest. Enabling it puts it back where it is, awake. The
  // setters work on a disabled body and count once it is enabled.
  void setEnabled(BodyId id, bool enabled);
  bool isEnabled(BodyId id) const;
  bool isParticle(BodyId id) const;
  Transform transform(BodyId id) const;
  void setTransform(BodyId id, const Vec3& position, const Quat& rotation);
  // The same, waking the body only when `wake` is true: a sleeping body teleported with wake false
  // stays asleep where it is put until something reaches it (a level streamed in, a respawn point).
  // A body frozen by the fault guard takes the new state either way.
  void setTransform(BodyId id, const Vec3& position, const Quat& rotation, bool wake);
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
  // The body's friction, bounciness and rolling resistance; a new material counts from the next
  // step's contacts (ice under a slipping boot, a bumper switched on). Out of range (as BodyDef)
  // throws Error and changes nothing.
  BodyMaterial material(BodyId id) const;
  void setMaterial(BodyId id, const BodyMaterial& material);
  // BodyDef::gravityScale (finite) and the velocity damping (1/s, >= 0), from the next step; an
  // invalid value throws Error and changes nothing. They act on dynamic bodies only. Wake the body.
  float gravityScale(BodyId id) const;
  void setGravityScale(BodyId id, float scale);
  float linearDamping(BodyId id) const;
  float angularDamping(BodyId id) const;
  void setDamping(BodyId id, float linear, float angular);
  // Every live body, in slot order (the order of the step's stages).
  std::vector<BodyId> bodies() const;

  // ---- Parts (BodyDef::parts, docs/parts.md). A body of one shape has one part, index 0: its shape
  // at the body origin with the body's material, sensor flag and filter. A part index out of range
  // throws Error. ----
  std::uint32_t partCount(BodyId id) const;
  const Shape& partShape(BodyId id, std::uint32_t part) const;
  Transform partLocalPose(BodyId id, std::uint32_t part) const;  // in the body frame, before its scale
  bool partIsSensor(BodyId id, std::uint32_t part) const;
  std::uint64_t partUserData(BodyId id, std::uint32_t part) const;
  // As setMaterial and setCollisionFilter, for one part; on a body made of parts, setMaterial and
  // setCollisionFilter set every part, and material, layer, mask and group read part 0 (layer and
  // mask: the union of the parts'; group: 0).
  BodyMaterial partMaterial(BodyId id, std::uint32_t part) const;
  void setPartMaterial(BodyId id, std::uint32_t part, const BodyMaterial& material);
  CollisionFilter partFilter(BodyId id, std::uint32_t part) const;
  void setPartFilter(BodyId id, std::uint32_t part, const CollisionFilter& filter);
  // Adds a part (checked as BodyDef::parts; Error and no change for a bad one) and returns its
  // index, the last. A body of one shape becomes a body made of parts, its shape part 0. Removes a
  // part: those after it move down one index; a body keeps at least one part. Both recompute the
  // body's mass, centre of mass and inertia from its parts (scaled to BodyDef::mass if it was given),
  // keep the body origin where it is and the velocity of every point of the body, move the anchors
  // of its constraints with the centre of mass, and wake it. Contacts of the removed part end
  // (their End events open the next step's events); other contacts go on. Not for a particle, nor a
  // body of one plane.
  // Returns the new part's index, or without exceptions kNoPart after an Error.
  std::uint32_t addPart(BodyId id, const PartDef& part);
  static constexpr std::uint32_t kNoPart = 0xFFFFFFFFu;
  void removePart(BodyId id, std::uint32_t part);

  // ---- Joints (collide/joints.h, docs/joints.md). Stale ids throw Error; destroying a body
  // destroys its joints. ----
  // Each throws Error naming the field for a bad definition (stale body, a == b, no dynamic body,
  // a non-finite or zero axis, limits out of order, ...).
  JointId createDistanceConstraint(const DistanceConstraintDef& def);
  JointId createBallJoint(const BallJointDef& def);
  JointId createHingeJoint(const HingeJointDef& def);
  JointId createSliderJoint(const SliderJointDef& def);
  JointId createFixedJoint(const FixedJointDef& def);
  JointId createConeJoint(const ConeJointDef& def);
  void destroyConstraint(JointId id);
  bool isValid(JointId id) const;
  std::size_t constraintCount() const;
  JointType jointType(JointId id) const;
  BodyId jointBodyA(JointId id) const;
  BodyId jointBodyB(JointId id) const;
  float constraintLength(JointId id) const;         // the rest length (0 for a ball joint)
  float constraintCurrentLength(JointId id) const;  // the anchors' distance now
  // The anchors in the world now, as each body carries its own.
  Vec3 jointAnchorA(JointId id) const;
  Vec3 jointAnchorB(JointId id) const;
  // The joint's axis in the world now, as body a carries it (hinge, slider, cone; x of the joint
  // frame for the others).
  Vec3 jointAxis(JointId id) const;
  // The free coordinate now: a hinge's angle and a cone joint's twist (rad, (-pi, pi]), a slider's
  // offset (m), a distance joint's length; 0 for ball and fixed joints. Its rate, from the bodies'
  // velocities (rad/s, m/s).
  float jointPosition(JointId id) const;
  float jointSpeed(JointId id) const;
  // The force (N) and torque (N m) the joint carried in the last step's last substep, and the
  // motor's share along the free coordinate (N m for a hinge, N for a slider).
  float jointForce(JointId id) const;
  float jointTorque(JointId id) const;
  float jointMotorForce(JointId id) const;
  // Whether the last step solved the joint's rigid rows in its joint tree, exactly, rather than by
  // Gauss-Seidel: false for a joint that closes a loop, a mesh's joints, soft and distance joints,
  // and before the first step (docs/joints.md, "Joint trees").
  bool jointInTree(JointId id) const;
  // The fields of the definitions, read and changed after creation; each setter checks as the
  // definition does (Error and no change), wakes the joint's bodies, and takes effect next step.
  // Limits, motor and spring belong to hinge, slider (and cone: twist limits; distance: limits,
  // spring); softness to every type (the fixed joint's linear rows; setJointAngularSoftness for its
  // rotation rows). A setter that does not apply to the joint's type throws Error.
  JointLimits jointLimits(JointId id) const;
  void setJointLimits(JointId id, const JointLimits& limits);
  JointMotor jointMotor(JointId id) const;
  void setJointMotor(JointId id, const JointMotor& motor);
  JointSpring jointSpring(JointId id) const;
  void setJointSpring(JointId id, const JointSpring& spring);
  JointSoftness jointSoftness(JointId id) const;
  void setJointSoftness(JointId id, const JointSoftness& softness);
  JointSoftness jointAngularSoftness(JointId id) const;
  void setJointAngularSoftness(JointId id, const JointSoftness& softness);
  float coneSwingLimit(JointId id) const;
  void setConeSwingLimit(JointId id, float swingLimit);
  float jointBreakForce(JointId id) const;
  void setJointBreakForce(JointId id, float force);  // > 0; kUnbreakable for none
  float jointBreakTorque(JointId id) const;
  void setJointBreakTorque(JointId id, float torque);
  // A ball, cone or hinge joint's friction torque (N m), a slider's friction force (N); >= 0.
  float jointFriction(JointId id) const;
  void setJointFriction(JointId id, float friction);
  bool jointCollideConnected(JointId id) const;
  void setJointCollideConnected(JointId id, bool collide);

  void setPreSolveCallback(PreSolveCallback callback);
  void setPreSolveCallback(PreSolveFilter filter);
  // The pair filter (above); an empty function for none.
  void setPairFilter(PairFilter filter);
  // A body's collision filter (BodyDef::layer, mask, group), changed at once: the next step's pairs
  // follow it (a contact it rules out ends then). Wakes the body.
  void setCollisionFilter(BodyId id, std::uint32_t layer, std::uint32_t mask, std::int32_t group);
  std::uint32_t layer(BodyId id) const;
  std::uint32_t mask(BodyId id) const;
  std::int32_t group(BodyId id) const;
  // The listener told of each step's contact events with the whole contact (events.h); nullptr for
  // none. The world does not own it: it must outlive the world or be unset first.
  void setContactListener(ContactListener* listener);

  // Advances by dt > 0 (finite); throws Error otherwise.
  void step(float dt);

  // The funnel of the last step, and its totals over all steps.
  const StepStats& lastStats() const;
  const StepStats& totalStats() const;
  // The heap memory the world holds now, by stage (WorldMemory).
  WorldMemory memoryUse() const;

  // ---- Snapshots (rollback netcode, save games, replays; docs/snapshots.md) ----
  // The world's whole state as bytes: its settings, bodies with their shapes, the broad phase's
  // proxies and pairs, contacts with their warm-start impulses, friction anchors and manifold caches,
  // joints with theirs, sleep timers, the last step's events and statistics. A world that loads it
  // continues bit-identically to this one (the same build of collide; docs/determinism.md). The
  // same state gives the same bytes. Not saved: the callbacks (pre-solve, pair filter, contact
  // listener) and the task settings (workerCount, enqueueTask, finishTask, userTaskContext), which
  // belong to the world that loads it.
  std::vector<std::uint8_t> saveSnapshot() const;
  // Replaces this world's state with a snapshot's, keeping this world's callbacks and task
  // settings; ids from the saved world are valid here. Throws Error naming the fault, and changes
  // nothing, for bytes that are not a snapshot, a snapshot of another format version or another
  // build's layout, a corrupt or truncated one, or contents no world could hold.
  void loadSnapshot(std::span<const std::uint8_t> snapshot);
  // Events of the last step, in a deterministic order.
  std::span<const ContactEvent> contactEvents() const;
  std::span<const SensorEvent> sensorEvents() const;
  // Bodies frozen by the last step because their state became non-finite (see FaultEvent).
  std::span<const FaultEvent> faultEvents() const;
  // The joints that broke in the last step (their break force or torque exceeded); already
  // destroyed.
  std::span<const JointBreakEvent> jointBreakEvents() const;
  // The number of touching (non-sensor) contact pairs after the last step.
  std::size_t touchingContactCount() const;
  // Every touching (non-sensor) contact after the last step, whole, in the contacts' pair order (the
  // events' order); and those of one body (a scan of all contacts). For gameplay queries ("what is
  // this crate resting on, how hard") and drawing. The world is not to be changed from the visitor.
  void visitContacts(const std::function<void(const ContactData&)>& visitor) const;
  void visitContacts(BodyId body, const std::function<void(const ContactData&)>& visitor) const;

  // ---- Queries between steps, through the broad phase. ----
  // The closest body whose shape the ray hits within ray.maxDistance (the lecture's picking: the
  // broad phase's boxes find the candidates, each candidate's shape is cast exactly). Only bodies
  // whose layer passes the mask ((layer & mask) != 0); sensors are skipped, having no surface to
  // hit. Equal distances go to the lower body index, so every broad-phase type gives the same
  // answer. The direction is normalised here; a non-finite origin, a zero or non-finite direction
  // or a NaN or negative maxDistance throws Error. A ray that starts inside a solid shape hits it
  // at distance 0 with normal -direction (as collide::rayCast).
  std::optional<RayCastResult> castRay(const Ray& ray, LayerMask mask = kAllLayers) const;
  // The same with a full filter (QueryFilter: layer mask, sensors, a callback per body).
  std::optional<RayCastResult> castRay(const Ray& ray, const QueryFilter& filter) const;
  // The first hit found, the cheapest ray (line of sight, "is anything there?"): not necessarily the
  // closest, but the same one for the same world. Input as castRay.
  std::optional<RayCastResult> castRayAny(const Ray& ray, const QueryFilter& filter = {}) const;
  // Every body the ray hits (one hit each, its first), sorted nearest first, equal distances by
  // body index. Input as castRay.
  std::vector<RayCastResult> castRayAll(const Ray& ray, const QueryFilter& filter = {}) const;
  // Hands each body the ray hits to the collector, which clips the ray or stops it (RayHitCollector);
  // no allocation of its own. Input as castRay; an unset collector throws Error.
  void castRayCollect(const Ray& ray, const RayHitCollector& collector, const QueryFilter& filter = {}) const;

  // Shape casts (sweeps): a convex shape (sphere, capsule, box, k-DOP, ellipsoid, cylinder, hull) at
  // `pose` moved along `translation` without turning, against every body the swept box reaches, by the
  // narrow phase's timeOfImpact. A start already touching (within 1.25 mm) reports fraction 0 and
  // initiallyOverlapping. A shape that is not convex, an invalid pose or a non-finite translation
  // throws Error. The earliest contact (ties to the lower body index):
  std::optional<ShapeCastResult> castShape(const Shape& shape, const Transform& pose, const Vec3& translation,
                                           const QueryFilter& filter = {}) const;
  // Every body reached, sorted by fraction, equal fractions by body index.
  std::vector<ShapeCastResult> castShapeAll(const Shape& shape, const Transform& pose,
                                            const Vec3& translation, const QueryFilter& filter = {}) const;

  // Every body the shape placed at `pose` overlaps exactly (the narrow phase's collide() finds a contact,
  // touching included; not just the boxes), sorted by body index. A mesh is its surface here: a shape
  // wholly inside a closed mesh does not overlap it. A plane query shape or an invalid pose throws Error.
  std::vector<OverlapResult> overlapShape(const Shape& shape, const Transform& pose,
                                          const QueryFilter& filter = {}) const;
  // The same, each answer handed to a collector as it is found (by body index, then part), which may
  // clip a cast or stop any of them early (queries.h); no list is built. An unset collector throws
  // Error.
  void castShapeCollect(const Shape& shape, const Transform& pose, const Vec3& translation,
                        const ShapeCastCollector& collector, const QueryFilter& filter = {}) const;
  void overlapShapeCollect(const Shape& shape, const Transform& pose, const OverlapCollector& collector,
                           const QueryFilter& filter = {}) const;
  void overlapPointCollect(const Vec3& point, const PointCollector& collector,
                           const QueryFilter& filter = {}) const;
  // Line of sight between two points, exact: true when no shape the filter sees (sensors aside,
  // unless asked) touches the segment, by the shapes themselves, not their boxes (a ray cast that
  // stops at the first hit). BroadPhase::hasLineOfSight is the conservative, cheaper test by boxes.
  // Non-finite points throw Error.
  bool hasLineOfSight(const Vec3& from, const Vec3& to, const QueryFilter& filter = {}) const;
  // Every body whose solid holds the point (collide::containsPoint: the boundary counts; a plane's solid
  // is its half-space; a closed mesh holds its inside, an open mesh no point), sorted by body index.
  // A non-finite point throws Error.
  std::vector<BodyId> overlapPoint(const Vec3& point, const QueryFilter& filter = {}) const;
  // The pairs the broad phase kept in the last step (proxy boxes overlapping, static-static never),
  // in its order (by proxy index); pairs with a body destroyed since are left out. For drawing and
  // inspection: it allocates.
  std::vector<BodyPair> broadPhasePairs() const;
  // The broad phase, read-only: its box queries, and visitNodes for drawing its structure. A body's
  // proxy box holds its shape grown by the contact tuning's speculative distance (by the step's
  // predicted motion too, from the start of a step), so between steps it holds where the body is.
  const BroadPhase& broadPhase() const;

  // Draws what `options` asks for through the engine's DebugDraw (collide/debug_draw.h,
  // docs/debug-draw.md): every part's shape (coloured by body type and state: DebugColors), world
  // boxes, the broad phase's structure, touching contacts with their normals and impulses, the
  // constraints, centres of mass; in slot order, the same calls for the same world. Out-of-range
  // lengths in the options throw Error before anything is drawn.
  void draw(DebugDraw& draw, const DebugDrawOptions& options = {}) const;

  // Sum over dynamic bodies.
  Vec3 linearMomentum() const;
  float kineticEnergy() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace collide
