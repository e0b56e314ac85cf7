// The ball (spherical) joint: the point block, C = pB - pA, and its friction against turning.
//
// Four ball joints of one wave share no moving body, so the Gauss-Seidel waves take them four at a
// time in SIMD lanes (warmStartBalls, solveBalls): each lane does the operations of warmStartBall
// and solveBall in the same order, IEEE operation for IEEE operation (GLM's formulas for the
// quaternion and matrix products, the determinant and the inverse, spelled out), so the lanes give
// bit for bit what one joint after another gives.
#include "dynamics/joints/joint_rows.h"

#include "simd/simd.h"

#include <array>
#include <cstddef>
#include <cstring>

namespace collide::detail {

static_assert(kBallLanes == kLanes);

void warmStartBall(const JointSolverView& view, Joint& joint) {
  // In a tree with no friction impulse there is nothing to apply here (a net of 10,000 of them).
  if (joint.inTree && joint.frictionImpulse == Vec3(0.0f)) return;
  std::optional<JointFrame> scratch;
  const JointFrame& f = jointFrame(view, joint, scratch);
  applyAngularImpulse(f.a, f.b, joint.frictionImpulse);
  if (!joint.inTree) applyImpulse(f.a, f.b, f.rA, f.rB, joint.linearImpulse);
}

void solveBall(const JointSolverView& view, Joint& joint, float h, float rigidHertz, bool useBias) {
  if (joint.inTree && !(joint.friction > 0.0f)) return;
  std::optional<JointFrame> scratch;
  const JointFrame& f = jointFrame(view, joint, scratch);
  solveAngularFriction(f, joint.friction, h, joint.frictionImpulse);
  if (joint.inTree) return;
  solvePoint(f, rowSoftness(joint.softness, rigidHertz, h, useBias), joint.linearImpulse);
}

void equalityRowsBall(const JointFrame& f, Joint& joint, EqualityRows& rows) { addPointRows(f, joint, rows); }

bool ballInLanes(const Joint& joint) {
  return joint.type == JointType::Ball && !joint.inTree && !(joint.friction > 0.0f);
}

namespace {

using Vec = Vec3W;
// A 3 x 3 matrix in lanes, GLM's column-major order: m[3 c + r] is column c, row r.
using Mat = std::array<FloatW, 9>;

// Where the lanes read the solver's records, in floats (gatherRows takes four from there).
constexpr std::size_t kStartRotation = offsetof(SolverBodyStart, rotation) / sizeof(float);
constexpr std::size_t kInfoMass = offsetof(SolverBodyInfo, inverseMass) / sizeof(float);
static_assert(offsetof(SolverBodyStart, rotation) == sizeof(Vec3));
static_assert(offsetof(SolverBodyInfo, inverseInertiaWorld) ==
              offsetof(SolverBodyInfo, inverseMass) + sizeof(float));
static_assert(offsetof(SolverBodyInfo, linearAcceleration) ==
              offsetof(SolverBodyInfo, inverseInertiaWorld) + sizeof(Mat3));

// One end of four joints, as jointBody gives it.
struct EndLanes {
  Vec center;
  FloatW qx, qy, qz, qw;  // the rotation now
  Vec v, w;               // zero where the body does not move (static, or stopped by the guard)
  FloatW inverseMass;
  Mat inverseInertia;                       // zero but for a dynamic body
  std::array<SolverBody*, kLanes> write{};  // the dynamic bodies the impulses change
};

// The records one lane reads for one end. A body the solver does not move reads stand-ins: a
// static body's pose is its state's, read where it lies (BodyState begins as SolverBodyStart does)
// and selected by `ground`, so that it is taken as it is, not through a product with the identity;
// a body the guard stopped keeps its motion since the step began but reads zero velocities; and
// neither has mass.
struct EndRecords {
  const float* body[kLanes];
  const float* start[kLanes];
  const float* info[kLanes];
  float ground[kLanes];
  // A stopped body's copy with its velocities zeroed, made only for one (no constructors to run).
  alignas(SolverBody) unsigned char stopped[kLanes][sizeof(SolverBody)];
};
static_assert(offsetof(BodyState, centerOfMass) == offsetof(SolverBodyStart, centerOfMass));
static_assert(offsetof(BodyState, rotation) == offsetof(SolverBodyStart, rotation));

COLLIDE_INLINE void gatherEnd(const JointSolverView& view, const std::uint32_t (&body)[kLanes], EndRecords& r,
                              EndLanes& end) {
  static const SolverBodyInfo kNoMass{};
  static const SolverBody kAtRest{};
  end.write = {};
  for (int i = 0; i < kLanes; ++i) {
    const std::int32_t j = view.solverOf[body[i]];
    r.ground[i] = 0.0f;
    if (j == kNoSolverBody) {
      r.body[i] = reinterpret_cast<const float*>(&kAtRest);
      r.start[i] = reinterpret_cast<const float*>(&view.storage.states[body[i]]);
      r.info[i] = reinterpret_cast<const float*>(&kNoMass);
      r.ground[i] = 1.0f;
      continue;
    }
    const auto index = static_cast<std::size_t>(j);
    const SolverBodyInfo& info = view.infos[index];
    SolverBody& b = view.bodies[index];
    r.start[i] = reinterpret_cast<const float*>(&view.starts[index]);
    r.body[i] = reinterpret_cast<const float*>(&b);
    r.info[i] = reinterpret_cast<const float*>(info.dynamic && !info.faulted ? &info : &kNoMass);
    if (info.faulted) {
      SolverBody copy = b;
      copy.linearVelocity = Vec3(0.0f);
      copy.angularVelocity = Vec3(0.0f);
      std::memcpy(r.stopped[i], &copy, sizeof(SolverBody));
      r.body[i] = reinterpret_cast<const float*>(r.stopped[i]);
    } else if (info.dynamic) {
      end.write[static_cast<std::size_t>(i)] = &b;
    }
  }
  FloatW pad, unused;
  gatherRows(r.body, 0, end.v.x, end.v.y, end.v.z, pad);
  gatherRows(r.body, 4, end.w.x, end.w.y, end.w.z, pad);
  Vec dp;
  gatherRows(r.body, 8, dp.x, dp.y, dp.z, pad);
  FloatW dqx, dqy, dqz, dqw;
  gatherRows(r.body, 12, dqx, dqy, dqz, dqw);
  Vec c;
  gatherRows(r.start, 0, c.x, c.y, c.z, pad);
  FloatW sx, sy, sz, sw;
  gatherRows(r.start, kStartRotation, sx, sy, sz, sw);
  Mat& m = end.inverseInertia;
  gatherRows(r.info, kInfoMass, end.inverseMass, m[0], m[1], m[2]);
  gatherRows(r.info, kInfoMass + 4, m[3], m[4], m[5], m[6]);
  gatherRows(r.info, kInfoMass + 8, m[7], m[8], pad, unused);

  // jointBody: start + delta for a body the solver holds (GLM's quaternion product, dq * start).
  const FloatW isGround = greaterW(setW(r.ground[0], r.ground[1], r.ground[2], r.ground[3]), zeroW());
  const Vec moved = c + dp;
  end.center = {selectW(isGround, c.x, moved.x), selectW(isGround, c.y, moved.y),
                selectW(isGround, c.z, moved.z)};
  const FloatW w = dqw * sw - dqx * sx - dqy * sy - dqz * sz;
  const FloatW x = dqw * sx + dqx * sw + dqy * sz - dqz * sy;
  const FloatW y = dqw * sy + dqy * sw + dqz * sx - dqx * sz;
  const FloatW z = dqw * sz + dqz * sw + dqx * sy - dqy * sx;
  end.qx = selectW(isGround, sx, x);
  end.qy = selectW(isGround, sy, y);
  end.qz = selectW(isGround, sz, z);
  end.qw = selectW(isGround, sw, w);
}

// GLM's q * v: v + ((u x v) w + u x (u x v)) 2, u the vector part.
COLLIDE_INLINE Vec rotate(const EndLanes& e, const Vec& v) {
  const Vec u{e.qx, e.qy, e.qz};
  const Vec uv = cross(u, v);
  const Vec uuv = cross(u, uv);
  const FloatW two = splat(2.0f);
  return {v.x + (uv.x * e.qw + uuv.x) * two, v.y + (uv.y * e.qw + uuv.y) * two,
          v.z + (uv.z * e.qw + uuv.z) * two};
}

// GLM's m * v.
COLLIDE_INLINE Vec times(const Mat& m, const Vec& v) {
  return {m[0] * v.x + m[3] * v.y + m[6] * v.z, m[1] * v.x + m[4] * v.y + m[7] * v.z,
          m[2] * v.x + m[5] * v.y + m[8] * v.z};
}

// GLM's a * b: column c, row r is a[0][r] b[c][0] + a[1][r] b[c][1] + a[2][r] b[c][2].
COLLIDE_INLINE Mat times(const Mat& a, const Mat& b) {
  Mat out;
  for (int c = 0; c < 3; ++c) {
    for (int r = 0; r < 3; ++r)
      out[3 * c + r] = a[r] * b[3 * c] + a[3 + r] * b[3 * c + 1] + a[6 + r] * b[3 * c + 2];
  }
  return out;
}

// skew(r), as joint_rows.h builds it: columns (0, r.z, -r.y), (-r.z, 0, r.x), (r.y, -r.x, 0).
COLLIDE_INLINE Mat skewLanes(const Vec& r) {
  const FloatW zero = zeroW();
  return {zero, r.z, negateW(r.y), negateW(r.z), zero, r.x, r.y, negateW(r.x), zero};
}

// The velocities back to the dynamic bodies.
COLLIDE_INLINE void scatterEnd(const EndLanes& e) {
  FloatW vRows[kLanes];
  FloatW wRows[kLanes];
  scatterRows(e.v.x, e.v.y, e.v.z, zeroW(), vRows);
  scatterRows(e.w.x, e.w.y, e.w.z, zeroW(), wRows);
  for (int i = 0; i < kLanes; ++i) {
    SolverBody* body = e.write[static_cast<std::size_t>(i)];
    if (!body) continue;
    float* target = reinterpret_cast<float*>(body);
    storeW(target, vRows[i]);
    storeW(target + 4, wRows[i]);
  }
}

// applyImpulse: p on B at rB, -p on A at rA (on a body without mass, a change of zero, not
// written back).
COLLIDE_INLINE void applyImpulseLanes(EndLanes& a, EndLanes& b, const Vec& rA, const Vec& rB, const Vec& p) {
  a.v = a.v - a.inverseMass * p;
  a.w = a.w - times(a.inverseInertia, cross(rA, p));
  b.v = b.v + b.inverseMass * p;
  b.w = b.w + times(b.inverseInertia, cross(rB, p));
}

COLLIDE_INLINE Vec loadVec(const float (&v)[3][kLanes]) { return {loadW(v[0]), loadW(v[1]), loadW(v[2])}; }
COLLIDE_INLINE void storeVec(float (&v)[3][kLanes], const Vec& x) {
  storeW(v[0], x.x);
  storeW(v[1], x.y);
  storeW(v[2], x.z);
}

struct Lanes {
  EndRecords recordsA, recordsB;
  EndLanes a, b;
  Vec rA, rB;
};

COLLIDE_INLINE void gatherLanes(const JointSolverView& view, const BallLaneGroup& group, Lanes& l) {
  gatherEnd(view, group.bodyA, l.recordsA, l.a);
  gatherEnd(view, group.bodyB, l.recordsB, l.b);
  l.rA = rotate(l.a, loadVec(group.anchorA));
  l.rB = rotate(l.b, loadVec(group.anchorB));
}

}  // namespace

void loadBallGroup(const Array<Joint>& joints, const std::uint32_t (&which)[kBallLanes],
                   BallLaneGroup& group) {
  for (int i = 0; i < kLanes; ++i) {
    const Joint& joint = joints[which[i]];
    group.joint[i] = which[i];
    group.bodyA[i] = joint.bodyA;
    group.bodyB[i] = joint.bodyB;
    for (int c = 0; c < 3; ++c) {
      group.anchorA[c][i] = joint.localAnchorA[c];
      group.anchorB[c][i] = joint.localAnchorB[c];
      group.impulse[c][i] = joint.linearImpulse[c];
      group.frictionImpulse[c][i] = joint.frictionImpulse[c];
    }
    group.softness[i] = joint.softness;
  }
}

void storeBallGroup(const BallLaneGroup& group, Array<Joint>& joints) {
  for (int i = 0; i < kLanes; ++i) {
    Joint& joint = joints[group.joint[i]];
    for (int c = 0; c < 3; ++c) joint.linearImpulse[c] = group.impulse[c][i];
  }
}

void warmStartBalls(const JointSolverView& view, const BallLaneGroup& group) {
  Lanes l;
  gatherLanes(view, group, l);
  // applyAngularImpulse with the friction impulse, then applyImpulse with the point block's.
  const Vec friction = loadVec(group.frictionImpulse);
  l.a.w = l.a.w - times(l.a.inverseInertia, friction);
  l.b.w = l.b.w + times(l.b.inverseInertia, friction);
  applyImpulseLanes(l.a, l.b, l.rA, l.rB, loadVec(group.impulse));
  scatterEnd(l.a);
  scatterEnd(l.b);
}

void solveBalls(const JointSolverView& view, BallLaneGroup& group, float h, float rigidHertz, bool useBias) {
  Lanes l;
  gatherLanes(view, group, l);
  Softness soft[kLanes];
  for (int i = 0; i < kLanes; ++i) soft[i] = rowSoftness(group.softness[i], rigidHertz, h, useBias);
  const FloatW biasRate = setW(soft[0].biasRate, soft[1].biasRate, soft[2].biasRate, soft[3].biasRate);
  const FloatW massScale = setW(soft[0].massScale, soft[1].massScale, soft[2].massScale, soft[3].massScale);
  const FloatW impulseScale =
      setW(soft[0].impulseScale, soft[1].impulseScale, soft[2].impulseScale, soft[3].impulseScale);
  const Vec d = (l.b.center + l.rB) - (l.a.center + l.rA);

  // pointInverseMass: (mA + mB) I - [rA] IA [rA] - [rB] IB [rB].
  const Mat sA = skewLanes(l.rA);
  const Mat sB = skewLanes(l.rB);
  const Mat pA = times(times(sA, l.a.inverseInertia), sA);
  const Mat pB = times(times(sB, l.b.inverseInertia), sB);
  const FloatW mass = l.a.inverseMass + l.b.inverseMass;
  const FloatW zero = zeroW();
  Mat k;
  for (int e = 0; e < 9; ++e) k[e] = ((e % 4 == 0 ? mass : zero) - pA[e]) - pB[e];

  // GLM's determinant and inverse (m[c][r] = k[3 c + r]).
  const FloatW det = k[0] * (k[4] * k[8] - k[7] * k[5]) - k[3] * (k[1] * k[8] - k[7] * k[2]) +
                     k[6] * (k[1] * k[5] - k[4] * k[2]);
  const FloatW solvable = greaterW(det, zero);
  if (!anyW(solvable)) return;
  const FloatW ood = splat(1.0f) / det;
  Mat inv;
  inv[0] = (k[4] * k[8] - k[7] * k[5]) * ood;
  inv[3] = negateW(k[3] * k[8] - k[6] * k[5]) * ood;
  inv[6] = (k[3] * k[7] - k[6] * k[4]) * ood;
  inv[1] = negateW(k[1] * k[8] - k[7] * k[2]) * ood;
  inv[4] = (k[0] * k[8] - k[6] * k[2]) * ood;
  inv[7] = negateW(k[0] * k[7] - k[6] * k[1]) * ood;
  inv[2] = (k[1] * k[5] - k[4] * k[2]) * ood;
  inv[5] = negateW(k[0] * k[5] - k[3] * k[2]) * ood;
  inv[8] = (k[0] * k[4] - k[3] * k[1]) * ood;

  const Vec cdot = (l.b.v + cross(l.b.w, l.rB)) - (l.a.v + cross(l.a.w, l.rA));
  const Vec accumulated = loadVec(group.impulse);
  const Vec impulse = negateW(massScale) * times(inv, cdot + biasRate * d) - impulseScale * accumulated;
  // A lane whose block is singular changes nothing (solvePoint returns).
  const Vec sum = accumulated + impulse;
  storeVec(group.impulse,
           Vec{selectW(solvable, sum.x, accumulated.x), selectW(solvable, sum.y, accumulated.y),
               selectW(solvable, sum.z, accumulated.z)});
  const Vec vA = l.a.v, wA = l.a.w, vB = l.b.v, wB = l.b.w;
  applyImpulseLanes(l.a, l.b, l.rA, l.rB, impulse);
  // Where the block is singular the velocities stay as they were.
  const auto keep = [&](Vec& now, const Vec& before) {
    now = {selectW(solvable, now.x, before.x), selectW(solvable, now.y, before.y),
           selectW(solvable, now.z, before.z)};
  };
  keep(l.a.v, vA);
  keep(l.a.w, wA);
  keep(l.b.v, vB);
  keep(l.b.w, wB);
  scatterEnd(l.a);
  scatterEnd(l.b);
}

}  // namespace collide::detail
