// Minimum-area enclosing rectangle by rotating calipers (Freeman & Shapira, "Determining the
// minimum-area encasing rectangle for an arbitrary closed curve", CACM 1975; Toussaint, "Solving
// geometric problems with the rotating calipers", MELECON 1983).
#include "bounding/min_area_rectangle.h"

#include <algorithm>
#include <cmath>

namespace collide::bounding {

namespace {

double cross(const glm::dvec2& o, const glm::dvec2& a, const glm::dvec2& b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

}  // namespace

Array<glm::dvec2> convexHull2d(Array<glm::dvec2> points) {
  std::sort(points.begin(), points.end(),
            [](const glm::dvec2& a, const glm::dvec2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 3) return points;
  Array<glm::dvec2> hull(2 * points.size());
  std::size_t k = 0;
  // Lower chain left to right, then upper chain right to left; a non-left turn pops (collinear
  // points are dropped, so every hull vertex is a strict corner).
  for (const glm::dvec2& p : points) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p) <= 0.0) --k;
    hull[k++] = p;
  }
  const std::size_t lowerSize = k + 1;
  for (std::size_t i = points.size() - 1; i-- > 0;) {
    while (k >= lowerSize && cross(hull[k - 2], hull[k - 1], points[i]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);  // the last point repeats the first
  return hull;
}

Rectangle2d minimumAreaRectangle(std::span<const glm::dvec2> hull) {
  Rectangle2d best;
  const std::size_t n = hull.size();
  if (n == 0) return best;
  if (n < 3) {
    const glm::dvec2 d = hull[n - 1] - hull[0];
    const double length = glm::length(d);
    if (length > 0.0) best.axis = d / length;
    const glm::dvec2 perpendicular(-best.axis.y, best.axis.x);
    best.min = best.max = glm::dvec2(glm::dot(best.axis, hull[0]), glm::dot(perpendicular, hull[0]));
    best.max.x = glm::dot(best.axis, hull[n - 1]);
    return best;
  }
  double bestArea = INFINITY;
  // The three calipers: farthest along the edge (right), farthest from it (top) and farthest against
  // it (left). Around a convex polygon each moves forward only, so the whole sweep is O(n).
  std::size_t right = 1, top = 1, left = 1;
  auto next = [n](std::size_t i) { return i + 1 == n ? 0 : i + 1; };
  for (std::size_t i = 0; i < n; ++i) {
    const glm::dvec2 edge = hull[next(i)] - hull[i];
    const glm::dvec2 axis = edge / glm::length(edge);
    const glm::dvec2 perpendicular(-axis.y, axis.x);  // inward: the polygon is to the left of its edges
    if (i == 0) right = next(i);
    // Each caliper stops at its maximum; the step bound keeps a rounding plateau from looping.
    for (std::size_t steps = 0; steps < n && glm::dot(axis, hull[next(right)]) > glm::dot(axis, hull[right]);
         ++steps)
      right = next(right);
    if (i == 0) top = right;
    for (std::size_t steps = 0;
         steps < n && glm::dot(perpendicular, hull[next(top)]) > glm::dot(perpendicular, hull[top]); ++steps)
      top = next(top);
    if (i == 0) left = top;
    for (std::size_t steps = 0; steps < n && glm::dot(axis, hull[next(left)]) < glm::dot(axis, hull[left]);
         ++steps)
      left = next(left);
    Rectangle2d candidate;
    candidate.axis = axis;
    candidate.min = {glm::dot(axis, hull[left]), glm::dot(perpendicular, hull[i])};
    candidate.max = {glm::dot(axis, hull[right]), glm::dot(perpendicular, hull[top])};
    if (candidate.area() < bestArea) {
      bestArea = candidate.area();
      best = candidate;
    }
  }
  return best;
}

}  // namespace collide::bounding
