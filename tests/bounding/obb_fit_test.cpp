// Oriented box fitting: a rotated box's own corners give back that box; every point is always
// inside; the box is never larger than the AABB nor the PCA-aligned box, both of which are among
// its candidates.
#include <collide/bounding.h>
#include <gtest/gtest.h>

#include "bounding/point_set.h"
#include "support/collide_error.h"
#include "support/point_clouds.h"

#include <string>

using namespace collide;
using collide::test::Random;

namespace {

void expectContainsAll(const OrientedBox& box, const std::vector<Vec3>& points, float tolerance) {
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec3 local = box.transform.inverseApplyToPoint(points[i]);
    EXPECT_LE(std::abs(local.x), box.box.halfExtents.x + tolerance) << "point " << i;
    EXPECT_LE(std::abs(local.y), box.box.halfExtents.y + tolerance) << "point " << i;
    EXPECT_LE(std::abs(local.z), box.box.halfExtents.z + tolerance) << "point " << i;
  }
}

// The box aligned with the principal axes of the points (the fit's own PCA, whose solver is tested
// in symmetric_eigen_test): one of the fit's candidates.
float pcaBoxVolume(const std::vector<Vec3>& points) {
  const bounding::PrincipalAxes pca = bounding::principalAxes(points);
  double volume = 1.0;
  for (int k = 0; k < 3; ++k) {
    double low = INFINITY, high = -INFINITY;
    for (const Vec3& p : points) {
      low = std::min(low, glm::dot(pca.axes[k], glm::dvec3(p)));
      high = std::max(high, glm::dot(pca.axes[k], glm::dvec3(p)));
    }
    volume *= high - low;
  }
  return float(volume);
}

}  // namespace

TEST(FitOrientedBox, RotatedBoxCornersAndInteriorPointsGiveThatBox) {
  Random random(101);
  for (int trial = 0; trial < 50; ++trial) {
    const Vec3 half(random.uniform(0.2f, 2.0f), random.uniform(0.2f, 2.0f), random.uniform(0.2f, 2.0f));
    const Transform pose{random.inCube(10.0f), random.rotation(), 1.0f};
    std::vector<Vec3> points;
    for (int i = 0; i < 8; ++i)
      points.push_back(pose.applyToPoint(
          Vec3(i & 1 ? half.x : -half.x, i & 2 ? half.y : -half.y, i & 4 ? half.z : -half.z)));
    for (int i = 0; i < 50; ++i)
      points.push_back(pose.applyToPoint(
          Vec3(random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1)) * half));
    const OrientedBox box = fitOrientedBox(points);
    const float trueVolume = 8.0f * half.x * half.y * half.z;
    SCOPED_TRACE("trial " + std::to_string(trial));
    EXPECT_NEAR(box.volume(), trueVolume, 1e-3f * trueVolume);
    EXPECT_NEAR(glm::length(box.transform.position - pose.position), 0.0f, 1e-4f);
    expectContainsAll(box, points, 1e-5f * test::cloudScale(points));
  }
}

TEST(FitOrientedBox, RandomCloudsAreContainedAndNoLargerThanTheAabbOrThePcaBox) {
  Random random(102);
  for (int trial = 0; trial < 40; ++trial) {
    const Vec3 stretch(random.uniform(0.1f, 3.0f), random.uniform(0.1f, 3.0f), random.uniform(0.1f, 3.0f));
    const Transform pose{random.inCube(5.0f), random.rotation(), 1.0f};
    std::vector<Vec3> points;
    const int n = random.integer(4, 300);
    for (int i = 0; i < n; ++i) {
      // Half the clouds fill a stretched cube, half a stretched ball's surface.
      const Vec3 p = trial % 2 ? random.inCube(1.0f) : random.direction();
      points.push_back(pose.applyToPoint(p * stretch));
    }
    const OrientedBox box = fitOrientedBox(points);
    SCOPED_TRACE("trial " + std::to_string(trial) + ", " + std::to_string(n) + " points");
    expectContainsAll(box, points, 1e-5f * test::cloudScale(points));
    EXPECT_LE(box.volume(), boundingBox(points).volume() * (1.0f + 1e-5f));
    EXPECT_LE(box.volume(), pcaBoxVolume(points) * (1.0f + 1e-4f));
  }
}

TEST(FitOrientedBox, LargeHullsSearchACoarseHullAndStillHoldEveryPoint) {
  // Points on a stretched, turned ball's surface: every one is a hull vertex, past the 1,024 of the
  // exhaustive search. The box from the coarse hull's frames holds every point, is no larger than
  // the axis-aligned box or the principal axes' box, and is close to the ellipsoid's own box (the
  // tightest box of an ellipsoid is its axes' box, 8 abc).
  Random random(103);
  const Vec3 radii(2.0f, 1.0f, 0.5f);
  const Transform pose{random.inCube(5.0f), random.rotation(), 1.0f};
  std::vector<Vec3> points;
  for (int i = 0; i < 5000; ++i) points.push_back(pose.applyToPoint(random.direction() * radii));
  const OrientedBox box = fitOrientedBox(points);
  expectContainsAll(box, points, 1e-5f * test::cloudScale(points));
  EXPECT_LE(box.volume(), boundingBox(points).volume() * (1.0f + 1e-5f));
  EXPECT_LE(box.volume(), pcaBoxVolume(points) * (1.0f + 1e-4f));
  EXPECT_LE(box.volume(), 8.0f * radii.x * radii.y * radii.z * 1.02f);
}

TEST(FitOrientedBox, FlatOrTooFewPointsAreRejectedWithTheReason) {
  const std::vector<Vec3> one = {{1, 2, 3}};
  if (const std::optional<std::string> error = ::collide::test::errorOf([&] { fitOrientedBox(one); });
      !error) {
    FAIL() << "a single point accepted";
  } else {
    EXPECT_NE((*error).find("fit_oriented_box"), std::string::npos) << *error;
    EXPECT_NE((*error).find("at least 4 points"), std::string::npos) << *error;
  }
  const std::vector<Vec3> square = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5f, 0.5f, 0}};
  if (const std::optional<std::string> error = ::collide::test::errorOf([&] { fitOrientedBox(square); });
      !error) {
    FAIL() << "a flat set accepted";
  } else {
    EXPECT_NE((*error).find("coplanar"), std::string::npos) << *error;
  }
  EXPECT_COLLIDE_ERROR(fitOrientedBox(std::span<const Vec3>{}));
  const std::vector<Vec3> withNan = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, NAN}};
  if (const std::optional<std::string> error = ::collide::test::errorOf([&] { fitOrientedBox(withNan); });
      !error) {
    FAIL() << "NaN accepted";
  } else {
    EXPECT_NE((*error).find("point 3 is not finite"), std::string::npos) << *error;
  }
}
