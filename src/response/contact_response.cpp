// The lecture's friction models applied to the step's prolonged contacts after the solve
// (contact_response.h).
#include "response/contact_response.h"

#include "response/friction.h"
#include "response/stored_bodies.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace collide::detail {

namespace {

bool solverActed(const Contact& c) {
  for (int i = 0; i < c.manifold.count; ++i)
    if (c.points[i].maxNormalImpulse > 0.0f) return true;
  return false;
}

}  // namespace

void applyProlongedFriction(BodyStorage& bodies, Array<Contact>& contacts, const Array<std::uint32_t>& solved,
                            FrictionModel model, float dt) {
  if (model != FrictionModel::Viscous && model != FrictionModel::Damping) return;
  for (const std::uint32_t index : solved) {
    Contact& c = contacts[index];
    // Lecture, slide 12: friction acts on a prolonged contact only, from its second step.
    if (!c.wasTouching || !(c.touching || solverActed(c))) continue;
    BodyState& sa = bodies.states[c.bodyA];
    BodyState& sb = bodies.states[c.bodyB];
    ImpactBody a = impactBodyOf(sa);
    ImpactBody b = impactBodyOf(sb);
    const Vec3 point = averagePoint(c.manifold, -std::numeric_limits<float>::infinity());
    // A fault earlier in this step: the guard freezes its bodies at the step's end.
    if (!canApplyImpact(a, b, point, c.manifold.normal)) continue;
    if (model == FrictionModel::Viscous) {
      applyViscousFriction(a, b, point, c.manifold.normal, c.friction, dt);
    } else {
      applyDampingFriction(a, b, point, c.manifold.normal, std::clamp(c.friction, 0.0f, 1.0f));
    }
    writeBack(bodies.records[c.bodyA], sa, a);
    writeBack(bodies.records[c.bodyB], sb, b);
  }
}

void applyRollingResistance(BodyStorage& bodies, Array<Contact>& contacts,
                            const Array<std::uint32_t>& solved) {
  for (const std::uint32_t index : solved) {
    const Contact& c = contacts[index];
    if (!(c.rollingResistance > 0.0f)) continue;
    float normalImpulse = 0.0f;
    for (int i = 0; i < c.manifold.count; ++i) normalImpulse += c.points[i].totalNormalImpulse;
    if (!(normalImpulse > 0.0f)) continue;
    BodyState& sa = bodies.states[c.bodyA];
    BodyState& sb = bodies.states[c.bodyB];
    const Mat3 inverseA = sa.inverseMass == 0.0f ? Mat3(0.0f) : sa.inverseInertiaWorld;
    const Mat3 inverseB = sb.inverseMass == 0.0f ? Mat3(0.0f) : sb.inverseInertiaWorld;
    const Vec3 rolling = sb.angularVelocity - sa.angularVelocity;
    const Mat3 k = inverseA + inverseB;
    if (rolling == Vec3(0.0f) || !(std::abs(glm::determinant(k)) > 0.0f)) continue;
    Vec3 impulse = -(glm::inverse(k) * rolling);  // the angular impulse on B that stops the rolling
    const float most = c.rollingResistance * normalImpulse;
    const float length = glm::length(impulse);
    if (!std::isfinite(length)) continue;
    if (length > most) impulse *= most / length;
    if (bodies.records[c.bodyA].type == BodyType::Dynamic) sa.angularVelocity -= inverseA * impulse;
    if (bodies.records[c.bodyB].type == BodyType::Dynamic) sb.angularVelocity += inverseB * impulse;
  }
}

}  // namespace collide::detail
