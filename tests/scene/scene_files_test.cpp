// The files a scene reads: OBJ paths stay inside the scene's folder unless the loader is told
// otherwise, and only regular files within the size limits are read (a directory, a device, a FIFO
// or a huge file is refused with a message naming it, instead of a hang or exhausted memory).
#include "support/scene_data.h"
#include "support/temp_folder.h"

#include <collide/scene/limits.h>
#include <collide/scene/obj_file.h>
#include <collide/scene/scene.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace collide::scene {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

using collide::test::kSceneData;

using test::TempFolder;

void copyCube(const fs::path& to) {
  fs::copy_file(kSceneData + "/cube.obj", to, fs::copy_options::overwrite_existing);
}

// A one-body scene whose static mesh reads `file` (a JSON string's contents).
std::string meshScene(const std::string& file) {
  return R"({"format": "collide-scene/1", "bodies": [{"name": "m", "type": "static",
      "shape": {"type": "mesh", "file": ")" +
         file + R"("}}]})";
}

// The message of the Error that parsing the scene throws ("" if it does not throw).
std::string sceneError(const std::string& text, const fs::path& baseDir, const LoadOptions& options = {}) {
  try {
    parseScene(text, "scene.json", baseDir, options);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

std::string loadError(const fs::path& path) {
  try {
    loadSceneFile(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

std::string objError(const fs::path& path) {
  try {
    readObjFile(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

std::size_t meshTriangles(const std::string& text, const fs::path& baseDir, const LoadOptions& options = {}) {
  return parseScene(text, "scene.json", baseDir, options).bodies.at(0).def.shape.mesh().triangles().size();
}

TEST(SceneFiles, ObjPathsInsideTheScenesFolderAreRead) {
  TempFolder folder;
  fs::create_directories(folder.path() / "meshes" / "old");
  copyCube(folder.path() / "meshes" / "cube.obj");
  EXPECT_EQ(meshTriangles(meshScene("meshes/cube.obj"), folder.path()), 12u);
  EXPECT_EQ(meshTriangles(meshScene("meshes/old/../cube.obj"), folder.path()), 12u);
  EXPECT_EQ(meshTriangles(meshScene("./meshes//cube.obj"), folder.path()), 12u);
  // A symbolic link that stays inside the folder is followed.
  fs::create_symlink("meshes/cube.obj", folder.path() / "link.obj");
  EXPECT_EQ(meshTriangles(meshScene("link.obj"), folder.path()), 12u);
}

TEST(SceneFiles, ObjPathsOutsideTheScenesFolderAreRefused) {
  TempFolder folder;
  fs::create_directories(folder.path() / "scene" / "meshes");
  copyCube(folder.path() / "outside.obj");
  const fs::path scene = folder.path() / "scene";
  const std::string absolute = (folder.path() / "outside.obj").string();

  EXPECT_THAT(
      sceneError(meshScene(absolute), scene),
      HasSubstr("scene.json: bodies[0].shape.file: must be a relative path, got the absolute path \"" +
                absolute + "\""));
  EXPECT_THAT(sceneError(meshScene("/etc/passwd"), scene), HasSubstr("must be a relative path"));
  EXPECT_THAT(sceneError(meshScene("../outside.obj"), scene),
              HasSubstr("bodies[0].shape.file: leads outside the scene's folder, got \"../outside.obj\""));
  // Checked after normalising: the climb out need not come first.
  EXPECT_THAT(sceneError(meshScene("meshes/../../outside.obj"), scene),
              HasSubstr("leads outside the scene's folder"));
  // A symbolic link inside the folder that leads out of it counts as leaving, as does a folder link.
  fs::create_symlink(folder.path() / "outside.obj", scene / "meshes" / "link.obj");
  fs::create_symlink(folder.path(), scene / "up");
  EXPECT_THAT(sceneError(meshScene("meshes/link.obj"), scene),
              HasSubstr("bodies[0].shape.file: leads outside the scene's folder through a symbolic link, got "
                        "\"meshes/link.obj\""));
  EXPECT_THAT(sceneError(meshScene("up/outside.obj"), scene), HasSubstr("through a symbolic link"));
  // Every refusal says how to allow it.
  EXPECT_THAT(sceneError(meshScene("../outside.obj"), scene), HasSubstr("--allow-outside-paths"));

  // Allowed explicitly, each of them is read.
  const LoadOptions allow{.allowOutsidePaths = true};
  EXPECT_EQ(meshTriangles(meshScene(absolute), scene, allow), 12u);
  EXPECT_EQ(meshTriangles(meshScene("../outside.obj"), scene, allow), 12u);
  EXPECT_EQ(meshTriangles(meshScene("meshes/link.obj"), scene, allow), 12u);
  EXPECT_EQ(meshTriangles(meshScene("up/outside.obj"), scene, allow), 12u);
}

TEST(SceneFiles, SceneFileOptionsReachTheObjPaths) {
  TempFolder folder;
  fs::create_directories(folder.path() / "scene");
  copyCube(folder.path() / "outside.obj");
  std::ofstream(folder.path() / "scene" / "s.json") << meshScene("../outside.obj");
  EXPECT_THAT(loadError(folder.path() / "scene" / "s.json"),
              HasSubstr("s.json: bodies[0].shape.file: leads outside the scene's folder"));
  const Scene s = loadSceneFile(folder.path() / "scene" / "s.json", LoadOptions{.allowOutsidePaths = true});
  EXPECT_EQ(s.bodies.at(0).def.shape.mesh().triangles().size(), 12u);
}

TEST(SceneFiles, ADirectoryIsNotAFile) {
  TempFolder folder;
  fs::create_directories(folder.path() / "meshes");
  EXPECT_THAT(loadError(folder.path()),
              HasSubstr("scene file " + folder.path().string() + ": is a directory, not a file"));
  EXPECT_THAT(objError(folder.path()),
              HasSubstr("OBJ file " + folder.path().string() + ": is a directory, not a file"));
  EXPECT_THAT(sceneError(meshScene("meshes"), folder.path()),
              HasSubstr("bodies[0].shape.file: OBJ file " + (folder.path() / "meshes").string() +
                        ": is a directory, not a file"));
  EXPECT_THAT(sceneError(meshScene(""), folder.path()),
              HasSubstr("bodies[0].shape.file: must name an OBJ file"));
}

TEST(SceneFiles, DevicesAndFifosAreNotRead) {
  // /dev/zero never ends: read as text it would take memory until allocation fails.
  EXPECT_THAT(objError("/dev/zero"), HasSubstr("OBJ file /dev/zero: is a device, not a regular file"));
  EXPECT_THAT(loadError("/dev/zero"), HasSubstr("scene file /dev/zero: is a device, not a regular file"));
  EXPECT_THAT(sceneError(meshScene("/dev/zero"), kSceneData, LoadOptions{.allowOutsidePaths = true}),
              HasSubstr("bodies[0].shape.file: OBJ file /dev/zero: is a device"));
  // Opening a FIFO for reading waits for a writer: it must be refused before it is opened.
  TempFolder folder;
  const fs::path fifo = folder.path() / "pipe.obj";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_THAT(objError(fifo), HasSubstr("pipe.obj: is a FIFO (named pipe), not a regular file"));
  EXPECT_THAT(sceneError(meshScene("pipe.obj"), folder.path()), HasSubstr("pipe.obj: is a FIFO"));
}

TEST(SceneFiles, FilesOverTheSizeLimitsAreNotRead) {
  TempFolder folder;
  // Sparse files: the size is what is checked, before reading.
  const fs::path obj = folder.path() / "huge.obj";
  std::ofstream(obj).put('\n');
  fs::resize_file(obj, kMaxObjFileBytes + 1);
  EXPECT_THAT(objError(obj),
              HasSubstr("huge.obj: is 268435457 bytes, larger than the limit of 268435456 bytes (256 MiB)"));
  EXPECT_THAT(sceneError(meshScene("huge.obj"), folder.path()), HasSubstr("bodies[0].shape.file: OBJ file "));
  EXPECT_THAT(sceneError(meshScene("huge.obj"), folder.path()), HasSubstr("larger than the limit"));
  const fs::path scene = folder.path() / "huge.json";
  std::ofstream(scene).put('{');
  fs::resize_file(scene, kMaxSceneFileBytes + 1);
  EXPECT_THAT(loadError(scene),
              HasSubstr("huge.json: is 67108865 bytes, larger than the limit of 67108864 bytes (64 MiB)"));
  // At the limit, a file is read and parsed: here a scene followed by zero bytes, which JSON refuses.
  std::ofstream(scene, std::ios::trunc) << R"({"format": "collide-scene/1"})";
  fs::resize_file(scene, kMaxSceneFileBytes);
  EXPECT_THAT(loadError(scene), HasSubstr("huge.json: malformed JSON at line 1, column 30"));
}

}  // namespace
}  // namespace collide::scene
