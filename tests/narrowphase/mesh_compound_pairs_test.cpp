// Mesh and compound cells with real TriangleMesh and Compound shapes (built by their factories):
// a flat grid of two-triangle quads under a sphere and a box, and a compound on a plane.
#include <collide/narrowphase.h>
#include <gtest/gtest.h>

#include <random>
#include <set>

#include "narrowphase/convex_distance.h"
#include "narrowphase/pair_functions.h"
#include "support/flat_grid.h"
#include "support/narrowphase_helpers.h"

using namespace collide;
using namespace collide::test;

TEST(MeshPairs, SphereRollingAcrossAFlatGridAlwaysPushesStraightUp) {
  // A sphere sunk 0.05 into the grid, moved in small steps across quad edges, diagonals and
  // vertices: the contact normal (mesh A to sphere B) is +y and the depth 0.05 everywhere.
  const Shape grid = test::flatGrid(6);
  const float radius = 0.5f, depth = 0.05f;
  Manifold m;
  int contacts = 0;
  for (int step = 0; step <= 400; ++step) {
    const float t = float(step) / 400.0f;
    const Vec3 centre(-2.0f + 4.0f * t, radius - depth, -1.3f + 2.0f * t);
    ASSERT_TRUE(collide::collide(grid, Transform::identity(), Sphere{radius}, at(centre), m))
        << "step " << step;
    ++contacts;
    EXPECT_LT(angleDegrees(m.normal, Vec3(0, 1, 0)), 1e-3f) << "step " << step;
    EXPECT_NEAR(m.maxDepth(), depth, 1e-4f) << "step " << step;
  }
  EXPECT_EQ(contacts, 401);
}

TEST(MeshPairs, BoxRestingOnAFlatGridGivesFourStableCorners) {
  // A box face-down on the grid, sunk 0.02, its corners inside four different quads: four
  // points, normal +y, each at a bottom corner of the box; the same ids under small wobbles.
  const Shape grid = test::flatGrid(6);
  const Vec3 h(0.7f, 0.3f, 0.6f);
  const float depth = 0.02f;
  const Vec3 centre(0.1f, h.y - depth, -0.15f);
  Manifold m;
  ASSERT_TRUE(collide::collide(grid, Transform::identity(), Box{h}, at(centre), m));
  ASSERT_EQ(m.count, 4);
  EXPECT_LT(angleDegrees(m.normal, Vec3(0, 1, 0)), 1e-3f);
  std::set<std::uint32_t> ids;
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(m.points[i].depth, depth, 1e-4f);
    EXPECT_NEAR(m.points[i].pointOnB.y, 0.0f - depth, 1e-4f);
    EXPECT_NEAR(std::abs(m.points[i].pointOnB.x - centre.x), h.x, 1e-4f);
    EXPECT_NEAR(std::abs(m.points[i].pointOnB.z - centre.z), h.z, 1e-4f);
    ids.insert(m.points[i].featureId);
  }
  ASSERT_EQ(ids.size(), 4u);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> small(-1.0f, 1.0f);
  for (int trial = 0; trial < 200; ++trial) {
    const Transform tb = at(centre + Vec3(0.02f * small(rng), 0.003f * small(rng), 0.02f * small(rng)),
                            axisAngle(randomUnit(rng), 0.3f * small(rng)));
    ASSERT_TRUE(collide::collide(grid, Transform::identity(), Box{h}, tb, m)) << "trial " << trial;
    ASSERT_EQ(m.count, 4) << "trial " << trial;
    EXPECT_LT(angleDegrees(m.normal, Vec3(0, 1, 0)), 1.0f) << "trial " << trial;
    std::set<std::uint32_t> now;
    for (int i = 0; i < 4; ++i) now.insert(m.points[i].featureId);
    EXPECT_EQ(now, ids) << "trial " << trial;
  }
}

TEST(MeshPairs, BoxSlidingAcrossAFlatGridAlwaysPushesStraightUp) {
  // A box turned 20° about y, sunk 0.03, moved in small steps across quad edges, diagonals and
  // vertices, and slightly tilted: the normal stays +y (internal edges give no side normal), the
  // deepest point is the lowest corner, and there are four points (the bottom corners).
  const Shape grid = test::flatGrid(6);
  const Vec3 h(0.4f, 0.25f, 0.3f);
  const float depth = 0.03f;
  std::mt19937 rng(12);
  std::uniform_real_distribution<float> small(-1.0f, 1.0f);
  Manifold m;
  for (int step = 0; step <= 400; ++step) {
    const float t = float(step) / 400.0f;
    const Quat rotation = axisAngle({0, 1, 0}, 20.0f) * axisAngle(randomUnit(rng), 0.2f * small(rng));
    const Transform tb = at(Vec3(-1.7f + 3.4f * t, h.y - depth, -1.1f + 2.0f * t), rotation);
    ASSERT_TRUE(collide::collide(grid, Transform::identity(), Box{h}, tb, m)) << "step " << step;
    EXPECT_LT(angleDegrees(m.normal, Vec3(0, 1, 0)), 1e-3f) << "step " << step;
    EXPECT_EQ(m.count, 4) << "step " << step;
    float lowest = 1e30f;
    for (int i = 0; i < 8; ++i) {
      const Vec3 corner = tb.applyToPoint(Vec3(i & 1 ? h.x : -h.x, i & 2 ? h.y : -h.y, i & 4 ? h.z : -h.z));
      lowest = std::min(lowest, corner.y);
    }
    EXPECT_NEAR(m.maxDepth(), -lowest, 1e-5f) << "step " << step;
  }
}

TEST(MeshPairs, InternalEdgeGivesTheFaceNormalWhereLooseTrianglesBump) {
  // A narrow box (half width 0.05, half height 0.2) straddling the quad edge x = 0, centred at x = 0.01, sunk
  // 0.08: deeper than it overlaps either triangle sideways (0.06 and 0.04), so for each triangle alone the
  // horizontal axis across the shared edge separates best, and the deepest of those contacts is a
  // side normal: a bump. The mesh knows the edge is flat: +y, depth 0.08.
  const Shape grid = test::flatGrid(6);
  const Vec3 h(0.05f, 0.2f, 0.05f);
  const Transform tb = at({0.01f, h.y - 0.08f, 0.5f});
  Manifold m;
  ASSERT_TRUE(collide::collide(grid, Transform::identity(), Box{h}, tb, m));
  EXPECT_LT(angleDegrees(m.normal, Vec3(0, 1, 0)), 1e-3f);
  EXPECT_NEAR(m.maxDepth(), 0.08f, 1e-5f);
  EXPECT_EQ(m.count, 4);
  // The two triangles under the box (z > x on the right, z < x + 1 on the left), loose: no
  // adjacency, every edge active. The box is pushed sideways out of the deeper overlap, along -x.
  const std::array<Vec3, 3> under[] = {{Vec3(0, 0, 0), Vec3(0, 0, 1), Vec3(1, 0, 1)},
                                       {Vec3(-1, 0, 0), Vec3(0, 0, 1), Vec3(0, 0, 0)}};
  Manifold loose;
  ASSERT_TRUE(detail::collideTrianglesConvex(under, Transform::identity(), Box{h}, tb, 0.0f, loose));
  EXPECT_LT(angleDegrees(loose.normal, Vec3(-1, 0, 0)), 1e-3f);
  EXPECT_NEAR(loose.maxDepth(), 0.06f, 1e-5f);
}

TEST(MeshPairs, TheMeshOutlineStillPushesSideways) {
  // The grid's outline edge x = 3 is active: a box beside the grid, its side 0.01 over the edge
  // and straddling the surface (0.25 above and below), is pushed out along +x by 0.01.
  const Shape grid = test::flatGrid(6);
  const Vec3 h(0.4f, 0.25f, 0.3f);
  Manifold m;
  ASSERT_TRUE(collide::collide(grid, Transform::identity(), Box{h}, at({3.0f + h.x - 0.01f, 0.0f, 0.2f}), m));
  EXPECT_LT(angleDegrees(m.normal, Vec3(1, 0, 0)), 1e-3f);
  EXPECT_NEAR(m.maxDepth(), 0.01f, 1e-5f);
}

TEST(MeshPairs, TriangleSatAgreesWithGjkEpaOnRandomPolyhedra) {
  // One loose triangle against a random box, or a random hull (12 points), in random poses: the
  // triangle SAT's verdict is GJK's (outside a 1e-4 band), and its depth lies between the minimum
  // penetration (EPA on the triangle as a three-point polytope) and that depth with the face
  // preference's allowance (2 % plus 1e-3 of the sizes), within 1e-4.
  std::mt19937 rng(31);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  int compared = 0, verdicts = 0, depthFailures = 0;
  std::string first;
  for (int i = 0; i < 1000; ++i) {
    const std::array<Vec3, 3> triangle = {Vec3(-1.0f, 0.0f, -0.6f), Vec3(0.3f, 0.0f, 1.0f),
                                          Vec3(0.9f, 0.1f, -0.7f)};
    Shape shape = randomPrimitive(ShapeType::Box, rng);
    if (i % 2 == 1) {
      std::vector<Vec3> points(12);
      for (Vec3& p : points) p = Vec3(0.2f + unit(rng), 0.2f + unit(rng), 0.2f + unit(rng)) * randomUnit(rng);
      shape = Shape(ConvexHull::fromPoints(points));
    }
    const Transform tb =
        at(Vec3(unit(rng) - 0.5f, 1.6f * (unit(rng) - 0.5f), unit(rng) - 0.5f), uniformRotation(rng));
    DistanceResult reference;
    const bool near =
        detail::convexSignedDistance(detail::makePointsSupport(triangle.data(), 3, Transform::identity()),
                                     detail::makeConvexSupport(shape, tb), 1.0f, reference);
    Manifold m;
    const bool hit =
        detail::collideTrianglesConvex(std::span(&triangle, 1), Transform::identity(), shape, tb, 0.0f, m);
    const bool overlapping = near && reference.distance < 0.0f;
    if (near && std::abs(reference.distance) < 1e-4f) continue;
    if (hit != overlapping) {
      ++verdicts;
      if (first.empty())
        first = "pair " + std::to_string(i) + ": verdict, distance " + std::to_string(reference.distance);
      continue;
    }
    if (!hit) continue;
    ++compared;
    const float depth = -reference.distance, size = 1e-3f * 2.0f;
    if (m.maxDepth() < depth - 1e-4f || m.maxDepth() > (depth + size) / 0.98f + 1e-4f) {
      ++depthFailures;
      if (first.empty())
        first = "pair " + std::to_string(i) + ": depth " + std::to_string(m.maxDepth()) + ", EPA " +
                std::to_string(depth);
    }
  }
  SCOPED_TRACE(first);
  EXPECT_EQ(verdicts, 0);
  EXPECT_EQ(depthFailures, 0);
  EXPECT_GT(compared, 200);
}

TEST(CompoundPairs, TwoSphereCompoundOnAPlaneGivesTwoPoints) {
  // A dumbbell of two spheres (radius 0.5 at x = ±1) lying on y = 0, sunk 0.1: one contact under
  // each sphere, normal from the compound (A) down into the plane (B).
  std::vector<Compound::Child> children;
  children.push_back({Shape(Sphere{0.5f}), at({-1.0f, 0.0f, 0.0f})});
  children.push_back({Shape(Sphere{0.5f}), at({1.0f, 0.0f, 0.0f})});
  const Shape dumbbell = Compound::fromChildren(std::move(children));
  Manifold m;
  ASSERT_TRUE(collide::collide(dumbbell, at({0.2f, 0.4f, 0.0f}), Plane{}, Transform::identity(), m));
  ASSERT_EQ(m.count, 2);
  EXPECT_NEAR(m.normal.y, -1.0f, 1e-6f);
  std::set<float> xs;
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(m.points[i].depth, 0.1f, 1e-5f);
    EXPECT_NEAR(m.points[i].pointOnA.y, -0.1f, 1e-5f);
    xs.insert(std::round(m.points[i].pointOnA.x * 100.0f) / 100.0f);
  }
  EXPECT_EQ(xs, (std::set<float>{-0.8f, 1.2f}));
  EXPECT_NE(m.points[0].featureId, m.points[1].featureId);
  // The other order: the plane is A, the normal up.
  ASSERT_TRUE(collide::collide(Plane{}, Transform::identity(), dumbbell, at({0.2f, 0.4f, 0.0f}), m));
  ASSERT_EQ(m.count, 2);
  EXPECT_NEAR(m.normal.y, 1.0f, 1e-6f);
}

TEST(CompoundPairs, ChildrenApartAlongTheirOwnNormalsStayApartInTheMerge) {
  // A sphere and a box on a turned compound, 5 cm above a box: both children's contacts are
  // speculative, at normals 24 degrees apart. The box child's speculative edge contact has its
  // closest points at an edge's end, 0.5 m apart sideways; measured along the sphere's normal that
  // pair reads as 8 cm deep. The merged manifold must keep it apart, as overlap() says the shapes
  // are (the narrow-phase fuzzer's finding, its decoded input).
  const Quat childTurn(1.0f, 1.52587891e-05f, 1.52587891e-05f, 1.52587891e-05f);
  std::vector<Compound::Child> children;
  children.push_back({Shape(Sphere{0.400013894f}),
                      Transform{Vec3(3.05175781e-05f, 0.499977112f, 3.05175781e-05f), childTurn, 1.0f}});
  children.push_back({Shape(Box{Vec3(0.299990058f)}),
                      Transform{Vec3(3.05175781e-05f, -0.499977112f, 3.05175781e-05f), childTurn, 1.0f}});
  const Shape compound = Compound::fromChildren(std::move(children));
  const Transform compoundAt{Vec3(4.57763672e-05f),
                             Quat(0.706718922f, -0.0331171714f, 1.0783675e-05f, -0.706718922f), 1.0f};
  const Shape box = Box{Vec3(0.299990058f)};
  const Transform boxAt{Vec3(4.57763672e-05f, -0.749965668f, 4.57763672e-05f),
                        Quat(1.0f, 1.53510809e-05f, 1.53510809e-05f, 1.53510809e-05f), 1.0f};
  ASSERT_FALSE(overlap(compound, compoundAt, box, boxAt));
  Manifold m;
  ASSERT_TRUE(collide::collide(compound, compoundAt, box, boxAt, m, 0.25f));
  ASSERT_GT(m.count, 0);
  for (int i = 0; i < m.count; ++i) EXPECT_LT(m.points[i].depth, -0.04f) << "point " << i;
  // The other order, through the mirroring wrapper.
  ASSERT_TRUE(collide::collide(box, boxAt, compound, compoundAt, m, 0.25f));
  for (int i = 0; i < m.count; ++i) EXPECT_LT(m.points[i].depth, -0.04f) << "point " << i;
}

namespace {

// The R4 terrain (reference-scenes.md) over x in [x0, x0 + n], z in [z0, z0 + n], triangulated as
// the scene is: y = 0.5 sin(0.3 x) cos(0.3 z).
TriangleMesh r4TerrainPatch(int x0, int z0, int n) {
  std::vector<Vec3> vertices;
  std::vector<MeshTriangle> triangles;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const double x = x0 + i, z = z0 + j;
      vertices.emplace_back(float(x), float(0.5 * std::sin(0.3 * x) * std::cos(0.3 * z)), float(z));
    }
  }
  auto at = [&](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      triangles.push_back({{at(i, j), at(i, j + 1), at(i + 1, j)}});
      triangles.push_back({{at(i + 1, j), at(i, j + 1), at(i + 1, j + 1)}});
    }
  }
  return TriangleMesh::fromTriangles(std::move(vertices), std::move(triangles));
}

// Hull `index` of R4's generator: 12 points from std::mt19937(42), normal draws x, y, z, scaled
// to length 0.5.
ConvexHull r4Hull(int index) {
  std::mt19937 rng(42);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::vector<Vec3> points(12);
  for (int h = 0; h <= index; ++h) {
    for (Vec3& p : points) {
      const double x = gauss(rng);
      const double y = gauss(rng);
      const double z = gauss(rng);
      const double scale = 0.5 / std::sqrt(x * x + y * y + z * z);
      p = Vec3(float(x * scale), float(y * scale), float(z * scale));
    }
  }
  return ConvexHull::fromPoints(points);
}

}  // namespace

TEST(MeshPairs, HullOverASlightlyConvexEdgeKeepsTheSurfaceNormal) {
  // R4, hull 1008 falling at 7 m/s, one step before it lands (margin 0.15 for its speed): over the
  // terrain's edge x = 1, a convex bend of 2.8° between triangles tilted 8° and 6°, the triangle
  // on the far side of the edge alone separates best along an edge-edge axis 35° from vertical, a
  // normal no point of that edge can have on the surface (its normals lie between the two faces').
  // Taken for the manifold, it dropped the face contacts under the hull (more than 25° away) and
  // the hull landed on one sideways point, 9.8 cm deep. The contact normals must stay within the
  // surface's: within 10° of vertical here, with the face points under the hull.
  const Shape terrain(r4TerrainPatch(-2, -4, 6));
  const Shape hull(r4Hull(1008));
  const Transform pose = at({0.75f, 0x1.68a95ep-2f, -2.25f});
  Manifold m;
  ASSERT_TRUE(collide::collide(terrain, Transform::identity(), hull, pose, m, 0.15f));
  EXPECT_LT(angleDegrees(m.normal, Vec3(0, 1, 0)), 10.0f);
  EXPECT_GE(m.count, 3);
  // Still apart by 5 cm or more along the surface: every point speculative.
  EXPECT_LT(m.maxDepth(), -0.05f);
}
