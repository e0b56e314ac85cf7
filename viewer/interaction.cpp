#include "interaction.h"

#include <cmath>
#include <numbers>

namespace collide::viewer {

bool MouseSpring::grab(World& world, const Ray& ray, const Vec3& viewForward) {
  release(world);
  const std::optional<RayCastResult> hit = world.castRay(ray);
  if (!hit || world.type(hit->body) != BodyType::Dynamic) return false;
  body_ = hit->body;
  // A particle cannot turn, so its anchor must be its centre: it is pulled by the centre.
  const bool particle = world.isParticle(body_);
  localPoint_ = particle ? Vec3(0.0f) : world.transform(body_).inverseApplyToPoint(hit->point);
  depth_ = glm::dot(hit->point - ray.origin, viewForward);
  target_ = hit->point;

  BodyDef anchor;
  anchor.type = BodyType::Kinematic;
  anchor.shape = Shape(Sphere{0.01f});
  anchor.position = hit->point;
  anchor.layer = 0;  // touches nothing, and castRay never finds it
  anchor.mask = 0;
  anchor.name = "mouse spring anchor";
  anchor_ = world.createBody(anchor);

  // Stiffness m omega^2 (compliance is its inverse): the same few hertz whatever the mass.
  const float omega = 2.0f * std::numbers::pi_v<float> * hertz;
  DistanceConstraintDef spring;
  spring.a = anchor_;
  spring.b = body_;
  spring.localAnchorA = Vec3(0.0f);
  if (!particle) spring.localAnchorB = localPoint_;
  spring.length = 0.0f;
  spring.compliance = 1.0f / (world.mass(body_) * omega * omega);
  spring.dampingRatio = dampingRatio;
  joint_ = world.createDistanceConstraint(spring);
  world.wakeBody(body_);
  return true;
}

void MouseSpring::drag(World& world, const Ray& ray, const Vec3& viewForward) {
  if (!active()) return;
  if (!world.isValid(body_) || !world.isValid(joint_)) {
    release(world);
    return;
  }
  // The cursor's ray meets the plane facing the camera at the grab's depth at this distance.
  const float along = glm::dot(ray.direction, viewForward);
  if (along <= 1e-4f) return;  // the ray runs parallel to that plane: keep the last target
  target_ = ray.origin + ray.direction * (depth_ / along);
  world.setTransform(anchor_, target_, Quat(1.0f, 0.0f, 0.0f, 0.0f));
  world.wakeBody(body_);
}

void MouseSpring::release(World& world) {
  // Destroying the anchor destroys the constraint; the body may be gone already.
  if (!anchor_.isNull() && world.isValid(anchor_)) world.destroyBody(anchor_);
  forget();
}

Vec3 MouseSpring::grabbedPoint(const World& world) const {
  if (!active() || !world.isValid(body_)) return target_;
  if (world.isParticle(body_)) return world.centerOfMass(body_);
  return world.transform(body_).applyToPoint(localPoint_);
}

BodyId shootSphere(World& world, const Ray& ray, const SphereShot& shot) {
  const Vec3 direction = glm::normalize(ray.direction);
  BodyDef def;
  def.shape = Shape(Sphere{shot.radius});
  def.position = ray.origin;
  def.linearVelocity = shot.speed * direction;
  // Spin about the horizontal axis across the shot, or about x for a vertical shot.
  Vec3 across = glm::cross(direction, Vec3(0.0f, 1.0f, 0.0f));
  if (glm::length(across) < 1e-3f) across = Vec3(1.0f, 0.0f, 0.0f);
  def.angularVelocity = shot.spin * glm::normalize(across);
  def.density = shot.density;
  def.ccd = shot.ccd;
  def.name = "shot";
  return world.createBody(def);
}

}  // namespace collide::viewer
