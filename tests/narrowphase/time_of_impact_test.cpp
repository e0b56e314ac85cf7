// Time of impact against answers that can be written down (sphere on a plane, boxes in a line, a
// turning plank reaching a ball) and against a brute-force scan of the distance along the sweep.
#include <collide/narrowphase.h>
#include <gtest/gtest.h>

#include "support/collide_error.h"
#include "support/narrowphase_helpers.h"

#include <cmath>
#include <random>

using namespace collide;
using namespace collide::test;

namespace {

constexpr float kTarget = 0.005f;
constexpr float kTimeTolerance = 0.00125f;

Sweep moving(const Vec3& from, const Vec3& to, const Quat& rotation = Quat(1.0f, 0.0f, 0.0f, 0.0f)) {
  return Sweep::between(at(from, rotation), at(to, rotation));
}

// The signed distance of A and B at time t of their sweeps (meshes: the nearest triangle).
float distanceAt(const Shape& a, const Sweep& sa, const Shape& b, const Sweep& sb, float t) {
  if (b.type() == ShapeType::Mesh) {
    // A sphere against a mesh surface: the nearest surface point from the centre, less the radius.
    const Transform ta = sa.at(t), tb = sb.at(t);
    return std::abs(closestPoint(b, tb, ta.position).signedDistance) - a.sphere().radius * ta.scale;
  }
  return distance(a, sa.at(t), b, sb.at(t)).distance;
}

// The brute-force check of one answer: no earlier time (sampled) is closer than the target, and
// at the returned time the gap is the target within the tolerance.
void expectFirstContact(const Shape& a, const Sweep& sa, const Shape& b, const Sweep& sb, const ToiResult& r,
                        int samples = 200) {
  const float end = r.hit() ? r.t : 1.0f;
  for (int i = 0; i < samples; ++i) {
    const float t = end * static_cast<float>(i) / static_cast<float>(samples);
    ASSERT_GT(distanceAt(a, sa, b, sb, t), kTarget - 2e-4f) << "t = " << t << " before the reported " << end;
  }
  if (r.state == ToiResult::State::Hit) {
    const float gap = distanceAt(a, sa, b, sb, r.t);
    EXPECT_GT(gap, kTarget - 2e-4f);
    EXPECT_LT(gap, kTarget + kTimeTolerance + 2e-4f);
  }
}

}  // namespace

TEST(TimeOfImpact, SphereFallingOnPlaneAtKnownSpeed) {
  // Centre from y = 10 to y = -10 over the step: the gap reaches the target when y = r + target.
  const Shape sphere(Sphere{0.5f});
  const Shape plane(Plane{Vec3(0.0f, 1.0f, 0.0f), 0.0f});
  const ToiResult r = timeOfImpact(sphere, moving(Vec3(0, 10, 0), Vec3(0, -10, 0)), plane,
                                   Sweep::fixed(Transform::identity()));
  ASSERT_EQ(r.state, ToiResult::State::Hit);
  EXPECT_NEAR(r.t, (10.0f - 0.5f - kTarget) / 20.0f, 1e-6f);
  EXPECT_NEAR(r.normal.y, -1.0f, 1e-6f);  // from the sphere (A) to the plane (B)
  EXPECT_NEAR(r.point.y, 0.5f * kTarget, 1e-4f);
  // The same with the plane as A: the normal flips.
  const ToiResult mirrored = timeOfImpact(plane, Sweep::fixed(Transform::identity()), sphere,
                                          moving(Vec3(0, 10, 0), Vec3(0, -10, 0)));
  EXPECT_NEAR(mirrored.t, r.t, 1e-6f);
  EXPECT_NEAR(mirrored.normal.y, 1.0f, 1e-6f);
}

// Fuzzing found it: a plane whose rotation is within the validation's tolerance of unit (|q|^2
// 0.9991), against a flat ellipsoid it overlaps. The normal of the time of impact and of the
// contact is unit all the same. (timeOfImpact also accepted a rotation just outside that tolerance,
// which collide refuses: both now take the same.)
TEST(TimeOfImpact, NearlyUnitPlaneRotationGivesAUnitNormal) {
  const Shape plane(Plane{Vec3(1.53181591e-05f, 1.0f, 1.53181591e-05f), 3.05175818e-05f});
  Transform planeAt;
  planeAt.position = Vec3(4.57763672e-05f, 4.57763672e-05f, -3.0f);
  planeAt.rotation =
      std::sqrt(0.9991f) * glm::normalize(Quat(1.52587891e-05f, -0.999328613f, 0.01673913f, 1.52587891e-05f));
  ASSERT_TRUE(isValid(planeAt));
  Transform outside = planeAt;
  outside.rotation = Quat(1.52587891e-05f, -0.999328613f, 0.01673913f, 1.52587891e-05f);  // |q|^2 0.99894
  ASSERT_FALSE(isValid(outside));
  const Shape flat(Ellipsoid{Vec3(1.63467324f, 0.0100910962f, 1.01275837f)});
  Transform from;
  from.position = Vec3(-2.98828101f, 4.57763672e-05f, -2.97070265f);
  from.rotation = Quat(8.84407928e-06f, -0.577341437f, -0.575095057f, -0.579605579f);
  Transform to;
  to.position = Vec3(-6.97265577f, -3.97663856f, -6.96289015f);
  to.rotation = Quat(-0.579972565f, 8.84967903e-06f, -0.576591969f, 0.575476885f);
  const ToiResult r = timeOfImpact(plane, Sweep::fixed(planeAt), flat, Sweep::between(from, to));
  ASSERT_NE(r.state, ToiResult::State::Separated);
  EXPECT_NEAR(glm::length(r.normal), 1.0f, 1e-5f);
  Manifold m;
  if (collide::collide(plane, planeAt, flat, from, m)) {
    EXPECT_NEAR(glm::length(m.normal), 1.0f, 1e-5f);
  }
  EXPECT_COLLIDE_ERROR(timeOfImpact(plane, Sweep::fixed(outside), flat, Sweep::between(from, to)));
}

TEST(TimeOfImpact, MissesAndStartsOverlapping) {
  const Shape sphere(Sphere{0.5f});
  const Shape box(Box{Vec3(1.0f)});
  // Moving away, and passing beside.
  EXPECT_EQ(timeOfImpact(sphere, moving(Vec3(0, 3, 0), Vec3(0, 8, 0)), box, Sweep::fixed({})).state,
            ToiResult::State::Separated);
  EXPECT_EQ(timeOfImpact(sphere, moving(Vec3(-5, 2, 0), Vec3(5, 2, 0)), box, Sweep::fixed({})).state,
            ToiResult::State::Separated);
  // Stops short of the box.
  EXPECT_EQ(timeOfImpact(sphere, moving(Vec3(0, 5, 0), Vec3(0, 2, 0)), box, Sweep::fixed({})).state,
            ToiResult::State::Separated);
  // Touching at the start (within target + tolerance), whatever the motion.
  const ToiResult touching =
      timeOfImpact(sphere, moving(Vec3(0, 1.503f, 0), Vec3(0, -5, 0)), box, Sweep::fixed({}));
  EXPECT_EQ(touching.state, ToiResult::State::Overlapping);
  EXPECT_EQ(touching.t, 0.0f);
  // The same for the conservative advancement path (box against box).
  EXPECT_EQ(timeOfImpact(box, moving(Vec3(0, 1.0f, 0), Vec3(0, 5, 0)), box, Sweep::fixed({})).state,
            ToiResult::State::Overlapping);
}

TEST(TimeOfImpact, BoxesInALineByConservativeAdvancement) {
  // Box A (half 0.5) moves 10 m along x towards box B (half 0.5) centred at x = 5: the faces close
  // 4 m, so the gap reaches the target at t = (4 - target) / 10.
  const Shape box(Box{Vec3(0.5f)});
  const ToiResult r =
      timeOfImpact(box, moving(Vec3(0.0f), Vec3(10, 0, 0)), box, Sweep::fixed(at(Vec3(5, 0, 0))));
  ASSERT_EQ(r.state, ToiResult::State::Hit);
  EXPECT_LE(r.t, (4.0f - kTarget) / 10.0f + 1e-6f);
  EXPECT_GE(r.t, (4.0f - kTarget - kTimeTolerance) / 10.0f - 1e-6f);
  EXPECT_NEAR(r.normal.x, 1.0f, 1e-4f);
  EXPECT_LE(r.iterations, 4);  // face against face: the tangent bound is exact
  // Both moving towards each other at 5 m each: the same closing motion, the same time.
  const ToiResult both =
      timeOfImpact(box, moving(Vec3(0.0f), Vec3(5, 0, 0)), box, moving(Vec3(5, 0, 0), Vec3(0, 0, 0)));
  ASSERT_EQ(both.state, ToiResult::State::Hit);
  EXPECT_NEAR(both.t, r.t, kTimeTolerance / 10.0f + 1e-6f);
  // Rotated boxes: checked by brute force.
  std::mt19937 rng(7);
  for (int i = 0; i < 50; ++i) {
    const Quat qa = uniformRotation(rng), qb = uniformRotation(rng);
    const Sweep sa = moving(Vec3(-4, 0.3f, 0), Vec3(4, -0.2f, 0.1f), qa);
    const Sweep sb = Sweep::fixed(at(Vec3(0.5f, 0, 0), qb));
    const ToiResult hit = timeOfImpact(box, sa, box, sb);
    ASSERT_TRUE(hit.hit());
    expectFirstContact(box, sa, box, sb, hit);
  }
}

TEST(TimeOfImpact, TurningPlankReachesBallAtTheAnalyticAngle) {
  // A plank 2 long, 0.1 thick, turning about z through 90 degrees during the sweep, starting along x.
  // A ball of radius 0.1 sits at 45 degrees, 0.6 from the axis: the plank's face meets it when the
  // ball centre is (0.05 + 0.1 + target) from the plank's axis line: 0.6 sin(45° - phi) = 0.15 + target.
  const Shape plank(Box{Vec3(1.0f, 0.05f, 0.05f)});
  const Shape ball(Sphere{0.1f});
  const Quat end = axisAngle(Vec3(0, 0, 1), 90.0f);
  const Sweep sweep = Sweep::between(at(Vec3(0.0f)), at(Vec3(0.0f), end));
  const Vec3 ballAt = 0.6f * Vec3(std::cos(kPi / 4.0f), std::sin(kPi / 4.0f), 0.0f);
  const ToiResult r = timeOfImpact(plank, sweep, ball, Sweep::fixed(at(ballAt)));
  ASSERT_EQ(r.state, ToiResult::State::Hit);
  const float phi = kPi / 4.0f - std::asin((0.15f + kTarget) / 0.6f);
  const float expected = phi / (kPi / 2.0f);
  // Within the tolerance, turned into an angle at 0.6 m, turned into t.
  EXPECT_LE(r.t, expected + 1e-5f);
  EXPECT_GE(r.t, expected - (kTimeTolerance / 0.6f) / (kPi / 2.0f) - 1e-5f);
  // Catto's bound: each advance is (d - target) / (angle * r_max) with r_max = |(1, .05, .05)|; the
  // count is finite and small.
  EXPECT_LT(r.iterations, 40);
  // A ball beyond the plank's reach (1.1 from the axis) is never hit.
  const ToiResult miss = timeOfImpact(plank, sweep, ball, Sweep::fixed(at(1.3f * ballAt / 0.6f)));
  EXPECT_EQ(miss.state, ToiResult::State::Separated);
}

TEST(TimeOfImpact, FastSpinningThinPlankNeverSkipsTheBall) {
  // Random small balls in the plane a propeller-like plank turns in (about its local z, the thin
  // face leading), up to 170 degrees in the sweep: the answer is the first time the sampled
  // distance reaches the target.
  const Shape plank(Box{Vec3(1.0f, 0.02f, 0.1f)});
  const Shape ball(Sphere{0.05f});
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  int hits = 0;
  for (int i = 0; i < 100; ++i) {
    const Quat start = uniformRotation(rng);
    const Vec3 axis = start * Vec3(0, 0, 1);
    const float turn = glm::radians(170.0f * (0.5f + 0.5f * u(rng)));
    const Quat end = glm::normalize(glm::angleAxis(turn, axis) * start);
    const Sweep sweep = Sweep::between(at(Vec3(0.0f), start), at(0.05f * u(rng) * axis, end));
    const float angle = kPi * u(rng), radius = 0.6f + 0.35f * u(rng);
    const Vec3 ballAt = start * Vec3(radius * std::cos(angle), radius * std::sin(angle), 0.1f * u(rng));
    if (distance(plank, sweep.at(0.0f), ball, at(ballAt)).distance < 0.01f) continue;
    const ToiResult r = timeOfImpact(plank, sweep, ball, Sweep::fixed(at(ballAt)));
    hits += r.hit() ? 1 : 0;
    expectFirstContact(plank, sweep, ball, Sweep::fixed(at(ballAt)), r, 1000);
  }
  EXPECT_GT(hits, 20);  // the scan checked real hits, not only misses
}

TEST(TimeOfImpact, ExactSphereSweepsMatchBruteForce) {
  // Sphere against box, capsule, sphere and a one-triangle mesh from random directions: the exact
  // (segment against Minkowski sum) answers, checked by scanning the distance along the sweep.
  const Shape sphere(Sphere{0.05f});
  const std::vector<Shape> others = {
      Shape(Box{Vec3(0.5f, 0.01f, 0.4f)}), Shape(Capsule{0.1f, 0.4f}), Shape(Sphere{0.3f}),
      Shape(TriangleMesh::fromTriangles({Vec3(-0.5f, 0, -0.5f), Vec3(0.6f, 0, -0.4f), Vec3(0, 0, 0.7f)},
                                        {MeshTriangle{{0, 1, 2}}}))};
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (const Shape& other : others) {
    int hits = 0;
    for (int i = 0; i < 300; ++i) {
      const Transform placed = at(Vec3(0.0f), uniformRotation(rng), 1.0f + 0.5f * u(rng));
      const Vec3 from = 1.5f * randomUnit(rng);
      const Vec3 to = -from + 0.6f * Vec3(u(rng), u(rng), u(rng));
      const Sweep sweep = moving(from, to);
      if (distanceAt(sphere, sweep, other, Sweep::fixed(placed), 0.0f) < 0.01f) continue;
      const ToiResult r = timeOfImpact(sphere, sweep, other, Sweep::fixed(placed));
      // The exact path: one segment cast (none when the mesh's BVH finds no triangle near).
      EXPECT_LE(r.iterations, 1) << "the exact path, not conservative advancement";
      hits += r.hit() ? 1 : 0;
      expectFirstContact(sphere, sweep, other, Sweep::fixed(placed), r, 2000);
      if (r.state == ToiResult::State::Hit) {
        EXPECT_NEAR(distanceAt(sphere, sweep, other, Sweep::fixed(placed), r.t), kTarget, 2e-4f);
      }
    }
    EXPECT_GT(hits, 50) << toString(other.type());
  }
}

TEST(TimeOfImpact, MeshesAreTwoSided) {
  const Shape triangle(TriangleMesh::fromTriangles({Vec3(-1, 0, -1), Vec3(1, 0, -1), Vec3(0, 0, 1)},
                                                   {MeshTriangle{{0, 1, 2}}}));
  const Shape sphere(Sphere{0.05f});
  for (float side : {1.0f, -1.0f}) {  // from the front (counter-clockwise side, +y) and the back
    const ToiResult r =
        timeOfImpact(sphere, moving(Vec3(0, 2 * side, 0), Vec3(0, -3 * side, 0)), triangle, Sweep::fixed({}));
    ASSERT_EQ(r.state, ToiResult::State::Hit) << side;
    EXPECT_NEAR(r.t, (2.0f - 0.05f - kTarget) / 5.0f, 1e-5f);
    EXPECT_NEAR(r.normal.y, -side, 1e-4f);
  }
  // Starting within reach of the face (inside the rounded triangle's slab, over the triangle):
  // touching at the start, not a miss.
  EXPECT_EQ(
      timeOfImpact(sphere, moving(Vec3(0, 0.054f, 0), Vec3(0, -1, 0)), triangle, Sweep::fixed({})).state,
      ToiResult::State::Overlapping);
  ToiSettings deeper;
  deeper.targetSeparation = 0.0f;  // the world's second query for touching pairs: no deeper than now
  const ToiResult stop =
      timeOfImpact(sphere, moving(Vec3(0, 0.054f, 0), Vec3(0, -1, 0)), triangle, Sweep::fixed({}), deeper);
  ASSERT_EQ(stop.state, ToiResult::State::Hit);
  EXPECT_NEAR(stop.t, 0.004f / 1.054f, 1e-5f);
  // A box (conservative advancement per triangle) from both sides as well.
  const Shape box(Box{Vec3(0.1f)});
  for (float side : {1.0f, -1.0f}) {
    const ToiResult r =
        timeOfImpact(box, moving(Vec3(0, 2 * side, 0), Vec3(0, -3 * side, 0)), triangle, Sweep::fixed({}));
    ASSERT_EQ(r.state, ToiResult::State::Hit) << side;
    EXPECT_NEAR(r.t, (2.0f - 0.1f - kTarget) / 5.0f, kTimeTolerance / 5.0f + 1e-5f);
  }
}

TEST(TimeOfImpact, CompoundChildMatchesTheShapeAlone) {
  const Shape child(Box{Vec3(0.2f, 0.1f, 0.3f)});
  const Transform offset = at(Vec3(0.5f, 0.2f, 0), axisAngle(Vec3(1, 1, 0), 30.0f));
  const Shape compound(Compound::fromChildren({Compound::Child{child, offset}}));
  const Shape wall(Box{Vec3(0.05f, 2.0f, 2.0f)});
  const Quat q0 = axisAngle(Vec3(0, 1, 0), 10.0f), q1 = axisAngle(Vec3(0, 1, 0), 60.0f);
  const Sweep body = Sweep::between(at(Vec3(-3, 0, 0), q0), at(Vec3(3, 0, 0), q1), Vec3(0.1f, 0, 0));
  const ToiResult viaCompound = timeOfImpact(compound, body, wall, Sweep::fixed({}));
  // The child alone placed by the body's sweep at both ends, turning about the same centre.
  Sweep alone = body;
  alone.rotation0 = glm::normalize(q0 * offset.rotation);
  alone.rotation1 = glm::normalize(q1 * offset.rotation);
  alone.localCenter = glm::conjugate(offset.rotation) * (body.localCenter - offset.position);
  const ToiResult viaChild = timeOfImpact(child, alone, wall, Sweep::fixed({}));
  ASSERT_TRUE(viaCompound.hit());
  EXPECT_NEAR(viaCompound.t, viaChild.t, 1e-5f);
  for (float t : {0.0f, 0.5f, 1.0f}) {  // the composed sweep places the child where the compound does
    const Transform childWorld = body.at(t) * offset;
    EXPECT_LT(glm::length(childWorld.position - alone.at(t).position), 1e-5f);
  }
}

TEST(TimeOfImpact, SweepInterpolatesAboutTheCentre) {
  const Quat q1 = axisAngle(Vec3(0, 0, 1), 90.0f);
  const Sweep s = Sweep::between(at(Vec3(0.0f)), at(Vec3(2, 0, 0), q1), Vec3(1, 0, 0));
  EXPECT_NEAR(s.angle(), kPi / 2.0f, 1e-5f);
  // The centre (local (1,0,0)) moves in a straight line: at t = 0.5 it is halfway.
  const Transform mid = s.at(0.5f);
  const Vec3 centre = mid.applyToPoint(Vec3(1, 0, 0));
  const Vec3 expected = 0.5f * (Vec3(1, 0, 0) + (Vec3(2, 0, 0) + q1 * Vec3(1, 0, 0)));
  EXPECT_LT(glm::length(centre - expected), 1e-5f);
  EXPECT_LT(glm::length(s.at(1.0f).position - Vec3(2, 0, 0)), 1e-5f);
  EXPECT_EQ(Sweep::fixed(at(Vec3(1, 2, 3))).angle(), 0.0f);
}

TEST(TimeOfImpact, BadInputThrows) {
  const Shape sphere(Sphere{0.5f});
  const Shape plane(Plane{});
  Sweep bad = Sweep::fixed({});
  bad.center1 = Vec3(std::nanf(""), 0, 0);
  EXPECT_COLLIDE_ERROR(timeOfImpact(sphere, bad, sphere, Sweep::fixed({})));
  bad = Sweep::fixed({});
  bad.rotation1 = Quat(2.0f, 0, 0, 0);
  EXPECT_COLLIDE_ERROR(timeOfImpact(sphere, Sweep::fixed({}), sphere, bad));
  bad = Sweep::fixed({});
  bad.scale = 0.0f;
  EXPECT_COLLIDE_ERROR(timeOfImpact(sphere, bad, sphere, Sweep::fixed({})));
  EXPECT_COLLIDE_ERROR(timeOfImpact(plane, Sweep::fixed({}), plane, Sweep::fixed(at(Vec3(0, -1, 0)))));
  const Sweep turning = Sweep::between(at(Vec3(0.0f)), at(Vec3(0.0f), axisAngle(Vec3(1, 0, 0), 10.0f)));
  EXPECT_COLLIDE_ERROR(timeOfImpact(plane, turning, sphere, Sweep::fixed(at(Vec3(0, 3, 0)))));
  ToiSettings settings;
  settings.targetSeparation = std::nanf("");
  EXPECT_COLLIDE_ERROR(
      timeOfImpact(sphere, Sweep::fixed({}), sphere, Sweep::fixed(at(Vec3(3, 0, 0))), settings));
  settings = {};
  settings.tolerance = 0.0f;
  EXPECT_COLLIDE_ERROR(
      timeOfImpact(sphere, Sweep::fixed({}), sphere, Sweep::fixed(at(Vec3(3, 0, 0))), settings));
  settings = {};
  settings.maxIterations = 0;
  EXPECT_COLLIDE_ERROR(
      timeOfImpact(sphere, Sweep::fixed({}), sphere, Sweep::fixed(at(Vec3(3, 0, 0))), settings));
}
