// Plane pairs (src/narrowphase/plane_pairs.cpp) on what the narrow-phase fuzzer found: a mesh may
// hold vertices that no triangle uses, and plane x mesh took them for the surface.
#include <collide/narrowphase.h>

#include <gtest/gtest.h>

#include <vector>

namespace collide {
namespace {

// One triangle 1 m above the ground plane y = 0, and, with `strayBelow`, a vertex no triangle uses
// 1 m below it (as an OBJ file with a leftover vertex gives).
Shape triangleAboveTheGround(bool strayBelow) {
  std::vector<Vec3> vertices{Vec3(0.0f, 1.0f, 0.0f), Vec3(1.0f, 1.0f, 0.0f), Vec3(0.0f, 1.0f, 1.0f)};
  if (strayBelow) vertices.push_back(Vec3(0.5f, -1.0f, 0.5f));
  return TriangleMesh::fromTriangles(std::move(vertices), {MeshTriangle{{0, 2, 1}}});
}

TEST(PlanePairs, MeshVertexThatNoTriangleUsesMakesNoContact) {
  const Shape ground = Plane{Vec3(0.0f, 1.0f, 0.0f), 0.0f};
  for (const bool stray : {false, true}) {
    const Shape mesh = triangleAboveTheGround(stray);
    Manifold m;
    EXPECT_FALSE(collide::collide(ground, Transform::identity(), mesh, Transform::identity(), m, 0.1f))
        << (stray ? "with" : "without") << " the stray vertex";
    EXPECT_EQ(m.count, 0);
    EXPECT_FALSE(overlap(ground, Transform::identity(), mesh, Transform::identity()));
  }
}

TEST(PlanePairs, MeshTriangleThroughThePlaneTouchesWithItsVerticesBelow) {
  // The same mesh lowered by 1.2 m: the triangle is 0.2 m deep, the stray vertex 2.2 m; only the
  // triangle's three vertices make contacts, each 0.2 m deep.
  const Shape ground = Plane{Vec3(0.0f, 1.0f, 0.0f), 0.0f};
  const Shape mesh = triangleAboveTheGround(true);
  Transform lowered;
  lowered.position = Vec3(0.0f, -1.2f, 0.0f);
  Manifold m;
  ASSERT_TRUE(collide::collide(ground, Transform::identity(), mesh, lowered, m));
  ASSERT_EQ(m.count, 3);
  for (int i = 0; i < m.count; ++i) {
    EXPECT_NEAR(m.points[i].depth, 0.2f, 1e-5f) << "point " << i;
    EXPECT_NEAR(m.points[i].pointOnB.y, -0.2f, 1e-5f) << "a triangle's vertex, not the stray one at -2.2";
  }
}

}  // namespace
}  // namespace collide
