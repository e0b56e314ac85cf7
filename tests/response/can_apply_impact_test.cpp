// The step asks canApplyImpact before it applies the impact and friction laws, instead of catching
// their errors: the predicate must accept exactly what the laws' validation accepts, so that the
// laws never throw inside the step and never skip a body they would have resolved.
#include "response/impact.h"
#include "response/impact_body.h"
#include "support/collide_error.h"

#include <collide/error.h>

#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <vector>

namespace collide::detail {
namespace {

constexpr float kNan = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

ImpactBody body(float inverseMass, const Mat3& inverseInertia) {
  ImpactBody b;
  b.inverseMass = inverseMass;
  b.inverseInertia = inverseInertia;
  b.linearVelocity = Vec3(1.0f, -2.0f, 0.5f);
  b.angularVelocity = Vec3(0.1f, 0.0f, -0.3f);
  b.centerOfMass = Vec3(0.0f, 1.0f, 0.0f);
  return b;
}

// B coming down onto A along the normal (0, 1, 0), fast: an impact to resolve.
ImpactBody approaching(ImpactBody b) {
  b.linearVelocity.y -= 3.0f;
  return b;
}

// Whether the interpolated impact (which validates the bodies and the contact, and inverts the
// inertias to glue two finite masses) accepts the case.
bool lawsAccept(ImpactBody a, ImpactBody b, const Vec3& point, const Vec3& normal) {
  return !::collide::test::errorOf([&] { (void)resolveImpactInterpolated(a, b, point, normal, 0.5f); });
}

TEST(CanApplyImpact, AgreesWithTheImpactLawsOnEveryKindOfBadBody) {
  const Mat3 inertia(2.0f);
  const std::vector<std::pair<std::string, ImpactBody>> good = {{"rigid body", body(1.0f, inertia)},
                                                                {"infinite mass", body(0.0f, Mat3(0.0f))},
                                                                {"particle", body(0.5f, Mat3(0.0f))}};
  std::vector<std::pair<std::string, ImpactBody>> bad;
  ImpactBody b = body(1.0f, inertia);
  b.linearVelocity.x = kNan;
  bad.emplace_back("NaN linear velocity", b);
  b = body(1.0f, inertia);
  b.angularVelocity.y = kInf;
  bad.emplace_back("infinite angular velocity", b);
  b = body(1.0f, inertia);
  b.centerOfMass.z = kNan;
  bad.emplace_back("NaN centre of mass", b);
  bad.emplace_back("NaN inverse mass", body(kNan, inertia));
  bad.emplace_back("negative inverse mass", body(-1.0f, inertia));
  bad.emplace_back("infinite mass that turns", body(0.0f, inertia));
  Mat3 infinite(1.0f);
  infinite[0][0] = kInf;
  bad.emplace_back("infinite inverse inertia", body(1.0f, infinite));

  const Vec3 point(0.0f, 0.5f, 0.0f), normal(0.0f, 1.0f, 0.0f);
  for (const auto& [nameA, a] : good) {
    for (const auto& [nameB, other] : good) {
      SCOPED_TRACE(nameA + " and " + nameB);
      EXPECT_TRUE(canApplyImpact(a, approaching(other), point, normal));
      EXPECT_TRUE(lawsAccept(a, approaching(other), point, normal));
    }
    for (const auto& [what, other] : bad) {
      SCOPED_TRACE(nameA + " and " + what);
      EXPECT_FALSE(canApplyImpact(a, approaching(other), point, normal));
      EXPECT_FALSE(canApplyImpact(approaching(other), a, point, normal));
      EXPECT_FALSE(lawsAccept(a, approaching(other), point, normal));
    }
  }
  // An inertia that cannot be inverted matters only where two finite masses are glued.
  Mat3 singular(1.0f);
  singular[2][2] = 0.0f;
  const ImpactBody flat = body(1.0f, singular);
  for (const auto& [name, a] : good) {
    SCOPED_TRACE(name + " and a singular inertia");
    EXPECT_EQ(canApplyImpact(a, approaching(flat), point, normal),
              lawsAccept(a, approaching(flat), point, normal));
  }
  EXPECT_FALSE(canApplyImpact(good[0].second, approaching(flat), point, normal));
  EXPECT_TRUE(canApplyImpact(good[1].second, approaching(flat), point, normal));

  for (const Vec3& badNormal : {Vec3(0.0f, 2.0f, 0.0f), Vec3(kNan, 1.0f, 0.0f), Vec3(0.0f)}) {
    EXPECT_FALSE(canApplyImpact(good[0].second, good[1].second, point, badNormal));
    EXPECT_FALSE(lawsAccept(good[0].second, good[1].second, point, badNormal));
  }
  EXPECT_FALSE(canApplyImpact(good[0].second, good[1].second, Vec3(kInf, 0.0f, 0.0f), normal));
  EXPECT_FALSE(lawsAccept(good[0].second, good[1].second, Vec3(kInf, 0.0f, 0.0f), normal));
}

}  // namespace
}  // namespace collide::detail
