// An orbit camera: it looks at a target from a yaw, a pitch and a distance. Left drag turns it,
// right (or middle) drag pans the target in the view plane, the wheel zooms.
#pragma once

#include <collide/math.h>

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace collide::viewer {

struct OrbitCamera {
  Vec3 target{0.0f};
  float yaw = 0.6f;     // radians about +y
  float pitch = 0.45f;  // radians above the horizon
  float distance = 20.0f;
  float fovY = 0.8f;  // radians

  Vec3 eye() const {
    const Vec3 offset(std::cos(pitch) * std::sin(yaw), std::sin(pitch), std::cos(pitch) * std::cos(yaw));
    return target + distance * offset;
  }
  glm::mat4 view() const { return glm::lookAt(eye(), target, Vec3(0.0f, 1.0f, 0.0f)); }
  glm::mat4 projection(float aspect) const {
    return glm::perspective(fovY, aspect, std::max(0.01f, 0.01f * distance), 1000.0f + 10.0f * distance);
  }

  // Unit, from the eye to the target.
  Vec3 forward() const { return glm::normalize(target - eye()); }

  // The ray from the eye through a point of the viewport (x to the right, y down, in the same
  // units as width and height: window coordinates for the cursor), as the projection draws it.
  Ray rayThrough(float x, float y, float width, float height) const {
    const float ndcX = 2.0f * x / std::max(width, 1.0f) - 1.0f;
    const float ndcY = 1.0f - 2.0f * y / std::max(height, 1.0f);
    const glm::mat4 v = view();
    const Vec3 right(v[0][0], v[1][0], v[2][0]);
    const Vec3 up(v[0][1], v[1][1], v[2][1]);
    const float halfHeight = std::tan(0.5f * fovY);
    const float aspect = std::max(width, 1.0f) / std::max(height, 1.0f);
    const Vec3 direction = forward() + ndcX * halfHeight * aspect * right + ndcY * halfHeight * up;
    return Ray{eye(), glm::normalize(direction), 1e30f};
  }

  void orbit(float dx, float dy) {
    yaw -= 0.008f * dx;
    pitch = std::clamp(pitch + 0.008f * dy, -1.55f, 1.55f);
  }
  void pan(float dx, float dy, float viewportHeight) {
    // One pixel moves the target by the size a pixel has at the target's depth.
    const float metresPerPixel = 2.0f * distance * std::tan(0.5f * fovY) / std::max(viewportHeight, 1.0f);
    const glm::mat4 v = view();
    const Vec3 right(v[0][0], v[1][0], v[2][0]);
    const Vec3 up(v[0][1], v[1][1], v[2][1]);
    target += metresPerPixel * (-dx * right + dy * up);
  }
  void zoom(float wheel) { distance = std::clamp(distance * std::pow(0.88f, wheel), 0.1f, 5000.0f); }

  // Frames a box: the target at its centre, far enough back to see all of it, looking across its
  // longer horizontal side (a wall such as the pyramid is seen face on, not edge on).
  void frame(const Aabb& box) {
    target = 0.5f * (box.min + box.max);
    const Vec3 size = box.max - box.min;
    yaw = size.x >= size.z ? 0.45f : 1.5708f - 0.45f;
    const float radius = std::max(0.5f * glm::length(box.max - box.min), 0.5f);
    distance = radius / std::sin(0.5f * fovY) * 0.9f;
  }
};

}  // namespace collide::viewer
