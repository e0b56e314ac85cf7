// Assertions shared by the tests.
#pragma once

#include <collide/math.h>
#include <gtest/gtest.h>

#include <cmath>

namespace collide::test {

// The tolerance of the closed forms the shape tests check (float arithmetic on unit sizes).
inline constexpr float kEps = 1e-5f;
// A finite float near the largest: two of them add up to infinity.
inline constexpr float kHuge = 3.0e38f;

inline bool isFinite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Component-wise |actual - expected| <= tolerance.
inline void expectVecNear(const Vec3& actual, const Vec3& expected, float tolerance = 1e-5f) {
  EXPECT_NEAR(actual.x, expected.x, tolerance);
  EXPECT_NEAR(actual.y, expected.y, tolerance);
  EXPECT_NEAR(actual.z, expected.z, tolerance);
}

// Euclidean |actual - expected| < tolerance, printing both vectors.
inline void expectVecWithin(const Vec3& actual, const Vec3& expected, float tolerance) {
  EXPECT_LT(glm::length(actual - expected), tolerance)
      << "[" << actual.x << " " << actual.y << " " << actual.z << "] vs [" << expected.x << " " << expected.y
      << " " << expected.z << "]";
}

}  // namespace collide::test
