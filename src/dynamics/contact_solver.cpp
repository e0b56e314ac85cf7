#include "dynamics/contact_solver.h"

#include "dynamics/constraint_graph.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace collide::detail {

Softness makeSoftness(float hertz, float dampingRatio, float h) {
  if (hertz == 0.0f) return {0.0f, 1.0f, 0.0f};
  const float omega = 2.0f * kPi * hertz;
  const float a1 = 2.0f * dampingRatio + h * omega;
  const float a2 = h * omega * a1;
  const float a3 = 1.0f / (1.0f + a2);
  return {omega / a1, a2 * a3, a3};
}

namespace {

// Four solver bodies as lanes: their velocities (what the solver changes) and their change of pose
// since the step began (read once per batch for the current separations, then dropped, so that the
// velocities keep the registers). A lane without a body (static, or an empty lane) reads a body at
// rest that has not moved.
struct VelocityW {
  Vec3W v, w;
};
struct PoseW {
  Vec3W dp;
  FloatW qx, qy, qz, qw;
};

const SolverBody kRestingBody{};

COLLIDE_INLINE void bodyPointers(const std::vector<SolverBody>& bodies,
                                 const std::array<std::int32_t, kLanes>& index, const float* (&out)[kLanes]) {
  for (int i = 0; i < kLanes; ++i)
    out[i] = reinterpret_cast<const float*>(index[i] >= 0 ? &bodies[index[i]] : &kRestingBody);
}

// Four rows of a field (x, y, z, and the fourth float) of the four lanes' bodies, as columns.
COLLIDE_INLINE void gatherRows(const float* const (&b)[kLanes], std::size_t offset, FloatW& x, FloatW& y,
                               FloatW& z, FloatW& last) {
  x = loadW(b[0] + offset);
  y = loadW(b[1] + offset);
  z = loadW(b[2] + offset);
  last = loadW(b[3] + offset);
  transpose(x, y, z, last);
}

COLLIDE_INLINE VelocityW gatherVelocities(const std::vector<SolverBody>& bodies,
                                          const std::array<std::int32_t, kLanes>& index) {
  const float* b[kLanes];
  bodyPointers(bodies, index, b);
  VelocityW out;
  FloatW pad;
  gatherRows(b, 0, out.v.x, out.v.y, out.v.z, pad);
  gatherRows(b, 4, out.w.x, out.w.y, out.w.z, pad);
  return out;
}

COLLIDE_INLINE PoseW gatherPoses(const std::vector<SolverBody>& bodies,
                                 const std::array<std::int32_t, kLanes>& index) {
  const float* b[kLanes];
  bodyPointers(bodies, index, b);
  PoseW out;
  FloatW pad;
  gatherRows(b, 8, out.dp.x, out.dp.y, out.dp.z, pad);
  gatherRows(b, 12, out.qx, out.qy, out.qz, out.qw);
  return out;
}

// The contact solver changes velocities only; lanes of bodies it must not write are skipped.
COLLIDE_INLINE void scatter(std::vector<SolverBody>& bodies, const std::array<std::int32_t, kLanes>& index,
                            const std::array<bool, kLanes>& write, const VelocityW& body) {
  FloatW v0 = body.v.x, v1 = body.v.y, v2 = body.v.z, v3 = zeroW();
  FloatW w0 = body.w.x, w1 = body.w.y, w2 = body.w.z, w3 = zeroW();
  transpose(v0, v1, v2, v3);
  transpose(w0, w1, w2, w3);
  const FloatW vRows[kLanes] = {v0, v1, v2, v3};
  const FloatW wRows[kLanes] = {w0, w1, w2, w3};
  for (int i = 0; i < kLanes; ++i) {
    if (!write[i]) continue;
    float* target = reinterpret_cast<float*>(&bodies[index[i]]);
    storeW(target, vRows[i]);
    storeW(target + 4, wRows[i]);
  }
}

// conj(q) v q for unit q: v seen in the frame before the rotation q.
COLLIDE_INLINE Vec3W rotateInverse(const PoseW& q, const Vec3W& v) {
  const Vec3W u{-q.qx, -q.qy, -q.qz};
  const Vec3W t = splat(2.0f) * cross(u, v);
  return v + q.qw * t + cross(u, t);
}

// The small-angle rotation vector of q (2 x its vector part, on the shortest arc): the static
// anchors are kept only while the bodies barely turn, where this is exact to second order.
COLLIDE_INLINE Vec3W smallRotation(const PoseW& q) {
  const FloatW negative = greaterW(zeroW(), q.qw);
  const FloatW two = selectW(negative, splat(-2.0f), splat(2.0f));
  return {two * q.qx, two * q.qy, two * q.qz};
}

COLLIDE_INLINE void applyLinear(VelocityW& a, VelocityW& b, const ContactBatch& c, FloatW impulse,
                                const Vec3W& direction) {
  addScaled(a.v, -(impulse * c.inverseMassA), direction);
  addScaled(b.v, impulse * c.inverseMassB, direction);
}

}  // namespace

void ContactSolver::prepare(std::vector<Contact>& contacts, const BodyStorage& storage,
                            const std::vector<SolverBody>& bodies, const std::vector<SolverBodyInfo>& infos,
                            const std::vector<std::int32_t>& solverOf, const ContactSolverSettings& settings,
                            float h) {
  pushOutSpeed_ = settings.tuning.pushOutSpeed;
  restitutionThreshold_ = settings.tuning.restitutionThreshold;
  anchorReach_ = settings.tuning.frictionAnchorReach;
  // Every spring is capped at a quarter of the substep rate (h omega <= pi / 2), where Gauss-Seidel
  // still resolves it; stiffer, coupled points overshoot and stacks shiver (docs/architecture.md).
  const float maxHertz = kMaxHertzPerSubstepRate / h;
  const Softness soft =
      makeSoftness(std::min(settings.tuning.hertz, maxHertz), settings.tuning.dampingRatio, h);
  // A one-way pair has half the effective mass to move: Box2D v3 doubles its stiffness, within the cap.
  const Softness oneWaySoft =
      makeSoftness(std::min(2.0f * settings.tuning.hertz, maxHertz), settings.tuning.dampingRatio, h);

  // The contacts to solve and the solver bodies each may write.
  solvedContacts.clear();
  writtenBodies_.clear();
  for (std::uint32_t ci = 0; ci < contacts.size(); ++ci) {
    const Contact& contact = contacts[ci];
    if (contact.sensor || !contact.enabled || contact.asleep || contact.manifold.count == 0) continue;
    const std::int32_t a = solverOf[contact.bodyA];
    const std::int32_t b = solverOf[contact.bodyB];
    solvedContacts.push_back(ci);
    writtenBodies_.push_back(
        {a >= 0 && infos[a].dynamic ? a : kNoSolverBody, b >= 0 && infos[b].dynamic ? b : kNoSolverBody});
  }
  colorConstraints(writtenBodies_, bodies.size(), colorOf_, colorBits_);

  // Batches: each colour in order, four contacts a batch; then the overflow, one contact a batch.
  // A counting sort by colour keeps the contact order within each colour (determinism).
  std::array<std::uint32_t, kGraphColors + 2> start{};
  for (const std::uint8_t color : colorOf_) ++start[color + 1];
  for (int color = 0; color <= kGraphColors; ++color) start[color + 1] += start[color];
  order_.resize(solvedContacts.size());
  {
    std::array<std::uint32_t, kGraphColors + 2> next = start;
    for (std::size_t i = 0; i < solvedContacts.size(); ++i) order_[next[colorOf_[i]]++] = solvedContacts[i];
  }
  solvedContacts.swap(order_);
  batches.clear();
  for (int color = 0; color <= kGraphColors; ++color) {
    const std::uint32_t perBatch = color == kOverflowColor ? 1 : kLanes;
    for (std::uint32_t first = start[color]; first < start[color + 1]; first += perBatch) {
      ContactBatch& batch = batches.emplace_back();
      std::memset(static_cast<void*>(&batch), 0, sizeof(ContactBatch));
      batch.bodyA.fill(kNoSolverBody);
      batch.bodyB.fill(kNoSolverBody);
      batch.contact.fill(-1);
      const std::uint32_t last = std::min(first + perBatch, start[color + 1]);
      for (std::uint32_t i = first; i < last; ++i)
        batch.contact[i - first] = static_cast<std::int32_t>(solvedContacts[i]);
    }
  }

  for (ContactBatch& c : batches) {
    for (int lane = 0; lane < kLanes; ++lane) {
      if (c.contact[lane] < 0) continue;
      Contact& contact = contacts[static_cast<std::size_t>(c.contact[lane])];
      const BodyState& stateA = storage.states[contact.bodyA];
      const BodyState& stateB = storage.states[contact.bodyB];
      const std::int32_t ia = solverOf[contact.bodyA];
      const std::int32_t ib = solverOf[contact.bodyB];
      c.bodyA[lane] = ia;
      c.bodyB[lane] = ib;
      c.writeA[lane] = ia >= 0 && infos[ia].dynamic;
      c.writeB[lane] = ib >= 0 && infos[ib].dynamic;
      const float mA = c.writeA[lane] ? infos[ia].inverseMass : 0.0f;
      const float mB = c.writeB[lane] ? infos[ib].inverseMass : 0.0f;
      const Mat3 iA = c.writeA[lane] ? infos[ia].inverseInertiaWorld : Mat3(0.0f);
      const Mat3 iB = c.writeB[lane] ? infos[ib].inverseInertiaWorld : Mat3(0.0f);
      const Vec3 vA = ia >= 0 ? bodies[ia].linearVelocity : Vec3(0.0f);
      const Vec3 wA = ia >= 0 ? bodies[ia].angularVelocity : Vec3(0.0f);
      const Vec3 vB = ib >= 0 ? bodies[ib].linearVelocity : Vec3(0.0f);
      const Vec3 wB = ib >= 0 ? bodies[ib].angularVelocity : Vec3(0.0f);
      laneOf(c.inverseMassA, lane) = mA;
      laneOf(c.inverseMassB, lane) = mB;

      const Vec3 n = contact.manifold.normal;
      Vec3 t1, t2;
      orthonormalBasis(n, t1, t2);
      setLane(c.normal, lane, n);
      setLane(c.tangent1, lane, t1);
      setLane(c.tangent2, lane, t2);
      const float friction = settings.friction ? contact.friction : 0.0f;
      laneOf(c.friction, lane) = friction;
      laneOf(c.restitution, lane) = contact.restitution;
      const Softness& s = (mA == 0.0f || mB == 0.0f) ? oneWaySoft : soft;
      laneOf(c.biasRate, lane) = s.biasRate;
      laneOf(c.massScale, lane) = s.massScale;
      laneOf(c.impulseScale, lane) = s.impulseScale;

      const int count = contact.manifold.count;
      c.pointCount = std::max(c.pointCount, count);
      Vec3 centroid(0.0f);
      for (int k = 0; k < count; ++k) {
        const ContactPoint& mp = contact.manifold.points[k];
        ContactPointState& state = contact.points[k];
        BatchPoint& p = c.points[k];
        const Vec3 point = mp.midpoint();
        centroid += point;
        const Vec3 rA = point - stateA.centerOfMass;
        const Vec3 rB = point - stateB.centerOfMass;
        const Vec3 crossA = glm::cross(rA, n);
        const Vec3 crossB = glm::cross(rB, n);
        setLane(p.anchorA, lane, rA);
        setLane(p.anchorB, lane, rB);
        setLane(p.crossA, lane, crossA);
        setLane(p.crossB, lane, crossB);
        const Vec3 turnA = iA * crossA;
        const Vec3 turnB = iB * crossB;
        setLane(p.turnA, lane, turnA);
        setLane(p.turnB, lane, turnB);
        laneOf(p.baseSeparation, lane) = -mp.depth - glm::dot(rB - rA, n);
        const float kn = mA + mB + glm::dot(crossA, turnA) + glm::dot(crossB, turnB);
        laneOf(p.normalMass, lane) = kn > 0.0f ? 1.0f / kn : 0.0f;
        laneOf(p.normalImpulse, lane) = state.normalImpulse;
        const Vec3 dv = vB + glm::cross(wB, rB) - vA - glm::cross(wA, rA);
        laneOf(p.approachVelocity, lane) = glm::dot(dv, n);
      }
      centroid /= static_cast<float>(count);

      // The friction patch at the centroid.
      const Vec3 rA = centroid - stateA.centerOfMass;
      const Vec3 rB = centroid - stateB.centerOfMass;
      const Vec3 t1A = glm::cross(rA, t1), t2A = glm::cross(rA, t2);
      const Vec3 t1B = glm::cross(rB, t1), t2B = glm::cross(rB, t2);
      setLane(c.tangent1CrossA, lane, t1A);
      setLane(c.tangent2CrossA, lane, t2A);
      setLane(c.tangent1CrossB, lane, t1B);
      setLane(c.tangent2CrossB, lane, t2B);
      const Vec3 u1A = iA * t1A, u2A = iA * t2A;
      const Vec3 u1B = iB * t1B, u2B = iB * t2B;
      setLane(c.tangent1TurnA, lane, u1A);
      setLane(c.tangent2TurnA, lane, u2A);
      setLane(c.tangent1TurnB, lane, u1B);
      setLane(c.tangent2TurnB, lane, u2B);
      // The tangents are orthonormal, so the linear part of the off-diagonal term vanishes.
      const float k11 = mA + mB + glm::dot(t1A, u1A) + glm::dot(t1B, u1B);
      const float k12 = glm::dot(t1A, u2A) + glm::dot(t1B, u2B);
      const float k22 = mA + mB + glm::dot(t2A, u2A) + glm::dot(t2B, u2B);
      const float det = k11 * k22 - k12 * k12;
      if (det > 0.0f) {
        laneOf(c.tangentMass11, lane) = k22 / det;
        laneOf(c.tangentMass12, lane) = -k12 / det;
        laneOf(c.tangentMass22, lane) = k11 / det;
      }
      const Vec3 twistA = iA * n, twistB = iB * n;
      setLane(c.twistTurnA, lane, twistA);
      setLane(c.twistTurnB, lane, twistB);
      const float kt = glm::dot(n, twistA) + glm::dot(n, twistB);
      laneOf(c.twistMass, lane) = kt > 0.0f ? 1.0f / kt : 0.0f;
      float radius = 0.0f;
      for (int k = 0; k < count; ++k) radius += glm::length(contact.manifold.points[k].midpoint() - centroid);
      laneOf(c.twistRadius, lane) = kTwistRadiusScale * radius / static_cast<float>(count);
      if (friction == 0.0f) {
        contact.frictionImpulse = Vec3(0.0f);
        contact.twistImpulse = 0.0f;
      }
      // Warm start: last step's friction impulse, on this step's tangents (the tangent basis of a
      // normal can turn by 180 degrees between steps, so coefficients would not carry over).
      laneOf(c.tangentImpulse1, lane) = glm::dot(contact.frictionImpulse, t1);
      laneOf(c.tangentImpulse2, lane) = glm::dot(contact.frictionImpulse, t2);
      laneOf(c.twistImpulse, lane) = contact.twistImpulse;

      // The static anchor: kept in each body's frame from where the patch stuck; re-taken here when
      // the patch slid last step, is new, or has drifted beyond the reach.
      const auto anchorHere = [&] {
        contact.stickLocalA = glm::conjugate(stateA.rotation) * rA;
        contact.stickLocalB = glm::conjugate(stateB.rotation) * rB;
      };
      laneOf(c.surfaceSpeed1, lane) = glm::dot(contact.surfaceVelocity, t1);
      laneOf(c.surfaceSpeed2, lane) = glm::dot(contact.surfaceVelocity, t2);
      const bool anchored = friction > 0.0f && contact.surfaceVelocity == Vec3(0.0f);
      laneOf(c.stickRate, lane) = anchored ? s.biasRate : 0.0f;
      if (!contact.stuck || contact.sliding || !anchored) anchorHere();
      Vec3 stickA = stateA.rotation * contact.stickLocalA;
      Vec3 stickB = stateB.rotation * contact.stickLocalB;
      Vec3 gap = (stateB.centerOfMass + stickB) - (stateA.centerOfMass + stickA);
      gap -= glm::dot(gap, n) * n;
      if (glm::dot(gap, gap) > anchorReach_ * anchorReach_) {
        anchorHere();
        stickA = rA;
        stickB = rB;
        gap = Vec3(0.0f);
      }
      contact.stuck = anchored;
      contact.sliding = false;
      setLane(c.stickA, lane, stickA);
      setLane(c.stickB, lane, stickB);
      laneOf(c.stickGap1, lane) = glm::dot(gap, t1);
      laneOf(c.stickGap2, lane) = glm::dot(gap, t2);
    }
  }
}

void ContactSolver::warmStart(std::vector<SolverBody>& bodies) {
  for (ContactBatch& c : batches) {
    VelocityW a = gatherVelocities(bodies, c.bodyA);
    VelocityW b = gatherVelocities(bodies, c.bodyB);
    for (int k = 0; k < c.pointCount; ++k) {
      BatchPoint& p = c.points[k];
      // The events' impulse counts every substep's warm start as well as the solve's increments.
      p.totalNormalImpulse = p.totalNormalImpulse + p.normalImpulse;
      applyLinear(a, b, c, p.normalImpulse, c.normal);
      addScaled(a.w, -p.normalImpulse, p.turnA);
      addScaled(b.w, p.normalImpulse, p.turnB);
    }
    applyLinear(a, b, c, c.tangentImpulse1, c.tangent1);
    applyLinear(a, b, c, c.tangentImpulse2, c.tangent2);
    addScaled(a.w, -c.tangentImpulse1, c.tangent1TurnA);
    addScaled(a.w, -c.tangentImpulse2, c.tangent2TurnA);
    addScaled(b.w, c.tangentImpulse1, c.tangent1TurnB);
    addScaled(b.w, c.tangentImpulse2, c.tangent2TurnB);
    addScaled(a.w, -c.twistImpulse, c.twistTurnA);
    addScaled(b.w, c.twistImpulse, c.twistTurnB);
    scatter(bodies, c.bodyA, c.writeA, a);
    scatter(bodies, c.bodyB, c.writeB, b);
  }
}

void ContactSolver::solve(std::vector<SolverBody>& bodies, float h, bool useBias) {
  if (useBias) {
    solvePass<true>(bodies, h);
  } else {
    solvePass<false>(bodies, h);
  }
}

// One pass; the biased and the relax pass are two instantiations, so neither tests the flag inside.
template <bool useBias>
void ContactSolver::solvePass(std::vector<SolverBody>& bodies, float h) {
  const FloatW zero = zeroW();
  const FloatW one = splat(1.0f);
  const FloatW inverseH = splat(1.0f / h);
  const FloatW maxPushOut = splat(-pushOutSpeed_);
  for (ContactBatch& c : batches) {
    // The current separation from the anchors carried along with each body's change of pose, without
    // a new narrow-phase query (Box2D v3): n . (dq r) = (conj(dq) n) . r. And in the biased pass,
    // how far the static anchors drifted apart along the tangents.
    Vec3W normalA, normalB;
    FloatW moved, drift1 = zero, drift2 = zero;
    {
      const PoseW pa = gatherPoses(bodies, c.bodyA);
      const PoseW pb = gatherPoses(bodies, c.bodyB);
      normalA = rotateInverse(pa, c.normal);
      normalB = rotateInverse(pb, c.normal);
      const Vec3W dp = pb.dp - pa.dp;
      moved = dot(dp, c.normal);
      if constexpr (useBias) {
        const Vec3W drift = dp + cross(smallRotation(pb), c.stickB) - cross(smallRotation(pa), c.stickA);
        drift1 = c.stickGap1 + dot(drift, c.tangent1);
        drift2 = c.stickGap2 + dot(drift, c.tangent2);
      }
    }
    VelocityW a = gatherVelocities(bodies, c.bodyA);
    VelocityW b = gatherVelocities(bodies, c.bodyB);

    FloatW normalSum = zero;
    for (int k = 0; k < c.pointCount; ++k) {
      BatchPoint& p = c.points[k];
      const FloatW separation = moved + dot(normalB, p.anchorB) - dot(normalA, p.anchorA) + p.baseSeparation;
      // Speculative: a point still apart may close exactly its gap within the substep.
      const FloatW apart = greaterW(separation, zero);
      FloatW bias = separation * inverseH;
      FloatW massScale = one;
      FloatW impulseScale = zero;
      if constexpr (useBias) {
        bias = selectW(apart, bias, maxW(c.biasRate * separation, maxPushOut));
        massScale = selectW(apart, one, c.massScale);
        impulseScale = selectW(apart, zero, c.impulseScale);
      } else {
        bias = selectW(apart, bias, zero);
      }
      const FloatW vn = dot(b.v - a.v, c.normal) + dot(b.w, p.crossB) - dot(a.w, p.crossA);
      FloatW impulse = -(p.normalMass * massScale * (vn + bias)) - impulseScale * p.normalImpulse;
      // Contacts only push: the accumulated impulse stays >= 0.
      const FloatW total = maxW(p.normalImpulse + impulse, zero);
      impulse = total - p.normalImpulse;
      p.normalImpulse = total;
      p.maxNormalImpulse = maxW(p.maxNormalImpulse, impulse);
      p.totalNormalImpulse = p.totalNormalImpulse + impulse;
      normalSum = normalSum + total;
      applyLinear(a, b, c, impulse, c.normal);
      addScaled(a.w, -impulse, p.turnA);
      addScaled(b.w, impulse, p.turnB);
    }

    // Friction patch: the tangential velocity at the centroid, plus in the biased pass the gap of the
    // static anchors, driven to zero inside the Coulomb disc.
    const Vec3W dv = b.v - a.v;
    FloatW v1 =
        dot(dv, c.tangent1) + dot(b.w, c.tangent1CrossB) - dot(a.w, c.tangent1CrossA) - c.surfaceSpeed1;
    FloatW v2 =
        dot(dv, c.tangent2) + dot(b.w, c.tangent2CrossB) - dot(a.w, c.tangent2CrossA) - c.surfaceSpeed2;
    FloatW massScale = one;
    FloatW impulseScale = zero;
    if constexpr (useBias) {
      v1 = v1 + c.stickRate * drift1;
      v2 = v2 + c.stickRate * drift2;
      massScale = c.massScale;
      impulseScale = c.impulseScale;
    }
    FloatW next1 = c.tangentImpulse1 - massScale * (c.tangentMass11 * v1 + c.tangentMass12 * v2) -
                   impulseScale * c.tangentImpulse1;
    FloatW next2 = c.tangentImpulse2 - massScale * (c.tangentMass12 * v1 + c.tangentMass22 * v2) -
                   impulseScale * c.tangentImpulse2;
    const FloatW limit = c.friction * normalSum;
    const FloatW length = sqrtW(next1 * next1 + next2 * next2);
    const FloatW beyond = greaterW(length, limit);
    const FloatW scale = selectW(beyond, limit / maxW(length, splat(1e-30f)), one);
    next1 = next1 * scale;
    next2 = next2 * scale;
    if constexpr (useBias) c.sliding = orW(c.sliding, beyond);
    const FloatW d1 = next1 - c.tangentImpulse1;
    const FloatW d2 = next2 - c.tangentImpulse2;
    c.tangentImpulse1 = next1;
    c.tangentImpulse2 = next2;
    applyLinear(a, b, c, d1, c.tangent1);
    applyLinear(a, b, c, d2, c.tangent2);
    addScaled(a.w, -d1, c.tangent1TurnA);
    addScaled(a.w, -d2, c.tangent2TurnA);
    addScaled(b.w, d1, c.tangent1TurnB);
    addScaled(b.w, d2, c.tangent2TurnB);

    // Twist about the normal.
    const FloatW spin = dot(b.w - a.w, c.normal);
    const FloatW twistLimit = c.friction * c.twistRadius * normalSum;
    const FloatW twist = maxW(minW(c.twistImpulse - c.twistMass * spin, twistLimit), -twistLimit);
    const FloatW dt = twist - c.twistImpulse;
    c.twistImpulse = twist;
    addScaled(a.w, -dt, c.twistTurnA);
    addScaled(b.w, dt, c.twistTurnB);

    scatter(bodies, c.bodyA, c.writeA, a);
    scatter(bodies, c.bodyB, c.writeB, b);
  }
}

// Newton's restitution on the approach velocity measured before the solve: the soft contact has
// absorbed the impact by now, so the bounce is added at the end (Box2D v3's b2ApplyRestitution).
void ContactSolver::applyRestitution(std::vector<SolverBody>& bodies) {
  const FloatW zero = zeroW();
  const FloatW threshold = splat(-restitutionThreshold_);
  for (ContactBatch& c : batches) {
    if (!anyW(greaterW(c.restitution, zero))) continue;
    VelocityW a = gatherVelocities(bodies, c.bodyA);
    VelocityW b = gatherVelocities(bodies, c.bodyB);
    for (int k = 0; k < c.pointCount; ++k) {
      BatchPoint& p = c.points[k];
      const FloatW bounce =
          andW(andW(greaterW(threshold, p.approachVelocity), greaterW(p.maxNormalImpulse, zero)),
               greaterW(c.restitution, zero));
      if (!anyW(bounce)) continue;
      const FloatW vn = dot(b.v - a.v, c.normal) + dot(b.w, p.crossB) - dot(a.w, p.crossA);
      FloatW impulse = -(p.normalMass * (vn + c.restitution * p.approachVelocity));
      const FloatW total = maxW(p.normalImpulse + impulse, zero);
      impulse = selectW(bounce, total - p.normalImpulse, zero);
      p.normalImpulse = p.normalImpulse + impulse;
      p.maxNormalImpulse = maxW(p.maxNormalImpulse, impulse);
      p.totalNormalImpulse = p.totalNormalImpulse + impulse;
      applyLinear(a, b, c, impulse, c.normal);
      addScaled(a.w, -impulse, p.turnA);
      addScaled(b.w, impulse, p.turnB);
    }
    scatter(bodies, c.bodyA, c.writeA, a);
    scatter(bodies, c.bodyB, c.writeB, b);
  }
}

void ContactSolver::store(std::vector<Contact>& contacts) const {
  for (const ContactBatch& c : batches) {
    for (int lane = 0; lane < kLanes; ++lane) {
      if (c.contact[lane] < 0) continue;
      Contact& contact = contacts[static_cast<std::size_t>(c.contact[lane])];
      for (int k = 0; k < contact.manifold.count; ++k) {
        const BatchPoint& p = c.points[k];
        ContactPointState& state = contact.points[k];
        state.normalImpulse = laneOf(p.normalImpulse, lane);
        state.maxNormalImpulse = laneOf(p.maxNormalImpulse, lane);
        state.totalNormalImpulse = laneOf(p.totalNormalImpulse, lane);
        state.relativeVelocity = laneOf(p.approachVelocity, lane);
      }
      contact.frictionImpulse = laneOf(c.tangentImpulse1, lane) * laneOf(c.tangent1, lane) +
                                laneOf(c.tangentImpulse2, lane) * laneOf(c.tangent2, lane);
      contact.twistImpulse = laneOf(c.twistImpulse, lane);
      contact.sliding = laneSet(c.sliding, lane);
    }
  }
}

}  // namespace collide::detail
