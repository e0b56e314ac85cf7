// Differential tests against independent implementations: libccd (GJK overlap verdict and GJK+EPA
// penetration, fed with our support mappings) and FCL (distance between its own primitives, so
// that our support mappings are checked too). 10,000 random pairs per convex pair type among
// sphere, capsule, box, ellipsoid and cylinder in optimised builds (2,000 in debug builds, which
// are ~10x slower).
#include <collide/narrowphase.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "narrowphase/ccd_reference.h"
#include "narrowphase/convex_support.h"
#include "narrowphase/test_helpers.h"

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

struct Tally {
  int verdictCompared = 0, verdictMismatches = 0;
  int depthCompared = 0, depthFailures = 0, normalFailures = 0, normalTies = 0, referenceErrors = 0;
  int distanceCompared = 0, distanceFailures = 0;
  std::string firstFailure;
};

void note(Tally& tally, const std::string& text) {
  if (tally.firstFailure.empty()) tally.firstFailure = text;
}

Tally runPairType(ShapeType typeA, ShapeType typeB, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  ccd_t ccd = makeCcd();
  Tally tally;
  for (int i = 0; i < kPairsPerType; ++i) {
    const Shape shapeA = randomPrimitive(typeA, rng);
    const Shape shapeB = randomPrimitive(typeB, rng);
    const Transform transformA = at(Vec3(unit(rng), unit(rng), unit(rng)) - 0.5f, randomRotation(rng));
    // Centre distances from 0 to 1.6 times the sum of the bounding radii: both overlapping and
    // separated pairs are common for every pair type (spheres overlap below 1.0).
    const float reach = boundingRadius(shapeA) + boundingRadius(shapeB);
    const Transform transformB =
        at(transformA.position + randomUnit(rng) * (1.6f * reach * unit(rng)), randomRotation(rng));
    const DistanceResult ours = collide::distance(shapeA, transformA, shapeB, transformB);
    const detail::ConvexSupport a = detail::makeConvexSupport(shapeA, transformA);
    const detail::ConvexSupport b = detail::makeConvexSupport(shapeB, transformB);
    char where[160];
    std::snprintf(where, sizeof where, "pair %d (seed %u): ours %.6f", i, seed, ours.distance);

    if (std::abs(ours.distance) > kBand) {
      ++tally.verdictCompared;
      const bool theirs = ccdGJKIntersect(&a, &b, &ccd) != 0;
      if (theirs != ours.overlapping) {
        ++tally.verdictMismatches;
        note(tally, std::string(where) + ": libccd overlap verdict differs");
      }
    }
    if (ours.overlapping && -ours.distance > kBand) {
      ccd_real_t depth = 0;
      ccd_vec3_t direction, position;
      if (ccdGJKPenetration(&a, &b, &ccd, &depth, &direction, &position) != 0) continue;  // counted above
      ++tally.depthCompared;
      const float ourDepth = -ours.distance;
      const float theirDepth = static_cast<float>(depth);
      const Vec3 theirNormal = glm::normalize(Vec3(direction.v[0], direction.v[1], direction.v[2]));
      const float tolerance = 1e-3f * std::max(ourDepth, theirDepth) + 1e-5f;
      // A normal is judged by its directional depth, the translation along it that separates the
      // shapes; the true depth is the smallest of them. Ours must (1) equal its own normal's
      // directional depth and (2) be no larger than libccd's normal's directional depth. Where
      // libccd's depth equals its own directional depth (libccd 2.1's EPA often stops early or
      // returns 0 on curved shapes; those answers are counted, not compared), (3) the depths agree
      // and (4) the normals are within a degree unless both directions separate equally well.
      const float ourDirectional = directionalDepth(a, b, ours.normal);
      const float theirDirectional = directionalDepth(a, b, theirNormal);
      const bool theirsConsistent = std::abs(theirDirectional - theirDepth) <= tolerance;
      if (std::abs(ourDirectional - ourDepth) > tolerance) {
        ++tally.depthFailures;
        note(tally, std::string(where) + ": our depth is not the separating translation along our normal");
      } else if (ourDepth > theirDirectional + tolerance) {
        ++tally.depthFailures;
        note(tally, std::string(where) + ": libccd's normal separates with less, " +
                        std::to_string(theirDirectional));
      } else if (!theirsConsistent) {
        ++tally.referenceErrors;
      } else if (std::abs(ourDepth - theirDepth) > tolerance) {
        ++tally.referenceErrors;  // ours separates with less (checked above): libccd stopped early
      } else if (angleDegrees(ours.normal, theirNormal) > 1.0f) {
        if (ourDirectional <= theirDirectional + 1e-5f * (1.0f + ourDepth)) {
          ++tally.normalTies;  // the depth is flat around its minimum (nearly concentric shapes)
        } else {
          ++tally.normalFailures;
          note(tally, std::string(where) + ": libccd's normal " +
                          std::to_string(angleDegrees(ours.normal, theirNormal)) +
                          " degrees away separates with less");
        }
      }
    }
#if defined(COLLIDE_HAVE_FCL)
    if (!ours.overlapping && ours.distance > kBand) {
      const auto geometryA = fclGeometry(shapeA);
      const auto geometryB = fclGeometry(shapeB);
      fcl::DistanceRequestd request(true, false, 0.0, 0.0, 1e-8, fcl::GST_LIBCCD);
      fcl::DistanceResultd result;
      fcl::distance(geometryA.get(), fclTransform(transformA, typeA), geometryB.get(),
                    fclTransform(transformB, typeB), request, result);
      ++tally.distanceCompared;
      if (std::abs(result.min_distance - ours.distance) > 1e-4) {
        ++tally.distanceFailures;
        note(tally, std::string(where) + ": FCL distance " + std::to_string(result.min_distance));
      }
    }
#endif
  }
  return tally;
}

}  // namespace

TEST(NarrowphaseDifferential, AgreesWithLibccdAndFclOnRandomConvexPairs) {
  unsigned seed = 1234;
  for (std::size_t i = 0; i < std::size(kTypes); ++i) {
    for (std::size_t j = i; j < std::size(kTypes); ++j) {
      const Tally tally = runPairType(kTypes[i], kTypes[j], seed++);
      const std::string pair = std::string(toString(kTypes[i])) + " x " + std::string(toString(kTypes[j]));
      SCOPED_TRACE(pair + ": " + tally.firstFailure);
      std::printf(
          "%-20s verdicts %5d (%d differ), depths %5d (%d fail, %d normal fail, %d ties, %d libccd "
          "errors), distances %5d (%d fail)\n",
          pair.c_str(), tally.verdictCompared, tally.verdictMismatches, tally.depthCompared,
          tally.depthFailures, tally.normalFailures, tally.normalTies, tally.referenceErrors,
          tally.distanceCompared, tally.distanceFailures);
      // Known residue (docs/narrowphase.md, "Open issues"): about 1 pair in 20,000 where EPA stops
      // before converging on a cylinder's rim, or GJK's normal is loose for cores a hair apart.
      // Allowed: 1 in 2,000 per pair type; everything else must agree exactly as specified.
      const int allowed = kPairsPerType / 2000;
      EXPECT_LE(tally.verdictMismatches, allowed);
      EXPECT_LE(tally.depthFailures + tally.normalFailures, allowed);
      EXPECT_LE(tally.distanceFailures, allowed);
      // libccd must give a usable reference for a good share of the pairs, or the test says little.
      EXPECT_GT(tally.depthCompared - tally.referenceErrors, tally.depthCompared / 3);
      EXPECT_GT(tally.depthCompared, kPairsPerType / 5);
#if defined(COLLIDE_HAVE_FCL)
      EXPECT_GT(tally.distanceCompared, kPairsPerType / 5);
#endif
    }
  }
}

#else
TEST(NarrowphaseDifferential, DISABLED_NeedsLibccd) {}
#endif
