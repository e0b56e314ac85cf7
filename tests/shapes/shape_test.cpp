// Shape: validation of every primitive's fields and of the query arguments, dispatch by type, and
// how the queries scale with the transform.
#include <collide/shapes.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "support/collide_error.h"
#include "support/test_assertions.h"

namespace collide {
namespace {

using ::testing::HasSubstr;

using test::kInf;
using test::kNan;
const float kBadSizes[] = {0.0f, -1.0f, kNan, kInf, -kInf};

TEST(ShapeValidation, SphereRejectsBadRadius) {
  for (float bad : kBadSizes) {
    EXPECT_THAT([&] { Shape(Sphere{bad}); }, ::collide::test::ReportsError(HasSubstr("radius"))) << bad;
  }
}

TEST(ShapeValidation, CapsuleRejectsBadRadiusAndHalfHeight) {
  for (float bad : kBadSizes) {
    EXPECT_THAT(
        [&] {
          Shape(Capsule{bad, 1.0f});
        },
        ::collide::test::ReportsError(HasSubstr("radius")))
        << bad;
    EXPECT_THAT(
        [&] {
          Shape(Capsule{1.0f, bad});
        },
        ::collide::test::ReportsError(HasSubstr("half_height")))
        << bad;
  }
}

TEST(ShapeValidation, BoxRejectsABadHalfExtentInAnyAxis) {
  for (float bad : kBadSizes) {
    for (int axis = 0; axis < 3; ++axis) {
      Vec3 halfExtents(1.0f);
      halfExtents[axis] = bad;
      EXPECT_THAT([&] { Shape(Box{halfExtents}); }, ::collide::test::ReportsError(HasSubstr("half_extents")))
          << bad;
    }
  }
}

TEST(ShapeValidation, EllipsoidRejectsABadRadiusInAnyAxis) {
  for (float bad : kBadSizes) {
    for (int axis = 0; axis < 3; ++axis) {
      Vec3 radii(1.0f);
      radii[axis] = bad;
      EXPECT_THAT([&] { Shape(Ellipsoid{radii}); }, ::collide::test::ReportsError(HasSubstr("radii"))) << bad;
    }
  }
}

TEST(ShapeValidation, CylinderRejectsBadRadiusAndHalfHeight) {
  for (float bad : kBadSizes) {
    EXPECT_THAT(
        [&] {
          Shape(Cylinder{bad, 1.0f});
        },
        ::collide::test::ReportsError(HasSubstr("radius")))
        << bad;
    EXPECT_THAT(
        [&] {
          Shape(Cylinder{1.0f, bad});
        },
        ::collide::test::ReportsError(HasSubstr("half_height")))
        << bad;
  }
}

TEST(ShapeValidation, PlaneRejectsZeroNonUnitOrNonFiniteNormalAndBadDistance) {
  for (const Vec3& bad : {Vec3(0.0f), Vec3(0.0f, 2.0f, 0.0f), Vec3(0.5f, 0.5f, 0.0f), Vec3(kNan, 1.0f, 0.0f),
                          Vec3(0.0f, kInf, 0.0f)}) {
    EXPECT_THAT([&] { Shape(Plane{bad, 0.0f}); }, ::collide::test::ReportsError(HasSubstr("normal")));
  }
  for (float bad : {kNan, kInf}) {
    EXPECT_THAT(
        [&] {
          Shape(Plane{Vec3(0.0f, 1.0f, 0.0f), bad});
        },
        ::collide::test::ReportsError(HasSubstr("distance")));
  }
}

TEST(ShapeValidation, MessageNamesTheValue) {
  EXPECT_THAT([] { Shape(Sphere{-2.5f}); }, ::collide::test::ReportsError(HasSubstr("-2.5")));
}

TEST(QueryValidation, RayWithZeroNonUnitOrNonFiniteDirectionIsRejected) {
  const Shape s(Sphere{1.0f});
  for (const Vec3& bad :
       {Vec3(0.0f), Vec3(kNan, 0.0f, 0.0f), Vec3(0.0f, 2.0f, 0.0f), Vec3(kInf, 0.0f, 0.0f)}) {
    EXPECT_THAT(
        [&] {
          rayCast(s, Transform{}, Ray{Vec3(0.0f, 0.0f, -5.0f), bad});
        },
        ::collide::test::ReportsError(HasSubstr("direction")));
  }
  EXPECT_THAT(
      [&] {
        rayCast(s, Transform{}, Ray{Vec3(kNan, 0.0f, 0.0f), Vec3(0.0f, 0.0f, 1.0f)});
      },
      ::collide::test::ReportsError(HasSubstr("origin")));
  EXPECT_THAT(
      [&] {
        rayCast(s, Transform{}, Ray{Vec3(0.0f), Vec3(0.0f, 0.0f, 1.0f), -1.0f});
      },
      ::collide::test::ReportsError(HasSubstr("maxDistance")));
  EXPECT_THAT(
      [&] {
        rayCast(s, Transform{}, Ray{Vec3(0.0f), Vec3(0.0f, 0.0f, 1.0f), kNan});
      },
      ::collide::test::ReportsError(HasSubstr("maxDistance")));
}

TEST(QueryValidation, InvalidTransformIsRejectedByEveryWorldQuery) {
  const Shape s(Box{Vec3(1.0f)});
  Transform nanPosition;
  nanPosition.position.x = kNan;
  Transform zeroScale;
  zeroScale.scale = 0.0f;
  Transform negativeScale;
  negativeScale.scale = -1.0f;
  Transform infiniteScale;
  infiniteScale.scale = kInf;
  Transform nonUnitRotation;
  nonUnitRotation.rotation = Quat(2.0f, 0.0f, 0.0f, 0.0f);
  Transform nanRotation;
  nanRotation.rotation.x = kNan;
  const Ray ray{Vec3(0.0f, 0.0f, -5.0f), Vec3(0.0f, 0.0f, 1.0f)};
  for (const Transform& bad :
       {nanPosition, zeroScale, negativeScale, infiniteScale, nonUnitRotation, nanRotation}) {
    EXPECT_THAT([&] { containsPoint(s, bad, Vec3(0.0f)); },
                ::collide::test::ReportsError(HasSubstr("transform")));
    EXPECT_THAT([&] { closestPoint(s, bad, Vec3(0.0f)); },
                ::collide::test::ReportsError(HasSubstr("transform")));
    EXPECT_THAT([&] { rayCast(s, bad, ray); }, ::collide::test::ReportsError(HasSubstr("transform")));
    // A bad transform would give NaN or inside-out boxes: worldBounds refuses it like the rest.
    EXPECT_THAT([&] { worldBounds(s, bad); }, ::collide::test::ReportsError(HasSubstr("transform")));
  }
  EXPECT_THAT([&] { worldBounds(s, nonUnitRotation); },
              ::collide::test::ReportsError(HasSubstr("rotation (w 2")));
  EXPECT_THAT([&] { worldBounds(s, zeroScale); }, ::collide::test::ReportsError(HasSubstr("scale 0")));
}

TEST(QueryValidation, NonFinitePointIsRejected) {
  const Shape s(Sphere{1.0f});
  EXPECT_THAT([&] { containsPoint(s, Transform{}, Vec3(kNan)); },
              ::collide::test::ReportsError(HasSubstr("point")));
  EXPECT_THAT([&] { closestPoint(s, Transform{}, Vec3(kInf)); },
              ::collide::test::ReportsError(HasSubstr("point")));
}

TEST(QueryValidation, MassPropertiesRejectBadDensityScaleAndPlanes) {
  const Shape s(Sphere{1.0f});
  for (float bad : kBadSizes) {
    EXPECT_THAT([&] { massProperties(s, bad); }, ::collide::test::ReportsError(HasSubstr("density"))) << bad;
    EXPECT_THAT([&] { massProperties(s, 1.0f, bad); }, ::collide::test::ReportsError(HasSubstr("scale")))
        << bad;
  }
  EXPECT_THAT([] { massProperties(Plane{}, 1.0f); }, ::collide::test::ReportsError(HasSubstr("plane")));
}

TEST(QueryValidation, SupportRejectsPlanesAndZeroOrNonFiniteDirections) {
  EXPECT_THAT([] { support(Plane{}, Vec3(0.0f, 1.0f, 0.0f)); },
              ::collide::test::ReportsError(HasSubstr("plane")));
  // A zero direction has no farthest point (the sphere's, capsule's and ellipsoid's would be NaN).
  for (const Shape& s :
       {Shape(Sphere{1.0f}), Shape(Capsule{}), Shape(Box{}), Shape(Ellipsoid{}), Shape(Cylinder{})}) {
    EXPECT_THAT([&] { support(s, Vec3(0.0f)); }, ::collide::test::ReportsError(HasSubstr("direction")))
        << toString(s.type());
    EXPECT_THAT([&] { support(s, Vec3(kNan, 0.0f, 0.0f)); },
                ::collide::test::ReportsError(HasSubstr("direction")));
  }
}

TEST(Support, TinyAndHugeDirectionsGiveTheSamePoint) {
  // Bug: a direction of length 1e-25 has a squared length that underflows to 0 in float, and the
  // proxies that normalise it returned NaN.
  const Vec3 d = glm::normalize(Vec3(1.0f, 2.0f, -0.5f));
  for (const Shape& s : {Shape(Sphere{1.0f}), Shape(Capsule{}), Shape(Box{}), Shape(Ellipsoid{Vec3(1, 2, 3)}),
                         Shape(Cylinder{})}) {
    const Vec3 reference = support(s, d);
    for (float magnitude : {1e-25f, 1e-10f, 1e10f, 1e30f}) {
      const Vec3 p = support(s, magnitude * d);
      EXPECT_NEAR(glm::length(p - reference), 0.0f, 1e-6f) << toString(s.type()) << " at |d| = " << magnitude;
    }
  }
}

TEST(ShapeDispatch, TypeNamesAndConvexity) {
  EXPECT_EQ(Shape(Sphere{}).type(), ShapeType::Sphere);
  EXPECT_EQ(Shape(Capsule{}).type(), ShapeType::Capsule);
  EXPECT_EQ(Shape(Plane{}).type(), ShapeType::Plane);
  EXPECT_EQ(Shape(Box{}).type(), ShapeType::Box);
  EXPECT_EQ(Shape(Ellipsoid{}).type(), ShapeType::Ellipsoid);
  EXPECT_EQ(Shape(Cylinder{}).type(), ShapeType::Cylinder);
  EXPECT_EQ(toString(ShapeType::Sphere), "sphere");
  EXPECT_EQ(toString(ShapeType::Capsule), "capsule");
  EXPECT_EQ(toString(ShapeType::Plane), "plane");
  EXPECT_EQ(toString(ShapeType::Box), "box");
  EXPECT_EQ(toString(ShapeType::Kdop), "kdop");
  EXPECT_EQ(toString(ShapeType::Ellipsoid), "ellipsoid");
  EXPECT_EQ(toString(ShapeType::Cylinder), "cylinder");
  EXPECT_EQ(toString(ShapeType::ConvexHull), "convex_hull");
  EXPECT_EQ(toString(ShapeType::Mesh), "mesh");
  EXPECT_EQ(toString(ShapeType::Compound), "compound");
  for (const Shape& s :
       {Shape(Sphere{}), Shape(Capsule{}), Shape(Box{}), Shape(Ellipsoid{}), Shape(Cylinder{})}) {
    EXPECT_TRUE(s.isConvex()) << toString(s.type());
  }
  EXPECT_FALSE(Shape(Plane{}).isConvex());
}

TEST(ShapeDispatch, AccessorsReturnTheStoredParameters) {
  EXPECT_EQ(Shape(Sphere{0.25f}).sphere().radius, 0.25f);
  EXPECT_EQ(Shape(Capsule{0.25f, 2.0f}).capsule().halfHeight, 2.0f);
  EXPECT_EQ(Shape(Box{Vec3(1, 2, 3)}).box().halfExtents, Vec3(1, 2, 3));
  EXPECT_EQ(Shape(Ellipsoid{Vec3(1, 2, 3)}).ellipsoid().radii, Vec3(1, 2, 3));
  EXPECT_EQ(Shape(Cylinder{0.25f, 2.0f}).cylinder().radius, 0.25f);
  EXPECT_EQ(Shape(Plane{Vec3(1, 0, 0), 3.0f}).plane().distance, 3.0f);
}

TEST(ShapeDispatch, LocalBoundsPerType) {
  auto expectBox = [](const Shape& s, const Vec3& half) {
    const Aabb box = localBounds(s);
    EXPECT_EQ(box.min, -half) << toString(s.type());
    EXPECT_EQ(box.max, half) << toString(s.type());
  };
  expectBox(Sphere{2.0f}, Vec3(2.0f));
  expectBox(Capsule{1.0f, 2.0f}, Vec3(1.0f, 3.0f, 1.0f));
  expectBox(Box{Vec3(1, 2, 3)}, Vec3(1, 2, 3));
  expectBox(Ellipsoid{Vec3(1, 2, 3)}, Vec3(1, 2, 3));
  expectBox(Cylinder{1.0f, 2.0f}, Vec3(1.0f, 2.0f, 1.0f));
}

TEST(ShapeDispatch, WorldBoundsUnderIdentityAreTheLocalBounds) {
  for (const Shape& s : {Shape(Sphere{2.0f}), Shape(Capsule{1.0f, 2.0f}), Shape(Box{Vec3(1, 2, 3)}),
                         Shape(Ellipsoid{Vec3(1, 2, 3)}), Shape(Cylinder{1.0f, 2.0f})}) {
    const Aabb local = localBounds(s), world = worldBounds(s, Transform{});
    EXPECT_EQ(local.min, world.min) << toString(s.type());
    EXPECT_EQ(local.max, world.max) << toString(s.type());
  }
}

TEST(ShapeDispatch, LocalBoundingSphereEnclosesTheLocalBoxCornersOrSupport) {
  for (const Shape& s : {Shape(Sphere{2.0f}), Shape(Capsule{1.0f, 2.0f}), Shape(Box{Vec3(1, 2, 3)}),
                         Shape(Ellipsoid{Vec3(1, 2, 3)}), Shape(Cylinder{1.0f, 2.0f})}) {
    const BoundingSphere sphere = localBoundingSphere(s);
    // The support in every direction of a fine set lies inside; and the sphere is not loose by more
    // than the farthest support point (the proxies are centred, so radius = max |support|).
    float farthest = 0.0f;
    for (int i = -4; i <= 4; ++i) {
      for (int j = -4; j <= 4; ++j) {
        for (int k = -4; k <= 4; ++k) {
          if (i == 0 && j == 0 && k == 0) continue;
          const Vec3 p = support(s, Vec3(float(i), float(j), float(k)));
          EXPECT_TRUE(sphere.contains(p, 1e-5f)) << toString(s.type());
          farthest = std::max(farthest, glm::length(p - sphere.center));
        }
      }
    }
    EXPECT_NEAR(sphere.radius, farthest, 1e-2f * sphere.radius) << toString(s.type());
  }
}

TEST(ShapeScaling, QueriesScaleWithTheTransform) {
  const Shape s(Box{Vec3(1.0f, 2.0f, 3.0f)});
  const Transform unit{Vec3(1.0f, 2.0f, 3.0f), glm::angleAxis(0.6f, glm::normalize(Vec3(1, -1, 2))), 1.0f};
  Transform scaled = unit;
  scaled.scale = 2.5f;
  // A world point at offset v from the origin of `unit` corresponds to offset 2.5 v under `scaled`.
  const Vec3 localQuery(3.0f, -1.0f, 0.5f);
  const SurfacePoint a = closestPoint(s, unit, unit.applyToPoint(localQuery));
  const SurfacePoint b = closestPoint(s, scaled, scaled.applyToPoint(localQuery));
  EXPECT_NEAR(b.signedDistance, 2.5f * a.signedDistance, 1e-4f);
  EXPECT_NEAR(glm::length(b.normal - a.normal), 0.0f, 1e-5f);
  const Vec3 direction = unit.applyToDirection(glm::normalize(Vec3(-1.0f, 0.2f, 0.1f)));
  const auto hitA = rayCast(s, unit, Ray{unit.applyToPoint(localQuery), direction});
  const auto hitB = rayCast(s, scaled, Ray{scaled.applyToPoint(localQuery), direction});
  ASSERT_TRUE(hitA && hitB);
  EXPECT_NEAR(hitB->distance, 2.5f * hitA->distance, 1e-4f);
  // A segment that reaches the unscaled hit but not the scaled one.
  EXPECT_FALSE(rayCast(s, scaled, Ray{scaled.applyToPoint(localQuery), direction, 1.1f * hitA->distance}));
  const Aabb boxA = worldBounds(s, unit), boxB = worldBounds(s, scaled);
  EXPECT_NEAR(glm::length(boxB.halfExtents() - 2.5f * boxA.halfExtents()), 0.0f, 1e-4f);
  EXPECT_TRUE(containsPoint(s, scaled, scaled.applyToPoint(Vec3(0.9f, 1.9f, 2.9f))));
  EXPECT_FALSE(containsPoint(s, scaled, scaled.applyToPoint(Vec3(1.1f, 0.0f, 0.0f))));
}

TEST(ShapeScaling, MassGrowsAsScaleCubedAndInertiaAsTheFifthPower) {
  for (const Shape& s : {Shape(Sphere{0.5f}), Shape(Capsule{0.3f, 0.7f}), Shape(Box{Vec3(0.2f, 0.4f, 0.6f)}),
                         Shape(Ellipsoid{Vec3(0.3f, 0.5f, 0.7f)}), Shape(Cylinder{0.4f, 0.6f})}) {
    const MassProperties one = massProperties(s, 2.0f);
    const MassProperties three = massProperties(s, 2.0f, 3.0f);
    EXPECT_NEAR(three.mass, 27.0f * one.mass, 1e-5f * three.mass) << toString(s.type());
    EXPECT_NEAR(three.volume, 27.0f * one.volume, 1e-5f * three.volume);
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(three.inertia[i][i], 243.0f * one.inertia[i][i], 1e-5f * three.inertia[i][i])
          << toString(s.type());
    }
  }
}

}  // namespace
}  // namespace collide
