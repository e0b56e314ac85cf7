// Scene -> World: distance constraints and sleeping from scene files behave as the World's own
// (a pendulum keeps its length and swings to the height it started from, default lengths are the
// anchors' distance at load time, a dropped box falls asleep), and the World's refusals keep the
// field path.
#include <collide/scene/runner.h>
#include <collide/scene/scene.h>

#include <nlohmann/json.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

namespace collide::scene {
namespace {

using ::testing::HasSubstr;

// A particle bob on a rigid 1.5 m constraint from a static pivot, released 60 degrees from vertical.
constexpr const char* kPendulum = R"({"format": "collide-scene/1",
  "bodies": [
    {"name": "pivot", "type": "static", "shape": {"type": "sphere", "radius": 0.05}, "position": [0, 3, 0]},
    {"name": "bob", "type": "dynamic", "particle": true, "mass": 1,
     "shape": {"type": "sphere", "radius": 0.1}, "position": [1.29903811, 2.25, 0]}],
  "constraints": [{"type": "distance", "a": "pivot", "b": "bob", "length": 1.5}]})";

TEST(SceneWorld, PendulumFromAFileHoldsItsLength) {
  SceneWorld sw = buildWorld(parseScene(kPendulum, "pendulum.json"));
  ASSERT_EQ(sw.constraints.size(), 1u);
  const JointId rope = sw.constraints[0];
  EXPECT_FLOAT_EQ(sw.world.constraintLength(rope), 1.5f);
  float worstStretch = 0.0f, leftmost = 1.3f;
  for (int step = 0; step < 120; ++step) {  // 2 s: most of one period (2.6 s at 60 degrees)
    sw.world.step(1.0f / 60.0f);
    worstStretch = std::max(worstStretch, std::abs(sw.world.constraintCurrentLength(rope) - 1.5f) / 1.5f);
    leftmost = std::min(leftmost, sw.world.transform(sw.bodies[1]).position.x);
  }
  EXPECT_LT(worstStretch, 0.01f);
  // Energy brings the bob to the mirror of its start, x = -1.299; the constraint must not eat it.
  EXPECT_LT(leftmost, -1.2f);
}

TEST(SceneWorld, ABallJointFromAFileHoldsItsRodOnThePivot) {
  // A 1 m rod hung by its top end at (0, 3, 0), turned 60 degrees about z: it swings through the
  // bottom to the mirror of its start, its top end on the pivot. The ball joint's bodies do not
  // collide by default, and its fields are its own.
  const Scene s = parseScene(R"({"format": "collide-scene/1",
    "bodies": [
      {"name": "pivot", "type": "static", "shape": {"type": "sphere", "radius": 0.05}, "position": [0, 3, 0]},
      {"name": "rod", "type": "dynamic", "mass": 1, "shape": {"type": "box", "half_extents": [0.01, 0.5, 0.01]},
       "position": [0.43301270, 2.75, 0], "rotation": [0, 0, 0.5, 0.86602540]}],
    "constraints": [{"type": "ball", "a": "pivot", "b": "rod", "anchor": [0, 3, 0]}]})",
                             "ball.json");
  ASSERT_EQ(s.constraints.size(), 1u);
  EXPECT_EQ(s.constraints[0].type, JointType::Ball);
  EXPECT_FALSE(s.constraints[0].collideConnected);
  SceneWorld sw = buildWorld(s);
  const JointId joint = sw.constraints[0];
  EXPECT_EQ(sw.world.jointType(joint), JointType::Ball);
  EXPECT_LT(sw.world.constraintCurrentLength(joint), 1e-5f);
  float worstGap = 0.0f, leftmost = 0.5f;
  for (int step = 0; step < 90; ++step) {  // 1.5 s: past the far turn (a period is 1.8 s at 60 degrees)
    sw.world.step(1.0f / 60.0f);
    worstGap = std::max(worstGap, sw.world.constraintCurrentLength(joint));
    leftmost = std::min(leftmost, sw.world.transform(sw.bodies[1]).position.x);
  }
  EXPECT_LT(worstGap, 0.005f);
  EXPECT_LT(leftmost, -0.40f);  // the mirror of x = 0.433, less what damping took

  // A ball joint's fields are its own, its anchor is required, and the joint types collide lacks
  // are unknown, each refused naming the field.
  const auto refusal = [](const std::string& constraint) {
    try {
      parseScene(R"({"format": "collide-scene/1",
        "bodies": [{"name": "p", "type": "static", "shape": {"type": "sphere", "radius": 1}},
                   {"name": "q", "type": "dynamic", "shape": {"type": "sphere", "radius": 1}}],
        "constraints": [)" +
                     constraint + "]}",
                 "bad.json");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_THAT(refusal(R"({"type": "ball", "a": "p", "b": "q", "anchor": [0, 0, 0], "length": 1})"),
              HasSubstr("constraints[0].length: unknown field"));
  EXPECT_THAT(refusal(R"({"type": "ball", "a": "p", "b": "q"})"),
              HasSubstr("constraints[0].anchor: missing required field"));
  EXPECT_THAT(refusal(R"({"type": "weld", "a": "p", "b": "q", "anchor": [0, 0, 0]})"),
              HasSubstr("unknown constraint type \"weld\""));
  EXPECT_THAT(refusal(R"({"type": "hinge", "a": "p", "b": "q", "anchor": [0, 0, 0]})"),
              HasSubstr("constraints[0].axis: missing required field"));
  EXPECT_THAT(refusal(R"({"type": "hinge", "a": "p", "b": "q", "anchor": [0, 0, 0], "axis": [0, 0, 0]})"),
              HasSubstr("constraints[0].axis: must be a non-zero direction"));
  EXPECT_THAT(refusal(R"({"type": "hinge", "a": "p", "b": "q", "anchor": [0, 0, 0], "axis": [0, 0, 1],
                          "limits": [1, -1]})"),
              HasSubstr("constraints[0].limits: lower must be <= upper"));
  EXPECT_THAT(refusal(R"({"type": "slider", "a": "p", "b": "q", "anchor": [0, 0, 0], "axis": [1, 0, 0],
                          "motor": {"speed": 1, "max_torque": 3}})"),
              HasSubstr("constraints[0].motor.max_torque: unknown field"));
  EXPECT_THAT(
      refusal(R"({"type": "cone", "a": "p", "b": "q", "anchor": [0, 0, 0], "axis": [1, 0, 0], "swing": 4})"),
      HasSubstr("constraints[0].swing: must be within [0, pi]"));
  EXPECT_THAT(refusal(R"({"type": "fixed", "a": "p", "b": "q", "break_force": 0})"),
              HasSubstr("constraints[0].break_force"));
}

TEST(SceneWorld, EveryJointTypeFromAFileGetsItsFields) {
  // A door on a hinge with limits and a motor, a slider, a weld, a cone and a rope, each read into
  // the World's joint with the file's fields.
  const Scene s = parseScene(R"({"format": "collide-scene/1",
    "bodies": [
      {"name": "frame", "type": "static", "shape": {"type": "box", "half_extents": [0.1, 0.1, 0.1]}, "position": [0, 3, 0]},
      {"name": "door", "type": "dynamic", "mass": 10, "shape": {"type": "box", "half_extents": [0.5, 0.025, 0.4]},
       "position": [0.5, 1, 0]},
      {"name": "carriage", "type": "dynamic", "shape": {"type": "box", "half_extents": [0.1, 0.1, 0.1]}, "position": [3, 3, 0]},
      {"name": "plate", "type": "dynamic", "shape": {"type": "box", "half_extents": [0.1, 0.1, 0.1]}, "position": [3, 3.2, 0]},
      {"name": "arm", "type": "dynamic", "shape": {"type": "box", "half_extents": [0.5, 0.05, 0.05]}, "position": [-0.5, 3, 0]},
      {"name": "weight", "type": "dynamic", "shape": {"type": "sphere", "radius": 0.1}, "position": [0, 2.5, 2]}],
    "constraints": [
      {"type": "hinge", "a": "frame", "b": "door", "anchor": [0, 1, 0], "axis": [0, 0, 1],
       "limits": [-0.7853982, 0.7853982], "motor": {"speed": 0, "max_torque": 1}, "name": "trapdoor"},
      {"type": "slider", "a": "frame", "b": "carriage", "anchor": [3, 3, 0], "axis": [1, 0, 0],
       "limits": [-1, 1], "motor": {"speed": 0.5, "max_force": 20}, "break_force": 1000, "friction": 3},
      {"type": "fixed", "a": "carriage", "b": "plate", "stiffness": 5, "damping": 0.7, "break_torque": 200},
      {"type": "cone", "a": "frame", "b": "arm", "anchor": [0, 3, 0], "axis": [-1, 0, 0], "swing": 0.5,
       "twist": [-0.2, 0.3], "collide_connected": true, "friction": 0.5},
      {"type": "distance", "a": "frame", "b": "weight", "limits": [0, 2.5], "break_force": 100000}]})",
                             "joints.json");
  SceneWorld sw = buildWorld(s);
  ASSERT_EQ(sw.constraints.size(), 5u);
  World& w = sw.world;
  const JointId hinge = sw.constraints[0], slider = sw.constraints[1], fixed = sw.constraints[2],
                cone = sw.constraints[3], rope = sw.constraints[4];
  EXPECT_EQ(w.jointType(hinge), JointType::Hinge);
  EXPECT_EQ(w.jointLimits(hinge), (JointLimits{true, -0.7853982f, 0.7853982f}));
  EXPECT_EQ(w.jointMotor(hinge), (JointMotor{true, 0.0f, 1.0f}));
  EXPECT_FALSE(w.jointCollideConnected(hinge));
  EXPECT_EQ(w.jointType(slider), JointType::Slider);
  EXPECT_EQ(w.jointMotor(slider), (JointMotor{true, 0.5f, 20.0f}));
  EXPECT_EQ(w.jointBreakForce(slider), 1000.0f);
  EXPECT_EQ(w.jointFriction(slider), 3.0f);
  EXPECT_EQ(w.jointFriction(hinge), 0.0f);
  EXPECT_EQ(w.jointType(fixed), JointType::Fixed);
  EXPECT_EQ(w.jointSoftness(fixed), (JointSoftness{5.0f, 0.7f}));
  EXPECT_EQ(w.jointAngularSoftness(fixed), (JointSoftness{5.0f, 0.7f}));
  EXPECT_EQ(w.jointBreakTorque(fixed), 200.0f);
  EXPECT_EQ(w.jointType(cone), JointType::Cone);
  EXPECT_EQ(w.coneSwingLimit(cone), 0.5f);
  EXPECT_EQ(w.jointLimits(cone), (JointLimits{true, -0.2f, 0.3f}));
  EXPECT_TRUE(w.jointCollideConnected(cone));
  EXPECT_EQ(w.jointFriction(cone), 0.5f);
  EXPECT_EQ(w.jointType(rope), JointType::Distance);
  EXPECT_EQ(w.jointLimits(rope), (JointLimits{true, 0.0f, 2.5f}));
  EXPECT_EQ(w.jointBreakForce(rope), 100000.0f);
  EXPECT_NEAR(w.jointAxis(cone).x, -1.0f, 1e-6f);
  // The door falls onto its lower limit; the carriage's motor drives it to its upper end.
  for (int step = 0; step < 240; ++step) w.step(1.0f / 60.0f);
  EXPECT_NEAR(w.jointPosition(hinge), -0.7853982f, 0.02f);
  EXPECT_NEAR(w.jointPosition(slider), 1.0f, 0.01f);
  EXPECT_LT(w.jointPosition(rope), 2.5f * 1.006f);
}

TEST(SceneWorld, DefaultLengthIsTheAnchorsDistanceAtLoad) {
  // Anchors are local points: the box turned 90 degrees about z carries its anchor (0.5, 0, 0) to
  // (2, 1.5, 0); the ceiling's (0, -0.5, 0) is at (0, 2.5, 0): sqrt(2^2 + 1^2) apart. Unset anchors
  // are centres of mass: the corner tetrahedron's is (0.25, 0.25, 0.25) from its origin.
  const Scene s = parseScene(R"({"format": "collide-scene/1",
    "bodies": [
      {"name": "ceiling", "type": "static", "shape": {"type": "box", "half_extents": [1, 0.5, 1]},
       "position": [0, 3, 0]},
      {"name": "crate", "type": "dynamic", "shape": {"type": "box", "half_extents": [0.5, 0.2, 0.2]},
       "position": [2, 1, 0], "rotation": [0, 0, 0.70710678, 0.70710678]},
      {"name": "gem", "type": "dynamic", "position": [3, 0, 0],
       "shape": {"type": "convex_hull", "points": [[0,0,0],[1,0,0],[0,1,0],[0,0,1]]}}],
    "constraints": [
      {"type": "distance", "a": "ceiling", "b": "crate", "anchor_a": [0, -0.5, 0], "anchor_b": [0.5, 0, 0]},
      {"type": "distance", "a": "ceiling", "b": "gem", "compliance": 0.01}]})");
  const SceneWorld sw = buildWorld(s);
  ASSERT_EQ(sw.constraints.size(), 2u);
  EXPECT_NEAR(sw.world.constraintLength(sw.constraints[0]), std::sqrt(5.0f), 1e-5f);
  EXPECT_NEAR(sw.world.constraintLength(sw.constraints[1]), glm::length(Vec3(3.25f, -2.75f, 0.25f)), 1e-5f);
}

// A unit box dropped from 1 m onto the ground: falling at first, resting (hence asleep, after the
// 0.5 s time to sleep) well within 3 s; with sleeping off the same box stays awake.
std::string droppedBox(bool sleeping) {
  return std::string(R"({"format": "collide-scene/1", "settings": {"sleeping": )") +
         (sleeping ? "true" : "false") + R"(},
    "bodies": [
      {"name": "ground", "type": "static", "shape": {"type": "box", "half_extents": [10, 0.5, 10]},
       "position": [0, -0.5, 0]},
      {"name": "box", "type": "dynamic", "shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5]},
       "position": [0, 1.5, 0]}]})";
}

TEST(SceneWorld, SleepingPutsADroppedBoxToSleep) {
  for (const bool sleeping : {true, false}) {
    SCOPED_TRACE(sleeping ? "sleeping on" : "sleeping off");
    const Scene scene = parseScene(droppedBox(sleeping), "drop.json");
    EXPECT_EQ(scene.world.sleeping, sleeping);
    SceneWorld sw = buildWorld(scene);
    const BodyId box = sw.bodies[1];
    for (int step = 0; step < 18; ++step) sw.world.step(scene.dt);  // 0.3 s: still falling
    EXPECT_TRUE(sw.world.isAwake(box));
    EXPECT_LT(sw.world.linearVelocity(box).y, -2.0f);
    for (int step = 18; step < 180; ++step) sw.world.step(scene.dt);
    EXPECT_EQ(sw.world.isAwake(box), !sleeping);
    EXPECT_NEAR(sw.world.transform(box).position.y, 0.5f, 0.01f);  // resting on the ground
  }
}

TEST(SceneWorld, SummaryAndRecordingReportSleepingBodies) {
  RunOptions options;
  options.steps = 180;
  options.recordEvery = 60;
  options.recordPath = (std::filesystem::temp_directory_path() /
                        ("collide_scene_test_" + std::to_string(::getpid()) + "_sleep_record.json"))
                           .string();
  const RunSummary asleep = runScene(parseScene(droppedBox(true), "drop.json"), options);
  EXPECT_TRUE(asleep.sleeping);
  EXPECT_EQ(asleep.awakeBodies, 0);
  EXPECT_EQ(asleep.asleepBodies, 1);
  EXPECT_THAT(formatSummary(asleep), HasSubstr("0 awake, 1 asleep"));
  const auto summary = nlohmann::json::parse(summaryJson(asleep));
  EXPECT_EQ(summary["sleeping"]["asleep"], 1);
  // The recording: the box awake in the first frame (t = 0), asleep in the last (t = 3 s).
  std::ifstream in(options.recordPath);
  const auto record = nlohmann::json::parse(in);
  std::filesystem::remove(options.recordPath);
  ASSERT_EQ(record["frames"].size(), 4u);
  EXPECT_EQ(record["frames"][0]["bodies"][1]["awake"], true);
  EXPECT_EQ(record["frames"][3]["bodies"][1]["awake"], false);
  EXPECT_EQ(record["frames"][3]["bodies"][0]["awake"], false);  // static
  options.recordPath.clear();
  const RunSummary awake = runScene(parseScene(droppedBox(false), "drop.json"), options);
  EXPECT_FALSE(awake.sleeping);
  EXPECT_EQ(awake.awakeBodies, 1);
  EXPECT_EQ(awake.asleepBodies, 0);
}

TEST(SceneWorldErrors, WorldRefusalsNameTheConstraint) {
  // Two static bodies: nothing the constraint could move. The World refuses, the path stays.
  try {
    buildWorld(parseScene(R"({"format": "collide-scene/1", "bodies": [
        {"name": "a", "type": "static", "shape": {"type": "sphere", "radius": 1}},
        {"name": "b", "type": "static", "shape": {"type": "sphere", "radius": 1}, "position": [3, 0, 0]},
        {"name": "c", "type": "dynamic", "shape": {"type": "sphere", "radius": 1}, "position": [6, 0, 0]}],
        "constraints": [{"type": "distance", "a": "a", "b": "c"}, {"type": "distance", "a": "a", "b": "b"}]})",
                          "statics.json"));
    ADD_FAILURE() << "a constraint between two static bodies was accepted";
  } catch (const Error& e) {
    EXPECT_THAT(
        std::string(e.what()),
        HasSubstr("statics.json: constraints[1]: distance constraint: a and b: at least one body must be "
                  "dynamic, got static and static"));
  }
  // A Scene assembled in code skips the parser's name check; buildWorld still names the field.
  Scene s = parseScene(R"({"format": "collide-scene/1", "bodies": [
      {"name": "a", "type": "dynamic", "shape": {"type": "sphere", "radius": 1}}]})",
                       "code");
  Constraint unknown;
  unknown.a = "a";
  unknown.b = "x";
  s.constraints.push_back(unknown);
  try {
    buildWorld(s);
    ADD_FAILURE() << "an unknown body name was accepted";
  } catch (const Error& e) {
    EXPECT_THAT(std::string(e.what()), HasSubstr("code: constraints[0].b: unknown body \"x\""));
  }
}

}  // namespace
}  // namespace collide::scene
