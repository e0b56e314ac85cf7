// Sweeps of parts far out (bodies/body_parts.h): whether every placement along a sweep stays
// finite, which the continuous pass and the sensor sweeps ask before placing a part on its sweep.
#include "bodies/body_parts.h"

#include <gtest/gtest.h>

#include <cmath>

namespace collide {
namespace {

TEST(PartSweeps, APlacementBeyondFloatsRangeIsRefusedAndEveryOtherKept) {
  Sweep near;
  near.center0 = Vec3(1.0f, 2.0f, 3.0f);
  near.center1 = Vec3(1.5f, 2.0f, 3.0f);
  near.localCenter = Vec3(0.0f, 0.5f, 0.0f);
  EXPECT_TRUE(detail::sweepStaysFinite(near));

  // Far, but every placement finite: 1e38 m out, offset 1e38 m.
  Sweep far = near;
  far.center0 = far.center1 = Vec3(1e38f, 0.0f, 0.0f);
  far.localCenter = Vec3(1e38f, 0.0f, 0.0f);
  EXPECT_TRUE(detail::sweepStaysFinite(far));
  for (const float t : {0.0f, 0.5f, 1.0f}) EXPECT_TRUE(std::isfinite(far.at(t).position.x));

  // Each term finite, their sum not: the centre at 2e38 m and the offset turned onto it, 2e38 m.
  Sweep over = near;
  over.center0 = over.center1 = Vec3(2e38f, 0.0f, 0.0f);
  over.localCenter = Vec3(-2e38f, 0.0f, 0.0f);
  EXPECT_FALSE(std::isfinite(over.at(1.0f).position.x));  // what the step would have placed
  EXPECT_FALSE(detail::sweepStaysFinite(over));

  // Ends far apart on either side: their difference overflows in Sweep::at.
  Sweep across = near;
  across.center0 = Vec3(-3e38f, 0.0f, 0.0f);
  across.center1 = Vec3(3e38f, 0.0f, 0.0f);
  EXPECT_FALSE(detail::sweepStaysFinite(across));

  Sweep nan = near;
  nan.localCenter.y = std::nanf("");
  EXPECT_FALSE(detail::sweepStaysFinite(nan));
}

}  // namespace
}  // namespace collide
