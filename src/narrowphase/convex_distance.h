// Signed distance of two convex shapes with convex radii: GJK on the cores, the radii subtracted,
// and EPA when the cores themselves overlap. The generic answer for every convex pair.
#pragma once

#include <collide/narrowphase.h>

#include "narrowphase/convex_support.h"

namespace collide::detail {

// The signed distance of A and B (negative: penetration depth) with closest (or deepest) points
// and the normal from A to B. Returns false, leaving `out` unspecified, when the shapes are
// certainly farther apart than maxDistance.
bool convexSignedDistance(const ConvexSupport& a, const ConvexSupport& b, float maxDistance,
                          DistanceResult& out);

}  // namespace collide::detail
