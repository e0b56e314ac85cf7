// What the mouse does to the World: drag a body (the lecture's picking: a ray from the cursor
// through the broad phase, World::castRay) and shoot spheres from the camera. No OpenGL here, so
// the viewer's tests drive it without a window.
#pragma once

#include <collide/world.h>

namespace collide::viewer {

// Pulls the grabbed point of a body towards the cursor, as Box2D's mouse joint: a soft spring of
// a few hertz whose stiffness scales with the body's mass, so light and heavy bodies follow alike.
// It is built from the library's own parts: a kinematic anchor body that collides with nothing
// (layer and mask 0) and a zero-length compliant distance constraint from the anchor to the hit
// point. While dragging, the anchor sits where the cursor's ray meets the plane facing the camera
// through the hit point (the hit's depth), so the body moves in the view plane.
class MouseSpring {
 public:
  float hertz = 4.0f;
  float dampingRatio = 0.7f;  // below 1: a little overshoot, so the pull is felt

  // Grabs the dynamic body the ray hits first, if any (static, kinematic and sensor bodies are not
  // grabbed; a body behind a static one is not either). `viewForward` is the camera's forward
  // direction, for the depth. Returns whether a body was grabbed. Releases any earlier grab.
  bool grab(World& world, const Ray& ray, const Vec3& viewForward);
  // Moves the anchor to the cursor's new ray at the grab's depth. Releases the grab if the body is
  // gone (destroyed since).
  void drag(World& world, const Ray& ray, const Vec3& viewForward);
  void release(World& world);
  // Drops the grab without touching the World: for when the World is replaced (restart).
  void forget() {
    body_ = anchor_ = BodyId{};
    joint_ = JointId{};
  }

  bool active() const { return !body_.isNull(); }
  BodyId body() const { return body_; }
  Vec3 target() const { return target_; }  // where the anchor is, world frame
  // The grabbed point on the body now, world frame.
  Vec3 grabbedPoint(const World& world) const;

 private:
  BodyId body_;
  BodyId anchor_;
  JointId joint_;
  Vec3 localPoint_{0.0f};  // the hit point in the body's frame
  float depth_ = 0.0f;     // along the view direction from the eye
  Vec3 target_{0.0f};
};

struct SphereShot {
  float speed = 40.0f;   // m/s
  float radius = 0.15f;  // m
  float density = 2000.0f;
  // rad/s about the axis across the shot (horizontal when possible): a spinning small ball is
  // the case the speculative contacts miss (docs/ccd.md), so spin is what shows tunnelling.
  float spin = 0.0f;
  bool ccd = true;  // BodyDef::ccd (the World's own ccd switch must be on too)
};

// Creates a dynamic sphere at the ray's origin moving along it at shot.speed; returns its id.
BodyId shootSphere(World& world, const Ray& ray, const SphereShot& shot);

}  // namespace collide::viewer
