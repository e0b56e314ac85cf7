// Assertions shared by the tests.
#pragma once

#include <collide/error.h>
#include <collide/math.h>
#include <gtest/gtest.h>

#include "support/collide_error.h"

#include <cmath>
#include <functional>
#include <limits>
#include <string>

namespace collide::test {

// The tolerance of the closed forms the shape tests check (float arithmetic on unit sizes).
inline constexpr float kEps = 1e-5f;
// A finite float near the largest: two of them add up to infinity.
inline constexpr float kHuge = 3.0e38f;

inline constexpr float kNan = std::numeric_limits<float>::quiet_NaN();
inline constexpr float kInf = std::numeric_limits<float>::infinity();
inline constexpr float kDegree = kPi / 180.0f;

inline bool isFinite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Element-wise |a - b| <= tolerance.
inline void expectMatNear(const Mat3& a, const Mat3& b, float tolerance) {
  for (int c = 0; c < 3; ++c) {
    for (int r = 0; r < 3; ++r) EXPECT_NEAR(a[c][r], b[c][r], tolerance) << "element " << c << "," << r;
  }
}

// f reports a collide::Error (support/collide_error.h), and its message names `word`.
inline void expectErrorMentions(const std::function<void()>& f, const std::string& word) {
  if (const std::optional<std::string> error = ::collide::test::errorOf([&] { f(); }); !error) {
    FAIL() << "no Error reported (expected one naming \"" << word << "\")";
  } else {
    EXPECT_NE((*error).find(word), std::string::npos) << *error;
  }
}

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
