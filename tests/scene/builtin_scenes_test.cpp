// Every built-in scene goes through the loader and runs; the reference scenes are built as
// reference-scenes.md specifies.
#include <collide/scene/builtin_scenes.h>
#include <collide/scene/runner.h>

#include <gtest/gtest.h>

#include <cmath>

namespace collide::scene {
namespace {

TEST(BuiltinScenes, EveryOneLoadsAndRunsTenSteps) {
  for (const BuiltinScene& builtin : builtinScenes()) {
    SCOPED_TRACE(std::string(builtin.name));
    const Scene scene = loadBuiltinScene(builtin.name);
    RunOptions options;
    options.steps = 10;
    const RunSummary s = runScene(scene, options);
    EXPECT_EQ(s.steps, 10);
    EXPECT_EQ(s.staticBodies + s.kinematicBodies + s.dynamicBodies, int(scene.bodies.size()));
    EXPECT_TRUE(std::isfinite(s.kineticEnergy));
    // The export is the same document: parsing it gives the same bodies.
    EXPECT_EQ(parseScene(builtinSceneJson(builtin.name)).bodies.size(), scene.bodies.size());
  }
}

TEST(BuiltinScenes, UnknownNameIsAnError) {
  EXPECT_FALSE(isBuiltinScene("no-such-scene"));
  EXPECT_THROW(loadBuiltinScene("no-such-scene"), Error);
}

TEST(BuiltinScenes, ReferenceCounts) {
  EXPECT_EQ(loadBuiltinScene("pile").bodies.size(), 4096u + 1u);
  EXPECT_EQ(loadBuiltinScene("rain").bodies.size(), 8000u + 5u);
  EXPECT_EQ(loadBuiltinScene("pyramid").bodies.size(), 465u + 1u);
  EXPECT_EQ(loadBuiltinScene("billiards").bodies.size(), 16u + 5u);
}

TEST(BuiltinScenes, PyramidCubesTouchExactly) {
  const Scene s = loadBuiltinScene("pyramid");
  // Row 0 spans x = -14.5 .. 14.5 at y = 0.5; the top cube sits at (0, 29.5, 0).
  EXPECT_EQ(s.bodies[1].def.position, Vec3(-14.5f, 0.5f, 0.0f));
  EXPECT_EQ(s.bodies.back().def.position, Vec3(0.0f, 29.5f, 0.0f));
  EXPECT_FLOAT_EQ(*s.bodies.back().def.mass, 1.0f);
}

TEST(BuiltinScenes, BilliardRackTouches) {
  const Scene s = loadBuiltinScene("billiards");
  // Bodies 6.. are the rack; neighbours in a row are 2R apart, rows sqrt(3)R apart.
  const float r = 0.028575f;
  const Vec3 apex = s.bodies[6].def.position, second = s.bodies[7].def.position,
             third = s.bodies[8].def.position;
  EXPECT_NEAR(glm::length(second - apex), 2 * r, 1e-6f);
  EXPECT_NEAR(glm::length(third - second), 2 * r, 1e-6f);
  EXPECT_EQ(s.bodies[5].def.linearVelocity, Vec3(6, 0, 0));
}

TEST(BuiltinScenes, TerrainHullsAreUnitDiameterPointClouds) {
  const Scene s = loadBuiltinScene("terrain");
  ASSERT_EQ(s.bodies.size(), 2001u);
  EXPECT_EQ(s.bodies[0].def.shape.mesh().triangles().size(), 20000u);
  for (std::size_t i = 1; i < s.bodies.size(); i += 97) {
    for (const Vec3& v : s.bodies[i].def.shape.convexHull().vertices())
      EXPECT_NEAR(glm::length(v), 0.5f, 1e-5f);
  }
}

}  // namespace
}  // namespace collide::scene
