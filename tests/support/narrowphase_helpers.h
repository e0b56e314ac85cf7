// Shared helpers for the narrow-phase tests: placements, random shapes and poses.
#pragma once

#include <collide/narrowphase.h>
#include <collide/shapes.h>

#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <random>
#include <vector>

namespace collide::test {

inline Transform at(const Vec3& position, const Quat& rotation = Quat(1.0f, 0.0f, 0.0f, 0.0f),
                    float scale = 1.0f) {
  return {position, rotation, scale};
}

inline Quat axisAngle(const Vec3& axis, float degrees) {
  return glm::angleAxis(glm::radians(degrees), glm::normalize(axis));
}

// A uniformly distributed rotation (Shoemake, "Uniform random rotations", Graphics Gems III).
inline Quat uniformRotation(std::mt19937& rng) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const float u1 = u(rng), u2 = u(rng), u3 = u(rng);
  const float a = std::sqrt(1.0f - u1), b = std::sqrt(u1);
  const float t1 = 2.0f * kPi * u2, t2 = 2.0f * kPi * u3;
  return glm::normalize(Quat(b * std::cos(t2), a * std::sin(t1), a * std::cos(t1), b * std::sin(t2)));
}

inline Vec3 randomUnit(std::mt19937& rng) {
  std::normal_distribution<float> n(0.0f, 1.0f);
  Vec3 v;
  do {
    v = Vec3(n(rng), n(rng), n(rng));
  } while (glm::dot(v, v) < 1e-6f);
  return glm::normalize(v);
}

// A primitive of the given type with sizes in [0.2, 1.2].
inline Shape randomPrimitive(ShapeType type, std::mt19937& rng) {
  std::uniform_real_distribution<float> size(0.2f, 1.2f);
  switch (type) {
    case ShapeType::Sphere:
      return Sphere{size(rng)};
    case ShapeType::Capsule:
      return Capsule{size(rng), size(rng)};
    case ShapeType::Box:
      return Box{Vec3(size(rng), size(rng), size(rng))};
    case ShapeType::Ellipsoid:
      return Ellipsoid{Vec3(size(rng), size(rng), size(rng))};
    case ShapeType::Cylinder:
      return Cylinder{size(rng), size(rng)};
    default:
      return Sphere{1.0f};
  }
}

// The sorted depths of a manifold, to compare manifolds regardless of point order.
inline std::vector<float> sortedDepths(const Manifold& m) {
  std::vector<float> depths;
  for (int i = 0; i < m.count; ++i) depths.push_back(m.points[i].depth);
  std::sort(depths.begin(), depths.end());
  return depths;
}

inline float angleDegrees(const Vec3& a, const Vec3& b) {
  return glm::degrees(std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0f, 1.0f)));
}

}  // namespace collide::test
