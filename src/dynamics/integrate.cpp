// Symplectic Euler per substep, as in Box2D v3's b2IntegrateVelocitiesTask / b2IntegratePositionsTask:
// velocities first (gravity, forces), then the constraints act on them, then positions move by the
// new velocities. No gyroscopic term (Box2D 2D has none; small for the compact shapes of games).
#include "dynamics/body_storage.h"

namespace collide::detail {

void integrateVelocities(BodyStorage& bodies, const Vec3& gravity, float h) {
  const std::size_t n = bodies.states.size();
  for (std::size_t i = 0; i < n; ++i) {
    const BodyRecord& record = bodies.records[i];
    if (!record.alive || record.type != BodyType::Dynamic) continue;
    BodyState& s = bodies.states[i];
    s.linearVelocity += h * (gravity + s.inverseMass * record.force);
    s.angularVelocity += h * (s.inverseInertiaWorld * record.torque);
  }
}

void integratePositions(BodyStorage& bodies, float h) {
  const std::size_t n = bodies.states.size();
  for (std::size_t i = 0; i < n; ++i) {
    const BodyRecord& record = bodies.records[i];
    if (!record.alive || record.type == BodyType::Static) continue;
    BodyState& s = bodies.states[i];
    s.centerOfMass += h * s.linearVelocity;
    const Vec3& w = s.angularVelocity;
    const Quat spin(0.0f, w.x, w.y, w.z);
    Quat q = s.rotation;
    q = q + (0.5f * h) * (spin * q);
    s.rotation = glm::normalize(q);
    if (record.type == BodyType::Dynamic) {
      s.inverseInertiaWorld = worldInverseInertia(record.inverseInertiaLocal, s.rotation);
    }
  }
}

}  // namespace collide::detail
