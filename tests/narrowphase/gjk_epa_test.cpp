// GJK distances and EPA depths against closed forms: spheres, capsules and boxes whose answers can
// be written down, and a brute-force minimisation for capsule–box.
#include <collide/narrowphase.h>
#include <gtest/gtest.h>

#include "geometry/closest_points.h"
#include "geometry/triangle.h"
#include "narrowphase/convex_distance.h"
#include "narrowphase/gjk.h"
#include "narrowphase/pair_functions.h"
#include "support/narrowphase_helpers.h"

using namespace collide;
using namespace collide::test;

namespace {

DistanceResult generic(const Shape& a, const Transform& ta, const Shape& b, const Transform& tb) {
  DistanceResult result;
  EXPECT_TRUE(detail::convexSignedDistance(detail::makeConvexSupport(a, ta), detail::makeConvexSupport(b, tb),
                                           1e30f, result));
  return result;
}

// Distance from a point to a placed box (negative inside), through the box's own closest point.
float pointBoxDistance(const Vec3& p, const Box& box, const Transform& t) {
  return closestPoint(box, t, p).signedDistance;
}

}  // namespace

TEST(Gjk, SphereAndCapsuleDistancesMatchClosedForms) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> unit(-2.0f, 2.0f);
  for (int i = 0; i < 500; ++i) {
    const Sphere sa{0.3f + 0.5f * std::abs(unit(rng))};
    const Capsule cb{0.2f + 0.4f * std::abs(unit(rng)), 0.3f + 0.5f * std::abs(unit(rng))};
    const Transform ta = at(Vec3(unit(rng), unit(rng), unit(rng)));
    const Transform tb = at(Vec3(unit(rng), unit(rng), unit(rng)), uniformRotation(rng));
    const Vec3 e0 = tb.applyToPoint(Vec3(0, -cb.halfHeight, 0)),
               e1 = tb.applyToPoint(Vec3(0, cb.halfHeight, 0));
    const float t = detail::closestParameterOnSegment(ta.position, e0, e1);
    const float expected = glm::length(ta.position - (e0 + t * (e1 - e0))) - sa.radius - cb.radius;
    EXPECT_NEAR(generic(sa, ta, cb, tb).distance, expected, 1e-5f);
    // Capsule–capsule: the segments' closest points.
    const Capsule ca{sa.radius, 0.4f};
    const Transform tc = at(ta.position, uniformRotation(rng));
    const Vec3 c0 = tc.applyToPoint(Vec3(0, -0.4f, 0)), c1 = tc.applyToPoint(Vec3(0, 0.4f, 0));
    const detail::SegmentPair pair = detail::closestPointsSegmentSegment(c0, c1, e0, e1);
    const float expectedCapsules = std::sqrt(pair.distanceSquared) - ca.radius - cb.radius;
    const DistanceResult d = generic(ca, tc, cb, tb);
    EXPECT_NEAR(d.distance, expectedCapsules, 2e-5f);
  }
}

TEST(Gjk, SphereBoxDistanceMatchesTheBoxsClosestPoint) {
  std::mt19937 rng(12);
  std::uniform_real_distribution<float> unit(-2.5f, 2.5f);
  for (int i = 0; i < 500; ++i) {
    const Box box{Vec3(0.3f, 0.6f, 0.9f)};
    const Transform tb = at(Vec3(0.1f, -0.2f, 0.3f), uniformRotation(rng));
    const Vec3 center(unit(rng), unit(rng), unit(rng));
    const float radius = 0.25f;
    const float expected = pointBoxDistance(center, box, tb) - radius;
    const DistanceResult d = generic(Sphere{radius}, at(center), box, tb);
    // Inside the box the closed form is the nearest face; EPA must find the same depth.
    EXPECT_NEAR(d.distance, expected, 1e-5f) << i;
    EXPECT_EQ(d.overlapping, expected < 0.0f);
    // The closest point on B lies on the box's surface.
    EXPECT_NEAR(pointBoxDistance(d.pointOnB, box, tb), 0.0f, 1e-5f);
  }
}

TEST(Gjk, CapsuleBoxDistanceMatchesBruteForceAlongTheSegment) {
  // The distance from a segment's point to a convex box is convex along the segment: a ternary
  // search over the segment finds the minimum.
  std::mt19937 rng(13);
  std::uniform_real_distribution<float> unit(-2.5f, 2.5f);
  int separated = 0;
  for (int i = 0; i < 300; ++i) {
    const Box box{Vec3(0.5f, 0.3f, 0.7f)};
    const Capsule capsule{0.2f, 0.6f};
    const Transform tb = at(Vec3(0.0f), uniformRotation(rng));
    const Transform ta = at(Vec3(unit(rng), unit(rng), unit(rng)), uniformRotation(rng));
    const Vec3 e0 = ta.applyToPoint(Vec3(0, -0.6f, 0)), e1 = ta.applyToPoint(Vec3(0, 0.6f, 0));
    double lo = 0.0, hi = 1.0;
    auto f = [&](double t) { return pointBoxDistance(e0 + float(t) * (e1 - e0), box, tb); };
    for (int k = 0; k < 100; ++k) {
      const double m1 = lo + (hi - lo) / 3.0, m2 = hi - (hi - lo) / 3.0;
      (f(m1) < f(m2) ? hi : lo) = (f(m1) < f(m2) ? m2 : m1);
    }
    const float coreDistance = f(0.5 * (lo + hi));
    if (coreDistance <= 0.0f) continue;  // the segment enters the box: not a distance query
    ++separated;
    EXPECT_NEAR(generic(capsule, ta, box, tb).distance, coreDistance - capsule.radius, 2e-5f);
  }
  EXPECT_GT(separated, 200);
}

// The warm-start cache must not change answers: a box and an ellipsoid move along a path that
// goes from apart to overlapping and back, each step warm-started from the previous one, and every
// step must give the cold start's status and distance. The closest points agree less closely: on a
// curved surface of radius R a point off by e changes the distance by e²/(2R), so GJK's distance
// tolerance (~1e-6 of |v|² + |v||w|, about 4e-6 here) leaves them sqrt(2 R 4e-6) ~ 2e-3 apart.
TEST(Gjk, WarmStartFromTheCacheGivesTheColdAnswersAlongAPath) {
  const Shape box = Box{Vec3(0.5f, 0.3f, 0.4f)};
  const Shape ellipsoid = Ellipsoid{Vec3(0.4f, 0.6f, 0.3f)};
  detail::GjkCache cache;
  int warmIterations = 0, coldIterations = 0, overlappingSteps = 0;
  for (int step = 0; step <= 200; ++step) {
    const float t = float(step) / 200.0f;
    const Transform ta = at(Vec3(0.0f), axisAngle(Vec3(0.2f, 1.0f, 0.1f), 40.0f * t));
    // x from 2 to 0.3 and back: apart, overlapping, apart.
    const float x = 0.3f + 1.7f * std::abs(2.0f * t - 1.0f);
    const Transform tb = at(Vec3(x, 0.1f, 0.05f), axisAngle(Vec3(1.0f, 0.3f, 0.0f), 90.0f * t));
    const auto a = detail::makeConvexSupport(box, ta);
    const auto b = detail::makeConvexSupport(ellipsoid, tb);
    const detail::GjkResult cold = detail::gjkDistance(a, b);
    const detail::GjkResult warm = detail::gjkDistance(a, b, 1e30f, &cache);
    ASSERT_EQ(warm.status, cold.status) << "step " << step;
    EXPECT_NEAR(warm.distance, cold.distance, 1e-5f) << "step " << step;
    if (cold.status == detail::GjkResult::Status::Separated) {
      EXPECT_NEAR(glm::length(warm.pointOnA - cold.pointOnA), 0.0f, 3e-3f) << "step " << step;
      EXPECT_NEAR(glm::length(warm.pointOnB - cold.pointOnB), 0.0f, 3e-3f) << "step " << step;
    } else {
      ++overlappingSteps;
    }
    warmIterations += warm.iterations;
    coldIterations += cold.iterations;
  }
  EXPECT_GT(overlappingSteps, 20);
  // Frame coherence is the point of the cache: far fewer support calls along the path.
  EXPECT_LT(warmIterations, coldIterations / 2) << warmIterations << " vs " << coldIterations;
}

namespace {

// The world triangles of a placed hull's faces (fans).
std::vector<std::array<Vec3, 3>> worldTriangles(const ConvexHull& hull, const Transform& t) {
  std::vector<std::array<Vec3, 3>> triangles;
  for (std::uint32_t f = 0; f < hull.faces().size(); ++f) {
    const std::vector<Vec3> loop = hull.faceVertices(f);
    for (std::size_t k = 1; k + 1 < loop.size(); ++k) {
      triangles.push_back({t.applyToPoint(loop[0]), t.applyToPoint(loop[k]), t.applyToPoint(loop[k + 1])});
    }
  }
  return triangles;
}

// The distance between two separated convex polyhedra by brute force over their surface
// triangles: the nearest of every vertex–triangle and edge–edge pair (a separated pair's closest
// points are such a pair).
float bruteForceDistance(const std::vector<std::array<Vec3, 3>>& a,
                         const std::vector<std::array<Vec3, 3>>& b) {
  float best = 1e30f;
  auto vertexTriangle = [&](const std::array<Vec3, 3>& from, const std::array<Vec3, 3>& to) {
    for (const Vec3& p : from) {
      const Vec3 q = detail::closestPointOnTriangle(p, to[0], to[1], to[2]).point;
      best = std::min(best, glm::length(p - q));
    }
  };
  for (const auto& ta : a) {
    for (const auto& tb : b) {
      vertexTriangle(ta, tb);
      vertexTriangle(tb, ta);
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
          const detail::SegmentPair pair =
              detail::closestPointsSegmentSegment(ta[i], ta[(i + 1) % 3], tb[j], tb[(j + 1) % 3]);
          best = std::min(best, std::sqrt(pair.distanceSquared));
        }
      }
    }
  }
  return best;
}

}  // namespace

// GJK between two 32-vertex hulls (the support scan over blocked coordinates, the signed-volume
// sub-simplex solver, B placed in A's frame), cold and warm-started, against the brute-force
// distance over the hulls' faces: within 1e-5, the witness points on the hulls' surfaces and as far
// apart as the distance.
TEST(Gjk, HullDistancesMatchBruteForceOverTheirFaces) {
  std::mt19937 rng(21);
  std::normal_distribution<float> normal(0.0f, 1.0f);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  auto hull = [&] {
    std::vector<Vec3> points(32);
    for (Vec3& p : points)
      p = (0.3f + 0.4f * unit(rng)) * glm::normalize(Vec3(normal(rng), normal(rng), normal(rng)));
    return ConvexHull::fromPoints(points);
  };
  int compared = 0, warmCompared = 0;
  for (int pair = 0; pair < 150; ++pair) {
    const Shape a(hull()), b(hull());
    const Transform ta =
        at(Vec3(normal(rng), normal(rng), normal(rng)), uniformRotation(rng), 0.5f + unit(rng));
    const Vec3 away = randomUnit(rng) * (1.4f * ta.scale + 0.9f + 0.5f * unit(rng));
    detail::GjkCache cache;
    for (int frame = 0; frame < 3; ++frame) {
      // B moves and turns a little from frame to frame: the warm start has something to do.
      const Transform tb =
          at(ta.position + away * (1.0f - 0.05f * frame), uniformRotation(rng), 0.7f + 0.3f * unit(rng));
      const float reference =
          bruteForceDistance(worldTriangles(a.convexHull(), ta), worldTriangles(b.convexHull(), tb));
      if (reference <= 1e-3f) continue;
      const auto sa = detail::makeConvexSupport(a, ta), sb = detail::makeConvexSupport(b, tb);
      const detail::GjkResult cold = detail::gjkDistance(sa, sb);
      const detail::GjkResult warm = detail::gjkDistance(sa, sb, 1e30f, &cache);
      for (const detail::GjkResult* result : {&cold, &warm}) {
        ASSERT_EQ(result->status, detail::GjkResult::Status::Separated)
            << "pair " << pair << " frame " << frame;
        EXPECT_NEAR(result->distance, reference, 1e-5f * (1.0f + reference))
            << "pair " << pair << " frame " << frame;
        EXPECT_NEAR(glm::length(result->pointOnB - result->pointOnA), reference, 2e-5f) << "pair " << pair;
        EXPECT_LT(glm::length(glm::normalize(result->pointOnB - result->pointOnA) - result->normal), 1e-2f);
        // On the surfaces: the closest point of each hull to the other's witness.
        EXPECT_NEAR(closestPoint(a, ta, result->pointOnA).signedDistance, 0.0f, 1e-5f) << "pair " << pair;
        EXPECT_NEAR(closestPoint(b, tb, result->pointOnB).signedDistance, 0.0f, 1e-5f) << "pair " << pair;
      }
      ++compared;
      if (frame > 0) ++warmCompared;
    }
  }
  EXPECT_GT(compared, 400);
  EXPECT_GT(warmCompared, 250);
}

TEST(Epa, DeepSphereInBoxAndBoxInSlabMatchClosedForms) {
  // Sphere whose centre is inside a box: depth = radius + gap to the nearest face.
  const Box box{Vec3(1.0f, 2.0f, 3.0f)};
  const DistanceResult d = generic(Sphere{0.5f}, at({0.2f, 1.5f, -0.4f}), box, Transform::identity());
  EXPECT_NEAR(-d.distance, 0.5f + 0.5f, 1e-5f);
  EXPECT_NEAR(d.normal.y, -1.0f, 1e-5f);
  // A tilted box sunk into a wide slab (a stand-in for a ground plane): the depth is the slab's top
  // minus the box's lowest vertex.
  std::mt19937 rng(21);
  for (int i = 0; i < 100; ++i) {
    const Quat rotation = uniformRotation(rng);
    const Box cube{Vec3(0.5f, 0.4f, 0.3f)};
    const Transform placed = at(Vec3(0.0f, 0.2f, 0.0f), rotation);
    float lowest = 1e30f;
    for (int c = 0; c < 8; ++c) {
      const Vec3 corner((c & 1) ? 0.5f : -0.5f, (c & 2) ? 0.4f : -0.4f, (c & 4) ? 0.3f : -0.3f);
      lowest = std::min(lowest, placed.applyToPoint(corner).y);
    }
    const Box slab{Vec3(50.0f, 1.0f, 50.0f)};
    const DistanceResult r = generic(slab, at({0.0f, -1.0f, 0.0f}), cube, placed);
    ASSERT_TRUE(r.overlapping);
    EXPECT_NEAR(-r.distance, 0.0f - lowest, 2e-5f) << i;
    EXPECT_NEAR(r.normal.y, 1.0f, 1e-4f);
  }
}

TEST(Epa, AxisAlignedBoxesPenetrateByTheirSmallestOverlap) {
  // For axis-aligned boxes A - B is a box too: the depth is the smallest overlap along an axis.
  std::mt19937 rng(22);
  std::uniform_real_distribution<float> unit(0.2f, 1.0f), offset(-0.8f, 0.8f);
  for (int i = 0; i < 200; ++i) {
    const Vec3 ha(unit(rng), unit(rng), unit(rng)), hb(unit(rng), unit(rng), unit(rng));
    const Vec3 d(offset(rng), offset(rng), offset(rng));
    const Vec3 overlapPerAxis = ha + hb - glm::abs(d);
    if (glm::min(overlapPerAxis.x, glm::min(overlapPerAxis.y, overlapPerAxis.z)) <= 1e-3f) continue;
    const float expected = glm::min(overlapPerAxis.x, glm::min(overlapPerAxis.y, overlapPerAxis.z));
    const DistanceResult r = generic(Box{ha}, Transform::identity(), Box{hb}, at(d));
    EXPECT_NEAR(-r.distance, expected, 2e-5f) << i;
  }
}

TEST(Distance, PlaneAndConvexAndRejectedShapes) {
  const Plane ground{{0.0f, 1.0f, 0.0f}, 0.0f};
  const DistanceResult above = collide::distance(ground, Transform::identity(), Sphere{0.5f}, at({1, 2, 3}));
  EXPECT_NEAR(above.distance, 1.5f, 1e-6f);
  EXPECT_FALSE(above.overlapping);
  EXPECT_NEAR(above.pointOnA.y, 0.0f, 1e-6f);
  const DistanceResult mirrored =
      collide::distance(Box{Vec3(0.5f)}, at({0, 0.2f, 0}), ground, Transform::identity());
  EXPECT_NEAR(mirrored.distance, -0.3f, 1e-6f);
  EXPECT_TRUE(mirrored.overlapping);
  EXPECT_NEAR(mirrored.normal.y, -1.0f, 1e-6f);
}

// Found by the narrow-phase fuzzer: a rotation 3.6e-4 off unit length (the queries accept 1e-3)
// turned GJK's normal into the world 1.0015 long. The normal is a direction: unit whatever the
// rotation's rounding. The rest is what such a rotation means: it turns and also stretches by
// |q|^2, which moves B in A's frame, and A's far side, by at most (|q|^2 - 1) times their reach.
TEST(Gjk, NormalStaysUnitUnderANearlyUnitRotation) {
  const Shape cylinder(Cylinder{0.400013894f, 0.600000739f});
  const Shape ball(Sphere{0.00999999978f});
  Transform ta, tb;
  ta.position = Vec3(4.57763672e-05f, 0.000137329102f, -0.744106293f);
  ta.rotation = Quat(1.52587891e-05f, 0.0269931555f, -1.0f, 1.52587891e-05f);  // |q| = 1.00036
  tb.position = Vec3(-2.92968655f, -0.741176367f, -0.741176367f);
  const DistanceResult d = distance(cylinder, ta, ball, tb);
  ASSERT_FALSE(d.overlapping);
  EXPECT_NEAR(glm::length(d.normal), 1.0f, 1e-5f);
  Transform unit = ta;
  unit.rotation = glm::normalize(ta.rotation);
  const DistanceResult reference = distance(cylinder, unit, ball, tb);
  const float stretch = glm::dot(ta.rotation, ta.rotation) - 1.0f;
  const float reach = glm::length(tb.position - ta.position) + glm::length(Vec3(0.4f, 0.6f, 0.0f));
  EXPECT_NEAR(d.distance, reference.distance, 2.0f * stretch * reach);
  EXPECT_GT(glm::dot(d.normal, reference.normal), std::cos(0.01f));
}
