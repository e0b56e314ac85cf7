#include "geometry/triangle.h"
#include "support/collide_error.h"
#include "support/test_meshes.h"

#include <collide/shapes.h>
#include <gtest/gtest.h>

#include <limits>
#include <random>
#include <set>
#include <string>
#include "support/test_assertions.h"

using namespace collide;

namespace {

using test::expectMatNear;

std::string meshError(std::vector<Vec3> vertices, std::vector<MeshTriangle> triangles) {
  return ::collide::test::errorOf(
             [&] { TriangleMesh::fromTriangles(std::move(vertices), std::move(triangles)); })
      .value_or("no error");
}

const std::vector<Vec3> kQuad = {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}};

}  // namespace

// ---- Topology and mass properties ----

TEST(TriangleMesh, BoxMeshIsClosedAndHasTheBoxMassProperties) {
  const Vec3 h(1.0f, 0.5f, 0.25f);
  const Vec3 offset(3.0f, -2.0f, 1.0f);
  const TriangleMesh mesh = test::boxMesh(h, [&](const Vec3& p) { return p + offset; });
  EXPECT_TRUE(mesh.isClosed());
  EXPECT_EQ(mesh.triangles().size(), 12u);
  EXPECT_NEAR(mesh.volume(), 8.0f * h.x * h.y * h.z, 1e-5f);
  test::expectVecWithin(mesh.centroid(), offset, 1e-5f);

  const MassProperties fromMesh = massProperties(Shape(mesh), 3.0f, 2.0f);
  const MassProperties fromBox = massProperties(Box{h}, 3.0f, 2.0f);
  EXPECT_NEAR(fromMesh.mass, fromBox.mass, 1e-4f * fromBox.mass);
  EXPECT_NEAR(fromMesh.volume, fromBox.volume, 1e-4f * fromBox.volume);
  test::expectVecWithin(fromMesh.centerOfMass, 2.0f * offset, 1e-4f);  // scale 2 moves the centroid too
  expectMatNear(fromMesh.inertia, fromBox.inertia, 1e-4f * fromBox.inertia[0][0]);
}

TEST(TriangleMesh, IcosphereVolumeConvergesToTheSphereFromBelow) {
  const float sphereVolume = 4.0f / 3.0f * kPi;
  float previousError = sphereVolume - test::icosphere(1).volume();
  for (int level = 2; level <= 4; ++level) {
    const TriangleMesh mesh = test::icosphere(level);
    ASSERT_TRUE(mesh.isClosed()) << "level " << level;
    const float error = sphereVolume - mesh.volume();
    EXPECT_GT(error, 0.0f) << "an inscribed polyhedron is smaller than its sphere";
    // Vertices on the sphere, edges halved per level: a second-order error shrinks fourfold.
    EXPECT_GT(previousError / error, 3.5f) << "level " << level;
    EXPECT_LT(previousError / error, 4.5f) << "level " << level;
    previousError = error;
    // Symmetric about the origin, and nearly isotropic inertia 2/5 m r^2 (unit density, r = 1).
    test::expectVecWithin(mesh.centroid(), Vec3(0.0f), 1e-5f);
    const float expected = 0.4f * mesh.volume();
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(mesh.unitInertia()[i][i], expected, 2.0f * error / sphereVolume * expected);
    }
  }
  EXPECT_LT(previousError / sphereVolume, 0.005f);  // 5120 triangles: within half a percent
}

TEST(TriangleMesh, OpenMeshesAreNotClosedAndContainNothing) {
  const TriangleMesh quad = TriangleMesh::fromTriangles(kQuad, {{{0, 2, 1}}, {{0, 3, 2}}});
  EXPECT_FALSE(quad.isClosed());
  EXPECT_FALSE(containsPoint(Shape(quad), Transform{}, {0.5f, 0.0f, 0.5f}));
  EXPECT_FALSE(containsPoint(Shape(quad), Transform{}, {0.5f, -0.1f, 0.5f}));
  EXPECT_COLLIDE_ERROR(massProperties(Shape(quad), 1.0f));

  const TriangleMesh ground = test::terrain(16, 1.0f, 2.0f, 1);
  EXPECT_FALSE(ground.isClosed());
  std::mt19937 rng(2);
  for (int i = 0; i < 200; ++i) {
    EXPECT_FALSE(containsPoint(Shape(ground), Transform{}, test::randomPoint(rng, -1.0f, 17.0f)));
  }
}

TEST(TriangleMesh, InconsistentlyWoundOrDuplicatedSurfacesAreNotClosed) {
  const TriangleMesh box = test::boxMesh(Vec3(1.0f));
  std::vector<MeshTriangle> flippedOne(box.triangles().begin(), box.triangles().end());
  std::swap(flippedOne[5].v[1], flippedOne[5].v[2]);
  std::vector<Vec3> vertices(box.vertices().begin(), box.vertices().end());
  EXPECT_FALSE(TriangleMesh::fromTriangles(vertices, flippedOne).isClosed());
  std::vector<MeshTriangle> missingOne(box.triangles().begin(), box.triangles().end() - 1);
  EXPECT_FALSE(TriangleMesh::fromTriangles(vertices, missingOne).isClosed());
  std::vector<MeshTriangle> doubled(box.triangles().begin(), box.triangles().end());
  doubled.insert(doubled.end(), box.triangles().begin(), box.triangles().end());
  EXPECT_FALSE(TriangleMesh::fromTriangles(vertices, doubled).isClosed());
}

TEST(TriangleMesh, InsideOutClosedMeshStillHasPositiveMassAndOutwardNormals) {
  const TriangleMesh box = test::boxMesh(Vec3(1.0f, 2.0f, 3.0f));
  std::vector<MeshTriangle> flipped(box.triangles().begin(), box.triangles().end());
  for (MeshTriangle& t : flipped) std::swap(t.v[1], t.v[2]);
  const TriangleMesh inverted =
      TriangleMesh::fromTriangles(std::vector<Vec3>(box.vertices().begin(), box.vertices().end()), flipped);
  EXPECT_TRUE(inverted.isClosed());
  EXPECT_LT(inverted.volume(), 0.0f);
  const MassProperties m = massProperties(Shape(inverted), 1.0f);
  EXPECT_NEAR(m.volume, 48.0f, 1e-4f);
  expectMatNear(m.inertia, massProperties(Box{{1.0f, 2.0f, 3.0f}}, 1.0f).inertia, 1e-3f);
  EXPECT_TRUE(containsPoint(Shape(inverted), Transform{}, {0.5f, 0.5f, 0.5f}));
  const SurfacePoint inside = closestPoint(Shape(inverted), Transform{}, {0.9f, 0.0f, 0.0f});
  test::expectVecWithin(inside.normal, Vec3(1, 0, 0), 1e-6f);
  EXPECT_NEAR(inside.signedDistance, -0.1f, 1e-5f);
}

TEST(TriangleMesh, BoundsAndTriangleAccess) {
  const TriangleMesh mesh = test::terrain(8, 0.5f, 1.0f, 4);
  Aabb expected;
  for (const Vec3& v : mesh.vertices()) expected.grow(v);
  EXPECT_EQ(localBounds(Shape(mesh)).min, expected.min);
  EXPECT_EQ(localBounds(Shape(mesh)).max, expected.max);
  const auto corners = mesh.triangle(3);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(corners[k], mesh.vertices()[mesh.triangles()[3].v[k]]);
  std::mt19937 rng(8);
  for (int i = 0; i < 50; ++i) {
    const Transform t = test::randomTransform(rng);
    const Aabb world = worldBounds(Shape(mesh), t);
    for (const Vec3& v : mesh.vertices()) EXPECT_TRUE(world.expanded(1e-4f).contains(t.applyToPoint(v)));
  }
}

// ---- Queries against references ----

TEST(TriangleMesh, RayCastsOnABoxMeshAgreeWithTheBoxShape) {
  const Vec3 h(1.0f, 0.6f, 0.3f);
  const Shape mesh(test::boxMesh(h));
  const Shape box(Box{h});
  std::mt19937 rng(12);
  int hits = 0, inside = 0;
  for (int i = 0; i < 1000; ++i) {
    const Transform t = test::randomTransform(rng);
    Ray ray;
    // Every tenth ray starts inside the box (|x| <= 0.3 < every half extent), the rest anywhere
    // around it.
    const float spread = i % 10 == 0 ? 0.3f : 2.5f;
    ray.origin = t.applyToPoint(test::randomPoint(rng, -spread, spread));
    ray.direction = glm::normalize(t.applyToPoint(test::randomPoint(rng, -1.2f, 1.2f)) - ray.origin);
    ray.maxDistance = i % 5 == 0 ? 2.0f : 1e30f;
    const std::optional<RayHit> expected = rayCast(box, t, ray);
    const std::optional<RayHit> actual = rayCast(mesh, t, ray);
    ASSERT_EQ(actual.has_value(), expected.has_value()) << "ray " << i;
    if (!expected) continue;
    ++hits;
    if (expected->distance == 0.0f) ++inside;
    EXPECT_NEAR(actual->distance, expected->distance, 1e-4f) << "ray " << i;
    test::expectVecWithin(actual->normal, expected->normal, 1e-4f);
    test::expectVecWithin(actual->point, expected->point, 1e-4f);
  }
  EXPECT_GT(hits, 300);  // enough rays hit for the comparison to mean something
  EXPECT_GE(inside, 100);
}

TEST(TriangleMesh, TerrainRayCastsMatchBruteForce) {
  const TriangleMesh mesh = test::terrain(64, 1.0f, 6.0f, 17);
  const Shape shape(mesh);
  std::mt19937 rng(13);
  int hits = 0;
  for (int i = 0; i < 2000; ++i) {
    Ray ray;
    ray.origin = test::randomPoint(rng, -10.0f, 74.0f);
    ray.origin.y = std::uniform_real_distribution<float>(-5.0f, 15.0f)(rng);
    Vec3 target = test::randomPoint(rng, 0.0f, 64.0f);
    target.y = std::uniform_real_distribution<float>(0.0f, 6.0f)(rng);
    ray.direction = glm::normalize(target - ray.origin);
    ray.maxDistance = i % 4 == 0 ? 20.0f : 1e30f;
    std::optional<detail::RayTriangleHit> best;
    std::uint32_t bestTriangle = 0;
    for (std::uint32_t t = 0; t < mesh.triangles().size(); ++t) {
      const auto [a, b, c] = mesh.triangle(t);
      const auto hit = detail::intersectRayTriangle(ray, a, b, c);
      if (hit && (!best || hit->distance < best->distance)) {
        best = hit;
        bestTriangle = t;
      }
    }
    const std::optional<RayHit> actual = rayCast(shape, Transform{}, ray);
    ASSERT_EQ(actual.has_value(), best.has_value()) << "ray " << i;
    if (!best) continue;
    ++hits;
    EXPECT_FLOAT_EQ(actual->distance, best->distance) << "ray " << i;
    if (actual->subShape != bestTriangle) {
      // Only a tie (a ray through a shared edge) may pick the other triangle.
      const auto [a, b, c] = mesh.triangle(actual->subShape);
      const auto other = detail::intersectRayTriangle(ray, a, b, c);
      ASSERT_TRUE(other);
      EXPECT_FLOAT_EQ(other->distance, best->distance);
    }
    // Two-sided: the normal faces the side the ray came from.
    EXPECT_LT(glm::dot(actual->normal, ray.direction), 0.0f);
  }
  EXPECT_GT(hits, 1000);
}

TEST(TriangleMesh, ClosestPointsMatchBruteForce) {
  const TriangleMesh mesh = test::terrain(64, 1.0f, 6.0f, 23);
  const Shape shape(mesh);
  std::mt19937 rng(14);
  for (int i = 0; i < 2000; ++i) {
    Vec3 p = test::randomPoint(rng, -8.0f, 72.0f);
    p.y = std::uniform_real_distribution<float>(-4.0f, 10.0f)(rng);
    float bestSquared = 1e30f;
    for (std::uint32_t t = 0; t < mesh.triangles().size(); ++t) {
      const auto [a, b, c] = mesh.triangle(t);
      const Vec3 q = detail::closestPointOnTriangle(p, a, b, c).point;
      bestSquared = std::min(bestSquared, glm::dot(p - q, p - q));
    }
    const SurfacePoint actual = closestPoint(shape, Transform{}, p);
    const float expected = std::sqrt(bestSquared);
    EXPECT_NEAR(actual.signedDistance, expected, 1e-5f * std::max(1.0f, expected)) << "point " << i;
    EXPECT_NEAR(glm::length(p - actual.point), expected, 1e-5f * std::max(1.0f, expected));
    // Open surface: the normal runs from the surface to the point.
    if (expected > 1e-3f) test::expectVecWithin(actual.normal, (p - actual.point) / expected, 1e-4f);
  }
}

TEST(TriangleMesh, ClosestPointsOnABoxMeshAgreeWithTheBoxShape) {
  const Vec3 h(1.0f, 0.6f, 0.3f);
  const Shape mesh(test::boxMesh(h));
  const Shape box(Box{h});
  std::mt19937 rng(15);
  int insideCount = 0;
  for (int i = 0; i < 2000; ++i) {
    const Transform t = test::randomTransform(rng);
    const Vec3 local = test::randomPoint(rng, -1.5f, 1.5f);
    const SurfacePoint expected = closestPoint(box, t, t.applyToPoint(local));
    const SurfacePoint actual = closestPoint(mesh, t, t.applyToPoint(local));
    EXPECT_NEAR(actual.signedDistance, expected.signedDistance, 1e-4f) << "point " << i;
    test::expectVecWithin(actual.point, expected.point, 1e-4f);
    // The outward face normal matches the box's wherever one face is nearest: inside, and outside
    // in a face region (exactly one coordinate beyond the box).
    const int beyond =
        int(std::abs(local.x) > h.x) + int(std::abs(local.y) > h.y) + int(std::abs(local.z) > h.z);
    if (beyond <= 1) {
      const Vec3 gaps = h - glm::abs(local);
      const float sorted[3] = {gaps.x, gaps.y, gaps.z};
      const float smallest = std::min({sorted[0], sorted[1], sorted[2]});
      int ties = 0;
      for (float g : sorted) ties += int(g - smallest < 1e-3f);
      if (ties == 1 || beyond == 1) test::expectVecWithin(actual.normal, expected.normal, 1e-4f);
    }
    insideCount += int(expected.signedDistance < 0.0f);
  }
  EXPECT_GT(insideCount, 100);
}

TEST(TriangleMesh, ContainmentOfABoxMeshAgreesWithTheBox) {
  const Vec3 h(1.0f, 0.6f, 0.3f);
  const Shape mesh(test::boxMesh(h));
  const Shape box(Box{h});
  std::mt19937 rng(16);
  const Transform t = test::randomTransform(rng);
  int inside = 0, compared = 0;
  for (int i = 0; i < 5000; ++i) {
    const Vec3 local = test::randomPoint(rng, -1.4f, 1.4f);
    if (std::abs(closestPoint(box, Transform{}, local).signedDistance) < 1e-4f) continue;
    const Vec3 world = t.applyToPoint(local);
    const bool expected = containsPoint(box, t, world);
    ASSERT_EQ(containsPoint(mesh, t, world), expected) << "point " << i;
    inside += int(expected);
    ++compared;
  }
  EXPECT_GT(inside, 300);
  EXPECT_GT(compared, 4900);
}

TEST(TriangleMesh, ContainmentOnALatticeThroughEdgesAndVertices) {
  // Lattice points line up with the box's edges, face diagonals and vertices, and some lie on the
  // surface (which counts as inside, like the box's closed set): the cases where a parity count
  // along an unlucky ray would go wrong.
  const Shape mesh(test::boxMesh(Vec3(1.0f)));
  const Shape box(Box{Vec3(1.0f)});
  for (int i = -6; i <= 6; ++i) {
    for (int j = -6; j <= 6; ++j) {
      for (int k = -6; k <= 6; ++k) {
        const Vec3 p = 0.25f * Vec3(i, j, k);
        ASSERT_EQ(containsPoint(mesh, Transform{}, p), containsPoint(box, Transform{}, p))
            << p.x << " " << p.y << " " << p.z;
      }
    }
  }
}

TEST(TriangleMesh, IcosphereContainmentAndSignedDistance) {
  const Shape sphere(test::icosphere(3));
  std::mt19937 rng(18);
  for (int i = 0; i < 1000; ++i) {
    const Vec3 p = test::randomUnitVector(rng) * std::uniform_real_distribution<float>(0.0f, 1.5f)(rng);
    const float r = glm::length(p);
    // Inscribed polyhedron: inside below the face distance (> 0.98 at level 3), outside beyond 1.
    if (r < 0.98f) {
      EXPECT_TRUE(containsPoint(sphere, Transform{}, p)) << r;
    }
    if (r > 1.0f) {
      EXPECT_FALSE(containsPoint(sphere, Transform{}, p)) << r;
    }
    const SurfacePoint s = closestPoint(sphere, Transform{}, p);
    EXPECT_EQ(s.signedDistance < 0.0f, containsPoint(sphere, Transform{}, p));
    EXPECT_NEAR(s.signedDistance, r - 1.0f, 0.03f);  // within the facets' sag of the sphere
    EXPECT_GT(glm::dot(s.normal, s.point), 0.9f);    // outward
  }
}

TEST(TriangleMesh, RayFromInsideAClosedMeshHitsAtZero) {
  const Shape mesh(test::boxMesh(Vec3(1.0f)));
  const Ray ray{{0.2f, 0.1f, 0.0f}, {0.0f, 1.0f, 0.0f}, 10.0f};
  const std::optional<RayHit> hit = rayCast(mesh, Transform{}, ray);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->distance, 0.0f);
  EXPECT_EQ(hit->normal, -ray.direction);
  // An open mesh has no inside: the same ray through a single quad hits the quad.
  const Shape quad(TriangleMesh::fromTriangles(kQuad, {{{0, 2, 1}}, {{0, 3, 2}}}));
  const std::optional<RayHit> quadHit = rayCast(quad, Transform{}, {{0.5f, -1.0f, 0.5f}, {0, 1, 0}, 10.0f});
  ASSERT_TRUE(quadHit);
  EXPECT_FLOAT_EQ(quadHit->distance, 1.0f);
  test::expectVecWithin(quadHit->normal, Vec3(0, -1, 0), 1e-6f);
}

// ---- Bad input ----

TEST(TriangleMesh, RejectsBadInputWithMessages) {
  const TriangleMesh box = test::boxMesh(Vec3(1.0f));
  const std::vector<Vec3> vertices(box.vertices().begin(), box.vertices().end());
  const std::vector<MeshTriangle> triangles(box.triangles().begin(), box.triangles().end());

  EXPECT_EQ(meshError(vertices, {}), "mesh: needs at least one triangle, got 0");

  std::vector<Vec3> nan = vertices;
  nan[5].y = std::numeric_limits<float>::quiet_NaN();
  EXPECT_NE(meshError(nan, triangles).find("vertex 5 is not finite"), std::string::npos);
  std::vector<Vec3> infinite = vertices;
  infinite[2].x = std::numeric_limits<float>::infinity();
  EXPECT_NE(meshError(infinite, triangles).find("vertex 2 is not finite"), std::string::npos);

  std::vector<MeshTriangle> outOfRange = triangles;
  outOfRange[3].v[1] = 9;
  EXPECT_EQ(meshError(vertices, outOfRange), "mesh: triangle 3 index 9 out of range (8 vertices)");

  std::vector<MeshTriangle> repeated = triangles;
  repeated[7].v[2] = repeated[7].v[0];
  EXPECT_NE(meshError(vertices, repeated).find("triangle 7 has zero area: it repeats a vertex index"),
            std::string::npos);

  // Three distinct but collinear vertices.
  std::vector<Vec3> line = vertices;
  line.push_back({0.0f, 0.0f, 0.0f});
  line.push_back({0.5f, 0.5f, 0.5f});
  std::vector<MeshTriangle> withSliver = triangles;
  withSliver.push_back({{7, 8, 9}});  // (1,1,1), origin, (0.5,0.5,0.5)
  EXPECT_NE(meshError(line, withSliver).find("triangle 12 has zero area"), std::string::npos);

  // Nonzero in float but far below the mesh's precision: a 1e-7-high sliver in a 2 m mesh.
  std::vector<Vec3> sliver = vertices;
  sliver.push_back({-1.0f, -1.0f, -1.0f + 1e-7f});
  sliver.push_back({1.0f, -1.0f, -1.0f});
  withSliver.back() = {{0, 9, 8}};
  EXPECT_NE(meshError(sliver, withSliver).find("triangle 12 has zero area"), std::string::npos);

  // A small triangle in a small mesh is fine: the tolerance is relative.
  EXPECT_NO_COLLIDE_ERROR(
      TriangleMesh::fromTriangles({{0, 0, 0}, {1e-4f, 0, 0}, {0, 1e-4f, 0}}, {{{0, 1, 2}}}));
}

namespace {

// Two triangles sharing the edge (0,0,-1)-(0,0,1), one on x < 0 and one on x > 0, both wound
// counter-clockwise seen from +y; the second's far vertex at height `lift` (0: flat, < 0: the
// surface bends down across the edge, a convex ridge seen from +y; > 0: a concave valley).
TriangleMesh hinge(float lift) {
  std::vector<Vec3> vertices = {{0, 0, -1}, {0, 0, 1}, {-1, 0, 0}, {1, lift, 0}};
  std::vector<MeshTriangle> triangles = {{{0, 2, 1}}, {{0, 1, 3}}};
  return TriangleMesh::fromTriangles(std::move(vertices), std::move(triangles));
}

int sharedEdge(const TriangleMesh& mesh, std::uint32_t triangle) {
  // The edge of the triangle between vertices 0 and 1 (either direction).
  const MeshTriangle& t = mesh.triangles()[triangle];
  for (int k = 0; k < 3; ++k) {
    const std::uint32_t a = t.v[k], b = t.v[(k + 1) % 3];
    if ((a == 0 && b == 1) || (a == 1 && b == 0)) return k;
  }
  return -1;
}

}  // namespace

TEST(TriangleMesh, EdgeKindsOfAHingeFollowItsBend) {
  using Kind = TriangleMesh::EdgeKind;
  // The normals of the two triangles are +y and, lifted by h over 1, tilted by atan(h).
  for (const auto& [lift, kind] : {std::pair{0.0f, Kind::Flat},
                                   {-0.5f, Kind::Convex},
                                   {0.5f, Kind::Concave},
                                   // 0.05° is under the 0.1° flat tolerance, 0.2° above it
                                   {std::tan(glm::radians(0.05f)), Kind::Flat},
                                   {-std::tan(glm::radians(0.2f)), Kind::Convex}}) {
    const TriangleMesh mesh = hinge(lift);
    for (std::uint32_t t = 0; t < 2; ++t) {
      const int shared = sharedEdge(mesh, t);
      ASSERT_GE(shared, 0);
      for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(mesh.edgeKind(t, k), k == shared ? kind : Kind::Boundary)
            << "lift " << lift << " edge " << k;
      }
    }
    // Flat hinges are one patch; no vertex is inside it (all lie on the outline).
    EXPECT_EQ(mesh.flatPatch(0) == mesh.flatPatch(1), kind == Kind::Flat) << "lift " << lift;
    for (std::uint32_t v = 0; v < 4; ++v) EXPECT_FALSE(mesh.isFlatVertex(v));
  }
}

TEST(TriangleMesh, EdgeBendIsTheAngleBetweenTheFacesNormals) {
  // The hinge's second triangle lifted by h over 1 turns its normal by atan(h): the shared edge's
  // bend cosine is cos(atan(h)) = 1 / sqrt(1 + h²) for either triangle, whichever way it bends;
  // the outline's is -1. A neighbour with the opposite winding (its normal flipped) bends the same.
  for (const float lift : {0.0f, -0.05f, 0.5f, -2.0f}) {
    const float expected = 1.0f / std::sqrt(1.0f + lift * lift);
    const TriangleMesh mesh = hinge(lift);
    std::vector<Vec3> vertices = {{0, 0, -1}, {0, 0, 1}, {-1, 0, 0}, {1, lift, 0}};
    const TriangleMesh flipped =
        TriangleMesh::fromTriangles(std::move(vertices), {{{{0, 2, 1}}}, {{{0, 3, 1}}}});
    for (const TriangleMesh* m : {&mesh, &flipped}) {
      for (std::uint32_t t = 0; t < 2; ++t) {
        const int shared = sharedEdge(*m, t);
        for (int k = 0; k < 3; ++k) {
          EXPECT_NEAR(m->edgeBendCosine(t, k), k == shared ? expected : -1.0f, 1e-6f) << "lift " << lift;
        }
      }
    }
  }
}

TEST(TriangleMesh, FlatGridHasFlatInteriorEdgesAndVertices) {
  // A 3 × 3 grid of quads (two triangles each) on y = 0: edges inside are flat, the outline's are
  // boundary; the 4 inner vertices are inside the flat patch, the 12 outline ones are not; one patch.
  const int n = 3;
  std::vector<Vec3> vertices;
  std::vector<MeshTriangle> triangles;
  for (int z = 0; z <= n; ++z)
    for (int x = 0; x <= n; ++x) vertices.emplace_back(float(x), 0.0f, float(z));
  auto index = [&](int x, int z) { return static_cast<std::uint32_t>(z * (n + 1) + x); };
  for (int z = 0; z < n; ++z) {
    for (int x = 0; x < n; ++x) {
      triangles.push_back({{index(x, z), index(x, z + 1), index(x + 1, z + 1)}});
      triangles.push_back({{index(x, z), index(x + 1, z + 1), index(x + 1, z)}});
    }
  }
  const TriangleMesh mesh = TriangleMesh::fromTriangles(vertices, triangles);
  int boundary = 0, flat = 0;
  for (std::uint32_t t = 0; t < triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const Vec3 a = vertices[triangles[t].v[k]], b = vertices[triangles[t].v[(k + 1) % 3]];
      const bool outline = (a.x == 0 && b.x == 0) || (a.x == n && b.x == n) || (a.z == 0 && b.z == 0) ||
                           (a.z == n && b.z == n);
      const auto kind = mesh.edgeKind(t, k);
      EXPECT_EQ(kind, outline ? TriangleMesh::EdgeKind::Boundary : TriangleMesh::EdgeKind::Flat);
      boundary += kind == TriangleMesh::EdgeKind::Boundary;
      flat += kind == TriangleMesh::EdgeKind::Flat;
      EXPECT_EQ(mesh.flatPatch(t), mesh.flatPatch(0));
    }
  }
  EXPECT_EQ(boundary, 4 * n);
  EXPECT_EQ(flat, 3 * 2 * n * n - 4 * n);  // each inner edge counted from both sides
  int inner = 0;
  for (std::uint32_t v = 0; v < vertices.size(); ++v) {
    const bool inside = vertices[v].x > 0 && vertices[v].x < n && vertices[v].z > 0 && vertices[v].z < n;
    EXPECT_EQ(mesh.isFlatVertex(v), inside) << v;
    inner += inside;
  }
  EXPECT_EQ(inner, (n - 1) * (n - 1));
}

TEST(TriangleMesh, ClosedBoxMeshEdgesAreConvexOrFlat) {
  // The 12-triangle box surface, wound outwards: the face diagonals are flat, the 12 box edges
  // convex from outside (24 triangle edges); six patches, one per face.
  const TriangleMesh mesh = test::boxMesh(Vec3(1.0f, 0.5f, 0.7f), [](const Vec3& p) { return p; });
  int convex = 0, flat = 0;
  std::set<std::uint32_t> patches;
  for (std::uint32_t t = 0; t < 12; ++t) {
    patches.insert(mesh.flatPatch(t));
    for (int k = 0; k < 3; ++k) {
      convex += mesh.edgeKind(t, k) == TriangleMesh::EdgeKind::Convex;
      flat += mesh.edgeKind(t, k) == TriangleMesh::EdgeKind::Flat;
    }
  }
  EXPECT_EQ(convex, 24);
  EXPECT_EQ(flat, 12);
  EXPECT_EQ(patches.size(), 6u);
}
