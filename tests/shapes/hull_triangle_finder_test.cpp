// Hulls from a host's triangle finder (collide/hooks.h, setHullTriangleFinder), the way a build
// without Qhull makes them: given Qhull's own hulls cut into triangles, in mixed orientations, the
// merge recovers Qhull's faces (a cube's six quads, a k-DOP's polygons), and a finder that returns
// too little or nonsense is refused by name.
#include <collide/hooks.h>
#include <collide/shapes.h>

#include "support/collide_error.h"
#include "support/hull_invariants.h"
#include "support/simple_geometry.h"
#include "support/test_random.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

namespace collide {
namespace {

using ::testing::HasSubstr;
using testing_support::isValidHalfEdgeHull;

// A finder that answers with triangles computed beforehand.
struct CannedTriangles {
  std::vector<std::uint32_t> indices;
  bool found = true;
  std::size_t askedFor = 0;
};

bool cannedFinder(const float*, std::size_t count, std::vector<std::uint32_t>& triangles, void* context) {
  auto* canned = static_cast<CannedTriangles*>(context);
  canned->askedFor = count;
  triangles = canned->indices;
  return canned->found;
}

// Installs the finder for one scope.
struct FinderInstalled {
  explicit FinderInstalled(CannedTriangles& canned) { setHullTriangleFinder(&cannedFinder, &canned); }
  ~FinderInstalled() { setHullTriangleFinder(nullptr); }
};

// Qhull's hull of `points` cut into triangles (each face fanned from its first vertex), as indices
// into `points`; every other triangle turned the other way round.
std::vector<std::uint32_t> qhullTriangles(const std::vector<Vec3>& points) {
  const ConvexHull hull = ConvexHull::fromPoints(points);
  const auto inputIndex = [&](std::uint32_t vertex) {
    const auto it = std::find(points.begin(), points.end(), hull.vertices()[vertex]);
    return static_cast<std::uint32_t>(it - points.begin());
  };
  std::vector<std::uint32_t> out;
  bool flip = false;
  for (const ConvexHull::Face& face : hull.faces()) {
    std::vector<std::uint32_t> loop;
    std::uint32_t edge = face.firstEdge;
    for (std::uint32_t i = 0; i < face.edgeCount; ++i) {
      loop.push_back(inputIndex(hull.halfEdges()[edge].origin));
      edge = hull.halfEdges()[edge].next;
    }
    for (std::size_t i = 1; i + 1 < loop.size(); ++i) {
      out.insert(out.end(), {loop[0], flip ? loop[i + 1] : loop[i], flip ? loop[i] : loop[i + 1]});
      flip = !flip;
    }
  }
  return out;
}

std::vector<std::uint32_t> faceSizes(const ConvexHull& hull) {
  std::vector<std::uint32_t> sizes;
  for (const ConvexHull::Face& face : hull.faces()) sizes.push_back(face.edgeCount);
  std::sort(sizes.begin(), sizes.end());
  return sizes;
}

void expectSameHull(const std::vector<Vec3>& points) {
  const ConvexHull reference = ConvexHull::fromPoints(points);
  CannedTriangles canned{qhullTriangles(points)};
  FinderInstalled installed(canned);
  const ConvexHull merged = ConvexHull::fromPoints(points);
  EXPECT_EQ(canned.askedFor, points.size());
  EXPECT_TRUE(isValidHalfEdgeHull(merged, 1e-4f));
  EXPECT_EQ(merged.vertices().size(), reference.vertices().size());
  EXPECT_EQ(merged.edgeCount(), reference.edgeCount());
  EXPECT_EQ(faceSizes(merged), faceSizes(reference));
  EXPECT_NEAR(merged.volume(), reference.volume(), 1e-5f * reference.volume());
  EXPECT_LT(glm::length(merged.centroid() - reference.centroid()), 1e-5f);
}

TEST(HullTriangleFinder, ACubesTrianglesMergeIntoSixQuads) {
  const std::vector<Vec3> corners = test::boxCorners(Vec3(1.0f, 0.5f, 2.0f));
  expectSameHull(corners);
  CannedTriangles canned{qhullTriangles(corners)};
  ASSERT_EQ(canned.indices.size(), 36u);  // 12 triangles in
  FinderInstalled installed(canned);
  EXPECT_EQ(ConvexHull::fromPoints(corners).faces().size(), 6u);
}

TEST(HullTriangleFinder, KdopAndRandomHullsMatchQhulls) {
  std::mt19937 rng(11);
  expectSameHull(test::randomPointsOnSphere(64, 2.0f, rng));
  std::vector<Vec3> kdopCorners;
  const Kdop kdop = Kdop::fromPoints(26, test::randomPointsOnSphere(200, 1.0f, rng));
  for (const Vec3& v : kdop.polytope().vertices()) kdopCorners.push_back(v);
  expectSameHull(kdopCorners);
}

TEST(HullTriangleFinder, BadTrianglesAreRefusedByName) {
  const std::vector<Vec3> corners = test::boxCorners(Vec3(1.0f));
  CannedTriangles canned{qhullTriangles(corners)};
  FinderInstalled installed(canned);
  const auto refused = [&](const char* what) {
    EXPECT_THAT([&] { (void)ConvexHull::fromPoints(corners); },
                ::collide::test::ReportsError(HasSubstr(what)))
        << what;
  };
  const std::vector<std::uint32_t> good = canned.indices;
  canned.indices.resize(good.size() - 3);  // one triangle missing: a hole
  refused("open surface");
  canned.indices = good;
  canned.indices[4] = 8;
  refused("the index 8 for 8 points");
  canned.indices = good;
  canned.indices.insert(canned.indices.end(), good.begin(), good.begin() + 3);  // a triangle twice
  refused("more than two triangles");
  canned.indices = good;
  canned.indices[2] = canned.indices[1];
  refused("zero area");
  canned.indices = good;
  canned.found = false;
  refused("found no hull");
}

TEST(HullTriangleFinder, WithoutAFinderQhullBuildsAgain) {
  EXPECT_TRUE(canBuildHulls());
  {
    CannedTriangles canned{{0, 1, 2}};
    FinderInstalled installed(canned);
    EXPECT_COLLIDE_ERROR((void)ConvexHull::fromPoints(test::boxCorners(Vec3(1.0f))));
  }
  EXPECT_EQ(ConvexHull::fromPoints(test::boxCorners(Vec3(1.0f))).faces().size(), 6u);
}

}  // namespace
}  // namespace collide
