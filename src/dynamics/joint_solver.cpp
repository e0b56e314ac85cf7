// The joints of the soft step (joint_solver.h): the dispatch over the types of joints/, the
// position projection, the joints' loads and breaking, and their poses.
#include "dynamics/joint_solver.h"

#include "dynamics/continuous.h"
#include "dynamics/joints/joint_rows.h"
#include "memory/heap_bytes.h"

#include <algorithm>
#include <cmath>

namespace collide::detail {

namespace {

bool isAwakeDynamic(const BodyRecord& r) { return r.alive && r.type == BodyType::Dynamic && r.awake; }

}  // namespace

float twistAngle(const Quat& q) {
  // The twist about x of q = swing * twist is the turn whose quaternion is (w, x, 0, 0) normalised;
  // taking w >= 0 picks the short way, an angle in (-pi, pi].
  return q.w >= 0.0f ? 2.0f * std::atan2(q.x, q.w) : 2.0f * std::atan2(-q.x, -q.w);
}

void prepareJoints(const JointSolverView& view, Array<Joint>& joints) {
  for (Joint& joint : joints) {
    const BodyRecord& a = view.storage.records[joint.bodyA];
    const BodyRecord& b = view.storage.records[joint.bodyB];
    // A disabled body takes no part in the step: its constraints rest with it.
    joint.active = joint.alive && a.enabled && b.enabled && (isAwakeDynamic(a) || isAwakeDynamic(b));
  }
}

namespace {

void warmStartJoint(const JointSolverView& view, Joint& joint) {
  switch (joint.type) {
    case JointType::Distance:
      warmStartDistance(view, joint);
      break;
    case JointType::Ball:
      warmStartBall(view, joint);
      break;
    case JointType::Hinge:
      warmStartHinge(view, joint);
      break;
    case JointType::Slider:
      warmStartSlider(view, joint);
      break;
    case JointType::Fixed:
      warmStartFixed(view, joint);
      break;
    case JointType::Cone:
      warmStartCone(view, joint);
      break;
  }
}

void solveJoint(const JointSolverView& view, Joint& joint, float h, float rigidHertz, bool useBias) {
  switch (joint.type) {
    case JointType::Distance:
      solveDistance(view, joint, h, rigidHertz, useBias);
      break;
    case JointType::Ball:
      solveBall(view, joint, h, rigidHertz, useBias);
      break;
    case JointType::Hinge:
      solveHinge(view, joint, h, rigidHertz, useBias);
      break;
    case JointType::Slider:
      solveSlider(view, joint, h, rigidHertz, useBias);
      break;
    case JointType::Fixed:
      solveFixed(view, joint, h, rigidHertz, useBias);
      break;
    case JointType::Cone:
      solveCone(view, joint, h, rigidHertz, useBias);
      break;
  }
}

}  // namespace

void JointWaves::prepare(const JointSolverView& view, const Array<Joint>& joints) {
  // The solver body a joint writes: a dynamic one (a particle's, a stopped body's too).
  const auto written = [&](std::uint32_t body) {
    const std::int32_t j = view.solverOf[body];
    return j != kNoSolverBody && view.infos[static_cast<std::size_t>(j)].dynamic ? j : std::int32_t{-1};
  };
  waveOf_.clear();
  waveStart_.assign(1, 0);
  if (joints.empty()) return;  // and the per-body scratch below is not grown
  lastWave_.assign(view.bodies.size(), 0);
  for (const Joint& joint : joints) {
    if (!joint.active) continue;
    const std::int32_t a = written(joint.bodyA);
    const std::int32_t b = written(joint.bodyB);
    std::uint32_t wave = 0;
    if (a >= 0) wave = std::max(wave, lastWave_[static_cast<std::size_t>(a)]);
    if (b >= 0) wave = std::max(wave, lastWave_[static_cast<std::size_t>(b)]);
    if (a >= 0) lastWave_[static_cast<std::size_t>(a)] = wave + 1;
    if (b >= 0) lastWave_[static_cast<std::size_t>(b)] = wave + 1;
    waveOf_.push_back(wave);
    if (waveStart_.size() < wave + 2) waveStart_.resize(wave + 2, 0);
    ++waveStart_[wave + 1];
  }
  for (std::size_t w = 0; w + 1 < waveStart_.size(); ++w) waveStart_[w + 1] += waveStart_[w];
  order_.resize(waveOf_.size());
  Array<std::uint32_t>& fill = lastWave_;  // reused: the next slot of each wave
  fill.assign(waveStart_.begin(), waveStart_.end());
  std::size_t k = 0;
  for (std::uint32_t i = 0; i < joints.size(); ++i) {
    if (joints[i].active) order_[fill[waveOf_[k++]]++] = i;
  }
}

void JointWaves::plan(const Array<Joint>& joints) {
  distance_.clear();
  for (std::uint32_t i = 0; i < joints.size(); ++i) {
    if (joints[i].active && joints[i].type == JointType::Distance) distance_.push_back(i);
  }
  groups_.clear();
  alone_.clear();
  groupStart_.assign(1, 0);
  aloneStart_.assign(1, 0);
  // A joint in no tree at the step's start stays out of them all step (only a tree's own joints
  // leave and rejoin it), and its type and friction do not change within a step.
  for (std::size_t w = 0; w + 1 < waveStart_.size(); ++w) {
    std::uint32_t waiting[kBallLanes];
    int count = 0;
    for (std::uint32_t k = waveStart_[w]; k < waveStart_[w + 1]; ++k) {
      const std::uint32_t i = order_[k];
      if (!ballInLanes(joints[i])) {
        alone_.push_back(i);
        continue;
      }
      waiting[count++] = i;
      if (count == kBallLanes) {
        loadBallGroup(joints, waiting, groups_.emplace_back());
        count = 0;
      }
    }
    // The last few of a wave go alone (a wave's joints share no moving body, so the order within
    // a wave changes nothing).
    for (int p = 0; p < count; ++p) alone_.push_back(waiting[p]);
    groupStart_.push_back(static_cast<std::uint32_t>(groups_.size()));
    aloneStart_.push_back(static_cast<std::uint32_t>(alone_.size()));
  }
}

void JointWaves::finish(Array<Joint>& joints) {
  for (const BallLaneGroup& group : groups_) storeBallGroup(group, joints);
}

template <typename One, typename Four>
void JointWaves::forEachJoint(const JointSolverView& view, Array<Joint>& joints, TaskRunner& tasks, One&& one,
                              Four&& four) {
  // A wave's groups lie in one run; its other joints and every body lie anywhere in their arrays (a
  // grid's or a pile's). When the bodies outgrow the cache, a joint alone is asked for ahead in two
  // stages: its record eight places on, then, four places on and with its body indices at hand,
  // what jointBody reads of its bodies. A group's bodies are not: the lookups cost more than the
  // misses they saved (joint_grid 3 % slower with the next group's bodies asked for, 4 % with the
  // one after).
  constexpr std::uint32_t kAhead = kJointBodiesAhead;
  const bool ahead = jointBodiesOutgrowCache(view);
  for (std::size_t w = 0; w + 1 < groupStart_.size(); ++w) {
    const std::uint32_t firstGroup = groupStart_[w];
    const std::uint32_t groups = groupStart_[w + 1] - firstGroup;
    const std::uint32_t firstAlone = aloneStart_[w];
    const std::uint32_t alone = aloneStart_[w + 1] - firstAlone;
    // Items: the groups, then the joints alone; a range holds about kJointsPerRange joints.
    const std::uint32_t perRange = groups > alone ? kJointsPerRange / kBallLanes : kJointsPerRange;
    tasks.parallelFor(groups + alone, perRange, [&](std::uint32_t first, std::uint32_t last, std::uint32_t) {
      for (std::uint32_t item = first; item < std::min(last, groups); ++item) {
        four(groups_[firstGroup + item]);
      }
      if (last <= groups) return;
      const std::uint32_t end = firstAlone + (last - groups);
      for (std::uint32_t k = firstAlone + (std::max(first, groups) - groups); k < end; ++k) {
        if (ahead && k + 2 * kAhead < end) prefetchRecord(joints[alone_[k + 2 * kAhead]]);
        if (ahead && k + kAhead < end) prefetchJointBodies(view, joints[alone_[k + kAhead]]);
        one(alone_[k]);
      }
    });
  }
}

void JointWaves::warmStart(const JointSolverView& view, Array<Joint>& joints, TaskRunner& tasks) {
  forEachJoint(
      view, joints, tasks, [&](std::uint32_t i) { warmStartJoint(view, joints[i]); },
      [&](const BallLaneGroup& group) { warmStartBalls(view, group); });
}

void JointWaves::solve(const JointSolverView& view, Array<Joint>& joints, float h, float rigidHertz,
                       bool useBias, TaskRunner& tasks) {
  forEachJoint(
      view, joints, tasks, [&](std::uint32_t i) { solveJoint(view, joints[i], h, rigidHertz, useBias); },
      [&](BallLaneGroup& group) { solveBalls(view, group, h, rigidHertz, useBias); });
}

std::size_t JointWaves::memoryBytes() const {
  return heapBytes(order_) + heapBytes(waveStart_) + heapBytes(waveOf_) + heapBytes(lastWave_) +
         heapBytes(groups_) + heapBytes(groupStart_) + heapBytes(alone_) + heapBytes(aloneStart_) +
         heapBytes(distance_);
}

bool projectJoints(const JointSolverView& view, Array<Joint>& joints,
                   std::span<const std::uint32_t> distance) {
  bool moved = false;
  for (int pass = 0; pass < kJointProjectionPasses; ++pass) {
    bool projected = false;
    for (const std::uint32_t i : distance) projected |= projectDistance(view, joints[i]);
    if (!projected) break;
    moved = true;
  }
  return moved;
}

void jointGroups(const BodyStorage& storage, const Array<Joint>& joints, Array<std::uint32_t>& groupOf) {
  groupOf.assign(storage.records.size(), kNoJointGroup);
  const auto root = [&](std::uint32_t i) {
    while (groupOf[i] != i) i = groupOf[i] = groupOf[groupOf[i]];
    return i;
  };
  for (const Joint& joint : joints) {
    if (!joint.alive || !joint.active) continue;
    const BodyRecord& a = storage.records[joint.bodyA];
    const BodyRecord& b = storage.records[joint.bodyB];
    if (a.type != BodyType::Dynamic || b.type != BodyType::Dynamic) continue;
    for (const std::uint32_t body : {joint.bodyA, joint.bodyB}) {
      if (groupOf[body] == kNoJointGroup) groupOf[body] = body;
    }
    const std::uint32_t rootA = root(joint.bodyA);
    const std::uint32_t rootB = root(joint.bodyB);
    groupOf[std::max(rootA, rootB)] = std::min(rootA, rootB);
  }
  for (std::uint32_t i = 0; i < groupOf.size(); ++i) {
    if (groupOf[i] != kNoJointGroup) groupOf[i] = root(i);
  }
}

JointLoad jointLoad(const Joint& joint, float h) {
  const float axial = axialImpulse(joint);
  float force = glm::length(joint.linearImpulse);
  float torque = glm::length(joint.angularImpulse);
  switch (joint.type) {
    case JointType::Distance:
      force = std::abs(joint.impulse + joint.lowerImpulse - joint.upperImpulse);
      torque = 0.0f;
      break;
    case JointType::Ball:
      torque = glm::length(joint.frictionImpulse);
      break;
    case JointType::Hinge:
      torque = glm::length(Vec3(axial, joint.angularImpulse.y, joint.angularImpulse.z));
      break;
    case JointType::Slider:
      force = glm::length(Vec3(axial, joint.linearImpulse.y, joint.linearImpulse.z));
      break;
    case JointType::Fixed:
      break;
    case JointType::Cone:
      torque = std::abs(joint.swingImpulse) + std::abs(joint.lowerImpulse - joint.upperImpulse) +
               glm::length(joint.frictionImpulse);
      break;
  }
  return {force / h, torque / h};
}

void findBrokenJoints(const BodyStorage& storage, const Array<Joint>& joints, float h,
                      Array<JointBreakEvent>& broken) {
  for (std::uint32_t i = 0; i < joints.size(); ++i) {
    const Joint& joint = joints[i];
    if (!joint.active || (joint.breakForce == kUnbreakable && joint.breakTorque == kUnbreakable)) continue;
    const JointLoad load = jointLoad(joint, h);
    if (load.force > joint.breakForce || load.torque > joint.breakTorque) {
      broken.push_back({JointId{i, joint.generation}, storage.idOf(joint.bodyA), storage.idOf(joint.bodyB),
                        load.force, load.torque});
    }
  }
}

JointPose jointPose(const BodyStorage& storage, const Joint& joint) {
  const BodyState& a = storage.states[joint.bodyA];
  const BodyState& b = storage.states[joint.bodyB];
  JointPose pose;
  pose.anchorA = a.centerOfMass + a.rotation * joint.localAnchorA;
  pose.anchorB = b.centerOfMass + b.rotation * joint.localAnchorB;
  pose.frameA = a.rotation * joint.localFrameA;
  pose.frameB = b.rotation * joint.localFrameB;
  pose.axisA = pose.frameA * Vec3(1.0f, 0.0f, 0.0f);
  pose.axisB = pose.frameB * Vec3(1.0f, 0.0f, 0.0f);
  switch (joint.type) {
    case JointType::Distance:
      pose.position = glm::length(pose.anchorB - pose.anchorA);
      break;
    case JointType::Hinge:
    case JointType::Cone:
      pose.position = twistAngle(glm::conjugate(pose.frameA) * pose.frameB);
      break;
    case JointType::Slider:
      pose.position = glm::dot(pose.axisA, pose.anchorB - pose.anchorA);
      break;
    case JointType::Ball:
    case JointType::Fixed:
      break;
  }
  return pose;
}

}  // namespace collide::detail
