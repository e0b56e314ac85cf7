// The lecture's impact and friction models applied to the step's contacts after the solve
// (contact_response.h).
#include "response/contact_response.h"

#include "response/friction.h"
#include "response/impact.h"

#include <algorithm>
#include <limits>

namespace collide::detail {

namespace {

ImpactBody impactBodyOf(const BodyState& s) {
  // Static and kinematic bodies already carry zero inverse mass and inertia in the body storage.
  ImpactBody body;
  body.inverseMass = s.inverseMass;
  body.inverseInertia = s.inverseMass == 0.0f ? Mat3(0.0f) : s.inverseInertiaWorld;
  body.linearVelocity = s.linearVelocity;
  body.angularVelocity = s.angularVelocity;
  body.centerOfMass = s.centerOfMass;
  return body;
}

// Only dynamic bodies take the result: a kinematic partner keeps its prescribed motion.
void writeBack(const BodyRecord& record, BodyState& s, const ImpactBody& body) {
  if (record.type != BodyType::Dynamic) return;
  s.linearVelocity = body.linearVelocity;
  s.angularVelocity = body.angularVelocity;
}

bool solverActed(const Contact& c) {
  for (int i = 0; i < c.manifold.count; ++i)
    if (c.points[i].maxNormalImpulse > 0.0f) return true;
  return false;
}

Vec3 averagePoint(const Manifold& m, float minDepth) {
  Vec3 sum(0.0f);
  int n = 0;
  for (int i = 0; i < m.count; ++i) {
    if (m.points[i].depth < minDepth) continue;
    sum += m.points[i].midpoint();
    ++n;
  }
  return sum / static_cast<float>(std::max(n, 1));
}

}  // namespace

void applyInterpolatedImpacts(BodyStorage& bodies, std::vector<Contact>& contacts,
                              const std::vector<std::uint32_t>& solved, float threshold, float slop) {
  for (const std::uint32_t index : solved) {
    Contact& c = contacts[index];
    if (c.wasTouching || !solverActed(c)) continue;  // a prolonged contact, or no impact this step
    float approach = 0.0f;
    for (int i = 0; i < c.manifold.count; ++i) approach = std::max(approach, -c.points[i].relativeVelocity);
    // Slow impacts do not bounce (resting contacts stay quiet); the soft solver's result stands.
    if (approach <= threshold) continue;

    BodyState& sa = bodies.states[c.bodyA];
    BodyState& sb = bodies.states[c.bodyB];
    const Vec3 normal = c.manifold.normal;
    // Undo this contact's impulses: the soft solver has already made the impact perfectly inelastic
    // along the normal, and the lecture's model needs the velocities before the impact. Exact for
    // the linear part; the angular part uses the end-of-step inertia (exact for a central impact).
    for (int i = 0; i < c.manifold.count; ++i) {
      const Vec3 impulse = c.points[i].totalNormalImpulse * normal;
      const Vec3 point = c.manifold.points[i].midpoint();  // anchors at the step start, as solved
      sa.linearVelocity += sa.inverseMass * impulse;
      sa.angularVelocity += sa.inverseInertiaWorld * glm::cross(point - sa.centerOfMass0, impulse);
      sb.linearVelocity -= sb.inverseMass * impulse;
      sb.angularVelocity -= sb.inverseInertiaWorld * glm::cross(point - sb.centerOfMass0, impulse);
    }
    ImpactBody a = impactBodyOf(sa);
    ImpactBody b = impactBodyOf(sb);
    // The points that touch first carry the impact: those within the slop of the deepest.
    const Vec3 point = averagePoint(c.manifold, c.manifold.maxDepth() - slop);
    try {
      resolveImpactInterpolated(a, b, point, normal, c.impactBounciness);
    } catch (const Error&) {
      // Refused: a non-finite velocity or contact from a fault earlier in this step (an
      // overflowing solve). The world's fault guard freezes those bodies at the end of the step;
      // the step itself must go on.
      continue;
    }
    writeBack(bodies.records[c.bodyA], sa, a);
    writeBack(bodies.records[c.bodyB], sb, b);
  }
}

void applyProlongedFriction(BodyStorage& bodies, std::vector<Contact>& contacts,
                            const std::vector<std::uint32_t>& solved, FrictionModel model, float dt) {
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
    try {
      if (model == FrictionModel::Viscous) {
        applyViscousFriction(a, b, point, c.manifold.normal, c.friction, dt);
      } else {
        applyDampingFriction(a, b, point, c.manifold.normal, std::clamp(c.friction, 0.0f, 1.0f));
      }
    } catch (const Error&) {
      continue;  // a fault earlier in this step, as in applyInterpolatedImpacts
    }
    writeBack(bodies.records[c.bodyA], sa, a);
    writeBack(bodies.records[c.bodyB], sb, b);
  }
}

void applyResponseModels(BodyStorage& bodies, std::vector<Contact>& contacts,
                         const std::vector<std::uint32_t>& solved, ImpactModel impactModel,
                         FrictionModel frictionModel, const ContactTuning& tuning, float dt) {
  if (impactModel == ImpactModel::Interpolated)
    applyInterpolatedImpacts(bodies, contacts, solved, tuning.restitutionThreshold, tuning.linearSlop);
  applyProlongedFriction(bodies, contacts, solved, frictionModel, dt);
}

}  // namespace collide::detail
