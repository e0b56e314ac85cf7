// Wireframes of the proxies for debug drawing (collide/debug_draw.h): each shape drawn from what it
// is (a box's edges, a hull's edges, a sphere's principal circles), in world space.
#include <collide/debug_draw.h>
#include <collide/error.h>
#include "base/fail.h"
#include "shapes/shape_functions.h"

#include <array>
#include <cmath>
#include <numbers>

namespace collide {

void DebugDraw::drawPoint(const Vec3& point, float size, const DebugColor& color) {
  const float half = 0.5f * size;
  for (int axis = 0; axis < 3; ++axis) {
    Vec3 d(0.0f);
    d[axis] = half;
    drawLine(point - d, point + d, color);
  }
}

namespace {

// The twelve edges of a box whose corner i (bit 0: x, bit 1: y, bit 2: z at its high side) is
// corner(i): each corner to the corners one bit away, each edge once.
template <typename Corner>
void drawBoxEdges(DebugDraw& draw, Corner&& corner, const DebugColor& color) {
  for (int i = 0; i < 8; ++i) {
    for (int bit = 1; bit < 8; bit <<= 1) {
      if ((i & bit) == 0) draw.drawLine(corner(i), corner(i | bit), color);
    }
  }
}

}  // namespace

void drawBox(DebugDraw& draw, const Aabb& box, const DebugColor& color) {
  drawBoxEdges(
      draw,
      [&](int i) {
        return Vec3(i & 1 ? box.max.x : box.min.x, i & 2 ? box.max.y : box.min.y,
                    i & 4 ? box.max.z : box.min.z);
      },
      color);
}

namespace {

// The curve local(t), t in [0, 1], in `segments` lines.
template <typename Curve>
void drawCurve(DebugDraw& draw, const Transform& t, const DebugColor& color, int segments, float turns,
               Curve&& local) {
  Vec3 previous = t.applyToPoint(local(0.0f));
  for (int k = 1; k <= segments; ++k) {
    const float angle = turns * 2.0f * std::numbers::pi_v<float> * float(k) / float(segments);
    const Vec3 next = t.applyToPoint(local(angle));
    draw.drawLine(previous, next, color);
    previous = next;
  }
}

// An ellipse about `center` with semi-axes along u and v (local frame).
void drawEllipse(DebugDraw& draw, const Transform& t, const DebugColor& color, int segments,
                 const Vec3& center, const Vec3& u, const Vec3& v, float turns = 1.0f) {
  drawCurve(draw, t, color, segments, turns,
            [&](float angle) { return center + std::cos(angle) * u + std::sin(angle) * v; });
}

void drawPolytope(DebugDraw& draw, const ConvexHull& hull, const Transform& t, const DebugColor& color) {
  const auto vertices = hull.vertices();
  for (const ConvexHull::Edge& edge : hull.edges())
    draw.drawLine(t.applyToPoint(vertices[edge.origin]), t.applyToPoint(vertices[edge.end]), color);
}

// The ends of a capsule's or cylinder's axis (local y) with circles there and four lines between.
void drawRound(DebugDraw& draw, const Transform& t, const DebugColor& color, int segments, float radius,
               float halfHeight) {
  const Vec3 x(radius, 0.0f, 0.0f), z(0.0f, 0.0f, radius), up(0.0f, halfHeight, 0.0f);
  drawEllipse(draw, t, color, segments, up, x, z);
  drawEllipse(draw, t, color, segments, -up, x, z);
  for (const Vec3& side : {x, -x, z, -z})
    draw.drawLine(t.applyToPoint(side - up), t.applyToPoint(side + up), color);
}

void drawPlane(DebugDraw& draw, const Plane& plane, const Transform& t, const DebugColor& color, float size) {
  const Vec3 normal = t.applyToDirection(plane.normal);
  const Vec3 center = t.applyToPoint(plane.normal * plane.distance);
  // A tangent basis: any unit vector across the normal, then the one across both.
  const Vec3 helper = std::abs(normal.x) < 0.9f ? Vec3(1.0f, 0.0f, 0.0f) : Vec3(0.0f, 1.0f, 0.0f);
  const Vec3 u = 0.5f * size * glm::normalize(glm::cross(normal, helper));
  const Vec3 v = glm::cross(normal, u);
  const std::array<Vec3, 4> corners{center - u - v, center + u - v, center + u + v, center - u + v};
  for (int i = 0; i < 4; ++i) draw.drawLine(corners[i], corners[(i + 1) % 4], color);
  draw.drawLine(corners[0], corners[2], color);
  draw.drawLine(corners[1], corners[3], color);
  draw.drawLine(center, center + 0.1f * size * normal, color);
}

}  // namespace

void drawShape(DebugDraw& draw, const Shape& shape, const Transform& t, const DebugColor& color,
               float planeSize, int segments) {
  if (segments < 3) COLLIDE_FAIL("drawShape: segments must be >= 3, got " + std::to_string(segments));
  if (!detail::usableShape(shape)) return;
  const Vec3 ex(1.0f, 0.0f, 0.0f), ey(0.0f, 1.0f, 0.0f), ez(0.0f, 0.0f, 1.0f);
  switch (shape.type()) {
    case ShapeType::Sphere: {
      const float r = shape.sphere().radius;
      drawEllipse(draw, t, color, segments, Vec3(0.0f), r * ex, r * ey);
      drawEllipse(draw, t, color, segments, Vec3(0.0f), r * ey, r * ez);
      drawEllipse(draw, t, color, segments, Vec3(0.0f), r * ez, r * ex);
      break;
    }
    case ShapeType::Ellipsoid: {
      const Vec3 r = shape.ellipsoid().radii;
      drawEllipse(draw, t, color, segments, Vec3(0.0f), r.x * ex, r.y * ey);
      drawEllipse(draw, t, color, segments, Vec3(0.0f), r.y * ey, r.z * ez);
      drawEllipse(draw, t, color, segments, Vec3(0.0f), r.z * ez, r.x * ex);
      break;
    }
    case ShapeType::Capsule: {
      const Capsule& c = shape.capsule();
      drawRound(draw, t, color, segments, c.radius, c.halfHeight);
      // The caps: half circles over each end in the xy and zy planes.
      const Vec3 up(0.0f, c.halfHeight, 0.0f);
      const int half = std::max(2, segments / 2);
      for (const Vec3& across : {c.radius * ex, c.radius * ez}) {
        drawEllipse(draw, t, color, half, up, across, c.radius * ey, 0.5f);
        drawEllipse(draw, t, color, half, -up, across, -c.radius * ey, 0.5f);
      }
      break;
    }
    case ShapeType::Cylinder:
      drawRound(draw, t, color, segments, shape.cylinder().radius, shape.cylinder().halfHeight);
      break;
    case ShapeType::Box: {
      const Vec3 h = shape.box().halfExtents;
      drawBoxEdges(
          draw,
          [&](int i) {
            return t.applyToPoint(Vec3(i & 1 ? h.x : -h.x, i & 2 ? h.y : -h.y, i & 4 ? h.z : -h.z));
          },
          color);
      break;
    }
    case ShapeType::ConvexHull:
      drawPolytope(draw, shape.convexHull(), t, color);
      break;
    case ShapeType::Kdop:
      drawPolytope(draw, shape.kdop().polytope(), t, color);
      break;
    case ShapeType::Mesh: {
      const TriangleMesh& mesh = shape.mesh();
      const auto vertices = mesh.vertices();
      for (const MeshTriangle& triangle : mesh.triangles()) {
        for (int k = 0; k < 3; ++k) {
          draw.drawLine(t.applyToPoint(vertices[triangle.v[k]]),
                        t.applyToPoint(vertices[triangle.v[(k + 1) % 3]]), color);
        }
      }
      break;
    }
    case ShapeType::Compound:
      for (const Compound::Child& child : shape.compound().children())
        drawShape(draw, child.shape, t * child.transform, color, planeSize, segments);
      break;
    case ShapeType::Plane:
      drawPlane(draw, shape.plane(), t, color, planeSize);
      break;
  }
}

}  // namespace collide
