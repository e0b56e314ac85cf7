// Non-penetration by projection (lecture, slide 11).
#include <gtest/gtest.h>

#include <collide/error.h>

#include <limits>
#include <random>

#include "response/penetration.h"
#include "support/collide_error.h"
#include "support/test_assertions.h"
#include "support/test_random.h"

using namespace collide;
using namespace collide::detail;
using namespace collide::test;

namespace {

using test::expectVecNear;

}  // namespace

TEST(Penetration, OneWayMovesOnlyTheMovableBodyByTheDepth) {
  const Vec3 n = glm::normalize(Vec3(1, 2, 2));
  const Displacements staticA = projectApart(0.0f, 0.5f, n, 0.3f);
  expectVecNear(staticA.a, Vec3(0.0f), 0.0f);
  expectVecNear(staticA.b, 0.3f * n, 1e-7f);
  const Displacements staticB = projectApart(2.0f, 0.0f, n, 0.3f);
  expectVecNear(staticB.a, -0.3f * n, 1e-7f);
  expectVecNear(staticB.b, Vec3(0.0f), 0.0f);
}

TEST(Penetration, TwoWaySplitsByInverseMass) {
  // mA = 1, mB = 4: A moves 4/5 of the depth, B 1/5; the mass-weighted centre stays.
  const Vec3 n(0, 0, 1);
  const Displacements d = projectApart(1.0f, 0.25f, n, 0.5f);
  expectVecNear(d.a, Vec3(0, 0, -0.4f), 1e-7f);
  expectVecNear(d.b, Vec3(0, 0, 0.1f), 1e-7f);
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> inverseMass(0.05f, 5.0f), depth(0.0f, 2.0f);
  for (int i = 0; i < 200; ++i) {
    const float wa = inverseMass(rng), wb = inverseMass(rng), h = depth(rng);
    const Vec3 normal = randomUnitVector(rng);
    const Displacements r = projectApart(wa, wb, normal, h);
    EXPECT_NEAR(glm::dot(r.b - r.a, normal), h, 1e-5f);                               // separated by depth
    expectVecNear(r.a / wa + r.b / wb, Vec3(0.0f), 1e-5f * (1.0f / wa + 1.0f / wb));  // centre of mass kept
    // The minimum of mA |dA|^2 + mB |dB|^2 over displacements that separate by the depth: moving both by
    // a common vector, or B by a tangential one, only raises it.
    const auto cost = [&](const Vec3& da, const Vec3& db) {
      return glm::dot(da, da) / wa + glm::dot(db, db) / wb;
    };
    const float best = cost(r.a, r.b);
    for (int k = 0; k < 10; ++k) {
      const Vec3 shift = 0.1f * randomInUnitBall(rng);
      Vec3 tangent = randomInUnitBall(rng);
      tangent -= glm::dot(tangent, normal) * normal;
      EXPECT_GE(cost(r.a + shift, r.b + shift + 0.1f * tangent), best * (1.0f - 1e-5f));
    }
  }
}

TEST(Penetration, NothingToDoForStaticPairsOrZeroDepth) {
  const Displacements both = projectApart(0.0f, 0.0f, Vec3(1, 0, 0), 1.0f);
  expectVecNear(both.a, Vec3(0.0f), 0.0f);
  expectVecNear(both.b, Vec3(0.0f), 0.0f);
  const Displacements touching = projectApart(1.0f, 1.0f, Vec3(1, 0, 0), 0.0f);
  expectVecNear(touching.a, Vec3(0.0f), 0.0f);
  expectVecNear(touching.b, Vec3(0.0f), 0.0f);
}

TEST(Penetration, BadInputThrows) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const Vec3 n(1, 0, 0);
  EXPECT_COLLIDE_ERROR(projectApart(-1.0f, 1.0f, n, 0.1f));
  EXPECT_COLLIDE_ERROR(projectApart(1.0f, nan, n, 0.1f));
  EXPECT_COLLIDE_ERROR(projectApart(1.0f, std::numeric_limits<float>::infinity(), n, 0.1f));
  EXPECT_COLLIDE_ERROR(projectApart(1.0f, 1.0f, Vec3(0.5f, 0, 0), 0.1f));
  EXPECT_COLLIDE_ERROR(projectApart(1.0f, 1.0f, Vec3(nan, 0, 0), 0.1f));
  EXPECT_COLLIDE_ERROR(projectApart(1.0f, 1.0f, n, -0.1f));
  EXPECT_COLLIDE_ERROR(projectApart(1.0f, 1.0f, n, nan));
}
