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

  // Far, but every placement finite, turned or not: 1e38 m out, offset 1e37 m.
  Sweep far = near;
  far.center0 = far.center1 = Vec3(1e38f, 0.0f, 0.0f);
  far.localCenter = Vec3(1e37f, 0.0f, 0.0f);
  far.rotation1 = glm::normalize(Quat(0.3f, 0.5f, -0.7f, 0.4f));
  EXPECT_TRUE(detail::sweepStaysFinite(far));
  for (const float t : {0.0f, 0.5f, 1.0f}) EXPECT_TRUE(std::isfinite(far.at(t).position.x));

  // A part 3e38 m from its body's centre, finite once turned, whose turn overflows on the way:
  // glm's q v forms twice w (u x v) + u x (u x v) before it cancels (the world fuzzer's input
  // sensor_sweep_turn_overflow: the sensor pass placed it and step() threw).
  Sweep turned = near;
  turned.center0 = turned.center1 = Vec3(-6.0f, -3.60934f, -6.0f);
  turned.localCenter = Vec3(2.99812e38f, 7.41681e36f, -7.60495e36f);
  turned.rotation1 = glm::normalize(Quat(-0.0121681f, 0.0121409f, -0.999769f, 0.0128956f));
  EXPECT_FALSE(std::isfinite(turned.at(1.0f).position.x));  // what the step would have placed
  EXPECT_FALSE(detail::sweepStaysFinite(turned));

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
