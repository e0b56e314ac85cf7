// Body storage: two contiguous arrays indexed by the body's slot. BodyState holds what the solver
// touches every substep (Box2D v3's b2BodyState / b2BodySim split: hot data walked linearly);
// BodyRecord holds the rest. Static and kinematic bodies have zero inverse mass and inertia, so the
// solver treats every pair the same way and the infinite-mass partner of a one-way pair never moves.
#pragma once

#include <collide/body.h>
#include <collide/broadphase.h>
#include <collide/narrowphase.h>
#include <collide/shapes.h>

#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace collide::detail {

struct BodyState {
  Vec3 centerOfMass{0.0f};  // world
  Quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
  Vec3 linearVelocity{0.0f};
  Vec3 angularVelocity{0.0f};
  Mat3 inverseInertiaWorld{0.0f};  // R I^-1 R^T, refreshed at the end of every step
  float inverseMass = 0.0f;
  // Where the step started: the solver measures current separations from these (Catto's
  // "relative positions": anchors move with the body's change of pose, not re-queried).
  Vec3 centerOfMass0{0.0f};
  Quat rotation0{1.0f, 0.0f, 0.0f, 0.0f};
};

// What a part of a body made of parts holds besides its shape and local pose (those are the body
// shape's compound child of the same index).
struct PartRecord {
  BodyMaterial material;
  float density = 1000.0f;
  bool sensor = false;
  std::uint32_t layer = 1;
  std::uint32_t mask = kAllLayers;
  std::int32_t group = 0;
  std::uint64_t userData = 0;
};

struct BodyRecord {
  // First the fields every narrow-phase pair reads (two records per pair: kept within the first
  // cache lines of the record, which matters in a scene of thousands of pairs).
  Shape shape{Sphere{}};
  BodyType type = BodyType::Dynamic;
  bool sensor = false;
  bool alive = false;
  bool awake = true;
  bool faulted = false;          // frozen by the fault guard (dynamics/fault_guard.h)
  bool enabled = true;           // World::setEnabled: a disabled body has no proxy and never wakes
  bool particle = false;         // point mass: no inertia, the rotation never changes
  bool ccd = false;              // BodyDef::ccd (never for sensors)
  bool isotropicInertia = true;  // I = lambda 1 (spheres, cubes...): w x (I w) = 0, no gyroscopic term
  std::uint32_t generation = 1;
  std::uint32_t layer = 1;
  std::uint32_t mask = kAllLayers;
  std::int32_t group = 0;
  float scale = 1.0f;
  float boundingRadius = 0.0f;  // around the centre of mass, for the speculative margin
  float originRadius = 0.0f;    // around the body origin, every body type (the manifold cache)
  // A body made of parts (BodyDef::parts): one record per child of `shape`, a compound; empty for a
  // body of one shape, whose part 0 is the shape and the record's own fields. For a body made of
  // parts, the record's fields summarise the parts: sensor when every part is one, layer and mask
  // the union of the parts', group 0, the material part 0's. Here, not with the other arrays: every
  // pair asks whether its bodies have parts.
  Array<PartRecord> parts;
  float bounciness = 0.0f;
  float friction = 0.5f;
  float rollingResistance = 0.0f;  // m
  float gravityScale = 1.0f;
  float linearDamping = 0.0f;    // 1/s
  float angularDamping = 0.0f;   // 1/s
  Vec3 localCenterOfMass{0.0f};  // in the body frame, already scaled
  ProxyId proxy;
  float mass = 0.0f;
  float minExtent = 0.0f;  // half the smallest side of the local box, scaled: "fast" is relative to it
  // Sleeping (WorldDef::sleeping): a sleeping body is skipped by integration and the solver.
  float sleepTime = 0.0f;    // s spent below the sleep thresholds
  std::uint32_t island = 0;  // the island's root body when it fell asleep
  Mat3 inertiaLocal{0.0f};   // about the centre of mass, body axes (zero for particles)
  Mat3 inverseInertiaLocal{0.0f};
  // The last exactly computed world box and the pose it was computed at (World::currentBounds).
  Aabb bounds;
  Vec3 boundsCenter{0.0f};
  Quat boundsRotation{1.0f, 0.0f, 0.0f, 0.0f};
  bool boundsValid = false;
  // The last pose at which the body penetrated nothing (PenetrationResponse::Revert goes back there).
  Vec3 validCenterOfMass{0.0f};
  Quat validRotation{1.0f, 0.0f, 0.0f, 0.0f};
  Vec3 force{0.0f};
  Vec3 torque{0.0f};
  std::string name;
  std::uint64_t userData = 0;
  std::optional<float> givenMass;  // BodyDef::mass: kept when parts are added or removed
  float density = 1000.0f;         // BodyDef::density: a body of one shape's part 0, if parts are added
};

class BodyStorage {
 public:
  std::uint32_t allocate();  // a free slot (reused first), record marked alive
  void free(std::uint32_t index);

  BodyId idOf(std::uint32_t index) const { return {index, records[index].generation}; }
  bool isAwakeDynamic(std::uint32_t index) const {
    const BodyRecord& r = records[index];
    return r.alive && r.type == BodyType::Dynamic && r.awake;
  }
  bool isSleeping(std::uint32_t index) const {
    const BodyRecord& r = records[index];
    return r.alive && r.type == BodyType::Dynamic && !r.awake;
  }
  bool isMovingKinematic(std::uint32_t index) const {
    const BodyState& s = states[index];
    return records[index].type == BodyType::Kinematic &&
           (s.linearVelocity != Vec3(0.0f) || s.angularVelocity != Vec3(0.0f));
  }
  // Forces and torques act for one step: cleared once it is solved.
  void clearForces();
  // The heap the bodies hold (World::memoryUse): the arrays, each record's parts and name.
  std::size_t memoryBytes() const;

  // The live bodies with a bounciness or a rolling resistance above 0, and the sensors (a part of
  // the body counts)
  // (World::createBody and destroyBody keep them; so must any setter of these fields): the stages
  // that only such bodies need (Newton impacts, rolling resistance, sensor crossings) skip their
  // scan of every contact or pair when there are none.
  void tally(const BodyRecord& record, int sign) {
    bool bouncy = record.bounciness > 0.0f, rolling = record.rollingResistance > 0.0f, sensor = record.sensor;
    for (const PartRecord& part : record.parts) {
      bouncy = bouncy || part.material.bounciness > 0.0f;
      rolling = rolling || part.material.rollingResistance > 0.0f;
      sensor = sensor || part.sensor;
    }
    if (bouncy) bouncyCount += sign;
    if (rolling) rollingCount += sign;
    if (sensor) sensorCount += sign;
  }

  Array<BodyRecord> records;
  Array<BodyState> states;
  std::size_t aliveCount = 0;
  std::size_t bouncyCount = 0;
  std::size_t rollingCount = 0;
  std::size_t sensorCount = 0;

  // The slots free for reuse, the last one taken first (a world snapshot keeps their order).
  const Array<std::uint32_t>& freeSlots() const { return freeSlots_; }
  // Takes records, states and free slots as a world snapshot had them; the counts follow. Throws
  // Error for free slots that are out of range, alive, or listed twice.
  void restore(Array<BodyRecord> records, Array<BodyState> states, Array<std::uint32_t> freeSlots);

 private:
  Array<std::uint32_t> freeSlots_;
};

// A pose every query on the body's shape takes: a finite centre and a finite unit rotation (the
// tolerance of isValid(Transform)). A step can leave a body without one (an overflowing velocity, a
// spin that integrates to a zero quaternion); the stages between the solve and the fault guard,
// which then freezes it, pass such a body by.
inline bool hasValidPose(const BodyState& state) {
  return isFinite(state.centerOfMass) && isFinite(state.rotation) &&
         std::abs(glm::dot(state.rotation, state.rotation) - 1.0f) < 1e-3f;
}

// The body origin (what the user places) from the centre of mass and rotation.
inline Vec3 bodyOrigin(const BodyRecord& record, const BodyState& state) {
  return state.centerOfMass - state.rotation * record.localCenterOfMass;
}

inline Transform bodyTransform(const BodyRecord& record, const BodyState& state) {
  return {bodyOrigin(record, state), state.rotation, record.scale};
}

// The body's motion over the step so far: from its pose at the step's start to its pose now.
inline Sweep bodySweep(const BodyRecord& record, const BodyState& state) {
  Sweep sweep;
  sweep.localCenter = record.localCenterOfMass;
  sweep.center0 = state.centerOfMass0;
  sweep.center1 = state.centerOfMass;
  sweep.rotation0 = state.rotation0;
  sweep.rotation1 = state.rotation;
  sweep.scale = record.scale;
  return sweep;
}

inline Mat3 worldInverseInertia(const Mat3& inverseInertiaLocal, const Quat& rotation) {
  const Mat3 r = glm::mat3_cast(rotation);
  return r * inverseInertiaLocal * glm::transpose(r);
}

}  // namespace collide::detail
