// The outputs of a run lose nothing the user owns: a path that is an input of the run or another
// output is refused before the run, every write and the close are checked, and a target is replaced
// only by a complete file.
#include "support/scene_data.h"
#include "support/temp_folder.h"

#include <collide/scene/output_file.h>
#include <collide/scene/runner.h>
#include <collide/scene/scene.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>

namespace collide::scene {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

using collide::test::kSceneData;

using test::TempFolder;

std::string contents(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void writeText(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// The message of the Error that `action` throws ("" if it does not throw).
std::string errorOf(const std::function<void()>& action) {
  try {
    action();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// small_drop.json and the cube.obj it reads, copied into `folder`.
Scene smallDropIn(const fs::path& folder) {
  fs::copy_file(kSceneData + "/small_drop.json", folder / "small_drop.json");
  fs::copy_file(kSceneData + "/cube.obj", folder / "cube.obj");
  return loadSceneFile(folder / "small_drop.json");
}

TEST(OutputFile, CommitReplacesTheTargetWithTheCompleteFile) {
  TempFolder folder;
  const fs::path target = folder.path() / "out.json";
  writeText(target, "old");
  fs::permissions(target, fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  OutputFile out(target, "summary");
  out.write("new ");
  EXPECT_EQ(contents(target), "old");  // untouched while writing
  out.write("text");
  out.commit();
  EXPECT_EQ(contents(target), "new text");
  EXPECT_EQ(fs::status(target).permissions(),
            fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  EXPECT_EQ(folder.files(), 1u);  // no temporary file left
}

TEST(OutputFile, AnUncommittedFileLeavesTheTargetUntouched) {
  TempFolder folder;
  const fs::path target = folder.path() / "out.json";
  writeText(target, "old");
  {
    OutputFile out(target, "summary");
    out.write(std::string(1 << 20, 'x'));  // past the buffer: written to the temporary file
  }
  EXPECT_EQ(contents(target), "old");
  EXPECT_EQ(folder.files(), 1u);
  {
    OutputFile out(folder.path() / "new.json", "summary");
    out.write("x");
  }
  EXPECT_EQ(folder.files(), 1u);  // nothing created either
}

TEST(OutputFile, ASymbolicLinkIsFollowedAndKept) {
  TempFolder folder;
  writeText(folder.path() / "real.json", "old");
  fs::create_symlink("real.json", folder.path() / "link.json");
  OutputFile out(folder.path() / "link.json", "summary");
  out.write("new");
  out.commit();
  EXPECT_TRUE(fs::is_symlink(folder.path() / "link.json"));
  EXPECT_EQ(contents(folder.path() / "real.json"), "new");
}

TEST(OutputFile, AFullDeviceFailsNamingTheFile) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  // A small write fails at the close, a large one while writing; neither replaces /dev/full.
  EXPECT_THAT(errorOf([] {
                OutputFile out("/dev/full", "events");
                out.write("{}\n");
                out.commit();
              }),
              HasSubstr("events file /dev/full: cannot be written: No space left on device"));
  EXPECT_THAT(errorOf([] {
                OutputFile out("/dev/full", "recording");
                out.write(std::string(1 << 20, 'x'));
              }),
              HasSubstr("recording file /dev/full: cannot be written"));
  EXPECT_TRUE(fs::is_character_file("/dev/full"));
  // A device is written directly: /dev/null takes the output.
  OutputFile null("/dev/null", "events");
  null.write("x");
  EXPECT_NO_THROW(null.commit());
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
}

TEST(OutputFile, AFolderThatCannotBeWrittenFailsAtOnce) {
  EXPECT_THAT(errorOf([] { OutputFile out("/no-such-folder/out.json", "summary"); }),
              HasSubstr("summary file /no-such-folder/out.json: cannot be written"));
}

TEST(CheckOutputPaths, TheScenesOwnFilesAreRefused) {
  TempFolder folder;
  const Scene scene = smallDropIn(folder.path());
  EXPECT_EQ(scene.file, folder.path() / "small_drop.json");
  ASSERT_EQ(scene.objFiles.size(), 1u);
  EXPECT_TRUE(fs::equivalent(scene.objFiles[0], folder.path() / "cube.obj"));

  const fs::path sceneFile = folder.path() / "small_drop.json";
  EXPECT_THAT(errorOf([&] {
                checkOutputPaths(scene, {{"recording", sceneFile}});
              }),
              HasSubstr("recording file " + sceneFile.string() + ": is the scene file being run"));
  // Spelled differently, through a link, or as a hard link: the same file.
  const fs::path dotted = folder.path() / "." / "small_drop.json";
  EXPECT_THAT(errorOf([&] {
                checkOutputPaths(scene, {{"summary", dotted}});
              }),
              HasSubstr("is the scene file"));
  fs::create_symlink("small_drop.json", folder.path() / "link.json");
  EXPECT_THAT(errorOf([&] {
                checkOutputPaths(scene, {{"summary", folder.path() / "link.json"}});
              }),
              HasSubstr("is the scene file"));
  fs::create_hard_link(folder.path() / "small_drop.json", folder.path() / "hard.json");
  EXPECT_THAT(errorOf([&] {
                checkOutputPaths(scene, {{"summary", folder.path() / "hard.json"}});
              }),
              HasSubstr("is the scene file"));
  EXPECT_THAT(errorOf([&] {
                checkOutputPaths(scene, {{"events", folder.path() / "cube.obj"}});
              }),
              HasSubstr("events file " + (folder.path() / "cube.obj").string() + ": is the OBJ file"));
  EXPECT_EQ(errorOf([&] { checkOutputPaths(scene, {{"events", folder.path() / "events.jsonl"}}); }), "");
}

TEST(CheckOutputPaths, TwoOutputsNeedTwoPaths) {
  TempFolder folder;
  const Scene scene = smallDropIn(folder.path());
  const fs::path a = folder.path() / "a.json";
  EXPECT_THAT(errorOf([&] {
                checkOutputPaths(scene, {{"recording", a}, {"events", ""}, {"summary", a}});
              }),
              HasSubstr("summary file " + a.string() + ": is also the recording file"));
  // Not yet existing, spelled differently: still the same path.
  fs::create_directory(folder.path() / "x");
  EXPECT_THAT(
      errorOf([&] {
        checkOutputPaths(scene, {{"recording", a}, {"events", folder.path() / "x" / ".." / "a.json"}});
      }),
      HasSubstr("is also the recording file"));
  EXPECT_EQ(errorOf([&] {
              checkOutputPaths(scene, {{"recording", "/dev/null"}, {"events", "/dev/null"}});
            }),
            "");
}

TEST(CheckOutputPaths, MissingFoldersAndDirectoriesAreRefused) {
  TempFolder folder;
  const Scene scene = smallDropIn(folder.path());
  const fs::path missing = folder.path() / "missing" / "out.json";
  EXPECT_THAT(errorOf([&] {
                checkOutputPaths(scene, {{"summary", missing}});
              }),
              HasSubstr("summary file " + missing.string() + ": cannot be written: the folder " +
                        (folder.path() / "missing").string() + " does not exist"));
  EXPECT_THAT(errorOf([&] {
                checkOutputPaths(scene, {{"recording", folder.path()}});
              }),
              HasSubstr("is a directory, not a file"));
  EXPECT_THAT(errorOf([&] {
                checkOutputPaths(scene, {{"recording", folder.path() / "cube.obj" / "x.json"}});
              }),
              HasSubstr("is not a folder"));
}

TEST(RunSceneOutputs, AFailedRunLeavesEveryTargetAsItWas) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  TempFolder folder;
  const Scene scene = smallDropIn(folder.path());
  const fs::path events = folder.path() / "events.jsonl", summary = folder.path() / "summary.json";
  writeText(events, "old events");
  writeText(summary, "old summary");
  RunOptions options;
  options.recordPath = "/dev/full";
  options.eventsPath = events.string();
  options.summaryPath = summary.string();
  EXPECT_THAT(errorOf([&] { runScene(scene, options); }),
              HasSubstr("recording file /dev/full: cannot be written"));
  EXPECT_EQ(contents(events), "old events");
  EXPECT_EQ(contents(summary), "old summary");
  EXPECT_EQ(folder.files(), 4u);  // the scene, the OBJ file and the two outputs: no temporary file left

  // The same run with every output writable replaces them.
  options.recordPath = (folder.path() / "record.json").string();
  runScene(scene, options);
  EXPECT_THAT(contents(summary), HasSubstr("\"state_hash\""));
  EXPECT_THAT(contents(folder.path() / "record.json"), HasSubstr("\"frames\""));
}

TEST(RunSceneOutputs, AnOutputOverAnInputIsRefusedBeforeTheRun) {
  TempFolder folder;
  const Scene scene = smallDropIn(folder.path());
  const std::string before = contents(folder.path() / "small_drop.json");
  RunOptions options;
  options.recordPath = (folder.path() / "small_drop.json").string();
  EXPECT_THAT(errorOf([&] { runScene(scene, options); }), HasSubstr("is the scene file being run"));
  EXPECT_EQ(contents(folder.path() / "small_drop.json"), before);
}

}  // namespace
}  // namespace collide::scene
