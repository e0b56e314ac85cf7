#include "support/collide_error.h"
#include "support/test_meshes.h"

#include <collide/shapes.h>
#include <gtest/gtest.h>

#include <limits>
#include <random>
#include <string>
#include "support/test_assertions.h"

using namespace collide;

namespace {

using test::expectMatNear;

std::string compoundError(std::vector<Compound::Child> children) {
  return ::collide::test::errorOf([&] { Compound::fromChildren(std::move(children)); }).value_or("no error");
}

Transform childTransform(std::mt19937& rng) {
  return {test::randomPoint(rng, -2.0f, 2.0f), test::randomRotation(rng),
          std::uniform_real_distribution<float>(0.7f, 1.5f)(rng)};
}

// Five different proxies, one of them a closed mesh, at fixed random places that overlap a little.
std::vector<Compound::Child> mixedChildren(std::mt19937& rng) {
  std::vector<Compound::Child> children;
  children.push_back({Shape(Box{{1.0f, 0.5f, 0.3f}}), childTransform(rng)});
  children.push_back({Shape(Sphere{0.7f}), childTransform(rng)});
  children.push_back({Shape(Capsule{0.3f, 0.8f}), childTransform(rng)});
  children.push_back({Shape(test::boxMesh(Vec3(0.6f, 0.4f, 0.9f))), childTransform(rng)});
  children.push_back({Shape(Cylinder{0.5f, 0.6f}), childTransform(rng)});
  return children;
}

}  // namespace

TEST(Compound, TwoDisjointBoxesSumByTheParallelAxisTheorem) {
  const Compound compound = Compound::fromChildren({
      {Shape(Box{{1.0f, 0.5f, 0.5f}}), {{2.0f, 0.0f, 0.0f}}},
      {Shape(Box{{0.5f, 0.5f, 0.5f}}), {{-1.0f, 1.0f, 0.0f}}},
  });
  const MassProperties m = massProperties(Shape(compound), 2.0f);
  // Box A: 2 x 1 x 1, mass 4 at (2, 0, 0). Box B: unit cube, mass 2 at (-1, 1, 0).
  EXPECT_FLOAT_EQ(m.mass, 6.0f);
  EXPECT_FLOAT_EQ(m.volume, 3.0f);
  // Centre of mass (4 (2,0,0) + 2 (-1,1,0)) / 6 = (1, 1/3, 0).
  test::expectVecWithin(m.centerOfMass, Vec3(1.0f, 1.0f / 3.0f, 0.0f), 1e-6f);
  // Own inertias, m/12 (b^2 + c^2): A = 4/12 (1+1, 4+1, 4+1) = (2/3, 5/3, 5/3); B = 2/12 * 2 = 1/3 each.
  // Offsets from the common centre: dA = (1, -1/3, 0), dB = (-2, 2/3, 0).
  // Parallel axis, m (|d|^2 - d_i^2) on the diagonal and -m d_i d_j off it:
  //   xx: 2/3 + 4 (1/9) + 1/3 + 2 (4/9)  = 1 + 4/9 + 8/9  = 7/3
  //   yy: 5/3 + 4 (1)   + 1/3 + 2 (4)    = 2 + 4 + 8      = 14
  //   zz: 5/3 + 4 (10/9) + 1/3 + 2 (40/9) = 2 + 40/9 + 80/9 = 46/3
  //   xy: -4 (1)(-1/3) - 2 (-2)(2/3)     = 4/3 + 8/3      = 4
  Mat3 expected(0.0f);
  expected[0][0] = 7.0f / 3.0f;
  expected[1][1] = 14.0f;
  expected[2][2] = 46.0f / 3.0f;
  expected[0][1] = expected[1][0] = 4.0f;
  expectMatNear(m.inertia, expected, 1e-5f);
}

TEST(Compound, OneChildHasTheMassPropertiesOfThatChildPlacedThere) {
  std::mt19937 rng(31);
  for (int trial = 0; trial < 20; ++trial) {
    const Transform t = test::randomTransform(rng);
    const Vec3 h(1.0f, 0.5f, 0.25f);
    const Compound compound = Compound::fromChildren({{Shape(Box{h}), t}});
    // Reference: a mesh of the box with its corners moved by t, integrated directly.
    const TriangleMesh placed = test::boxMesh(h, [&](const Vec3& p) { return t.applyToPoint(p); });
    const MassProperties expected = massProperties(Shape(placed), 1.5f);
    const MassProperties actual = massProperties(Shape(compound), 1.5f);
    EXPECT_NEAR(actual.mass, expected.mass, 1e-4f * expected.mass);
    test::expectVecWithin(actual.centerOfMass, expected.centerOfMass, 1e-4f);
    expectMatNear(actual.inertia, expected.inertia, 1e-4f * expected.inertia[0][0] + 1e-4f);
  }
}

TEST(Compound, NestedCompoundEqualsTheFlattenedOne) {
  std::mt19937 rng(32);
  const Transform t1 = test::randomTransform(rng), t2 = test::randomTransform(rng),
                  outer = test::randomTransform(rng);
  const Shape inner(
      Compound::fromChildren({{Shape(Box{{0.5f, 1.0f, 0.2f}}), t1}, {Shape(Sphere{0.4f}), t2}}));
  const Shape nested(Compound::fromChildren({{inner, outer}}));
  const Shape flat(Compound::fromChildren(
      {{Shape(Box{{0.5f, 1.0f, 0.2f}}), outer * t1}, {Shape(Sphere{0.4f}), outer * t2}}));
  const MassProperties a = massProperties(nested, 1.0f), b = massProperties(flat, 1.0f);
  EXPECT_NEAR(a.mass, b.mass, 1e-4f * b.mass);
  test::expectVecWithin(a.centerOfMass, b.centerOfMass, 1e-3f);
  expectMatNear(a.inertia, b.inertia, 1e-3f * b.inertia[0][0]);
  for (int i = 0; i < 200; ++i) {
    const Vec3 p = test::randomPoint(rng, -15.0f, 15.0f);
    const SurfacePoint sa = closestPoint(nested, Transform{}, p), sb = closestPoint(flat, Transform{}, p);
    EXPECT_NEAR(sa.signedDistance, sb.signedDistance, 1e-3f);
  }
}

TEST(Compound, BoundsAreTheUnionOfTheChildren) {
  std::mt19937 rng(33);
  const std::vector<Compound::Child> children = mixedChildren(rng);
  const Shape compound(Compound::fromChildren(children));
  for (int trial = 0; trial < 20; ++trial) {
    const Transform w = trial == 0 ? Transform{} : test::randomTransform(rng);
    Aabb expected;
    for (const Compound::Child& c : children) expected.grow(worldBounds(c.shape, w * c.transform));
    const Aabb actual = trial == 0 ? localBounds(compound) : worldBounds(compound, w);
    test::expectVecWithin(actual.min, expected.min, 1e-4f);
    test::expectVecWithin(actual.max, expected.max, 1e-4f);
  }
}

TEST(Compound, RayCastsMatchBruteForceOverChildren) {
  std::mt19937 rng(34);
  const std::vector<Compound::Child> children = mixedChildren(rng);
  const Shape compound(Compound::fromChildren(children));
  const Transform w = test::randomTransform(rng);
  int hits = 0, inside = 0;
  for (int i = 0; i < 1000; ++i) {
    Ray ray;
    // From anywhere around the compound (sometimes inside a child) towards one child.
    const Vec3 aim =
        children[rng() % children.size()].transform.position + test::randomPoint(rng, -1.0f, 1.0f);
    const Vec3 start = i % 3 == 0 ? children[rng() % children.size()].transform.position : Vec3(0.0f);
    ray.origin = w.applyToPoint(start + test::randomPoint(rng, -4.0f, 4.0f) * (i % 3 == 0 ? 0.2f : 1.0f));
    ray.direction = glm::normalize(w.applyToPoint(aim) - ray.origin);
    float best = std::numeric_limits<float>::infinity(), secondBest = best;
    std::uint32_t bestChild = 0;
    std::optional<RayHit> bestHit;
    for (std::uint32_t c = 0; c < children.size(); ++c) {
      const std::optional<RayHit> hit = rayCast(children[c].shape, w * children[c].transform, ray);
      if (!hit) continue;
      if (hit->distance < best) {
        secondBest = best;
        best = hit->distance;
        bestChild = c;
        bestHit = hit;
      } else {
        secondBest = std::min(secondBest, hit->distance);
      }
    }
    const std::optional<RayHit> actual = rayCast(compound, w, ray);
    ASSERT_EQ(actual.has_value(), bestHit.has_value()) << "ray " << i;
    if (!bestHit) continue;
    ++hits;
    inside += int(best == 0.0f);
    EXPECT_NEAR(actual->distance, best, 1e-4f * std::max(1.0f, best)) << "ray " << i;
    if (secondBest - best > 1e-3f) {  // the nearest child is unambiguous
      EXPECT_EQ(actual->subShape, bestChild) << "ray " << i;
      test::expectVecWithin(actual->normal, bestHit->normal, 1e-3f);
    }
  }
  EXPECT_GT(hits, 400);
  EXPECT_GT(inside, 20);
}

TEST(Compound, ContainmentAndClosestPointsMatchBruteForceOverChildren) {
  std::mt19937 rng(35);
  const std::vector<Compound::Child> children = mixedChildren(rng);
  const Shape compound(Compound::fromChildren(children));
  const Transform w = test::randomTransform(rng);
  int insideCount = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec3 near = children[rng() % children.size()].transform.position;
    const Vec3 p = w.applyToPoint(near + test::randomPoint(rng, -1.5f, 1.5f));
    bool inside = false;
    float minSigned = std::numeric_limits<float>::infinity();
    float nearestSurface = minSigned;
    for (const Compound::Child& c : children) {
      const Transform placed = w * c.transform;
      inside = inside || containsPoint(c.shape, placed, p);
      const float d = closestPoint(c.shape, placed, p).signedDistance;
      minSigned = std::min(minSigned, d);
      nearestSurface = std::min(nearestSurface, std::abs(d));
    }
    if (nearestSurface < 1e-3f) continue;  // on a child's surface: float noise decides
    EXPECT_EQ(containsPoint(compound, w, p), inside) << "point " << i;
    const SurfacePoint s = closestPoint(compound, w, p);
    // Outside: the nearest child surface (exact). Inside: the deepest child's surface (a bound).
    EXPECT_NEAR(s.signedDistance, minSigned, 1e-3f) << "point " << i;
    EXPECT_EQ(s.signedDistance < 0.0f, inside);
    insideCount += int(inside);
  }
  EXPECT_GT(insideCount, 100);
}

TEST(Compound, RejectsBadInputWithMessages) {
  EXPECT_EQ(compoundError({}), "compound: needs at least one child, got 0");
  EXPECT_EQ(compoundError({{Shape(Sphere{1.0f}), {}}, {Shape(Box{}), {}}, {Shape(Plane{}), {}}}),
            "compound: child 2 is a plane; a half-space cannot be part of a compound");

  Transform zeroScale;
  zeroScale.scale = 0.0f;
  EXPECT_NE(compoundError({{Shape(Sphere{1.0f}), {}}, {Shape(Sphere{1.0f}), zeroScale}})
                .find("child 1 has an invalid transform"),
            std::string::npos);
  Transform nanPosition;
  nanPosition.position.x = std::numeric_limits<float>::quiet_NaN();
  EXPECT_NE(compoundError({{Shape(Sphere{1.0f}), nanPosition}}).find("child 0 has an invalid transform"),
            std::string::npos);
  Transform notUnit;
  notUnit.rotation = Quat(2.0f, 0.0f, 0.0f, 0.0f);
  const std::string message =
      compoundError({{Shape(Box{}), {}}, {Shape(Box{}), {}}, {Shape(Box{}), {}}, {Shape(Box{}), notUnit}});
  EXPECT_NE(message.find("child 3 has an invalid transform"), std::string::npos) << message;
  EXPECT_NE(message.find("unit rotation"), std::string::npos) << message;

  // An open mesh is a fine child for queries, but the compound then has no mass.
  const Shape quad(TriangleMesh::fromTriangles({{0, 0, 0}, {1, 0, 0}, {1, 0, 1}}, {{{0, 2, 1}}}));
  const Shape withOpenMesh(Compound::fromChildren({{Shape(Sphere{1.0f}), {}}, {quad, {{3, 0, 0}}}}));
  if (const std::optional<std::string> error =
          ::collide::test::errorOf([&] { massProperties(withOpenMesh, 1.0f); });
      !error) {
    ADD_FAILURE() << "no error";
  } else {
    const std::string what = error->c_str();
    EXPECT_NE(what.find("child 1 has no mass"), std::string::npos) << what;
    EXPECT_NE(what.find("open triangle mesh"), std::string::npos) << what;
  }
  EXPECT_TRUE(rayCast(withOpenMesh, Transform{}, {{3.5f, 1.0f, 0.2f}, {0, -1, 0}, 5.0f}).has_value());
}
