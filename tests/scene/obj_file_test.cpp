// OBJ meshes (scene/src/obj_file.cpp): the text entry point that the file reader and the OBJ fuzzer
// share, what it reads from the formats a modelling tool writes, and how each kind of bad text is
// refused with an Error that names the file.
#include <collide/scene/limits.h>
#include <collide/scene/obj_file.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "support/scene_data.h"

namespace collide::scene {
namespace {

using ::testing::HasSubstr;

using collide::test::kSceneData;

std::string objParseError(const std::string& text) {
  try {
    parseObj(text, "test.obj");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(ObjFile, TextAndFileGiveTheSameMesh) {
  const ObjMesh fromFile = readObjFile(kSceneData + "/cube.obj");
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

TEST(ObjFile, LinesOtherThanVerticesAndFacesAreNotConverted) {
  // Skin weights with a joint of 1e300, a normal and a texture coordinate out of float range, a
  // polyline and points with indices out of int range, a parameter-space vertex: collide reads only
  // the vertices and faces, and tinyobjloader would convert these numbers to int and float unchecked
  // (undefined behaviour, which the sanitized run of this test reports: obj_fuzzer's finding). They
  // are comments to it, and the mesh is the one the vertices and faces give.
  const ObjMesh mesh = parseObj(
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nvw 0 1e300 0.5\nvn 1e300 0 0\nvt -1e300 0\n"
      "l 1 99999999999999999999\np -99999999999999999999\nvp 1e300\n  g  group\nf 1 2 3\n",
      "extras.obj");
  ASSERT_EQ(mesh.vertices.size(), 3u);
  ASSERT_EQ(mesh.triangles.size(), 1u);
  EXPECT_EQ(mesh.triangles[0].v, (std::array<std::uint32_t, 3>{0, 1, 2}));
}

TEST(ObjFile, BadTextIsRefusedWithTheFileName) {
  EXPECT_THAT(objParseError(""), HasSubstr("test.obj: no triangles"));
  EXPECT_THAT(objParseError("v 0 0 0\nv 1 0 0\nv 0 1 0\n"), HasSubstr("test.obj: no triangles"));
  EXPECT_THAT(objParseError("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"), HasSubstr("test.obj"));
  EXPECT_THAT(objParseError("\x01\x02\xff garbage\nf 1 2 3\n"), HasSubstr("test.obj"));
  EXPECT_THAT(objParseError("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n"), HasSubstr("test.obj"));  // 0 is no index
  try {
    readObjFile(kSceneData + "/missing.obj");
    ADD_FAILURE() << "a missing file must be refused";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("missing.obj: cannot be read"));
  }
}

// tinyobjloader reads a coordinate it cannot parse as 0: a mesh would change shape silently (a
// floor vertex at "nan" becomes the origin and a ball falls through), so each one is an error
// naming the file, the line and the token.
TEST(ObjFile, NonFiniteAndUnparsableCoordinatesNameTheLine) {
  const std::string before = "v 0 0 0\nv 1 0 0\n";
  const std::string after = "\nf 1 2 3\n";
  EXPECT_THAT(objParseError(before + "v nan 1 0" + after),
              HasSubstr("test.obj:3: vertex coordinate \"nan\" is not a finite number"));
  EXPECT_THAT(objParseError(before + "v 0 inf 0" + after),
              HasSubstr("test.obj:3: vertex coordinate \"inf\" is not a finite number"));
  EXPECT_THAT(objParseError(before + "v 0 1 -Infinity" + after),
              HasSubstr("test.obj:3: vertex coordinate \"-Infinity\" is not a finite number"));
  EXPECT_THAT(objParseError(before + "v 0 1 1e999" + after),
              HasSubstr("test.obj:3: vertex coordinate \"1e999\" is not a finite number"));
  // Finite as a double, infinite as the float a mesh stores.
  EXPECT_THAT(objParseError(before + "v 0 1 -1e39" + after),
              HasSubstr("test.obj:3: vertex coordinate \"-1e39\" is not a finite number within float range"));
  EXPECT_THAT(objParseError(before + "v 0 1.5x 0" + after),
              HasSubstr("test.obj:3: vertex coordinate \"1.5x\" is not a number"));
  EXPECT_THAT(objParseError(before + "v 0 1,5 0" + after),
              HasSubstr("test.obj:3: vertex coordinate \"1,5\" is not a number"));
  EXPECT_THAT(objParseError(before + "v 0 0x10 0" + after),
              HasSubstr("vertex coordinate \"0x10\" is not a number"));
  EXPECT_THAT(objParseError(before + "v 0 1" + after),
              HasSubstr("test.obj:3: a vertex needs x, y and z, got 2 numbers"));
  // w and the colour extension's numbers are numbers too.
  EXPECT_THAT(objParseError(before + "v 0 1 0 0.5 nan 0.5" + after),
              HasSubstr("test.obj:3: vertex coordinate \"nan\""));
  // Lines end at \n, \r\n or \r, as tinyobjloader reads them; bytes that do not print are escaped.
  EXPECT_THAT(objParseError("v 0 0 0\r\nv 1 0 0\rv 0 1 0\n# a comment\n  v\t0 \xff 0\nf 1 2 3\n"),
              HasSubstr("test.obj:5: vertex coordinate \"\\xff\" is not a number"));
}

TEST(ObjFile, CoordinatesAsModellingToolsWriteThemAreRead) {
  const ObjMesh mesh = parseObj(
      "v +1 -2.5 .5\nv 5. 1e-2 1.5E+02\nv 1e-50 -0 3 # a comment\nv 0 0 0 1\nv 0 1 0 0.5 0.5 0.5\n"
      "f 1 2 3\nf 4 5 1\n",
      "tools.obj");
  ASSERT_EQ(mesh.vertices.size(), 5u);
  EXPECT_EQ(mesh.vertices[0], Vec3(1.0f, -2.5f, 0.5f));
  EXPECT_EQ(mesh.vertices[1], Vec3(5.0f, 0.01f, 150.0f));
  EXPECT_EQ(mesh.vertices[2], Vec3(0.0f, 0.0f, 3.0f));  // 1e-50 is below float's smallest: 0
  EXPECT_EQ(mesh.vertices[4], Vec3(0.0f, 1.0f, 0.0f));
  EXPECT_EQ(mesh.triangles.size(), 2u);
}

TEST(ObjFile, FaceVerticesMustBeIndices) {
  const std::string vertices = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  EXPECT_THAT(objParseError(vertices + "f 1 2 x\n"),
              HasSubstr("test.obj:4: face vertex \"x\" is not an index"));
  EXPECT_THAT(objParseError(vertices + "f 1 2 3.5\n"),
              HasSubstr("test.obj:4: face vertex \"3.5\" is not an index"));
  EXPECT_THAT(objParseError(vertices + "f 1 2/a 3\n"),
              HasSubstr("test.obj:4: face vertex \"2/a\" is not an index"));
  EXPECT_THAT(objParseError(vertices + "f 1 2 3/1/1/1\n"),
              HasSubstr("face vertex \"3/1/1/1\" has more than three indices"));
  EXPECT_THAT(objParseError(vertices + "f 1 0 3\n"),
              HasSubstr("test.obj:4: face vertex \"0\": vertex indices start at 1"));
  // The forms a modelling tool writes.
  EXPECT_EQ(parseObj(vertices + "vt 0 0\nvn 0 0 1\nf 1/1/1 +2//1 -1/1\n", "forms.obj").triangles.size(), 1u);
}

TEST(ObjFile, PolygonsAndMeshesWithinTheLimits) {
  // Triangulating a polygon takes time quadratic in its vertices (tinyobjloader's ear clipping).
  std::string polygon = "f";
  for (std::size_t i = 1; i <= kMaxObjFaceVertices + 1; ++i) {
    polygon += ' ';
    polygon += std::to_string(i);
  }
  EXPECT_THAT(objParseError("v 0 0 0\n" + polygon + "\n"),
              HasSubstr("test.obj:2: a face of 257 vertices, more than the limit of 256"));
  // A circle of 256 vertices, the largest polygon allowed, is read.
  std::string circle;
  for (std::size_t i = 0; i < kMaxObjFaceVertices; ++i) {
    const double angle = 2.0 * 3.14159265358979 * double(i) / double(kMaxObjFaceVertices);
    circle += "v " + std::to_string(std::cos(angle)) + " " + std::to_string(std::sin(angle)) + " 0\n";
  }
  polygon.resize(polygon.rfind(' '));
  EXPECT_EQ(parseObj(circle + polygon + "\n", "circle.obj").triangles.size(), kMaxObjFaceVertices - 2);
  // Triangles are counted before tinyobjloader builds them: one too many, as 256-gons, is refused.
  std::string bigFace = "f";
  for (std::size_t i = 0; i < kMaxObjFaceVertices; ++i) bigFace += " 1";
  bigFace += "\n";
  const std::size_t perFace = kMaxObjFaceVertices - 2;
  std::string text = "v 0 0 0\n";
  for (std::size_t t = 0; t <= kMaxMeshTriangles; t += perFace) text += bigFace;
  EXPECT_THAT(objParseError(text),
              HasSubstr("test.obj: more than 4000000 triangles (the limit), reached at line"));
}

// `collide fit` reads its mesh with readObjFile: the error is the file's, with its line.
TEST(ObjFile, FileWithANonFiniteVertexIsRefused) {
  try {
    readObjFile(kSceneData + "/nan_vertex.obj");
    ADD_FAILURE() << "a NaN vertex must be refused";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("nan_vertex.obj:4: vertex coordinate \"nan\" is not a finite number"));
  }
}

}  // namespace
}  // namespace collide::scene
