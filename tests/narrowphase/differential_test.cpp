// Differential tests against independent implementations: libccd (GJK overlap verdict and GJK+EPA
// penetration, fed with our support mappings) and FCL (distance between its own primitives, so
// that our support mappings are checked too). 10,000 random pairs per convex pair type among
// sphere, capsule, box, ellipsoid and cylinder in optimised builds (2,000 in debug builds, which
// are ~10x slower).
#include <collide/narrowphase.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "narrowphase/convex_support.h"
#include "support/ccd_reference.h"
#include "support/narrowphase_helpers.h"
#include "support/support_reference.h"

#if defined(COLLIDE_HAVE_CCD)
#include <ccd/ccd.h>
#endif
#if defined(COLLIDE_HAVE_FCL)
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/distance.h>
#endif

using namespace collide;
using namespace collide::test;

#if defined(COLLIDE_HAVE_CCD)

namespace {

#if defined(NDEBUG)
constexpr int kPairsPerType = 10000;
#else
constexpr int kPairsPerType = 2000;
#endif

// The overlap verdicts may differ only this close to touching.
constexpr float kBand = 1e-4f;

constexpr ShapeType kTypes[] = {ShapeType::Sphere, ShapeType::Capsule, ShapeType::Box, ShapeType::Ellipsoid,
                                ShapeType::Cylinder};

float boundingRadius(const Shape& shape) { return localBoundingSphere(shape).radius; }

#if defined(COLLIDE_HAVE_FCL)
std::shared_ptr<fcl::CollisionGeometryd> fclGeometry(const Shape& shape) {
  switch (shape.type()) {
    case ShapeType::Sphere:
      return std::make_shared<fcl::Sphered>(shape.sphere().radius);
    case ShapeType::Capsule:
      return std::make_shared<fcl::Capsuled>(shape.capsule().radius, 2.0 * shape.capsule().halfHeight);
    case ShapeType::Box: {
      const Vec3 h = shape.box().halfExtents;
      return std::make_shared<fcl::Boxd>(2.0 * h.x, 2.0 * h.y, 2.0 * h.z);
    }
    case ShapeType::Ellipsoid: {
      const Vec3 r = shape.ellipsoid().radii;
      return std::make_shared<fcl::Ellipsoidd>(r.x, r.y, r.z);
    }
    case ShapeType::Cylinder:
      return std::make_shared<fcl::Cylinderd>(shape.cylinder().radius, 2.0 * shape.cylinder().halfHeight);
    default:
      return nullptr;
  }
}

fcl::Transform3d fclTransform(const Transform& t, ShapeType type) {
  fcl::Transform3d result = fcl::Transform3d::Identity();
  result.translation() = Eigen::Vector3d(t.position.x, t.position.y, t.position.z);
  Eigen::Matrix3d rotation =
      Eigen::Quaterniond(t.rotation.w, t.rotation.x, t.rotation.y, t.rotation.z).toRotationMatrix();
  // FCL's capsules and cylinders run along local z, ours along y: turn z onto y first.
  if (type == ShapeType::Capsule || type == ShapeType::Cylinder) {
    rotation = rotation * Eigen::AngleAxisd(-0.5 * M_PI, Eigen::Vector3d::UnitX()).toRotationMatrix();
  }
  result.linear() = rotation;
  return result;
}
#endif

struct ReferenceTally {
  int verdictCompared = 0, verdictMismatches = 0, verdictLibccdWrong = 0;
  int depthCompared = 0, depthFailures = 0, normalFailures = 0, normalTies = 0;
  int depthLibccdWrong = 0;  // compared against the brute-force reference instead
  int distanceCompared = 0, distanceFailures = 0, distanceFclWrong = 0;
  std::vector<std::string> failures;
};

void fail(ReferenceTally& tally, const std::string& text) {
  tally.failures.push_back(text);
  std::printf("  FAIL %s\n", text.c_str());
}

ReferenceTally runPairType(ShapeType typeA, ShapeType typeB, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  ccd_t ccd = makeCcd();
  ReferenceTally tally;
  for (int i = 0; i < kPairsPerType; ++i) {
    const Shape shapeA = randomPrimitive(typeA, rng);
    const Shape shapeB = randomPrimitive(typeB, rng);
    const Transform transformA = at(Vec3(unit(rng), unit(rng), unit(rng)) - 0.5f, uniformRotation(rng));
    // Centre distances from 0 to 1.6 times the sum of the bounding radii: both overlapping and
    // separated pairs are common for every pair type (spheres overlap below 1.0).
    const float reach = boundingRadius(shapeA) + boundingRadius(shapeB);
    const Transform transformB =
        at(transformA.position + randomUnit(rng) * (1.6f * reach * unit(rng)), uniformRotation(rng));
    const DistanceResult ours = collide::distance(shapeA, transformA, shapeB, transformB);
    const detail::ConvexSupport a = detail::makeConvexSupport(shapeA, transformA);
    const detail::ConvexSupport b = detail::makeConvexSupport(shapeB, transformB);
    char where[200];
    std::snprintf(where, sizeof where, "pair %d (seed %u): ours %.6f normal (%.5f %.5f %.5f)", i, seed,
                  ours.distance, ours.normal.x, ours.normal.y, ours.normal.z);
    // The brute-force reference, computed at most once per pair and only where needed (~50 µs).
    bool haveReference = false;
    SupportReference reference;
    auto bruteForce = [&]() -> const SupportReference& {
      if (!haveReference) reference = bruteForceSignedDistance(a, b);
      haveReference = true;
      return reference;
    };

    if (std::abs(ours.distance) > kBand) {
      ++tally.verdictCompared;
      const bool theirs = ccdGJKIntersect(&a, &b, &ccd) != 0;
      if (theirs != ours.overlapping) {
        // Judged by the reference: libccd is wrong when the reference agrees with our sign.
        const double signedDistance = bruteForce().signedDistance;
        if ((signedDistance < 0.0) == ours.overlapping && std::abs(signedDistance) > 0.5 * kBand) {
          ++tally.verdictLibccdWrong;
        } else {
          ++tally.verdictMismatches;
          fail(tally, std::string(where) + ": libccd overlap verdict differs, brute force " +
                          std::to_string(signedDistance));
        }
      }
    }
    if (ours.overlapping && -ours.distance > kBand) {
      ++tally.depthCompared;
      const float ourDepth = -ours.distance;
      const float tolerance = 1e-3f * ourDepth + 1e-5f;
      // A normal is judged by its directional depth, the translation along it that separates the
      // shapes; the true depth is the smallest of them, so every directional depth anyone computes
      // is an upper bound of it. Ours must (1) equal its own normal's directional depth and (2) be
      // no larger than any other normal's directional depth (libccd's, the brute force's).
      const float ourDirectional = directionalDepth(a, b, ours.normal);
      if (std::abs(ourDirectional - ourDepth) > tolerance) {
        ++tally.depthFailures;
        fail(tally, std::string(where) + ": our depth is not the separating translation along our normal, " +
                        std::to_string(ourDirectional));
        continue;
      }
      ccd_real_t depth = 0;
      ccd_vec3_t direction, position;
      bool libccdUsable = false;
      float theirDepth = 0.0f, theirDirectional = 0.0f;
      Vec3 theirNormal(0.0f, 1.0f, 0.0f);
      if (ccdGJKPenetration(&a, &b, &ccd, &depth, &direction, &position) == 0) {
        theirDepth = static_cast<float>(depth);
        theirNormal = glm::normalize(Vec3(direction.v[0], direction.v[1], direction.v[2]));
        theirDirectional = directionalDepth(a, b, theirNormal);
        if (ourDepth > theirDirectional + tolerance) {
          ++tally.depthFailures;
          fail(tally, std::string(where) + ": libccd's normal separates with less, " +
                          std::to_string(theirDirectional));
          continue;
        }
        // libccd is a usable reference when its normal achieves its depth (libccd 2.1's EPA often
        // stops early or returns 0 on curved shapes) and that depth is not beaten by ours.
        libccdUsable = std::abs(theirDirectional - theirDepth) <= tolerance &&
                       std::abs(ourDepth - theirDepth) <= tolerance;
      }
      Vec3 referenceNormal = theirNormal;
      float referenceDirectional = theirDirectional;
      if (!libccdUsable) {
        // libccd is certifiably wrong here (its normal does not achieve its depth, or ours separates
        // with less): the brute-force reference takes its place.
        ++tally.depthLibccdWrong;
        const SupportReference& r = bruteForce();
        referenceNormal = r.normal;
        referenceDirectional = static_cast<float>(-r.signedDistance);
        if (ourDepth > referenceDirectional + tolerance) {
          ++tally.depthFailures;
          fail(tally, std::string(where) + ": the brute-force reference separates with less, " +
                          std::to_string(referenceDirectional) + " along (" + std::to_string(r.normal.x) +
                          " " + std::to_string(r.normal.y) + " " + std::to_string(r.normal.z) + ")");
          continue;
        }
      }
      if (angleDegrees(ours.normal, referenceNormal) > 1.0f) {
        // Two directions more than a degree apart that separate equally well (nearly concentric
        // shapes, two parallel faces): the depth is flat around its minimum and either normal is
        // right. Otherwise the reference's normal is better and ours is wrong.
        if (ourDirectional <= referenceDirectional + 1e-5f * (1.0f + ourDepth)) {
          ++tally.normalTies;
        } else {
          ++tally.normalFailures;
          fail(tally, std::string(where) + ": the reference's normal " +
                          std::to_string(angleDegrees(ours.normal, referenceNormal)) +
                          " degrees away separates with less, " + std::to_string(referenceDirectional));
        }
      }
    }
    if (!ours.overlapping && ours.distance > kBand) {
      ++tally.distanceCompared;
      // Our normal's planes must be apart by our distance (-h(n) is a lower bound of the distance).
      const float ourGap = -directionalDepth(a, b, ours.normal);
      if (std::abs(ourGap - ours.distance) > 1e-4f) {
        ++tally.distanceFailures;
        fail(tally, std::string(where) + ": our normal's separating gap is " + std::to_string(ourGap));
        continue;
      }
#if defined(COLLIDE_HAVE_FCL)
      const auto geometryA = fclGeometry(shapeA);
      const auto geometryB = fclGeometry(shapeB);
      fcl::DistanceRequestd request(true, false, 0.0, 0.0, 1e-8, fcl::GST_LIBCCD);
      fcl::DistanceResultd result;
      fcl::distance(geometryA.get(), fclTransform(transformA, typeA), geometryB.get(),
                    fclTransform(transformB, typeB), request, result);
      if (std::abs(result.min_distance - ours.distance) > 1e-4) {
        // FCL's GJK can stop early: judged by the brute-force reference.
        const double signedDistance = bruteForce().signedDistance;
        if (std::abs(signedDistance - ours.distance) <= 1e-4 &&
            std::abs(signedDistance - result.min_distance) > 1e-4) {
          ++tally.distanceFclWrong;
        } else {
          ++tally.distanceFailures;
          fail(tally, std::string(where) + ": FCL distance " + std::to_string(result.min_distance) +
                          ", brute force " + std::to_string(signedDistance));
        }
      }
#endif
    }
  }
  return tally;
}

}  // namespace

TEST(NarrowphaseDifferential, AgreesWithLibccdAndFclOnRandomConvexPairs) {
  unsigned seed = 1234;
  for (std::size_t i = 0; i < std::size(kTypes); ++i) {
    for (std::size_t j = i; j < std::size(kTypes); ++j) {
      const std::string pair = std::string(toString(kTypes[i])) + " x " + std::string(toString(kTypes[j]));
      const ReferenceTally tally = runPairType(kTypes[i], kTypes[j], seed++);
      std::printf(
          "%-21s verdicts %5d (%d differ, %d libccd wrong), depths %5d (%d fail, %d normal fail, %d ties, "
          "%d libccd wrong), distances %5d (%d fail, %d FCL wrong)\n",
          pair.c_str(), tally.verdictCompared, tally.verdictMismatches, tally.verdictLibccdWrong,
          tally.depthCompared, tally.depthFailures, tally.normalFailures, tally.normalTies,
          tally.depthLibccdWrong, tally.distanceCompared, tally.distanceFailures, tally.distanceFclWrong);
      // No allowance: every disagreement outside the band must be the reference's, as judged by the
      // brute-force reference (support_reference.h).
      EXPECT_EQ(tally.verdictMismatches, 0) << pair;
      EXPECT_EQ(tally.depthFailures, 0) << pair;
      EXPECT_EQ(tally.normalFailures, 0) << pair;
      EXPECT_EQ(tally.distanceFailures, 0) << pair;
      // The comparisons must cover a good share of the pairs, or the test says little.
      EXPECT_GT(tally.depthCompared, kPairsPerType / 5) << pair;
      EXPECT_GT(tally.distanceCompared, kPairsPerType / 5) << pair;
    }
  }
}

#else
TEST(NarrowphaseDifferential, DISABLED_NeedsLibccd) {}
#endif
