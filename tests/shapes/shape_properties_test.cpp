// Properties every proxy must have, checked over random transforms and rays by the harness in
// tests/shape_property_harness.h. To cover another proxy, add one line to kCases.
#include "support/shape_property_harness.h"
#include "support/test_meshes.h"

#include <collide/shapes.h>
#include <gtest/gtest.h>

#include <functional>
#include <ostream>
#include <random>
#include <string>

namespace collide::test {
namespace {

struct ShapeCase {
  std::string name;
  std::function<Shape()> make;
  // worldBounds is the tightest box (true for the convex primitives and hulls; meshes and
  // compounds only promise a conservative one).
  bool exactBounds = true;
};

// Test names and failure messages show the case's name rather than its bytes.
void PrintTo(const ShapeCase& shapeCase, std::ostream* out) { *out << shapeCase.name; }

const std::vector<ShapeCase> kCases = {
    {"Sphere", [] { return Shape(Sphere{0.7f}); }},
    {"Capsule",
     [] {
       return Shape(Capsule{0.4f, 0.9f});
     }},
    {"FlatCapsule",
     [] {
       return Shape(Capsule{1.0f, 0.1f});
     }},
    {"Plane",
     [] {
       return Shape(Plane{glm::normalize(Vec3(0.3f, 1.0f, -0.2f)), 0.5f});
     }},
    {"Box", [] { return Shape(Box{Vec3(0.3f, 0.8f, 1.2f)}); }},
    {"Cube", [] { return Shape(Box{Vec3(0.5f)}); }},
    {"Ellipsoid", [] { return Shape(Ellipsoid{Vec3(1.2f, 0.5f, 0.8f)}); }},
    {"OblateEllipsoid", [] { return Shape(Ellipsoid{Vec3(1.5f, 0.3f, 1.5f)}); }},
    {"ProlateEllipsoid", [] { return Shape(Ellipsoid{Vec3(0.4f, 1.6f, 0.4f)}); }},
    {"Cylinder",
     [] {
       return Shape(Cylinder{0.6f, 0.9f});
     }},
    {"DiscCylinder",
     [] {
       return Shape(Cylinder{1.2f, 0.15f});
     }},
    {"ConvexHull",
     [] {
       const std::vector<Vec3> points = {{0.5f, 0, 0},  {-0.5f, 0, 0}, {0, 0.7f, 0},      {0, -0.7f, 0},
                                         {0, 0, 0.5f},  {0, 0, -0.5f}, {0.3f, 0.3f, 0.3f}, {-0.3f, -0.3f, 0.3f}};
       return Shape(ConvexHull::fromPoints(points));
     }},
    {"RandomHull",
     [] {
       std::mt19937 random(7);
       std::normal_distribution<float> normal(0.0f, 1.0f);
       std::vector<Vec3> points;
       for (int i = 0; i < 40; ++i) {
         const float x = normal(random);
         const float y = normal(random);
         const float z = normal(random);
         points.push_back(Vec3(0.9f, 0.6f, 0.4f) * Vec3(x, y, z));
       }
       return Shape(ConvexHull::fromPoints(points));
     }},
    {"Kdop18",
     [] {
       const std::vector<Vec3> points = {{0.5f, 0, 0},  {-0.5f, 0, 0}, {0, 0.7f, 0},      {0, -0.7f, 0},
                                         {0, 0, 0.5f},  {0, 0, -0.5f}, {0.3f, 0.3f, 0.3f}, {-0.3f, -0.3f, 0.3f}};
       return Shape(Kdop::fromPoints(18, points));
     }},
    {"Kdop26",
     [] {
       std::mt19937 random(11);
       std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
       std::vector<Vec3> points;
       for (int i = 0; i < 30; ++i) {
         const float x = uniform(random);
         const float y = uniform(random);
         const float z = uniform(random);
         points.push_back(Vec3(x, 0.5f * y, 0.8f * z));
       }
       return Shape(Kdop::fromPoints(26, points));
     }},
    {"BoxMesh", [] { return Shape(test::boxMesh(Vec3(0.4f, 0.7f, 0.3f))); }, false},
    {"Icosphere", [] { return Shape(test::icosphere(2)); }, false},
    {"Compound",
     [] {
       std::vector<Compound::Child> children;
       // Disjoint children: inside a union of overlapping ones, mass counts the overlap twice and
       // closest points are only a bound (see compound.cpp).
       children.push_back({Sphere{0.3f}, Transform{Vec3(-0.9f, 0, 0)}});
       children.push_back({Box{Vec3(0.4f, 0.1f, 0.2f)}, Transform{Vec3(0.0f), glm::angleAxis(0.4f, Vec3(0, 0, 1))}});
       children.push_back({Capsule{0.2f, 0.3f}, Transform{Vec3(0.9f, 0.1f, 0), Quat(1, 0, 0, 0), 1.5f}});
       return Shape(Compound::fromChildren(std::move(children)));
     },
     false},
};

// Per shape: 1000 transforms, each with a few rays, support directions and closest-point queries
// (a few thousand of each per shape) and its world box.
constexpr int kTransforms = 1000;

class ShapeProperties : public ::testing::TestWithParam<ShapeCase> {
 protected:
  template <class Check>
  void forEachTransform(std::uint32_t seed, Check&& check) {
    std::mt19937 rng(seed);
    FailureLog log;
    const Shape shape = GetParam().make();
    for (int i = 0; i < kTransforms; ++i) check(shape, randomTransform(rng), rng, log);
    EXPECT_EQ(log.count(), 0) << GetParam().name << ": " << log.count() << " violations, first ones:\n"
                              << log.messages();
  }
};

TEST_P(ShapeProperties, RayHitsLieOnTheSurfaceWithConsistentNormals) {
  forEachTransform(1, [](const Shape& shape, const Transform& t, std::mt19937& rng, FailureLog& log) {
    checkRayCasts(shape, t, rng, 8, log);
  });
}

TEST_P(ShapeProperties, WorldBoundsContainTheSurfaceAndExactOnesTouchIt) {
  const bool exact = GetParam().exactBounds;
  forEachTransform(2, [exact](const Shape& shape, const Transform& t, std::mt19937& rng, FailureLog& log) {
    checkWorldBounds(shape, t, rng, exact, log);
  });
}

TEST_P(ShapeProperties, SupportPointsAreOnTheSurfaceAndExtreme) {
  forEachTransform(3, [](const Shape& shape, const Transform& t, std::mt19937& rng, FailureLog& log) {
    checkSupport(shape, t, rng, 4, log);
  });
}

TEST_P(ShapeProperties, ClosestPointIsNearestAndAgreesWithContainment) {
  forEachTransform(4, [](const Shape& shape, const Transform& t, std::mt19937& rng, FailureLog& log) {
    checkClosestPoints(shape, t, rng, 4, log);
  });
}

TEST_P(ShapeProperties, MassPropertiesMatchMonteCarlo) {
  const Shape shape = GetParam().make();
  if (isInfinite(shape)) GTEST_SKIP() << "a half-space has no mass";
  expectMassPropertiesMatchMonteCarlo(shape, 1.0f, 1.0f);
}

TEST_P(ShapeProperties, MassPropertiesMatchMonteCarloUnderScale) {
  const Shape shape = GetParam().make();
  if (isInfinite(shape)) GTEST_SKIP() << "a half-space has no mass";
  // Mass grows as s^3 and inertia as s^5; the estimate samples the scaled shape directly.
  expectMassPropertiesMatchMonteCarlo(shape, 2.5f, 1.7f, 200000, 777);
}

INSTANTIATE_TEST_SUITE_P(Primitives, ShapeProperties, ::testing::ValuesIn(kCases),
                         [](const ::testing::TestParamInfo<ShapeCase>& info) { return info.param.name; });

}  // namespace
}  // namespace collide::test
