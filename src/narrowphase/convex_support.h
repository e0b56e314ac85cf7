// A convex shape placed in the world as GJK and EPA see it: a support mapping of its *core* plus a
// convex radius. A sphere is a point core with radius r, a capsule a segment core with radius r
// (Box2D's proxy radius, Jolt's convex radius): GJK then runs on the core, which converges in a few
// iterations and is exact for the rounded part, and the radius is subtracted afterwards.
#pragma once

#include <collide/shapes.h>

#include <cmath>
#include <cstdint>

namespace collide::detail {

struct ConvexSupport {
  enum class Kind : std::uint8_t { Point, Segment, Box, Ellipsoid, Cylinder, Hull, Points };

  Kind kind = Kind::Point;
  float radius = 0.0f;  // convex radius in world units; 0 for shapes without a rounded part
  Vec3 position{0.0f};  // world position of the local origin
  Mat3 rotation{1.0f};  // local to world
  float scale = 1.0f;
  // Segment: (0, halfHeight, 0); Box: half extents; Ellipsoid: radii; Cylinder: (radius, halfHeight, 0).
  Vec3 extent{0.0f};
  const ConvexHull* hull = nullptr;  // Hull (a convex hull or a k-DOP's polytope)
  const Vec3* points = nullptr;      // Points: local vertices (a triangle, a point cloud)
  std::uint32_t pointCount = 0;
  // When set, supportCore() answers for the whole shape, core plus radius (see
  // convexSignedDistance: EPA on the rounded shapes when their cores nearly touch).
  bool inflated = false;

  // The farthest point of the core in a world direction (need not be unit), in world coordinates.
  Vec3 supportCore(const Vec3& worldDirection) const {
    const Vec3 d = glm::transpose(rotation) * worldDirection;  // rotation is orthonormal
    const Vec3 p = position + rotation * (scale * localSupportCore(d));
    if (!inflated) return p;
    const float length = glm::length(worldDirection);
    return length > 0.0f ? p + (radius / length) * worldDirection : p;
  }

  // Between the shape's local frame and the world (the warm-start cache keeps local points).
  Vec3 toWorld(const Vec3& local) const { return position + rotation * (scale * local); }
  Vec3 toLocal(const Vec3& world) const { return (glm::transpose(rotation) * (world - position)) / scale; }

  // A point inside the core, to seed GJK's search direction.
  Vec3 center() const { return position; }

  Vec3 localSupportCore(const Vec3& d) const {
    switch (kind) {
      case Kind::Point:
        return Vec3(0.0f);
      case Kind::Segment:
        return Vec3(0.0f, d.y >= 0.0f ? extent.y : -extent.y, 0.0f);
      case Kind::Box:
        return {d.x >= 0.0f ? extent.x : -extent.x, d.y >= 0.0f ? extent.y : -extent.y,
                d.z >= 0.0f ? extent.z : -extent.z};
      case Kind::Ellipsoid: {
        // support(d) = r ∘ normalize(r ∘ d) for the unit sphere scaled by r.
        const Vec3 scaled = extent * d;
        const float length = glm::length(scaled);
        return length > 0.0f ? extent * (scaled / length) : Vec3(extent.x, 0.0f, 0.0f);
      }
      case Kind::Cylinder: {
        const float radial = std::sqrt(d.x * d.x + d.z * d.z);
        const float y = d.y >= 0.0f ? extent.y : -extent.y;
        if (radial < 1e-20f) return {0.0f, y, 0.0f};
        return {extent.x * d.x / radial, y, extent.x * d.z / radial};
      }
      case Kind::Hull:
        return hull->support(d);
      case Kind::Points: {
        std::uint32_t best = 0;
        float bestDot = glm::dot(points[0], d);
        for (std::uint32_t i = 1; i < pointCount; ++i) {
          const float value = glm::dot(points[i], d);
          if (value > bestDot) {
            bestDot = value;
            best = i;
          }
        }
        return points[best];
      }
    }
    return Vec3(0.0f);
  }
};

// The core and radius of a convex shape (sphere, capsule, box, k-DOP, ellipsoid, cylinder, hull).
// The shape must be convex; the transform valid. The shape must outlive the result.
ConvexSupport makeConvexSupport(const Shape& shape, const Transform& transform);

// A polytope given by its local vertices (a mesh triangle, a point cloud) placed by `transform`. The
// points must outlive the result.
ConvexSupport makePointsSupport(const Vec3* localPoints, std::uint32_t count, const Transform& transform);

}  // namespace collide::detail
