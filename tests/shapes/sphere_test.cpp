#include <collide/shapes.h>
#include <gtest/gtest.h>

using namespace collide;

TEST(Sphere, VolumeIsFourThirdsPiRCubed) {
  const MassProperties m = massProperties(Sphere{2.0f}, 1.0f);
  EXPECT_NEAR(m.volume, 4.0f / 3.0f * kPi * 8.0f, 1e-4f);
}
