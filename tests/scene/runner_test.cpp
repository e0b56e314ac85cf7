// The runner: determinism, the pair funnel of the billiard shot, the outputs, breakable bodies.
#include <collide/scene/builtin_scenes.h>
#include <collide/scene/runner.h>

#include <nlohmann/json.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <utility>

#include <unistd.h>

#include "support/scene_data.h"

namespace collide::scene {
namespace {

using collide::test::kSceneData;

std::filesystem::path scratch(const std::string& name) {
  return std::filesystem::temp_directory_path() /
         ("collide_scene_test_" + std::to_string(::getpid()) + "_" + name);
}

TEST(Runner, SameSceneTwiceGivesTheSameHash) {
  const Scene billiards = loadBuiltinScene("billiards");
  RunOptions options;
  options.steps = 60;
  const RunSummary first = runScene(billiards, options);
  const RunSummary second = runScene(billiards, options);
  EXPECT_EQ(first.stateHash, second.stateHash);
  // And the hash sees the state: fewer steps, another hash.
  options.steps = 59;
  EXPECT_NE(runScene(billiards, options).stateHash, first.stateHash);
}

// The lecture's argument for a broad phase: most potential pairs never touch. In the break shot,
// 21 bodies make 210 potential pairs a step; the balls touch the cloth and, in the rack, each other.
// A scene handed over (runScene(Scene&&), as `collide run` does) frees its body definitions once the
// world is built: the run is the same, bit for bit, and the scene's memory is what the run still reads.
TEST(Runner, AHandedOverSceneRunsAlikeAndFreesItsBodies) {
  for (const char* name : {"breakable", "character", "pile"}) {
    SCOPED_TRACE(name);
    RunOptions options;
    options.steps = 40;
    const Scene kept = loadBuiltinScene(name);
    const RunSummary held = runScene(kept, options);
    Scene handed = loadBuiltinScene(name);
    const RunSummary freed = runScene(std::move(handed), options);
    EXPECT_EQ(freed.stateHash, held.stateHash);
    EXPECT_EQ(freed.contactEvents, held.contactEvents);
    EXPECT_EQ(freed.dynamicBodies, held.dynamicBodies);
    EXPECT_LT(freed.sceneMemory, held.sceneMemory / 2);
  }
}

TEST(Runner, BilliardsContactsAreFewOfThePotentialPairs) {
  RunOptions options;
  options.steps = 120;
  const RunSummary s = runScene(loadBuiltinScene("billiards"), options);
  EXPECT_EQ(s.dynamicBodies, 16);
  EXPECT_EQ(s.staticBodies, 5);
  EXPECT_EQ(s.lastStep.potentialPairs, 21u * 20u / 2u);
  EXPECT_EQ(s.total.potentialPairs, 120u * 210u);
  EXPECT_GE(s.total.keptPairs, s.total.narrowPhaseTests);
  EXPECT_GE(s.total.narrowPhaseTests, s.total.contactPairs);
  // The 16 balls stay on the cloth: at least 16 contacts every step.
  EXPECT_GE(s.total.contactPairs, 120u * 16u);
  EXPECT_LT(s.total.contactPairs * 4, s.total.potentialPairs);
}

TEST(Runner, CueBallMomentumGoesIntoTheRack) {
  // Before the cue ball arrives (about 0.2 s), momentum is the cue ball's alone, minus what the
  // cloth's friction took; after the break the rack carries it forward (+x), until its first ball
  // reaches a cushion (step 24, 0.4 s) and comes back.
  RunOptions options;
  options.steps = 20;
  const RunSummary s = runScene(loadBuiltinScene("billiards"), options);
  EXPECT_GT(s.momentum.x, 0.0f);
  EXPECT_LT(s.momentum.x, 0.17f * 6.0f);
}

TEST(Runner, RecordingAndEventsFollowTheFormat) {
  const auto record = scratch("record.json"), events = scratch("events.jsonl");
  RunOptions options;
  options.steps = 25;
  options.recordPath = record.string();
  options.recordEvery = 10;
  options.eventsPath = events.string();
  const Scene scene = loadSceneFile(kSceneData + "/small_drop.json");
  const RunSummary s = runScene(scene, options);

  std::ifstream recordFile(record);
  const auto doc = nlohmann::json::parse(recordFile);
  EXPECT_FLOAT_EQ(doc["dt"].get<float>(), 1.0f / 60.0f);
  // Frames at steps 0, 10, 20 and always the last (25).
  ASSERT_EQ(doc["frames"].size(), 4u);
  EXPECT_EQ(doc["frames"][1]["step"], 10);
  EXPECT_EQ(doc["frames"][3]["step"], 25);
  EXPECT_NEAR(doc["frames"][3]["time"].get<double>(), 25.0 / 60.0, 1e-6);
  const auto& ball = doc["frames"][0]["bodies"][1];
  EXPECT_EQ(ball["name"], "ball");
  EXPECT_EQ(ball["position"], nlohmann::json::array({0, 0.6, 0}));
  EXPECT_EQ(ball["rotation"], nlohmann::json::array({0, 0, 0, 1}));
  for (const char* key : {"velocity", "angular_velocity"}) EXPECT_TRUE(ball.contains(key));

  // The ball starts 0.1 m above the ground and lands: one begin event, ball against ground.
  std::ifstream eventsFile(events);
  std::string line;
  int begins = 0;
  while (std::getline(eventsFile, line)) {
    const auto e = nlohmann::json::parse(line);
    for (const char* key : {"step", "type", "a", "b", "point", "normal", "impulse", "speed"}) {
      EXPECT_TRUE(e.contains(key)) << key;
    }
    if (e["type"] == "begin") {
      ++begins;
      EXPECT_TRUE((e["a"] == "ground" && e["b"] == "ball") || (e["a"] == "ball" && e["b"] == "ground"))
          << line;
      EXPECT_GT(e["speed"].get<float>(), 0.5f);  // fell 0.1 m: about 1.4 m/s
    }
  }
  EXPECT_EQ(begins, 1);
  EXPECT_EQ(s.contactEvents, 1u);
  std::filesystem::remove(record);
  std::filesystem::remove(events);
}

// A ball falls through a sensor slab: the events file has the sensor's begin and end, naming the
// sensor first and the visitor second, marked as sensor events (scene-format.md, "--events").
TEST(Runner, EventsFileHasSensorOverlaps) {
  const auto events = scratch("sensor_events.jsonl");
  const Scene scene = parseScene(R"({ "format": "collide-scene/1",
    "settings": { "dt": 0.016666667, "steps": 60 },
    "bodies": [
      { "name": "gate", "type": "static", "sensor": true,
        "shape": { "type": "box", "half_extents": [2, 0.25, 2] }, "position": [0, 1, 0] },
      { "name": "ball", "type": "dynamic", "shape": { "type": "sphere", "radius": 0.2 },
        "position": [0, 2.1, 0] } ] })",
                                 "sensor_drop");
  RunOptions options;
  options.steps = 60;
  options.eventsPath = events.string();
  runScene(scene, options);
  std::ifstream eventsFile(events);
  std::string line;
  std::vector<std::pair<std::string, int>> sensorLines;
  while (std::getline(eventsFile, line)) {
    const auto e = nlohmann::json::parse(line);
    if (!e.contains("sensor")) continue;
    EXPECT_EQ(e["sensor"], true);
    EXPECT_EQ(e["a"], "gate");
    EXPECT_EQ(e["b"], "ball");
    sensorLines.emplace_back(e["type"].get<std::string>(), e["step"].get<int>());
  }
  ASSERT_EQ(sensorLines.size(), 2u);
  EXPECT_EQ(sensorLines[0].first, "begin");
  EXPECT_EQ(sensorLines[1].first, "end");
  // After n steps of dt in 6 substeps (symplectic Euler) the ball has fallen g dt^2 n (n + 1/6) / 2.
  // It overlaps the slab once fallen 0.65 m (after 22 steps; 21 give 0.630 m) until fallen 1.55 m
  // (after 34 steps; 33 give 1.491 m), and a step's sensor test sees the poses the step starts from.
  EXPECT_EQ(sensorLines[0].second, 23);
  EXPECT_EQ(sensorLines[1].second, 35);
  std::filesystem::remove(events);
}

// A gravity of -3e38 m/s^2 is finite, but the ball's velocity overflows within a hundred steps: the
// fault guard freezes it, and the events file says so once.
TEST(Runner, EventsFileHasFaults) {
  const auto events = scratch("fault_events.jsonl");
  const Scene scene = parseScene(R"({ "format": "collide-scene/1",
    "settings": { "dt": 0.016666667, "steps": 100, "gravity": [0, -3e38, 0] },
    "bodies": [ { "name": "ball", "type": "dynamic", "shape": { "type": "sphere", "radius": 0.5 } } ] })",
                                 "overflow");
  RunOptions options;
  options.steps = 100;
  options.eventsPath = events.string();
  runScene(scene, options);
  std::ifstream eventsFile(events);
  std::string line;
  int faults = 0;
  while (std::getline(eventsFile, line)) {
    const auto e = nlohmann::json::parse(line);
    if (e["type"] != "fault") continue;
    ++faults;
    EXPECT_EQ(e["a"], "ball");
    EXPECT_GT(e["step"].get<int>(), 1);
    EXPECT_THAT(e["fields"].get<std::vector<std::string>>(), ::testing::Contains("linear_velocity"));
  }
  EXPECT_EQ(faults, 1);
  std::filesystem::remove(events);
}

// A 10 kg box on a ball joint that breaks above 50 N: the joint breaks in the first step (the box's
// weight is 98 N), once, and the events file names it, its bodies and its load.
TEST(Runner, EventsFileHasJointBreaks) {
  const auto events = scratch("joint_break_events.jsonl");
  const Scene scene = parseScene(R"({ "format": "collide-scene/1",
    "settings": { "dt": 0.016666667, "steps": 30 },
    "bodies": [ { "name": "hook", "type": "static", "shape": { "type": "sphere", "radius": 0.05 }, "position": [0, 3, 0] },
                { "name": "box", "type": "dynamic", "mass": 10, "shape": { "type": "box", "half_extents": [0.2, 0.2, 0.2] },
                  "position": [0, 2.5, 0] } ],
    "constraints": [ { "type": "ball", "name": "weak link", "a": "hook", "b": "box", "anchor": [0, 3, 0],
                       "break_force": 50 } ] })",
                                 "breaking");
  RunOptions options;
  options.steps = 30;
  options.eventsPath = events.string();
  const RunSummary summary = runScene(scene, options);
  EXPECT_EQ(summary.brokenJoints, 1);
  std::ifstream eventsFile(events);
  std::string line;
  int breaks = 0;
  while (std::getline(eventsFile, line)) {
    const auto e = nlohmann::json::parse(line);
    if (e["type"] != "joint_break") continue;
    ++breaks;
    EXPECT_EQ(e["step"], 1);
    EXPECT_EQ(e["joint"], "weak link");
    EXPECT_EQ(e["a"], "hook");
    EXPECT_EQ(e["b"], "box");
    EXPECT_GT(e["force"].get<double>(), 50.0);
  }
  EXPECT_EQ(breaks, 1);
  std::filesystem::remove(events);
}

// A run whose bodies the fault guard froze says so: a kinetic energy of 0 J at the end is not a
// pile at rest. overflow_fault.json flings two boxes at each other at 3e38 m/s.
TEST(Runner, FaultsAreInTheSummaryAndItsJson) {
  const RunSummary s = runScene(loadSceneFile(kSceneData + "/overflow_fault.json"));
  ASSERT_EQ(s.faults.size(), 2u);
  EXPECT_EQ(s.faults[0].step, 1);
  EXPECT_TRUE(s.faults[0].fields & FaultEvent::kLinearVelocity);
  EXPECT_THAT((std::vector<std::string>{s.faults[0].body, s.faults[1].body}),
              ::testing::UnorderedElementsAre("a", "b"));
  const std::string table = formatSummary(s);
  EXPECT_THAT(table, ::testing::HasSubstr("faults          2 bodies frozen by the fault guard"));
  EXPECT_THAT(table, ::testing::HasSubstr(s.faults[0].body + " at step 1: "));
  const auto j = nlohmann::json::parse(summaryJson(s));
  ASSERT_EQ(j["faults"].size(), 2u);
  EXPECT_EQ(j["faults"][0]["body"], s.faults[0].body);
  EXPECT_EQ(j["faults"][0]["step"], 1);
  EXPECT_THAT(j["faults"][0]["fields"].get<std::vector<std::string>>(),
              ::testing::Contains("linear_velocity"));

  // A run without faults says nothing of them, and its JSON has an empty list.
  RunOptions options;
  options.steps = 5;
  const RunSummary clean = runScene(loadBuiltinScene("billiards"), options);
  EXPECT_THAT(formatSummary(clean), ::testing::Not(::testing::HasSubstr("fault")));
  EXPECT_TRUE(nlohmann::json::parse(summaryJson(clean))["faults"].empty());
}

TEST(Runner, SummaryJsonHasTheTablesNumbers) {
  RunOptions options;
  options.steps = 5;
  const Scene billiards = loadBuiltinScene("billiards");  // kept: the scene's memory holds its bodies
  const RunSummary s = runScene(billiards, options);
  const auto j = nlohmann::json::parse(summaryJson(s));
  EXPECT_EQ(j["steps"], 5);
  EXPECT_EQ(j["bodies"]["dynamic"], 16);
  EXPECT_EQ(j["total"]["potential_pairs"], 5 * 210);
  EXPECT_EQ(j["last_step"]["contact_pairs"], s.lastStep.contactPairs);
  EXPECT_EQ(j["state_hash"].get<std::string>().size(), 16u);
  const std::string table = formatSummary(s);
  EXPECT_THAT(table, ::testing::HasSubstr("potential n(n-1)/2"));
  EXPECT_THAT(table, ::testing::HasSubstr("21: 5 static, 0 kinematic, 16 dynamic"));
  // The time by stage: in the table, and in the JSON adding up to its total.
  EXPECT_THAT(table, ::testing::HasSubstr("time by stage"));
  const auto& stages = j["total"]["stage_seconds"];
  double sum = 0.0;
  for (const char* stage : {"broad_phase", "narrow_phase", "solve", "continuous", "events", "islands"})
    sum += stages[stage].get<double>();
  EXPECT_NEAR(stages["total"].get<double>(), sum, 1e-12);
  EXPECT_NEAR(stages["total"].get<double>(), s.total.time.total(), 1e-12);
  EXPECT_LE(s.total.time.total(), s.wallSeconds);
  // The heap by stage: in the table, and in the JSON as the world reports it.
  EXPECT_THAT(table, ::testing::HasSubstr("heap at the end"));
  const auto& memory = j["memory_bytes"];
  std::size_t world = 0;
  for (const char* category : {"bodies", "broad_phase", "contacts", "solver", "joints", "islands"})
    world += memory[category].get<std::size_t>();
  EXPECT_EQ(memory["world"].get<std::size_t>(), world);
  EXPECT_EQ(world, s.worldMemory.total());
  EXPECT_GE(memory["bodies"].get<std::size_t>(), 21 * sizeof(BodyDef));  // far more per body in fact
  EXPECT_GE(memory["scene"].get<std::size_t>(), 21 * sizeof(Body));      // the scene's bodies
}

TEST(Runner, BreakableWallLosesBricksToTheBall) {
  RunOptions options;
  options.steps = 90;
  const RunSummary s = runScene(loadBuiltinScene("breakable"), options);
  EXPECT_GT(s.brokenBodies, 0);
  EXPECT_LT(s.brokenBodies, 45);  // the ball makes a hole, not the weight of the wall
  // Without the ball nothing breaks: the bricks' own weight stays under the threshold.
  Scene quiet = loadBuiltinScene("breakable");
  quiet.bodies.pop_back();
  EXPECT_EQ(runScene(quiet, options).brokenBodies, 0);
}

TEST(Runner, BadOptionsAreRefused) {
  const Scene scene = loadBuiltinScene("billiards");
  RunOptions options;
  options.steps = -1;
  EXPECT_THROW(runScene(scene, options), Error);
  options.steps = 1;
  options.recordEvery = 0;
  options.recordPath = scratch("never.json").string();
  EXPECT_THROW(runScene(scene, options), Error);
  options.recordEvery = 1;
  options.recordPath = "/nonexistent-dir/x.json";
  EXPECT_THROW(runScene(scene, options), Error);
}

}  // namespace
}  // namespace collide::scene
