// Random geometry for tests: unit vectors, rotations, points and transforms from a seeded
// std::mt19937, so every test is reproducible.
#pragma once

#include <collide/math.h>

#include <cmath>
#include <random>
#include <vector>

namespace collide::test {

inline Vec3 randomUnitVector(std::mt19937& rng) {
  std::normal_distribution<float> normal(0.0f, 1.0f);
  for (;;) {
    const Vec3 v(normal(rng), normal(rng), normal(rng));
    const float length = glm::length(v);
    if (length > 1e-3f) return v / length;
  }
}

// Uniform in the unit ball.
inline Vec3 randomInUnitBall(std::mt19937& rng) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  return randomUnitVector(rng) * std::cbrt(u(rng));
}

// `count` points on the sphere of `radius` about the origin, uniformly.
inline std::vector<Vec3> randomPointsOnSphere(int count, float radius, std::mt19937& rng) {
  std::normal_distribution<float> gaussian(0.0f, 1.0f);
  std::vector<Vec3> points;
  while (int(points.size()) < count) {
    const Vec3 p(gaussian(rng), gaussian(rng), gaussian(rng));
    if (glm::length(p) > 1e-3f) points.push_back(radius * glm::normalize(p));
  }
  return points;
}

// A uniformly random rotation: a normalised 4D Gaussian is uniform on the unit 3-sphere.
inline Quat randomRotation(std::mt19937& rng) {
  std::normal_distribution<float> normal(0.0f, 1.0f);
  for (;;) {
    const Quat q(normal(rng), normal(rng), normal(rng), normal(rng));
    const float length = glm::length(q);
    if (length > 1e-3f) return q / length;
  }
}

// Random position in [-5, 5]^3, uniform rotation, scale uniform in [0.3, 3].
inline Transform randomTransform(std::mt19937& rng) {
  std::uniform_real_distribution<float> position(-5.0f, 5.0f);
  std::uniform_real_distribution<float> scale(0.3f, 3.0f);
  Transform t;
  t.position = Vec3(position(rng), position(rng), position(rng));
  t.rotation = randomRotation(rng);
  t.scale = scale(rng);
  return t;
}

// Uniform in the box [lo, hi]^3.
inline Vec3 randomPoint(std::mt19937& rng, float lo, float hi) {
  std::uniform_real_distribution<float> u(lo, hi);
  const float x = u(rng);
  const float y = u(rng);
  const float z = u(rng);
  return {x, y, z};
}

}  // namespace collide::test
