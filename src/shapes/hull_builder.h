// Building convex hulls: input validation, Qhull for the facets, and our own half-edge topology and
// mass properties on top. The queries on a finished hull live in shapes/convex_hull.cpp.
#pragma once

#include <collide/shapes.h>

#include <span>
#include <string_view>

namespace collide {

// Throws Error, prefixed with `who` ("convex_hull", "kdop"), unless `points` holds at least 4 finite
// points that span a volume: not all identical, collinear or coplanar within 1e-6 of the set's size.
// Returns that size (the distance between two far-apart points, within a factor 2 of the diameter).
double requireSolidPointSet(std::string_view who, std::span<const Vec3> points);

class HullBuilder {
 public:
  // Relative flatness below which a point set has no volume (the distance to the best line or plane
  // found, divided by the set's diameter). Float coordinates carry ~1.2e-7 relative error, so a few
  // ulps above that.
  static constexpr double kFlatness = 1e-6;

  // The convex hull of the points: faces are the merged (coplanar) Qhull facets, counter-clockwise
  // from outside, with twin half-edges. Validates with requireSolidPointSet("convex_hull", points).
  static ConvexHull build(std::span<const Vec3> points);

  // A hull from the vertices, faces and half-edges another hull had (a world snapshot): the
  // topology checked (every index in range, twins that join the same vertices, each face a closed
  // loop of its own half-edges, every vertex under every face's plane), then everything else
  // derived as build derives it, so the hull is the one that was saved. Throws Error naming the
  // first fault.
  static ConvexHull restore(std::span<const Vec3> vertices, std::span<const ConvexHull::Face> faces,
                            std::span<const ConvexHull::HalfEdge> halfEdges);

 private:
  static void finish(ConvexHull& hull);
};

}  // namespace collide
