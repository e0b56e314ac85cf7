// The minimum-area rectangle around a planar point set (for oriented box fitting).
#pragma once

#include <collide/hooks.h>
#include <glm/glm.hpp>

#include <span>
#include <vector>

namespace collide::bounding {

// The convex hull of 2D points, counter-clockwise, without collinear vertices (Andrew's monotone
// chain, 1979). Fewer than 3 vertices when the points are collinear or identical.
Array<glm::dvec2> convexHull2d(Array<glm::dvec2> points);

struct Rectangle2d {
  glm::dvec2 axis{1.0, 0.0};  // unit direction of one side; the other side is its left perpendicular
  glm::dvec2 min{0.0};        // extents along (axis, perpendicular)
  glm::dvec2 max{0.0};
  double area() const { return (max.x - min.x) * (max.y - min.y); }
};

// The smallest-area enclosing rectangle of a convex polygon (counter-clockwise, as convexHull2d
// returns it). Freeman & Shapira 1975: the optimum has a side collinear with a polygon edge, so
// trying each edge suffices; rotating calipers (Toussaint 1983) find each edge's three other
// extremes in amortised constant time. A polygon with fewer than 3 vertices gets the rectangle of
// its segment (zero width).
Rectangle2d minimumAreaRectangle(std::span<const glm::dvec2> hull);

}  // namespace collide::bounding
