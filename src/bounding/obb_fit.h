// The oriented-box fit for a caller that already has the points' convex hull (fitAllProxies builds it
// once for every proxy).
#pragma once

#include <collide/bounding.h>

namespace collide::bounding {

OrientedBox fitOrientedBoxOnHull(std::span<const Vec3> points, const ConvexHull& hull);

}  // namespace collide::bounding
