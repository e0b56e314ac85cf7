// Math types: GLM vectors and quaternions, the rigid Transform with uniform scale, rays, axis-aligned
// boxes, bounding spheres, half-spaces (planes) and view frusta. Single precision, like the games
// that use us.
#pragma once

#include <collide/hooks.h>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <array>
#include <cstddef>
#include <cstdint>

namespace collide {

using Vec3 = glm::vec3;
using Vec4 = glm::vec4;
using Quat = glm::quat;
using Mat3 = glm::mat3;
using Mat4 = glm::mat4;

// The library is compiled with GLM's default configuration and takes these types by reference and
// in arrays: a game that configures GLM otherwise (its GLM_FORCE_ macros seen before this header)
// would hand it data laid out differently, and nothing would say so. These checks run in the game's
// own compilation. Conventions (units, axes, handedness, quaternions): docs/integration.md.
static_assert(sizeof(Vec3) == 12 && alignof(Vec3) == 4 && sizeof(Vec4) == 16 && alignof(Vec4) == 4,
              "collide: GLM's vectors are aligned or padded here (GLM_FORCE_DEFAULT_ALIGNED_GENTYPES or "
              "GLM_FORCE_ALIGNED_GENTYPES?); collide's API needs GLM's default, tightly packed vectors");
static_assert(sizeof(Mat3) == 36 && sizeof(Mat4) == 64 && alignof(Mat4) == 4,
              "collide: GLM's matrices are aligned or padded here; collide's API needs GLM's default layout");
static_assert(sizeof(Quat) == 16 && alignof(Quat) == 4 && offsetof(Quat, x) == 0 && offsetof(Quat, w) == 12,
              "collide: glm::quat stores its components in another order or alignment here "
              "(GLM_FORCE_QUAT_DATA_WXYZ?); collide's API needs GLM's default layout, x, y, z, w in memory "
              "(the constructor still takes w first)");

inline constexpr float kPi = 3.14159265358979323846f;

// A proxy moves by roto-translation and uniform scaling (lecture: "behaviour under transformations").
// World point = position + rotation * (scale * local point). Non-uniform scale is not a transform
// here: it would turn a sphere into an ellipsoid, so it is a shape parameter instead.
struct Transform {
  Vec3 position{0.0f};
  Quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // glm stores w first in the constructor
  float scale = 1.0f;

  static Transform identity() { return {}; }

  Vec3 applyToPoint(const Vec3& localPoint) const { return position + rotation * (scale * localPoint); }
  Vec3 applyToVector(const Vec3& localVector) const { return rotation * (scale * localVector); }
  // Directions (normals) rotate only: uniform scale does not change them.
  Vec3 applyToDirection(const Vec3& localDirection) const { return rotation * localDirection; }
  Vec3 inverseApplyToPoint(const Vec3& worldPoint) const {
    return glm::conjugate(rotation) * (worldPoint - position) / scale;
  }
  Vec3 inverseApplyToDirection(const Vec3& worldDirection) const {
    return glm::conjugate(rotation) * worldDirection;
  }

  Transform inverse() const {
    const Quat inverseRotation = glm::conjugate(rotation);
    const float inverseScale = 1.0f / scale;
    return {inverseRotation * (-position * inverseScale), inverseRotation, inverseScale};
  }
};

// (a * b) applies b first, then a: a child's world transform is parent * childLocal.
inline Transform operator*(const Transform& a, const Transform& b) {
  return {a.applyToPoint(b.position), glm::normalize(a.rotation * b.rotation), a.scale * b.scale};
}

bool isFinite(float value);
bool isFinite(const Vec3& v);
bool isFinite(const Quat& q);
// Finite position and rotation, a unit quaternion (within 1e-3) and a positive finite scale.
bool isValid(const Transform& transform);

// A ray or segment: origin + t * direction for t in [0, maxDistance]; direction is unit length.
struct Ray {
  Vec3 origin{0.0f};
  Vec3 direction{0.0f, 0.0f, 1.0f};
  float maxDistance = 1e30f;
};

struct RayHit {
  float distance = 0.0f;  // along the ray, in world units
  Vec3 point{0.0f};
  Vec3 normal{0.0f};           // unit, the surface normal at the hit, facing the ray's origin side
  std::uint32_t subShape = 0;  // triangle index for a mesh, child index for a compound
};

// Axis-aligned bounding box. An empty box has min > max.
struct Aabb {
  Vec3 min{1e30f};
  Vec3 max{-1e30f};

  static Aabb empty() { return {}; }
  static Aabb fromCenterHalfExtents(const Vec3& center, const Vec3& halfExtents) {
    return {center - halfExtents, center + halfExtents};
  }
  bool isEmpty() const { return min.x > max.x || min.y > max.y || min.z > max.z; }
  Vec3 center() const { return 0.5f * (min + max); }
  Vec3 halfExtents() const { return 0.5f * (max - min); }
  float volume() const {
    const Vec3 d = max - min;
    return isEmpty() ? 0.0f : d.x * d.y * d.z;
  }
  float surfaceArea() const {
    const Vec3 d = max - min;
    return isEmpty() ? 0.0f : 2.0f * (d.x * d.y + d.y * d.z + d.z * d.x);
  }
  void grow(const Vec3& p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  void grow(const Aabb& b) {
    min = glm::min(min, b.min);
    max = glm::max(max, b.max);
  }
  Aabb expanded(float margin) const { return {min - Vec3(margin), max + Vec3(margin)}; }
  bool contains(const Vec3& p) const {
    return p.x >= min.x && p.x <= max.x && p.y >= min.y && p.y <= max.y && p.z >= min.z && p.z <= max.z;
  }
  bool contains(const Aabb& b) const { return contains(b.min) && contains(b.max); }
  bool overlaps(const Aabb& b) const {
    return min.x <= b.max.x && b.min.x <= max.x && min.y <= b.max.y && b.min.y <= max.y && min.z <= b.max.z &&
           b.min.z <= max.z;
  }
};

Aabb merge(const Aabb& a, const Aabb& b);
// The world box of a local box under a transform: exact for the box, conservative for its contents.
Aabb transformAabb(const Aabb& local, const Transform& transform);
// Slab test. Returns the entry distance along the ray, or a negative value on a miss.
float rayAabbEntry(const Ray& ray, const Aabb& box);

struct BoundingSphere {
  Vec3 center{0.0f};
  float radius = 0.0f;

  bool contains(const Vec3& p, float tolerance = 0.0f) const {
    return glm::dot(p - center, p - center) <= (radius + tolerance) * (radius + tolerance);
  }
  bool overlaps(const BoundingSphere& other) const {
    const float r = radius + other.radius;
    return glm::dot(center - other.center, center - other.center) <= r * r;
  }
};

// A half-space (lecture, slide 58: the vec4 (n, k)): the surface is normal·x = distance, and the
// solid side is normal·x < distance. The same type is the "plane" proxy and a culling plane.
struct Plane {
  Vec3 normal{0.0f, 1.0f, 0.0f};  // unit
  float distance = 0.0f;

  static Plane fromPointNormal(const Vec3& point, const Vec3& unitNormal) {
    return {unitNormal, glm::dot(unitNormal, point)};
  }
  // Positive outside (in front of) the surface, negative in the solid.
  float signedDistance(const Vec3& p) const { return glm::dot(normal, p) - distance; }
};

enum class Side : std::uint8_t { Inside, Outside, Straddling };

// Side of a box or sphere relative to a half-space: Inside = entirely in the solid side.
Side classify(const Plane& plane, const Aabb& box);
Side classify(const Plane& plane, const BoundingSphere& sphere);

// A view frustum for culling: the intersection of six half-spaces whose normals point outwards.
struct Frustum {
  std::array<Plane, 6> planes;  // left, right, bottom, top, near, far

  // The clip-space depth range of the projection: OpenGL's z in [-w, w] (glm::perspective by
  // default), or Direct3D's, Vulkan's and Metal's z in [0, w] (glm::perspectiveZO, or
  // glm::perspective under GLM_FORCE_DEPTH_ZERO_TO_ONE).
  enum class ClipDepth : std::uint8_t { MinusOneToOne, ZeroToOne };

  // From a view-projection matrix (column vectors, as glm::perspective and glm::lookAt make it).
  static Frustum fromViewProjection(const Mat4& viewProjection, ClipDepth depth = ClipDepth::MinusOneToOne);

  // Conservative: false only when the volume is certainly outside.
  bool intersects(const Aabb& box) const;
  bool intersects(const BoundingSphere& sphere) const;
  bool contains(const Vec3& point) const;
};

// Orthonormal basis completing a unit vector (Duff et al. 2017, "Building an orthonormal basis,
// revisited").
void orthonormalBasis(const Vec3& unitNormal, Vec3& outTangent, Vec3& outBitangent);

}  // namespace collide
