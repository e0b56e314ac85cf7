// parseShape and loadShapeFile: one shape as a scene file writes it (for `collide query`), read with
// the scene's own rules and messages.
#include <collide/scene/scene.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "support/scene_data.h"

namespace collide::scene {
namespace {

using ::testing::HasSubstr;

using collide::test::kSceneData;

std::string shapeError(const std::string& text) {
  try {
    (void)parseShape(text, "shape.json", kSceneData);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(ShapeFile, ParsesEachKindAsASceneDoes) {
  const Shape box = parseShape(R"({"type": "box", "half_extents": [1, 2, 3]})");
  ASSERT_EQ(box.type(), ShapeType::Box);
  EXPECT_EQ(box.box().halfExtents, Vec3(1.0f, 2.0f, 3.0f));
  EXPECT_EQ(parseShape(R"({"type": "sphere", "radius": 0.25})").sphere().radius, 0.25f);
  // A mesh's OBJ file is found in the base folder.
  EXPECT_EQ(parseShape(R"({"type": "mesh", "file": "cube.obj"})", "shape", kSceneData).type(),
            ShapeType::Mesh);
  EXPECT_EQ(loadShapeFile(kSceneData + "/query_ball.json").sphere().radius, 0.25f);
  EXPECT_EQ(loadShapeFile(kSceneData + "/query_mesh.json").type(), ShapeType::Mesh);
}

TEST(ShapeFile, RefusesBadShapesNamingTheField) {
  EXPECT_THAT(shapeError(R"({"type": "sphere", "radius": -1})"),
              HasSubstr("shape.json: radius: must be > 0, got -1"));
  EXPECT_THAT(shapeError(R"({"type": "blob"})"), HasSubstr("blob"));
  EXPECT_THAT(shapeError(R"({"type": "mesh", "file": "../cube.obj"})"), HasSubstr("leads outside"));
  EXPECT_THAT(shapeError("[1, 2"), HasSubstr("malformed JSON"));
  EXPECT_THROW((void)loadShapeFile(kSceneData + "/no-such-shape.json"), Error);
}

}  // namespace
}  // namespace collide::scene
