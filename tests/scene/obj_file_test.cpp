// OBJ meshes (scene/src/obj_file.cpp): the text entry point that the file reader and the OBJ fuzzer
// share, what it reads from the formats a modelling tool writes, and how each kind of bad text is
// refused with an Error that names the file.
#include <collide/scene/obj_file.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

namespace collide::scene {
namespace {

using ::testing::HasSubstr;

const std::string kData = COLLIDE_SCENE_TEST_DATA;

std::string parseError(const std::string& text) {
  try {
    parseObj(text, "test.obj");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(ObjFile, TextAndFileGiveTheSameMesh) {
  const ObjMesh fromFile = readObjFile(kData + "/cube.obj");
  const std::string text =
      "v -0.5 -0.5 -0.5\nv 0.5 -0.5 -0.5\nv 0.5 0.5 -0.5\nv -0.5 0.5 -0.5\n"
      "v -0.5 -0.5 0.5\nv 0.5 -0.5 0.5\nv 0.5 0.5 0.5\nv -0.5 0.5 0.5\n"
      "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 4 8 7 3\nf 1 5 8 4\nf 2 3 7 6\n";
  const ObjMesh fromText = parseObj(text, "cube.obj");
  ASSERT_EQ(fromText.vertices.size(), 8u);
  ASSERT_EQ(fromText.triangles.size(), 12u);  // six quads, triangulated
  EXPECT_EQ(fromText.vertices, fromFile.vertices);
  for (std::size_t i = 0; i < fromText.triangles.size(); ++i) {
    EXPECT_EQ(fromText.triangles[i].v, fromFile.triangles[i].v) << "triangle " << i;
  }
}

TEST(ObjFile, ReadsIndexFormsObjectsAndPolygons) {
  // v/vt/vn and v//vn indices, a negative (relative) index, two objects, a pentagon, a material
  // library that is not there (ignored: a collision mesh has no materials).
  const ObjMesh mesh = parseObj(
      "mtllib missing.mtl\no first\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvt 0 0\nvn 0 0 1\n"
      "f 1/1/1 3/1/1 2/1/1\nf 1//1 2//1 4//1\nf -4 -1 -2\n"
      "o second\nv 2 0 0\nv 3 0 0\nv 3 1 0\nv 2.5 2 0\nv 2 1 0\nusemtl none\nf 5 6 7 8 9\n",
      "shapes.obj");
  ASSERT_EQ(mesh.vertices.size(), 9u);
  ASSERT_EQ(mesh.triangles.size(), 6u);  // three triangles and a pentagon's three
  EXPECT_EQ(mesh.triangles[2].v, (std::array<std::uint32_t, 3>{0, 3, 2})) << "-4 -1 -2 of four vertices";
  EXPECT_EQ(mesh.vertices[7], Vec3(2.5f, 2.0f, 0.0f));
}

TEST(ObjFile, BadTextIsRefusedWithTheFileName) {
  EXPECT_THAT(parseError(""), HasSubstr("test.obj: no triangles"));
  EXPECT_THAT(parseError("v 0 0 0\nv 1 0 0\nv 0 1 0\n"), HasSubstr("test.obj: no triangles"));
  EXPECT_THAT(parseError("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"), HasSubstr("test.obj"));
  EXPECT_THAT(parseError("\x01\x02\xff garbage\nf 1 2 3\n"), HasSubstr("test.obj"));
  EXPECT_THAT(parseError("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n"), HasSubstr("test.obj"));  // 0 is no index
  try {
    readObjFile(kData + "/missing.obj");
    ADD_FAILURE() << "a missing file must be refused";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("missing.obj: cannot be read"));
  }
}

}  // namespace
}  // namespace collide::scene
