// EPA, the expanding polytope algorithm: penetration depth and direction of two overlapping convex
// cores (van den Bergen, "Proximity Queries and Penetration Depth Computation on 3D Game Objects",
// GDC 2001). Starts from GJK's final simplex, which encloses the origin, and grows a polytope
// inside A - B towards its boundary face nearest to the origin.
#pragma once

#include "narrowphase/gjk.h"

namespace collide::detail {

struct EpaResult {
  float depth = 0.0f;             // between the cores, >= 0 up to rounding
  Vec3 normal{0.0f, 1.0f, 0.0f};  // unit, from A to B: moving B by depth * normal separates the cores
  Vec3 pointOnA{0.0f};            // A's core point deepest in B
  Vec3 pointOnB{0.0f};            // B's core point deepest in A
  int iterations = 0;
};

// The penetration of the cores of A and B (their radii are ignored). `simplex` is GJK's final
// simplex of an Overlapping result.
EpaResult epaPenetration(const ConvexSupport& a, const ConvexSupport& b, const Simplex& simplex);

}  // namespace collide::detail
