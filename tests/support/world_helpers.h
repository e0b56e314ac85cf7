// Small scene builders shared by the world and dynamics tests.
#pragma once

#include <collide/world.h>

#include <vector>

namespace collide::test {

// The step of most world tests: 60 Hz.
inline constexpr float kDt = 1.0f / 60.0f;
inline constexpr float kG = 9.81f;  // m/s^2, the default gravity's magnitude

inline WorldDef zeroGravityWorld() {
  WorldDef def;
  def.gravity = Vec3(0.0f);
  return def;
}

inline BodyDef sphereBody(const Vec3& position, float radius, float mass, const Vec3& velocity = Vec3(0.0f)) {
  BodyDef def;
  def.shape = Shape(Sphere{radius});
  def.position = position;
  def.mass = mass;
  def.linearVelocity = velocity;
  return def;
}

inline BodyDef boxBody(const Vec3& position, const Vec3& halfExtents, float mass) {
  BodyDef def;
  def.shape = Shape(Box{halfExtents});
  def.position = position;
  def.mass = mass;
  return def;
}

// A particle: a point mass that collides as a sphere and never turns.
inline BodyDef particleBody(const Vec3& position, float radius, float mass) {
  BodyDef def = sphereBody(position, radius, mass);
  def.particle = true;
  return def;
}

// The inertia tensor of a solid box of `mass` and half extents `half` about its centre.
inline Mat3 boxInertia(float mass, const Vec3& half) {
  const Vec3 s = 2.0f * half;
  return Mat3(mass / 12.0f * (s.y * s.y + s.z * s.z), 0, 0, 0, mass / 12.0f * (s.x * s.x + s.z * s.z), 0, 0,
              0, mass / 12.0f * (s.x * s.x + s.y * s.y));
}

// A static ground whose top face is y = 0 (the reference scenes' 200 x 200 box).
inline BodyDef groundBox() {
  BodyDef def;
  def.type = BodyType::Static;
  def.shape = Shape(Box{Vec3(100.0f, 0.5f, 100.0f)});
  def.position = Vec3(0.0f, -0.5f, 0.0f);
  return def;
}

inline BodyDef groundPlane() {
  BodyDef def;
  def.type = BodyType::Static;
  def.shape = Shape(Plane{Vec3(0.0f, 1.0f, 0.0f), 0.0f});
  return def;
}

// A small static sphere to hang joints from.
inline BodyId staticAnchor(World& world, const Vec3& at) {
  BodyDef def;
  def.type = BodyType::Static;
  def.shape = Shape(Sphere{0.01f});
  def.position = at;
  return world.createBody(def);
}

// Every listed body's pose and velocities as raw bytes: equal means bit-identical.
inline std::vector<unsigned char> stateBytes(const World& world, const std::vector<BodyId>& bodies) {
  std::vector<unsigned char> bytes;
  const auto append = [&](const void* data, std::size_t size) {
    const auto* p = static_cast<const unsigned char*>(data);
    bytes.insert(bytes.end(), p, p + size);
  };
  for (const BodyId b : bodies) {
    const Transform t = world.transform(b);
    const Vec3 v = world.linearVelocity(b);
    const Vec3 w = world.angularVelocity(b);
    append(&t.position, sizeof t.position);
    append(&t.rotation, sizeof t.rotation);
    append(&v, sizeof v);
    append(&w, sizeof w);
  }
  return bytes;
}

}  // namespace collide::test
