// Recordings read back (collide/scene/recording.h): what `collide run --record` writes gives the
// run's poses back bit for bit, and what is not a recording is refused naming the field.
#include <collide/scene/builtin_scenes.h>
#include <collide/scene/recording.h>
#include <collide/scene/runner.h>
#include <collide/scene/scene.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <map>
#include <string>

namespace collide::scene {
namespace {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

bool sameBits(const Vec3& a, const Vec3& b) { return std::memcmp(&a, &b, sizeof a) == 0; }
bool sameBits(const Quat& a, const Quat& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(Recording, GivesTheRunsPosesBackBitForBit) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "collide_recording_test.json";
  const Scene scene = loadBuiltinScene("ragdolls");
  RunOptions options;
  options.steps = 60;
  options.recordPath = path.string();
  runScene(scene, options);
  const Recording recording = loadRecording(path);
  std::filesystem::remove(path);
  ASSERT_EQ(recording.frames.size(), 61u);  // step 0 and every step after it
  EXPECT_EQ(recording.dt, scene.dt);
  EXPECT_EQ(recording.frames.back().step, 60);

  SceneWorld world = buildWorld(scene);
  for (int i = 0; i < 60; ++i) world.world.step(scene.dt);
  std::map<std::string, BodyId> byName;
  for (const BodyId id : world.bodies) byName[world.world.name(id)] = id;
  ASSERT_EQ(recording.frames.back().bodies.size(), world.bodies.size());
  for (const RecordedBody& body : recording.frames.back().bodies) {
    SCOPED_TRACE(body.name);
    const BodyId id = byName.at(body.name);
    const Transform t = world.world.transform(id);
    EXPECT_TRUE(sameBits(body.position, t.position));
    EXPECT_TRUE(sameBits(body.rotation, t.rotation));
    EXPECT_TRUE(sameBits(body.velocity, world.world.linearVelocity(id)));
  }
}

TEST(Recording, WhatIsNotARecordingIsRefusedNamingTheField) {
  const auto refused = [](const std::string& text, const std::string& message) {
    EXPECT_THAT([&] { parseRecording(text, "rec.json"); }, ThrowsMessage<Error>(HasSubstr(message))) << text;
  };
  const std::string body =
      R"({"name": "box", "position": [0, 1, 0], "rotation": [0, 0, 0, 1], "velocity": [0, 0, 0], )"
      R"("angular_velocity": [0, 0, 0]})";
  EXPECT_EQ(parseRecording(R"({"dt": 0.5, "frames": [{"step": 0, "time": 0, "bodies": [)" + body + "]}]}")
                .frames.front()
                .bodies.front()
                .name,
            "box");
  refused("[1, 2]", "rec.json: a recording must be a JSON object");
  refused(R"({"dt": -1, "frames": []})", "rec.json: dt: ");
  refused(
      R"({"dt": 0.5, "frames": [{"step": 0, "time": 0, "bodies": [{"name": "box", "position": [0, 1, 0], )"
      R"("rotation": [0, 0, 0, 2], "velocity": [0, 0, 0], "angular_velocity": [0, 0, 0]}]}]})",
      "rec.json: frames[0].bodies[0].rotation: must be a unit quaternion");
  refused(
      R"({"dt": 0.5, "frames": [{"step": 3, "time": 0, "bodies": []}, {"step": 2, "time": 0, "bodies": []}]})",
      "rec.json: frames[1].step: must come after the last frame's step 3, got 2");
  refused(R"({"dt": 0.5, "frames": [{"step": 0, "time": 0}]})",
          "rec.json: frames[0].bodies: missing required field");
  refused(R"({"dt": 0.5, "frames": [)", "rec.json: malformed JSON");
}

}  // namespace
}  // namespace collide::scene
