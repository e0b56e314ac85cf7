// The joints of the soft step (joint_solver.h): the dispatch over the types of joints/, the
// position projection, the joints' loads and breaking, and their poses.
#include "dynamics/joint_solver.h"

#include "dynamics/continuous.h"
#include "dynamics/joints/joint_rows.h"

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

void warmStartJoints(const JointSolverView& view, Array<Joint>& joints) {
  for (Joint& joint : joints) {
    if (!joint.active) continue;
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
}

void solveJoints(const JointSolverView& view, Array<Joint>& joints, float h, float rigidHertz, bool useBias) {
  for (Joint& joint : joints) {
    if (!joint.active) continue;
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
}

void projectJoints(const JointSolverView& view, Array<Joint>& joints) {
  for (int pass = 0; pass < kJointProjectionPasses; ++pass) {
    bool projected = false;
    for (Joint& joint : joints) {
      if (!joint.active) continue;
      if (joint.type == JointType::Distance) projected |= projectDistance(view, joint);
    }
    if (!projected) break;
  }
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
