// World::draw (collide/debug_draw.h, docs/debug-draw.md): the world's bodies, boxes, broad phase,
// contacts, constraints and centres of mass through an engine's DebugDraw.
#include <collide/debug_draw.h>

#include "base/fail.h"
#include "bodies/body_parts.h"
#include "world_impl.h"

#include <algorithm>
#include <cmath>
#include <iterator>

namespace collide {

using detail::BodyRecord;
using detail::BodyState;

namespace {

DebugColor bodyColor(const BodyRecord& r) {
  if (!r.enabled) return DebugColors::kDisabled;
  if (r.faulted) return DebugColors::kFaulted;
  switch (r.type) {
    case BodyType::Static:
      return DebugColors::kStatic;
    case BodyType::Kinematic:
      return DebugColors::kKinematic;
    case BodyType::Dynamic:
      break;
  }
  return r.awake ? DebugColors::kDynamic : DebugColors::kSleeping;
}

// Colours by tree depth: the root warm, deeper levels cycling through cooler hues.
DebugColor depthColor(int depth) {
  static constexpr DebugColor kLevels[] = {
      {1.00f, 0.45f, 0.25f}, {1.00f, 0.80f, 0.25f}, {0.55f, 0.95f, 0.30f}, {0.25f, 0.90f, 0.80f},
      {0.35f, 0.60f, 1.00f}, {0.75f, 0.45f, 1.00f}, {1.00f, 0.45f, 0.80f}};
  return kLevels[static_cast<std::size_t>(depth) % std::size(kLevels)];
}

void drawTriangles(DebugDraw& draw, const Shape& shape, const Transform& t, const DebugColor& color) {
  if (shape.type() == ShapeType::Compound) {
    for (const Compound::Child& child : shape.compound().children())
      drawTriangles(draw, child.shape, t * child.transform, color);
    return;
  }
  if (shape.type() != ShapeType::Mesh) return;
  const auto vertices = shape.mesh().vertices();
  for (const MeshTriangle& tri : shape.mesh().triangles()) {
    draw.drawTriangle(t.applyToPoint(vertices[tri.v[0]]), t.applyToPoint(vertices[tri.v[1]]),
                      t.applyToPoint(vertices[tri.v[2]]), color);
  }
}

// A joint's axis and limits at its anchor A, `length` long.
void drawJointFrame(DebugDraw& draw, const detail::JointPose& pose, const detail::Joint& joint,
                    float length) {
  if (joint.type != JointType::Hinge && joint.type != JointType::Slider && joint.type != JointType::Cone)
    return;
  const Vec3 at = pose.anchorA;
  draw.drawLine(at, at + length * pose.axisA, DebugColors::kJointAxis);
  // b's axis: its hinge or slider direction (on a's while the joint holds), a cone's swung axis.
  draw.drawLine(pose.anchorB, pose.anchorB + length * pose.axisB, DebugColors::kJointAxis);
  constexpr int kArcSegments = 12;
  if (joint.type == JointType::Hinge && joint.limits.enabled) {
    // The fan from the lower to the upper angle, from frame A's y axis turned about its x.
    const auto spoke = [&](float angle) {
      return at + length * (pose.frameA * Vec3(0.0f, std::cos(angle), std::sin(angle)));
    };
    draw.drawLine(at, spoke(joint.limits.lower), DebugColors::kJointLimit);
    draw.drawLine(at, spoke(joint.limits.upper), DebugColors::kJointLimit);
    for (int i = 0; i < kArcSegments; ++i) {
      const float span = joint.limits.upper - joint.limits.lower;
      draw.drawLine(spoke(joint.limits.lower + span * i / kArcSegments),
                    spoke(joint.limits.lower + span * (i + 1) / kArcSegments), DebugColors::kJointLimit);
    }
  } else if (joint.type == JointType::Slider && joint.limits.enabled) {
    const Vec3 across = length * 0.25f * (pose.frameA * Vec3(0.0f, 1.0f, 0.0f));
    for (const float offset : {joint.limits.lower, joint.limits.upper}) {
      const Vec3 mark = at + offset * pose.axisA;
      draw.drawLine(mark - across, mark + across, DebugColors::kJointLimit);
    }
    draw.drawLine(at + joint.limits.lower * pose.axisA, at + joint.limits.upper * pose.axisA,
                  DebugColors::kJointLimit);
  } else if (joint.type == JointType::Cone && joint.swingLimit < kPi) {
    // The rim: the directions at the swing angle from a's axis, round it.
    const auto rim = [&](float around) {
      const Vec3 local(std::cos(joint.swingLimit), std::sin(joint.swingLimit) * std::cos(around),
                       std::sin(joint.swingLimit) * std::sin(around));
      return at + length * (pose.frameA * local);
    };
    for (int i = 0; i < kArcSegments; ++i) {
      const float step = 2.0f * kPi / kArcSegments;
      draw.drawLine(rim(step * i), rim(step * (i + 1)), DebugColors::kJointLimit);
      if (i % 3 == 0) draw.drawLine(at, rim(step * i), DebugColors::kJointLimit);
    }
  }
}

}  // namespace

void World::draw(DebugDraw& draw, const DebugDrawOptions& options) const {
  const Impl& w = *impl_;
  if (!(options.normalLength >= 0.0f) || !(options.impulseScale >= 0.0f) || !(options.planeSize > 0.0f) ||
      !std::isfinite(options.normalLength) || !std::isfinite(options.impulseScale) ||
      !std::isfinite(options.planeSize)) {
    COLLIDE_FAIL(
        "world: draw: normalLength and impulseScale must be finite and >= 0, planeSize finite and > 0");
  }
  const auto& records = w.bodies.records;
  for (std::uint32_t i = 0; i < records.size(); ++i) {
    const BodyRecord& r = records[i];
    if (!r.alive) continue;
    const BodyState& s = w.bodies.states[i];
    const Transform pose = detail::bodyTransform(r, s);
    if (options.shapes) {
      const DebugColor color = bodyColor(r);
      for (std::uint32_t part = 0; part < detail::partCount(r); ++part) {
        const Shape& shape = detail::partShape(r, part);
        const Transform placed = pose * detail::partLocalPose(r, part);
        const DebugColor partColor =
            detail::partIsSensor(r, part) && r.enabled ? DebugColors::kSensor : color;
        drawShape(draw, shape, placed, partColor, options.planeSize);
        if (options.solidMeshes) drawTriangles(draw, shape, placed, partColor);
      }
    }
    if (options.bounds && r.enabled && r.shape.type() != ShapeType::Plane)
      drawBox(draw, worldBounds(r.shape, pose), DebugColors::kBounds);
    if (options.centersOfMass && r.type != BodyType::Static) {
      const Vec3 c = s.centerOfMass;
      const float l = options.normalLength;
      draw.drawLine(c, c + l * (s.rotation * Vec3(1.0f, 0.0f, 0.0f)), DebugColors::kAxisX);
      draw.drawLine(c, c + l * (s.rotation * Vec3(0.0f, 1.0f, 0.0f)), DebugColors::kAxisY);
      draw.drawLine(c, c + l * (s.rotation * Vec3(0.0f, 0.0f, 1.0f)), DebugColors::kAxisZ);
    }
    if (options.names && !r.name.empty()) draw.drawText(s.centerOfMass, r.name, DebugColors::kJoint);
  }
  if (options.broadPhase) {
    w.broadPhase->visitNodes([&](const BroadPhaseNode& node) {
      if (node.tree == MotionType::Static && !options.staticTree) return;
      if (node.depth < options.firstDepth || node.depth > options.lastDepth) return;
      drawBox(draw, node.box, depthColor(node.depth));
    });
  }
  if (options.contacts) {
    const float mark = 0.25f * options.normalLength;
    for (const detail::Contact& c : w.contacts) {
      if (!c.touching || c.sensor) continue;
      const Vec3 n = c.manifold.normal;
      for (int p = 0; p < c.manifold.count; ++p) {
        const Vec3 at = c.manifold.points[p].midpoint();
        draw.drawPoint(at, mark, DebugColors::kContactPoint);
        draw.drawLine(at, at + options.normalLength * n, DebugColors::kContactNormal);
        const float impulse = c.points[p].totalNormalImpulse;
        if (impulse > 0.0f)
          draw.drawLine(at, at + options.impulseScale * impulse * n, DebugColors::kContactImpulse);
      }
    }
  }
  if (options.joints) {
    for (const detail::Joint& joint : w.joints) {
      if (!joint.alive) continue;
      const Vec3 a = w.anchorWorld(joint.bodyA, joint.localAnchorA);
      const Vec3 b = w.anchorWorld(joint.bodyB, joint.localAnchorB);
      draw.drawLine(a, b, DebugColors::kJoint);
      draw.drawPoint(a, 0.25f * options.normalLength, DebugColors::kJoint);
      draw.drawPoint(b, 0.25f * options.normalLength, DebugColors::kJoint);
      drawJointFrame(draw, detail::jointPose(w.bodies, joint), joint, options.normalLength);
    }
  }
}

}  // namespace collide
