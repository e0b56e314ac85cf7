// Input checks shared by the bounding-volume fitters: the API boundary, so a clear Error, not a
// crash or a NaN proxy.
#include "bounding/point_set.h"

#include "base/fail.h"

#include <sstream>

namespace collide::bounding {

std::string formatPoint(const Vec3& p) {
  std::ostringstream out;
  out << '[' << p.x << ", " << p.y << ", " << p.z << ']';
  return out.str();
}

bool requireFinitePoints(std::string_view who, std::span<const Vec3> points) {
  if (points.empty())
    COLLIDE_FAIL(std::string(who) + ": the point set is empty, need at least one point", false);
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!isFinite(points[i])) {
      COLLIDE_FAIL(
          std::string(who) + ": point " + std::to_string(i) + " is not finite, got " + formatPoint(points[i]),
          false);
    }
  }
  return true;
}

}  // namespace collide::bounding
