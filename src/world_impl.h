// The world's data: what World's API bookkeeping (world.cpp) and its step (step.cpp) share. Each
// member belongs to the stage of its layer; the world only holds them and hands them over.
#pragma once

#include <collide/world.h>

#include "base/task_runner.h"
#include "bodies/body_bounds.h"
#include "bodies/body_storage.h"
#include "contacts/contact_cache.h"
#include "contacts/contact_events.h"
#include "contacts/contact_update.h"
#include "dynamics/island.h"
#include "dynamics/joint_solver.h"
#include "dynamics/solver.h"
#include "response/impacts.h"
#include "response/revert.h"

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

namespace collide {

// Throws Error naming the setting for a definition no world can run (world_def.cpp).
bool validateWorldDef(const WorldDef& def);

struct World::Impl {
  WorldDef def;
  detail::TaskRunner tasks;  // the step's parallel loops (workers as def says)
  detail::BodyStorage bodies;
  std::unique_ptr<BroadPhase> broadPhase;
  Array<ProxyPair> pairs;  // the broad phase's pairs of the last step
  detail::ProxyUpdate proxyUpdate;
  detail::ContactUpdate contactUpdate;
  Array<detail::Contact> contacts;      // in pair order
  Array<detail::ApartPair> apartPairs;  // the pairs the narrow phase found apart, in pair order
  detail::StepSolver stepSolver;
  Array<detail::Joint> joints;
  Array<std::uint32_t> jointGroups;  // the step's, for the continuous pass
  Array<std::uint32_t> freeJoints;
  std::size_t jointCount = 0;
  detail::StepEvents events;
  detail::Islands islands;
  detail::RevertResponse revert;
  detail::ImpactStage impacts;
  StepStats lastStats;
  StepStats totalStats;
  PreSolveCallback preSolve;
  PairFilter pairFilter;
  // The body pairs that constraints with collideConnected false keep apart, and how many such
  // constraints join each (detail::bodyPairKey).
  std::unordered_map<std::uint64_t, std::uint32_t> jointedApart;
  ContactListener* contactListener = nullptr;
  std::string callbackError;  // reported by step() once the step is complete
  std::size_t touchingCount = 0;
  float lastSubstep = 0.0f;  // the last step's substep, s (the joints' loads are impulses over it)

  // Whether the id names a live body of this generation (World::isValid).
  bool isLive(BodyId id) const;
  // The slot of a live body or joint; Error naming the operation for a stale or invalid id, and
  // without exceptions kBadSlot.
  static constexpr std::uint32_t kBadSlot = 0xFFFFFFFFu;
  std::uint32_t resolve(BodyId id, const char* operation) const;
  std::uint32_t resolve(JointId id, const char* operation) const;
  // What the getters read: the live body's or joint's record and state, or for a stale or invalid
  // id (Error; without exceptions) a default one.
  const detail::BodyRecord& recordOf(BodyId id, const char* operation) const;
  const detail::BodyState& stateOf(BodyId id, const char* operation) const;
  const detail::Joint& jointOf(JointId id, const char* operation) const;
  void freeJoint(std::uint32_t index);
  // Stores a new joint (its type's fields filled in), in a free slot if there is one, keeps its
  // bodies apart in the pair filters unless it lets them collide, and wakes both.
  JointId addJoint(detail::Joint joint);
  // Error (prefixed with `who`), and false, unless a and b are two different live bodies, one dynamic.
  bool requireJointBodies(BodyId a, BodyId b, const std::string& who) const;
  // A joint of `type` between a and b at the world anchor, its frame's x along `axis` (unset: the
  // world's frame), its local anchors and frames filled in; Error naming the field for bad bodies,
  // anchor or axis. `turns`: the joint holds the bodies' rotation, which a particle does not have.
  detail::Joint jointAt(BodyId a, BodyId b, const Vec3& anchor, const std::optional<Vec3>& axis,
                        JointType type, bool turns) const;
  // The live joint of `id` if its type is one of `types`; Error naming the operation otherwise (and
  // without exceptions null).
  detail::Joint* jointFor(JointId id, const char* operation, std::initializer_list<JointType> types);
  void wakeJoint(const detail::Joint& joint);
  // createHingeJoint and createSliderJoint (world_joints.cpp).
  template <typename Def>
  JointId addAxialJoint(const Def& def, JointType type);
  Vec3 anchorWorld(std::uint32_t body, const Vec3& localAnchor) const;
  // Body `index`'s contacts end (touching ones: End events with the next step's), what they touched
  // wakes (destroyBody, setEnabled).
  void endBodyContacts(std::uint32_t index);
  // Body `index`'s proxy: added with its box, layer and motion type; or, if it is enabled, given its
  // box and layer anew.
  void addProxy(std::uint32_t index);
  void updateProxy(std::uint32_t index);
  // Body `index`'s centre of mass moved by `shift` in its frame (new parts, a new type): the anchors
  // kept from the centre (its constraints', its contacts' friction anchors) follow.
  void centerMoved(std::uint32_t index, const Vec3& shift);
  // Gives body `index` these parts (World::addPart, removePart): setBodyParts, then the tallies, the
  // constraint anchors, the proxy and waking follow. Throws Error and changes nothing for parts the
  // body cannot have.
  void replaceParts(std::uint32_t index, Array<Compound::Child> children, Array<detail::PartRecord> parts);

  void step(float dt);
  WorldMemory memoryUse() const;  // World::memoryUse
};

}  // namespace collide
