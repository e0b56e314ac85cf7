// The axis-aligned bounding box of a point set: one pass of min and max, the cheapest proxy to fit
// (lecture, slide 52), and the only one whose fit is trivially exact.
#include <collide/bounding.h>

#include "bounding/point_set.h"

namespace collide {

Aabb boundingBox(std::span<const Vec3> points) {
  if (!bounding::requireFinitePoints("bounding_box", points)) return {};
  Aabb box = Aabb::empty();
  for (const Vec3& p : points) box.grow(p);
  return box;
}

}  // namespace collide
