// The minimal enclosing sphere against known answers and against a brute-force reference: the
// minimal sphere is the smallest sphere defined by 1 to 4 of the points (diametral, circumcircle or
// circumsphere) that contains them all (Welzl 1991, Lemma 1: the support set has at most 4 points).
#include <collide/bounding.h>
#include <gtest/gtest.h>

#include "support/collide_error.h"
#include "support/point_clouds.h"

#include <cmath>
#include <string>
#include <vector>

using namespace collide;
using collide::test::Random;

namespace {

using DVec3 = glm::dvec3;

struct ReferenceBall {
  DVec3 center{0.0};
  double radius = INFINITY;
};

// O(n^5) brute force: every ball through 1, 2, 3 or 4 of the points, the smallest containing all.
ReferenceBall bruteForceMinimalSphere(const std::vector<Vec3>& input) {
  std::vector<DVec3> p(input.begin(), input.end());
  const std::size_t n = p.size();
  double scale = 0.0;
  for (const DVec3& q : p) scale = std::max(scale, glm::length(q - p[0]));
  const double tolerance = 1e-7 * scale;  // only the reference's own rounding
  ReferenceBall best;
  auto consider = [&](const DVec3& center, double radius) {
    if (!std::isfinite(radius) || radius >= best.radius) return;
    for (const DVec3& q : p)
      if (glm::length(q - center) > radius + tolerance) return;
    best = {center, radius};
  };
  consider(p[0], 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      consider(0.5 * (p[i] + p[j]), 0.5 * glm::length(p[i] - p[j]));
      for (std::size_t k = j + 1; k < n; ++k) {
        const DVec3 ab = p[j] - p[i], ac = p[k] - p[i], normal = glm::cross(ab, ac);
        const double n2 = glm::dot(normal, normal);
        if (n2 > 0.0) {
          const DVec3 o =
              (glm::dot(ac, ac) * glm::cross(normal, ab) + glm::dot(ab, ab) * glm::cross(ac, normal)) /
              (2.0 * n2);
          consider(p[i] + o, glm::length(o));
        }
        for (std::size_t l = k + 1; l < n; ++l) {
          const DVec3 ad = p[l] - p[i];
          const double det = glm::dot(ab, glm::cross(ac, ad));
          if (det == 0.0) continue;
          const DVec3 o = (glm::dot(ab, ab) * glm::cross(ac, ad) + glm::dot(ac, ac) * glm::cross(ad, ab) +
                           glm::dot(ad, ad) * glm::cross(ab, ac)) /
                          (2.0 * det);
          consider(p[i] + o, glm::length(o));
        }
      }
    }
  }
  return best;
}

void expectContainsAll(const BoundingSphere& sphere, const std::vector<Vec3>& points,
                       float relativeTolerance) {
  const float tolerance = relativeTolerance * std::max(sphere.radius, test::cloudScale(points));
  for (std::size_t i = 0; i < points.size(); ++i) {
    EXPECT_LE(glm::length(points[i] - sphere.center), sphere.radius + tolerance) << "point " << i;
  }
}

// One of the degenerate or general families the random test cycles through.
std::vector<Vec3> randomCloud(Random& random, int family, std::string& outName) {
  const int n = random.integer(4, 30);
  const Vec3 offset = random.inCube(5.0f);
  const Quat rotation = random.rotation();
  std::vector<Vec3> points;
  switch (family) {
    case 0:
      outName = "cube";
      for (int i = 0; i < n; ++i) points.push_back(offset + random.inCube(1.0f));
      break;
    case 1: {
      outName = "circle";
      const float radius = random.uniform(0.1f, 3.0f);
      for (int i = 0; i < n; ++i) {
        const float angle = random.uniform(0.0f, 2.0f * kPi);
        points.push_back(offset + rotation * Vec3(radius * std::cos(angle), radius * std::sin(angle), 0.0f));
      }
      break;
    }
    case 2:
      outName = "coplanar";
      for (int i = 0; i < n; ++i)
        points.push_back(offset + rotation * Vec3(random.uniform(-2, 2), random.uniform(-1, 1), 0.0f));
      break;
    case 3:
      outName = "duplicates";
      for (int i = 0; i < n / 2; ++i) points.push_back(offset + random.inCube(1.0f));
      while (int(points.size()) < n) points.push_back(points[random.integer(0, int(points.size()) - 1)]);
      break;
    case 4: {
      outName = "collinear";
      const Vec3 direction = random.direction();
      for (int i = 0; i < n; ++i) points.push_back(offset + random.uniform(-3.0f, 3.0f) * direction);
      break;
    }
    case 5:
      outName = "single point";
      points.assign(random.integer(1, 5), offset);
      break;
    case 6:
      outName = "two points";
      points = {offset, offset + random.uniform(0.01f, 3.0f) * random.direction()};
      break;
    case 7: {
      outName = "sphere surface";
      const float radius = random.uniform(0.1f, 3.0f);
      for (int i = 0; i < n; ++i) points.push_back(offset + radius * random.direction());
      break;
    }
    default:
      outName = "flat box";  // thin in one direction: near-coplanar, the hard case for circumspheres
      for (int i = 0; i < n; ++i)
        points.push_back(offset + rotation * Vec3(random.uniform(-2, 2), random.uniform(-1, 1),
                                                  random.uniform(-1e-3f, 1e-3f)));
      break;
  }
  return points;
}

}  // namespace

TEST(MinimalSphere, UnitCubeCornersHaveRadiusHalfTheDiagonal) {
  std::vector<Vec3> corners;
  for (int i = 0; i < 8; ++i) corners.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  const BoundingSphere s = minimalBoundingSphere(corners);
  EXPECT_NEAR(s.radius, std::sqrt(3.0f) / 2.0f, 1e-6f);
  EXPECT_NEAR(glm::length(s.center - Vec3(0.5f)), 0.0f, 1e-6f);
}

TEST(MinimalSphere, RegularTetrahedronHasItsCircumradius) {
  // Alternate corners of the cube [-1, 1]^3: edge 2 sqrt(2), circumradius edge * sqrt(6) / 4 = sqrt(3).
  const std::vector<Vec3> tetrahedron = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
  const BoundingSphere s = minimalBoundingSphere(tetrahedron);
  EXPECT_NEAR(s.radius, std::sqrt(3.0f), 1e-6f);
  EXPECT_NEAR(glm::length(s.center), 0.0f, 1e-6f);
}

TEST(MinimalSphere, ObtuseTriangleUsesItsLongestSideNotItsCircumcircle) {
  // The circumcircle of an obtuse triangle is larger than the diametral sphere of its longest side.
  const std::vector<Vec3> triangle = {{-1, 0, 0}, {1, 0, 0}, {0, 0.1f, 0}};
  const BoundingSphere s = minimalBoundingSphere(triangle);
  EXPECT_NEAR(s.radius, 1.0f, 1e-6f);
  EXPECT_NEAR(glm::length(s.center), 0.0f, 1e-6f);
}

TEST(MinimalSphere, PointsOnASphereSurfaceIncludingThePolesGiveThatSphere) {
  // With the six poles present the diametral spheres of opposite poles already have radius R, and
  // every point is at distance R from the centre: the answer is exactly that sphere.
  Random random(7);
  const Vec3 center(3.0f, -2.0f, 1.0f);
  const float radius = 2.5f;
  std::vector<Vec3> points;
  for (int axis = 0; axis < 3; ++axis) {
    Vec3 e(0.0f);
    e[axis] = radius;
    points.push_back(center + e);
    points.push_back(center - e);
  }
  for (int i = 0; i < 500; ++i) points.push_back(center + radius * random.direction());
  const BoundingSphere s = minimalBoundingSphere(points);
  EXPECT_NEAR(s.radius, radius, 1e-5f * radius);
  EXPECT_NEAR(glm::length(s.center - center), 0.0f, 1e-5f * radius);
  expectContainsAll(s, points, 1e-6f);
}

TEST(MinimalSphere, SinglePointAndTwoPoints) {
  const std::vector<Vec3> one = {{1, 2, 3}};
  const BoundingSphere a = minimalBoundingSphere(one);
  EXPECT_EQ(a.radius, 0.0f);
  EXPECT_EQ(a.center, Vec3(1, 2, 3));
  const std::vector<Vec3> two = {{1, 2, 3}, {1, 2, 7}};
  const BoundingSphere b = minimalBoundingSphere(two);
  EXPECT_NEAR(b.radius, 2.0f, 1e-6f);
  EXPECT_NEAR(glm::length(b.center - Vec3(1, 2, 5)), 0.0f, 1e-6f);
}

TEST(MinimalSphere, MatchesBruteForceOn300RandomSetsIncludingDegenerateOnes) {
  Random random(20240611);
  for (int trial = 0; trial < 300; ++trial) {
    std::string family;
    const std::vector<Vec3> points = randomCloud(random, trial % 9, family);
    const BoundingSphere sphere = minimalBoundingSphere(points);
    const ReferenceBall reference = bruteForceMinimalSphere(points);
    const float scale = test::cloudScale(points);
    SCOPED_TRACE("trial " + std::to_string(trial) + " (" + family + ", " + std::to_string(points.size()) +
                 " points)");
    EXPECT_NEAR(sphere.radius, reference.radius, 1e-4 * reference.radius + 1e-6 * scale);
    expectContainsAll(sphere, points, 1e-5f);
  }
}

TEST(MinimalSphere, IsDeterministicAndIndependentOfInputOrder) {
  Random random(3);
  std::vector<Vec3> points;
  for (int i = 0; i < 200; ++i) points.push_back(random.inCube(1.0f));
  const BoundingSphere a = minimalBoundingSphere(points);
  const BoundingSphere b = minimalBoundingSphere(points);
  EXPECT_EQ(a.center, b.center);
  EXPECT_EQ(a.radius, b.radius);
  std::reverse(points.begin(), points.end());
  const BoundingSphere c = minimalBoundingSphere(points);
  // A different order may take another path to the same unique ball: equal up to rounding.
  EXPECT_NEAR(c.radius, a.radius, 1e-6f);
  EXPECT_NEAR(glm::length(c.center - a.center), 0.0f, 1e-5f);
}

TEST(MinimalSphere, RejectsEmptyAndNonFiniteInput) {
  EXPECT_THAT([] { minimalBoundingSphere({}); },
              ::collide::test::ReportsError(::testing::HasSubstr("empty")));
  const std::vector<Vec3> withNan = {{0, 0, 0}, {1, NAN, 0}};
  if (const std::optional<std::string> error =
          ::collide::test::errorOf([&] { minimalBoundingSphere(withNan); });
      !error) {
    FAIL() << "NaN accepted";
  } else {
    EXPECT_NE((*error).find("point 1 is not finite"), std::string::npos) << *error;
  }
  const std::vector<Vec3> withInf = {{INFINITY, 0, 0}};
  EXPECT_COLLIDE_ERROR(minimalBoundingSphere(withInf));
}
