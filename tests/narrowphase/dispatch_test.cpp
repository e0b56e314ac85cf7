// The pair table: every cell filled, mirrored pairs consistent, bad input rejected, the
// bounding-volume test conservative with respect to the collider test.
#include <collide/narrowphase.h>
#include <gtest/gtest.h>

#include "support/collide_error.h"
#include "support/narrowphase_helpers.h"

using namespace collide;
using namespace collide::test;

namespace {
constexpr ShapeType kAll[] = {
    ShapeType::Sphere,    ShapeType::Capsule,  ShapeType::Plane,      ShapeType::Box,  ShapeType::Kdop,
    ShapeType::Ellipsoid, ShapeType::Cylinder, ShapeType::ConvexHull, ShapeType::Mesh, ShapeType::Compound};
constexpr ShapeType kPrimitives[] = {ShapeType::Sphere, ShapeType::Capsule, ShapeType::Box,
                                     ShapeType::Ellipsoid, ShapeType::Cylinder};
}  // namespace

TEST(PairTable, EveryCellIsFilledAndOnlyPlanePlaneIsUnsupported) {
  for (const ShapeType a : kAll) {
    for (const ShapeType b : kAll) {
      const PairInfo info = pairInfo(a, b);
      EXPECT_FALSE(info.description.empty()) << toString(a) << " x " << toString(b);
      EXPECT_EQ(info.algorithm, pairInfo(b, a).algorithm) << toString(a) << " x " << toString(b);
      const bool planePlane = a == ShapeType::Plane && b == ShapeType::Plane;
      EXPECT_EQ(info.algorithm == PairAlgorithm::NotSupported, planePlane)
          << toString(a) << " x " << toString(b);
    }
  }
  EXPECT_EQ(pairInfo(ShapeType::Sphere, ShapeType::Sphere).algorithm, PairAlgorithm::Analytic);
  EXPECT_EQ(pairInfo(ShapeType::Box, ShapeType::Plane).algorithm, PairAlgorithm::Analytic);
  EXPECT_EQ(pairInfo(ShapeType::Ellipsoid, ShapeType::Cylinder).algorithm, PairAlgorithm::GjkEpa);
  EXPECT_EQ(pairInfo(ShapeType::Box, ShapeType::Capsule).algorithm, PairAlgorithm::GjkEpaClip);
  EXPECT_EQ(pairInfo(ShapeType::Mesh, ShapeType::Box).algorithm, PairAlgorithm::Mesh);
  EXPECT_EQ(pairInfo(ShapeType::Plane, ShapeType::Compound).algorithm, PairAlgorithm::Compound);
  const std::string table = describePairTable();
  EXPECT_NE(table.find("sphere x sphere: analytic"), std::string::npos);
  EXPECT_NE(table.find("plane x plane: not supported"), std::string::npos);
  EXPECT_EQ(std::count(table.begin(), table.end(), '\n'), kShapeTypeCount * kShapeTypeCount);
}

TEST(PairTable, PlanePlaneThrowsWithTheReason) {
  Manifold m;
  if (const std::optional<std::string> error = ::collide::test::errorOf(
          [&] { collide::collide(Plane{}, Transform::identity(), Plane{}, Transform::identity(), m); });
      !error) {
    FAIL() << "expected an Error";
  } else {
    EXPECT_NE((*error).find("plane–plane"), std::string::npos);
  }
  EXPECT_COLLIDE_ERROR(collide::distance(Plane{}, Transform::identity(), Plane{}, Transform::identity()));
}

TEST(PairTable, InvalidTransformsAndMarginsAreRejected) {
  Manifold m;
  const Transform good = Transform::identity();
  Transform nanPosition = good;
  nanPosition.position.x = std::nanf("");
  Transform infinite = good;
  infinite.position.y = INFINITY;
  Transform notUnit = good;
  notUnit.rotation = Quat(2.0f, 0.0f, 0.0f, 0.0f);
  Transform zeroScale = good;
  zeroScale.scale = 0.0f;
  Transform hugeButFinite = good;
  hugeButFinite.position = Vec3(3e38f, 3e38f, 0.0f);  // the cheap probe overflows; still valid
  for (const Transform& bad : {nanPosition, infinite, notUnit, zeroScale}) {
    EXPECT_COLLIDE_ERROR(collide::collide(Sphere{1.0f}, bad, Sphere{1.0f}, good, m));
    EXPECT_COLLIDE_ERROR(collide::collide(Sphere{1.0f}, good, Box{}, bad, m));
    EXPECT_COLLIDE_ERROR(overlap(Sphere{1.0f}, bad, Sphere{1.0f}, good));
    EXPECT_COLLIDE_ERROR(collide::distance(Sphere{1.0f}, good, Capsule{}, bad));
  }
  EXPECT_NO_COLLIDE_ERROR(collide::collide(Sphere{1.0f}, hugeButFinite, Sphere{1.0f}, good, m));
  EXPECT_COLLIDE_ERROR(collide::collide(Sphere{1.0f}, good, Sphere{1.0f}, good, m, -0.1f));
  EXPECT_COLLIDE_ERROR(collide::collide(Sphere{1.0f}, good, Sphere{1.0f}, good, m, std::nanf("")));
  const std::optional<std::string> error =
      ::collide::test::errorOf([&] { collide::collide(Sphere{1.0f}, good, Sphere{1.0f}, zeroScale, m); });
  ASSERT_TRUE(error.has_value());
  EXPECT_NE(error->find("shape B"), std::string::npos);
  EXPECT_NE(error->find("scale 0"), std::string::npos);
}

TEST(PairTable, AMeshAndAShapeBeyondFloatRangeApartDoNotTouch) {
  // Both poses valid, but the sphere's pose in the mesh's frame overflows (3e38 m on two axes): no
  // triangle reaches it, which is no contact rather than a refused transform (found by world_fuzzer).
  const Shape mesh(
      TriangleMesh::fromTriangles({Vec3(-1, 0, -1), Vec3(1, 0, -1), Vec3(0, 0, 1)}, {{0, 1, 2}}));
  Transform far = Transform::identity();
  far.position = Vec3(0.0f, 3e38f, 3e38f);
  const Transform turned{Vec3(0.0f), glm::angleAxis(0.5f, glm::normalize(Vec3(1.0f, 1.0f, 0.0f))), 1.0f};
  Manifold m;
  EXPECT_FALSE(collide::collide(mesh, turned, Shape(Sphere{1.0f}), far, m));
  EXPECT_EQ(m.count, 0);
  EXPECT_FALSE(collide::collide(Shape(Sphere{1.0f}), far, mesh, turned, m));
  EXPECT_FALSE(collide::collide(mesh, turned, mesh, far, m));
  // Near, the same pair touches.
  EXPECT_TRUE(collide::collide(mesh, Transform::identity(), Shape(Sphere{1.0f}),
                               Transform{Vec3(0.0f, 0.5f, 0.0f), Quat(1, 0, 0, 0), 1.0f}, m));
}

TEST(PairTable, AMeshTriangleThatOverflowsWhenPlacedGivesNoContact) {
  // Each vertex is finite and the triangle is sound in double, but turned into the world frame two
  // of its corners pass float's range: the triangle has no finite plane, so it cannot touch
  // anything. An ellipsoid far out where its box overlaps the triangle's (found by world_fuzzer;
  // the support function was handed the NaN normal).
  const Shape mesh(
      TriangleMesh::fromTriangles({Vec3(3.05175781e-05f, 1.85882354f, 3e38f), Vec3(3e38f, 3e38f, -2.0f),
                                   Vec3(2.0f, 1.98870826f, 1e30f), Vec3(1e30f, -1.99566638f, -1.99987793f)},
                                  {{1, 3, 0}}));
  const Transform placed{Vec3(-5.28770876f, -6.0f, -6.0f), Quat(-0.5f, -0.5f, -0.5f, -0.5f), 1.0f};
  const Transform far{Vec3(1e30f, 3e38f, 3e38f), Quat(1, 0, 0, 0), 1.0f};
  const Shape ellipsoid(Ellipsoid{Vec3(1.12939203f, 1.25373864f, 0.418111682f)});
  Manifold m;
  EXPECT_FALSE(collide::collide(mesh, placed, ellipsoid, far, m));
  EXPECT_EQ(m.count, 0);
  EXPECT_FALSE(collide::collide(ellipsoid, far, mesh, placed, m));
  EXPECT_FALSE(collide::collide(mesh, placed, Shape(Box{Vec3(1.0f)}), far, m));
  EXPECT_FALSE(collide::collide(mesh, placed, Shape(Sphere{1.0f}), far, m));
}

TEST(PairTable, ARotationOffUnitLengthStillGivesUnitNormals) {
  // A transform's rotation is valid within 1e-3 of unit length; rotating by such a quaternion
  // stretches a vector by its squared length, which took a cylinder-on-k-DOP manifold's normal
  // 1.5e-3 off unit length (found by narrowphase_fuzzer). Every pair of primitives, turned by
  // rotations 0.45e-3 longer or shorter than unit: the normals and the distances' normals are unit.
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  int checked = 0;
  for (const ShapeType ta : kPrimitives) {
    for (const ShapeType tb : kPrimitives) {
      for (int i = 0; i < 40; ++i) {
        const Shape a = randomPrimitive(ta, rng);
        const Shape b = randomPrimitive(tb, rng);
        const auto stretched = [&] {
          const Quat q = glm::normalize(Quat(unit(rng), unit(rng), unit(rng), unit(rng)));
          return q * (unit(rng) > 0.0f ? 1.00045f : 0.99955f);
        };
        const Transform pa{Vec3(unit(rng), unit(rng), unit(rng)) * 0.8f, stretched(), 1.0f};
        const Transform pb{Vec3(unit(rng), unit(rng), unit(rng)) * 0.8f, stretched(), 1.0f};
        Manifold m;
        if (collide::collide(a, pa, b, pb, m, 0.5f)) {
          EXPECT_NEAR(glm::length(m.normal), 1.0f, 1e-4f) << toString(ta) << " x " << toString(tb);
          ++checked;
        }
        if (a.type() != ShapeType::Plane || b.type() != ShapeType::Plane) {
          const DistanceResult d = distance(a, pa, b, pb);
          EXPECT_NEAR(glm::length(d.normal), 1.0f, 1e-4f) << toString(ta) << " x " << toString(tb);
        }
      }
    }
  }
  EXPECT_GT(checked, 500);
}

TEST(PairTable, CollideOfBAndAMirrorsCollideOfAAndB) {
  // Same depths, opposite normals, swapped points, for every ordered pair of primitives and planes.
  std::mt19937 rng(99);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  int compared = 0;
  for (const ShapeType ta : kPrimitives) {
    for (const ShapeType tb : kPrimitives) {
      for (int i = 0; i < 200; ++i) {
        const Shape a = randomPrimitive(ta, rng);
        const Shape b = randomPrimitive(tb, rng);
        const Transform pa = at(Vec3(unit(rng), unit(rng), unit(rng)), uniformRotation(rng));
        const Transform pb = at(Vec3(unit(rng), unit(rng), unit(rng)), uniformRotation(rng));
        Manifold ab, ba;
        const bool hitAB = collide::collide(a, pa, b, pb, ab);
        const bool hitBA = collide::collide(b, pb, a, pa, ba);
        ASSERT_EQ(hitAB, hitBA);
        if (!hitAB) continue;
        ++compared;
        ASSERT_EQ(ab.count, ba.count);
        EXPECT_NEAR(glm::dot(ab.normal, ba.normal), -1.0f, 1e-4f) << toString(ta) << " x " << toString(tb);
        const std::vector<float> da = sortedDepths(ab), db = sortedDepths(ba);
        for (std::size_t k = 0; k < da.size(); ++k)
          EXPECT_NEAR(da[k], db[k], 1e-4f + 1e-3f * std::abs(da[k]))
              << toString(ta) << " x " << toString(tb) << " #" << i;
      }
    }
  }
  EXPECT_GT(compared, 1000);
  // A plane against each primitive, both orders.
  const Plane ground{{0.0f, 1.0f, 0.0f}, 0.0f};
  for (const ShapeType tb : kPrimitives) {
    const Shape b = randomPrimitive(tb, rng);
    const Transform pb = at(Vec3(0.0f, 0.3f, 0.0f), uniformRotation(rng));
    Manifold ab, ba;
    ASSERT_TRUE(collide::collide(ground, Transform::identity(), b, pb, ab));
    ASSERT_TRUE(collide::collide(b, pb, ground, Transform::identity(), ba));
    EXPECT_EQ(ab.count, ba.count);
    EXPECT_NEAR(glm::dot(ab.normal, ba.normal), -1.0f, 1e-6f);
    for (int k = 0; k < ab.count; ++k) {
      EXPECT_NEAR(ab.points[k].depth, ba.points[k].depth, 1e-6f);
      EXPECT_EQ(ab.points[k].pointOnA, ba.points[k].pointOnB);
    }
  }
}

TEST(PairTable, OverlapIsConservativeForEveryCollidingPair) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> unit(-1.5f, 1.5f);
  int colliding = 0, rejected = 0;
  for (const ShapeType ta : kPrimitives) {
    for (const ShapeType tb : kPrimitives) {
      for (int i = 0; i < 200; ++i) {
        const Shape a = randomPrimitive(ta, rng);
        const Shape b = randomPrimitive(tb, rng);
        const Transform pa = at(Vec3(unit(rng), unit(rng), unit(rng)), uniformRotation(rng));
        const Transform pb = at(Vec3(unit(rng), unit(rng), unit(rng)), uniformRotation(rng));
        Manifold m;
        const bool hit = collide::collide(a, pa, b, pb, m);
        const bool maybe = overlap(a, pa, b, pb);
        if (hit) {
          ++colliding;
          EXPECT_TRUE(maybe) << toString(ta) << " x " << toString(tb);
        }
        if (!maybe) ++rejected;
      }
    }
  }
  EXPECT_GT(colliding, 500);
  EXPECT_GT(rejected, 500);  // and it does reject: an early out, not a constant true
  // Half-spaces: facing apart they do not meet, facing the same way they always do.
  const Plane up{{0.0f, 1.0f, 0.0f}, 0.0f};
  const Plane downBelow{{0.0f, -1.0f, 0.0f}, 1.0f};   // solid above y = -1
  const Plane downAbove{{0.0f, -1.0f, 0.0f}, -1.0f};  // solid above y = 1
  EXPECT_TRUE(overlap(up, Transform::identity(), downBelow, Transform::identity()));
  EXPECT_FALSE(overlap(up, Transform::identity(), downAbove, Transform::identity()));
  EXPECT_FALSE(overlap(up, Transform::identity(), Sphere{0.5f}, at({0.0f, 0.6f, 0.0f})));
  EXPECT_TRUE(overlap(Sphere{0.5f}, at({0.0f, 0.4f, 0.0f}), up, Transform::identity()));
}
