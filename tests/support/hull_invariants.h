// Structural checks of a half-edge convex hull, shared by the hull and k-DOP tests.
#pragma once

#include <collide/shapes.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace collide::testing_support {

// Euler's formula, twin and next consistency, planar counter-clockwise faces with outward unit
// planes, every vertex on or behind every plane (within `tolerance`), and merged coplanar faces.
inline ::testing::AssertionResult isValidHalfEdgeHull(const ConvexHull& hull, float tolerance) {
  const auto vertices = hull.vertices();
  const auto edges = hull.halfEdges();
  const auto faces = hull.faces();
  const long v = long(vertices.size()), e = long(hull.edgeCount()), f = long(faces.size());
  if (edges.size() % 2 != 0) return ::testing::AssertionFailure() << "odd half-edge count " << edges.size();
  if (v - e + f != 2)
    return ::testing::AssertionFailure() << "Euler: V - E + F = " << v << " - " << e << " + " << f;
  std::vector<int> vertexUse(vertices.size(), 0);
  for (std::uint32_t h = 0; h < edges.size(); ++h) {
    const ConvexHull::HalfEdge& edge = edges[h];
    if (edge.twin >= edges.size() || edge.next >= edges.size() || edge.origin >= vertices.size() ||
        edge.face >= faces.size()) {
      return ::testing::AssertionFailure() << "half-edge " << h << " has an index out of range";
    }
    const ConvexHull::HalfEdge& twin = edges[edge.twin];
    if (edge.twin == h || twin.twin != h) return ::testing::AssertionFailure() << "twin of twin of " << h;
    if (twin.origin != edges[edge.next].origin || edges[twin.next].origin != edge.origin) {
      return ::testing::AssertionFailure() << "twin of " << h << " does not swap the endpoints";
    }
    if (twin.face == edge.face) return ::testing::AssertionFailure() << "edge " << h << " has one face twice";
    // Merged faces: the neighbour across an edge has a vertex clearly behind this face's plane.
    float deepest = 0.0f;
    for (const Vec3& p : hull.faceVertices(twin.face)) {
      deepest = std::min(deepest, faces[edge.face].plane.signedDistance(p));
    }
    if (deepest > -tolerance) {
      return ::testing::AssertionFailure()
             << "faces " << edge.face << " and " << twin.face << " are coplanar";
    }
    ++vertexUse[edge.origin];
  }
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    if (vertexUse[i] < 3)
      return ::testing::AssertionFailure() << "vertex " << i << " starts " << vertexUse[i] << " edges";
  }
  // The faces around each vertex: those of the half-edges leaving it, in increasing order.
  for (std::uint32_t i = 0; i < vertices.size(); ++i) {
    std::vector<std::uint32_t> expected;
    for (const ConvexHull::HalfEdge& edge : edges)
      if (edge.origin == i) expected.push_back(edge.face);
    std::sort(expected.begin(), expected.end());
    const auto around = hull.facesAround(i);
    if (!std::equal(around.begin(), around.end(), expected.begin(), expected.end()))
      return ::testing::AssertionFailure() << "facesAround(" << i << ") is not the faces of its half-edges";
  }
  std::size_t edgeTotal = 0;
  for (std::uint32_t i = 0; i < faces.size(); ++i) {
    const ConvexHull::Face& face = faces[i];
    if (std::abs(glm::length(face.plane.normal) - 1.0f) > 1e-5f) {
      return ::testing::AssertionFailure() << "face " << i << " normal is not unit";
    }
    if (face.firstVertex != edges[face.firstEdge].origin)
      return ::testing::AssertionFailure()
             << "face " << i << " firstVertex is not its first half-edge's origin";
    std::uint32_t h = face.firstEdge;
    for (std::uint32_t k = 0; k < face.edgeCount; ++k) {
      if (edges[h].face != i)
        return ::testing::AssertionFailure() << "face " << i << " cycle leaves the face";
      if (k > 0 && h == face.firstEdge)
        return ::testing::AssertionFailure() << "face " << i << " cycle too short";
      h = edges[h].next;
    }
    if (h != face.firstEdge) return ::testing::AssertionFailure() << "face " << i << " cycle does not close";
    edgeTotal += face.edgeCount;
    const std::vector<Vec3> loop = hull.faceVertices(i);
    Vec3 newell(0.0f);
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const Vec3 a = loop[k] - loop[0], b = loop[(k + 1) % loop.size()] - loop[0];
      newell += glm::cross(a, b);
      if (std::abs(face.plane.signedDistance(loop[k])) > tolerance) {
        return ::testing::AssertionFailure()
               << "face " << i << " vertex off its plane by " << face.plane.signedDistance(loop[k]);
      }
    }
    if (glm::dot(newell, face.plane.normal) <= 0.0f) {
      return ::testing::AssertionFailure() << "face " << i << " is not counter-clockwise from outside";
    }
    for (const Vec3& p : vertices) {
      if (face.plane.signedDistance(p) > tolerance) {
        return ::testing::AssertionFailure()
               << "a vertex is " << face.plane.signedDistance(p) << " in front of face " << i;
      }
    }
  }
  if (edgeTotal != edges.size()) return ::testing::AssertionFailure() << "faces do not cover every half-edge";
  return ::testing::AssertionSuccess();
}

}  // namespace collide::testing_support
