// Debug drawing (docs/debug-draw.md): the interface an engine implements to see what collide sees,
// and what World::draw can draw through it. collide hands out world-space lines (and points, and
// optionally triangles and text) with a colour; the engine draws them however it draws lines.
#pragma once

#include <collide/math.h>
#include <collide/shapes.h>

#include <cstdint>
#include <string_view>

namespace collide {

// Red, green, blue in [0, 1].
using DebugColor = Vec3;

class DebugDraw {
 public:
  virtual ~DebugDraw() = default;
  virtual void drawLine(const Vec3& from, const Vec3& to, const DebugColor& color) = 0;
  // A marked point (a contact, a centre of mass); `size` is the length of the mark in metres. By
  // default three short crossed lines.
  virtual void drawPoint(const Vec3& point, float size, const DebugColor& color);
  // Optional: filled triangles (meshes' faces when DebugDrawOptions::solidMeshes) and text.
  virtual void drawTriangle(const Vec3& a, const Vec3& b, const Vec3& c, const DebugColor& color) {
    (void)a, (void)b, (void)c, (void)color;
  }
  virtual void drawText(const Vec3& at, std::string_view text, const DebugColor& color) {
    (void)at, (void)text, (void)color;
  }
};

// What World::draw draws. Each flag is one kind of thing; the colours say what a body is.
struct DebugDrawOptions {
  bool shapes = true;       // every part's shape as a wireframe, coloured by body type and state
  bool bounds = false;      // each body's world box
  bool broadPhase = false;  // the broad phase's structure (tree nodes by depth, or grid cells)
  bool staticTree = false;  // with broadPhase: the static bodies' tree too
  int firstDepth = 0;       // with broadPhase: the tree's levels from firstDepth to lastDepth
  int lastDepth = 1 << 30;
  bool contacts = false;  // touching contacts: points, normals and normal impulses
  // Each joint: its anchors and the line between them; a hinge's, slider's and cone's axis (as body
  // a carries it) and its current direction in b; a hinge's angle limits as a fan, a slider's as
  // marks on its axis, a cone's swing limit as the cone's rim (all normalLength long).
  bool joints = false;
  bool centersOfMass = false;  // each movable body's centre of mass and axes
  bool solidMeshes = false;    // meshes' triangles through drawTriangle as well as their edges
  bool names = false;          // each named body's name at its centre, through drawText
  float normalLength = 0.3f;   // m, the drawn contact normal
  float impulseScale = 0.1f;   // m per N s: the drawn normal impulse along the normal
  float planeSize = 20.0f;     // m, the side of the square that stands for a plane
};

// The colours World::draw uses.
struct DebugColors {
  static constexpr DebugColor kStatic{0.55f, 0.55f, 0.55f};
  static constexpr DebugColor kKinematic{0.35f, 0.55f, 1.0f};
  static constexpr DebugColor kDynamic{1.0f, 0.65f, 0.2f};
  static constexpr DebugColor kSleeping{0.5f, 0.33f, 0.1f};  // a dynamic body asleep
  static constexpr DebugColor kFaulted{1.0f, 0.0f, 1.0f};    // frozen by the fault guard
  static constexpr DebugColor kSensor{0.2f, 0.9f, 0.4f};     // a sensor part, whatever its body
  static constexpr DebugColor kDisabled{0.3f, 0.3f, 0.3f};
  static constexpr DebugColor kBounds{0.2f, 0.9f, 0.3f};
  static constexpr DebugColor kContactPoint{1.0f, 0.2f, 0.2f};
  static constexpr DebugColor kContactNormal{1.0f, 0.9f, 0.2f};
  static constexpr DebugColor kContactImpulse{1.0f, 0.4f, 0.1f};
  static constexpr DebugColor kJoint{0.9f, 0.9f, 0.9f};
  static constexpr DebugColor kJointAxis{0.9f, 0.3f, 0.9f};
  static constexpr DebugColor kJointLimit{0.6f, 0.3f, 0.9f};
  static constexpr DebugColor kAxisX{1.0f, 0.0f, 0.0f};
  static constexpr DebugColor kAxisY{0.0f, 1.0f, 0.0f};
  static constexpr DebugColor kAxisZ{0.0f, 0.0f, 1.0f};
};

// The shape at `transform` as a wireframe: a box's and a polyhedron's edges, a sphere's and an
// ellipsoid's three principal circles, a capsule's and a cylinder's end circles with four lines
// along the sides (and a capsule's caps' half circles), a mesh's triangle edges, a compound's
// children, a plane as a square of side `planeSize` centred on the point of the plane nearest the
// transform's origin, with its normal. Curves are drawn with `segments` lines per circle (>= 3).
void drawShape(DebugDraw& draw, const Shape& shape, const Transform& transform, const DebugColor& color,
               float planeSize = 20.0f, int segments = 24);

// The box's twelve edges.
void drawBox(DebugDraw& draw, const Aabb& box, const DebugColor& color);

}  // namespace collide
