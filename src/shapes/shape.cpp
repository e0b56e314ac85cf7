// Shape: validation at construction, and the world-frame queries mapped onto the local per-proxy
// functions of shape_functions.h.
#include "shapes/shape_functions.h"

#include "base/fail.h"
#include "memory/prefetch.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

namespace collide {

std::string_view toString(ShapeType type) {
  switch (type) {
    case ShapeType::Sphere:
      return "sphere";
    case ShapeType::Capsule:
      return "capsule";
    case ShapeType::Plane:
      return "plane";
    case ShapeType::Box:
      return "box";
    case ShapeType::Kdop:
      return "kdop";
    case ShapeType::Ellipsoid:
      return "ellipsoid";
    case ShapeType::Cylinder:
      return "cylinder";
    case ShapeType::ConvexHull:
      return "convex_hull";
    case ShapeType::Mesh:
      return "mesh";
    case ShapeType::Compound:
      return "compound";
  }
  return "unknown";
}

namespace {

std::string formatValue(float v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

std::string formatValue(const Vec3& v) {
  std::ostringstream out;
  out << '[' << v.x << ", " << v.y << ", " << v.z << ']';
  return out.str();
}

bool requirePositive(const char* shape, const char* field, float value) {
  if (!isFinite(value) || value <= 0.0f) {
    COLLIDE_FAIL(std::string(shape) + ": " + field + " must be finite and > 0, got " + formatValue(value),
                 false);
  }
  return true;
}

bool requirePositive(const char* shape, const char* field, const Vec3& value) {
  if (!isFinite(value) || value.x <= 0.0f || value.y <= 0.0f || value.z <= 0.0f) {
    COLLIDE_FAIL(std::string(shape) + ": " + field + " must be finite and > 0 in every axis, got " +
                     formatValue(value),
                 false);
  }
  return true;
}

bool validPlane(const Plane& plane) {
  if (!isFinite(plane.normal) || std::abs(glm::length(plane.normal) - 1.0f) > 1e-3f) {
    COLLIDE_FAIL("plane: normal must be a finite unit vector, got " + formatValue(plane.normal), false);
  }
  if (!isFinite(plane.distance))
    COLLIDE_FAIL("plane: distance must be finite, got " + formatValue(plane.distance), false);
  return true;
}

template <class T>
std::shared_ptr<const T> share(T&& value) {
  return std::make_shared<const T>(std::forward<T>(value));
}

}  // namespace

namespace detail {

// Polyhedra, meshes and compounds are validated by their factories, the only way to make them; a
// factory that failed without exceptions returned an empty one, refused here.
bool validateShape(const Shape& shape) {
  switch (shape.type()) {
    case ShapeType::Sphere:
      return requirePositive("sphere", "radius", shape.sphere().radius);
    case ShapeType::Capsule:
      return requirePositive("capsule", "radius", shape.capsule().radius) &&
             requirePositive("capsule", "half_height", shape.capsule().halfHeight);
    case ShapeType::Plane:
      return validPlane(shape.plane());
    case ShapeType::Box:
      return requirePositive("box", "half_extents", shape.box().halfExtents);
    case ShapeType::Ellipsoid:
      return requirePositive("ellipsoid", "radii", shape.ellipsoid().radii);
    case ShapeType::Cylinder:
      return requirePositive("cylinder", "radius", shape.cylinder().radius) &&
             requirePositive("cylinder", "half_height", shape.cylinder().halfHeight);
    case ShapeType::Kdop:
      if (shape.kdop().isEmpty()) COLLIDE_FAIL("kdop: empty (Kdop::fromPoints or fromSlabs failed)", false);
      return true;
    case ShapeType::ConvexHull:
      if (!std::get<std::shared_ptr<const ConvexHull>>(shape.data_))
        COLLIDE_FAIL("convex_hull: null hull", false);
      if (shape.convexHull().isEmpty())
        COLLIDE_FAIL("convex_hull: empty (ConvexHull::fromPoints failed)", false);
      return true;
    case ShapeType::Mesh:
      if (!std::get<std::shared_ptr<const TriangleMesh>>(shape.data_)) COLLIDE_FAIL("mesh: null mesh", false);
      if (shape.mesh().isEmpty()) COLLIDE_FAIL("mesh: empty (TriangleMesh::fromTriangles failed)", false);
      return true;
    case ShapeType::Compound:
      if (shape.compound().isEmpty()) COLLIDE_FAIL("compound: empty (Compound::fromChildren failed)", false);
      return true;
  }
  return true;
}

}  // namespace detail

// Each constructor checks its value; without exceptions a bad one is kept as it is, reported, and
// refused again by whatever uses the shape (detail::validateShape).
Shape::Shape(const Sphere& sphere) : data_(sphere) { detail::validateShape(*this); }
Shape::Shape(const Capsule& capsule) : data_(capsule) { detail::validateShape(*this); }

Shape::Shape(const Plane& plane) : data_(plane) {
  if (!detail::validateShape(*this)) return;
  // (normal, distance) is one 4-vector (lecture, slide 58): normalise both parts, so that the
  // surface normal·x = distance stays where the caller put it.
  const float length = glm::length(plane.normal);
  std::get<Plane>(data_).normal = plane.normal / length;
  std::get<Plane>(data_).distance = plane.distance / length;
}

Shape::Shape(const Box& box) : data_(box) { detail::validateShape(*this); }
Shape::Shape(const Ellipsoid& ellipsoid) : data_(ellipsoid) { detail::validateShape(*this); }
Shape::Shape(const Cylinder& cylinder) : data_(cylinder) { detail::validateShape(*this); }
Shape::Shape(Kdop kdop) : data_(share(std::move(kdop))) { detail::validateShape(*this); }
Shape::Shape(ConvexHull hull) : data_(share(std::move(hull))) { detail::validateShape(*this); }
Shape::Shape(TriangleMesh mesh) : data_(share(std::move(mesh))) { detail::validateShape(*this); }
Shape::Shape(Compound compound) : data_(share(std::move(compound))) { detail::validateShape(*this); }
Shape::Shape(std::shared_ptr<const ConvexHull> hull) : data_(std::move(hull)) {
  detail::validateShape(*this);
}
Shape::Shape(std::shared_ptr<const TriangleMesh> mesh) : data_(std::move(mesh)) {
  detail::validateShape(*this);
}

bool Shape::isConvex() const {
  switch (type()) {
    case ShapeType::Plane:
    case ShapeType::Mesh:
    case ShapeType::Compound:
      return false;
    default:
      return true;
  }
}

// ---- World-frame queries ----

namespace {

bool requireValid(const Transform& transform, const char* query) {
  if (!isValid(transform)) {
    COLLIDE_FAIL(std::string(query) +
                     ": transform must have a finite position, a unit rotation and a "
                     "finite scale > 0, got position " +
                     formatValue(transform.position) + ", rotation (w " + formatValue(transform.rotation.w) +
                     ", " +
                     formatValue(Vec3(transform.rotation.x, transform.rotation.y, transform.rotation.z)) +
                     "), scale " + formatValue(transform.scale),
                 false);
  }
  return true;
}

bool requireFinite(const Vec3& value, const char* query, const char* field = "point") {
  if (!isFinite(value)) {
    COLLIDE_FAIL(std::string(query) + ": " + field + " must be finite, got " + formatValue(value), false);
  }
  return true;
}

}  // namespace

Aabb localBounds(const Shape& shape) {
  if (!detail::usableShape(shape)) return {};
  return shape.visit([](const auto& s) { return detail::computeLocalBounds(s); });
}

Aabb worldBounds(const Shape& shape, const Transform& transform) {
  if (!detail::usableShape(shape) || !requireValid(transform, "worldBounds")) return {};
  const detail::ErrorScope scope;  // a compound's children: one message, and no box short of one
  const Aabb box = shape.visit([&](const auto& s) { return detail::computeWorldBounds(s, transform); });
  COLLIDE_RETURN_IF_FAILED({});
  return box;
}

namespace detail {

namespace {
const ConvexHull* polyhedronOf(const Shape& shape) {
  if (shape.type() == ShapeType::ConvexHull) return &shape.convexHull();
  if (shape.type() == ShapeType::Kdop) return &shape.kdop().polytope();
  return nullptr;
}
}  // namespace

void prefetchShapeHeader(const Shape& shape) {
  if (const ConvexHull* hull = polyhedronOf(shape)) prefetchBytes(hull, sizeof(ConvexHull));
}

void prefetchShapeArrays(const Shape& shape) {
  if (const ConvexHull* hull = polyhedronOf(shape)) {
    prefetchBytes(hull->vertices().data(), hull->vertices().size_bytes());
    prefetchBytes(hull->faces().data(), hull->faces().size_bytes());
    prefetchBytes(hull->vertexFaceTable().data(), hull->vertexFaceTable().size_bytes());
    prefetchBytes(hull->edges().data(), hull->edges().size_bytes());
  }
}

}  // namespace detail

BoundingSphere localBoundingSphere(const Shape& shape) {
  if (!detail::usableShape(shape)) return {};
  switch (shape.type()) {
    case ShapeType::Sphere:
      return {Vec3(0.0f), shape.sphere().radius};
    case ShapeType::Capsule:
      return {Vec3(0.0f), shape.capsule().radius + shape.capsule().halfHeight};
    case ShapeType::Plane:
      return {Vec3(0.0f), 1e30f};
    case ShapeType::Box:
      return {Vec3(0.0f), glm::length(shape.box().halfExtents)};
    case ShapeType::Ellipsoid: {
      const Vec3 r = shape.ellipsoid().radii;
      return {Vec3(0.0f), std::max({r.x, r.y, r.z})};
    }
    case ShapeType::Cylinder: {
      const Cylinder& c = shape.cylinder();
      return {Vec3(0.0f), std::sqrt(c.radius * c.radius + c.halfHeight * c.halfHeight)};
    }
    case ShapeType::ConvexHull: {
      // Centred on the box: cheap, and within sqrt(3) of the minimal sphere (bounding.h has that).
      const ConvexHull& hull = shape.convexHull();
      const Vec3 center = hull.bounds().center();
      float radiusSquared = 0.0f;
      for (const Vec3& v : hull.vertices())
        radiusSquared = std::max(radiusSquared, glm::dot(v - center, v - center));
      return {center, std::sqrt(radiusSquared)};
    }
    case ShapeType::Kdop: {
      const ConvexHull& hull = shape.kdop().polytope();
      const Vec3 center = hull.bounds().center();
      float radiusSquared = 0.0f;
      for (const Vec3& v : hull.vertices())
        radiusSquared = std::max(radiusSquared, glm::dot(v - center, v - center));
      return {center, std::sqrt(radiusSquared)};
    }
    case ShapeType::Mesh: {
      const TriangleMesh& mesh = shape.mesh();
      const Vec3 center = mesh.bounds().center();
      float radiusSquared = 0.0f;
      for (const Vec3& v : mesh.vertices())
        radiusSquared = std::max(radiusSquared, glm::dot(v - center, v - center));
      return {center, std::sqrt(radiusSquared)};
    }
    case ShapeType::Compound: {
      const Aabb box = shape.compound().bounds();
      const Vec3 center = box.center();
      float radius = 0.0f;
      for (const Compound::Child& child : shape.compound().children()) {
        const BoundingSphere s = localBoundingSphere(child.shape);
        const Vec3 childCenter = child.transform.applyToPoint(s.center);
        radius = std::max(radius, glm::length(childCenter - center) + s.radius * child.transform.scale);
      }
      return {center, radius};
    }
  }
  return {};
}

Vec3 support(const Shape& shape, const Vec3& direction) {
  if (!detail::usableShape(shape)) return Vec3(0.0f);
  if (!shape.isConvex()) {
    COLLIDE_FAIL(
        "support: a " + std::string(toString(shape.type())) + " is not convex and has no support function",
        Vec3(0.0f));
  }
  if (!requireFinite(direction, "support", "direction")) return Vec3(0.0f);
  // Only the direction matters. Dividing by the largest component keeps tiny (or huge) directions
  // from underflowing (overflowing) when a proxy normalises them; a zero one has no direction.
  const float largest = std::max({std::abs(direction.x), std::abs(direction.y), std::abs(direction.z)});
  if (largest == 0.0f)
    COLLIDE_FAIL("support: direction must be non-zero, got " + formatValue(direction), Vec3(0.0f));
  const Vec3 unitish = direction / largest;
  return shape.visit([&](const auto& s) -> Vec3 {
    using T = std::decay_t<decltype(s)>;
    if constexpr (std::is_same_v<T, Plane> || std::is_same_v<T, TriangleMesh> ||
                  std::is_same_v<T, Compound>) {
      return Vec3(0.0f);  // unreachable: rejected above
    } else {
      return detail::computeSupport(s, unitish);
    }
  });
}

MassProperties massProperties(const Shape& shape, float density, float scale) {
  const detail::ErrorScope scope;  // a compound's children fail inside it: one message, no partial sum
  if (!detail::usableShape(shape)) return {};
  if (!isFinite(density) || density <= 0.0f) {
    COLLIDE_FAIL("mass properties: density must be finite and > 0, got " + formatValue(density), {});
  }
  if (!isFinite(scale) || scale <= 0.0f) {
    COLLIDE_FAIL("mass properties: scale must be finite and > 0, got " + formatValue(scale), {});
  }
  if (shape.type() == ShapeType::Plane) {
    COLLIDE_FAIL("mass properties: a plane is an infinite half-space and has no mass; make it static", {});
  }
  if (shape.type() == ShapeType::Mesh && !shape.mesh().isClosed()) {
    COLLIDE_FAIL("mass properties: an open triangle mesh encloses no volume; close it or make it static", {});
  }
  MassProperties m = shape.visit([&](const auto& s) -> MassProperties {
    using T = std::decay_t<decltype(s)>;
    if constexpr (std::is_same_v<T, Plane>) {
      return {};  // unreachable: rejected above
    } else {
      return detail::computeMassProperties(s, density);
    }
  });
  COLLIDE_RETURN_IF_FAILED({});
  // Uniform scale s: volume and mass grow as s^3, lengths as s, inertia as mass * length^2 = s^5.
  const float s3 = scale * scale * scale;
  m.mass *= s3;
  m.volume *= s3;
  m.centerOfMass *= scale;
  m.inertia *= s3 * scale * scale;
  return m;
}

bool containsPoint(const Shape& shape, const Transform& transform, const Vec3& point) {
  if (!detail::usableShape(shape) || !requireValid(transform, "containsPoint") ||
      !requireFinite(point, "containsPoint"))
    return false;
  const Vec3 local = transform.inverseApplyToPoint(point);
  return shape.visit([&](const auto& s) { return detail::localContains(s, local); });
}

SurfacePoint closestPoint(const Shape& shape, const Transform& transform, const Vec3& point) {
  if (!detail::usableShape(shape) || !requireValid(transform, "closestPoint") ||
      !requireFinite(point, "closestPoint"))
    return {};
  const Vec3 local = transform.inverseApplyToPoint(point);
  SurfacePoint result = shape.visit([&](const auto& s) { return detail::localClosestPoint(s, local); });
  result.point = transform.applyToPoint(result.point);
  result.normal = transform.applyToDirection(result.normal);
  result.signedDistance *= transform.scale;
  return result;
}

std::optional<RayHit> rayCast(const Shape& shape, const Transform& transform, const Ray& ray) {
  if (!detail::usableShape(shape) || !requireValid(transform, "rayCast")) return std::nullopt;
  if (!isFinite(ray.origin) || !isFinite(ray.direction) || std::isnan(ray.maxDistance) ||
      ray.maxDistance < 0.0f) {
    COLLIDE_FAIL("rayCast: ray must have a finite origin and direction and maxDistance >= 0, got origin " +
                     formatValue(ray.origin) + ", direction " + formatValue(ray.direction) +
                     ", maxDistance " + formatValue(ray.maxDistance),
                 std::nullopt);
  }
  if (std::abs(glm::dot(ray.direction, ray.direction) - 1.0f) > 1e-3f) {
    COLLIDE_FAIL("rayCast: ray direction must be unit length, got " + formatValue(ray.direction),
                 std::nullopt);
  }
  Ray local;
  local.origin = transform.inverseApplyToPoint(ray.origin);
  local.direction = transform.inverseApplyToDirection(ray.direction);
  local.maxDistance = ray.maxDistance / transform.scale;
  if (!isFinite(local.origin)) {
    // The ray's origin is beyond float's range in the shape's frame (a shape placed near 3e38 m, a
    // ray near the origin). A bounded shape is then farther than any distance float can hold; a
    // plane, unbounded, is cast in the world frame instead, where its offset may still be finite.
    if (shape.type() != ShapeType::Plane) return std::nullopt;
    const Plane& plane = shape.plane();
    const Vec3 normal = transform.applyToDirection(plane.normal);
    const Plane world{normal, glm::dot(normal, transform.position) + transform.scale * plane.distance};
    if (!std::isfinite(world.distance)) return std::nullopt;
    std::optional<RayHit> hit = detail::localRayCast(world, ray);
    if (hit && !std::isfinite(hit->distance)) return std::nullopt;
    return hit;
  }
  std::optional<RayHit> hit = shape.visit([&](const auto& s) { return detail::localRayCast(s, local); });
  if (hit && !std::isfinite(hit->distance)) return std::nullopt;  // no distance float can hold
  if (hit) {
    hit->distance *= transform.scale;
    hit->point = ray.origin + hit->distance * ray.direction;
    hit->normal = transform.applyToDirection(hit->normal);
  }
  return hit;
}

}  // namespace collide
