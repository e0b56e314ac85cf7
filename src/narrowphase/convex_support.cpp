// Cores and radii of the convex proxies (see convex_support.h).
#include "narrowphase/convex_support.h"
#include "base/fail.h"

namespace collide::detail {

namespace {
void place(ConvexSupport& support, const Transform& transform) {
  support.position = transform.position;
  support.rotation = glm::mat3_cast(transform.rotation);
  support.scale = transform.scale;
}
}  // namespace

ConvexSupport makeConvexSupport(const Shape& shape, const Transform& transform) {
  ConvexSupport support;
  place(support, transform);
  using Kind = ConvexSupport::Kind;
  switch (shape.type()) {
    case ShapeType::Sphere:
      support.kind = Kind::Point;
      support.radius = shape.sphere().radius * transform.scale;
      break;
    case ShapeType::Capsule:
      support.kind = Kind::Segment;
      support.extent = Vec3(0.0f, shape.capsule().halfHeight, 0.0f);
      support.radius = shape.capsule().radius * transform.scale;
      break;
    case ShapeType::Box:
      support.kind = Kind::Box;
      support.extent = shape.box().halfExtents;
      break;
    case ShapeType::Ellipsoid:
      support.kind = Kind::Ellipsoid;
      support.extent = shape.ellipsoid().radii;
      break;
    case ShapeType::Cylinder:
      support.kind = Kind::Cylinder;
      support.extent = Vec3(shape.cylinder().radius, shape.cylinder().halfHeight, 0.0f);
      break;
    case ShapeType::Kdop:
      support.kind = Kind::Hull;
      support.hull = &shape.kdop().polytope();
      break;
    case ShapeType::ConvexHull:
      support.kind = Kind::Hull;
      support.hull = &shape.convexHull();
      break;
    case ShapeType::Plane:
    case ShapeType::Mesh:
    case ShapeType::Compound:
      COLLIDE_FAIL("narrow phase: a " + std::string(toString(shape.type())) + " has no support function",
                   support);
  }
  return support;
}

ConvexSupport makePointsSupport(const Vec3* localPoints, std::uint32_t count, const Transform& transform) {
  ConvexSupport support;
  place(support, transform);
  support.kind = ConvexSupport::Kind::Points;
  support.points = localPoints;
  support.pointCount = count;
  return support;
}

}  // namespace collide::detail
