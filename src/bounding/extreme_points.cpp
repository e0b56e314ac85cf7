// The extreme points of a set along fixed directions: a small stand-in for a large set's hull that
// the fitters search on (point_set.h).
#include "bounding/point_set.h"

#include <algorithm>
#include <cmath>

namespace collide::bounding {

Array<std::size_t> extremeIndices(std::span<const glm::dvec3> points, int directions) {
  Array<std::size_t> chosen;
  if (points.empty()) return chosen;
  const double golden = kPi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < directions; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / directions, r = std::sqrt(1.0 - z * z);
    const glm::dvec3 d(r * std::cos(golden * i), r * std::sin(golden * i), z);
    std::size_t low = 0, high = 0;
    double lowest = glm::dot(points[0], d), highest = lowest;
    for (std::size_t k = 1; k < points.size(); ++k) {
      const double h = glm::dot(points[k], d);
      if (h < lowest) lowest = h, low = k;
      if (h > highest) highest = h, high = k;
    }
    chosen.push_back(low);
    chosen.push_back(high);
  }
  std::sort(chosen.begin(), chosen.end());
  chosen.erase(std::unique(chosen.begin(), chosen.end()), chosen.end());
  return chosen;
}

Array<Vec3> extremePoints(std::span<const Vec3> points, int directions) {
  const Array<glm::dvec3> wide(points.begin(), points.end());
  Array<Vec3> out;
  for (const std::size_t k : extremeIndices(wide, directions)) out.push_back(points[k]);
  return out;
}

}  // namespace collide::bounding
