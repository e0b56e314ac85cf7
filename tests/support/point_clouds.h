// Deterministic random point clouds for the bounding-volume tests: the generator's output is fixed
// by the seed on every platform (no std::uniform_*_distribution, whose algorithm is unspecified).
#pragma once

#include <collide/math.h>

#include <glm/gtc/quaternion.hpp>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

namespace collide::test {

class Random {
 public:
  explicit Random(std::uint32_t seed) : engine_(seed) {}
  // Uniform in [0, 1).
  float unit() { return float(engine_() >> 8) * (1.0f / 16777216.0f); }
  float uniform(float low, float high) { return low + (high - low) * unit(); }
  int integer(int low, int highInclusive) {
    return low + int(engine_() % std::uint32_t(highInclusive - low + 1));
  }
  Vec3 inCube(float half) { return {uniform(-half, half), uniform(-half, half), uniform(-half, half)}; }
  // Uniform on the unit sphere (Marsaglia 1972).
  Vec3 direction() {
    for (;;) {
      const float a = uniform(-1.0f, 1.0f), b = uniform(-1.0f, 1.0f);
      const float s = a * a + b * b;
      if (s >= 1.0f || s < 1e-6f) continue;
      const float root = std::sqrt(1.0f - s);
      return {2.0f * a * root, 2.0f * b * root, 1.0f - 2.0f * s};
    }
  }
  // Uniform random rotation (Shoemake, "Uniform random rotations", Graphics Gems III).
  Quat rotation() {
    const float u1 = unit(), u2 = 2.0f * kPi * unit(), u3 = 2.0f * kPi * unit();
    const float a = std::sqrt(1.0f - u1), b = std::sqrt(u1);
    return glm::normalize(Quat(b * std::cos(u3), a * std::sin(u2), a * std::cos(u2), b * std::sin(u3)));
  }

 private:
  std::mt19937 engine_;
};

// The largest distance of a point from the first one: the scale for absolute tolerances.
inline float cloudScale(const std::vector<Vec3>& points) {
  float scale = 0.0f;
  for (const Vec3& p : points) scale = std::max(scale, glm::length(p - points.front()));
  return std::max(scale, 1e-30f);
}

}  // namespace collide::test
