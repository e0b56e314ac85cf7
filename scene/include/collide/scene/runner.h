// Runs a scene: steps its World and reports what `collide run` writes (docs/scene-format.md, "What
// collide run writes"): the summary, a recording of frames, contact events as JSON Lines, and a hash
// of the final state for determinism checks.
//
// Breakable bodies (our extension, the lecture's "ad-hoc effects" driven by collision events): each
// contact begin event adds its impulse to the damage of the breakable bodies it involves; a body
// whose damage exceeds its break_impulse is removed after the step.
#pragma once

#include <collide/scene/scene.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace collide::scene {

struct RunOptions {
  std::optional<int> steps;  // default: the scene's settings.steps
  std::string recordPath;    // empty: no recording
  int recordEvery = 1;
  std::string eventsPath;   // empty: no events file
  std::string summaryPath;  // empty: no summary file (summaryJson)
  bool progress = false;    // a progress bar on stderr
  // A world snapshot (World::saveSnapshot) written to snapshotPath after step snapshotAt (0: before
  // the first), and one read from fromSnapshotPath into the scene's world before the first step: the
  // run goes on from the saved state, its steps counted from 1 again. The scene must be the one the
  // snapshot was saved from (its bodies' names and ids); the breakable bodies' damage starts at zero.
  std::string snapshotPath;  // empty: no snapshot written
  int snapshotAt = 0;
  std::string fromSnapshotPath;  // empty: the scene's own initial state
};

struct RunSummary {
  std::string scene;
  int steps = 0;
  float dt = 0.0f;
  double wallSeconds = 0.0;
  int staticBodies = 0;
  int kinematicBodies = 0;
  int dynamicBodies = 0;
  int brokenBodies = 0;
  int brokenJoints = 0;  // joints whose load passed their break force or torque
  // Dynamic bodies at the end (broken ones left out); with sleeping off every one is awake.
  bool sleeping = false;  // the scene's settings.sleeping
  int awakeBodies = 0;
  int asleepBodies = 0;
  StepStats lastStep{};
  StepStats total{};
  std::uint64_t contactEvents = 0;
  // Bodies the world's fault guard froze because their state stopped being finite (FaultEvent), in
  // the order reported: the body's name, the step, and which parts of its state were bad.
  struct Fault {
    std::string body;
    int step = 0;
    std::uint8_t fields = 0;  // FaultEvent's bits
  };
  std::vector<Fault> faults;
  Vec3 momentum{0.0f};
  float kineticEnergy = 0.0f;
  std::uint64_t stateHash = 0;
  // The heap the world holds at the end of the run (its arrays only grow), and the scene's.
  WorldMemory worldMemory{};
  std::size_t sceneMemory = 0;
  // The scene's characters at the end: where they are, how they stand, how far along their paths.
  struct CharacterEnd {
    std::string name;
    Vec3 position{0.0f};  // the capsule's feet
    GroundState ground = GroundState::InAir;
    std::size_t waypointsReached = 0;
    std::size_t waypoints = 0;
  };
  std::vector<CharacterEnd> characters;
};

// Builds the scene's World and runs it. Throws collide::Error for a scene the World refuses, a
// negative step count, recordEvery < 1, or an output file that cannot be written. The output paths
// are checked (checkOutputPaths) and opened before the first step; each output is written through a
// temporary file (OutputFile) and replaces its target only when every output is complete, so a run
// that fails leaves the files at the targets as they were.
RunSummary runScene(const Scene& scene, const RunOptions& options = {});
// The same with the scene handed over: its body definitions (a pile's thousands of shapes, names
// and settings) are freed once the world is built and what the run reads of them is taken (names,
// break thresholds), so that the process does not hold every body twice while it steps.
RunSummary runScene(Scene&& scene, const RunOptions& options = {});

// FNV-1a over the bit patterns of every live body's position, rotation and velocities, in scene
// order: equal hashes mean bit-identical final states.
std::uint64_t stateHash(const SceneWorld& world);

// The parts of a state a FaultEvent names: "position", "rotation", "linear_velocity",
// "angular_velocity".
std::vector<std::string> faultFieldNames(std::uint8_t fields);

std::string formatSummary(const RunSummary& summary);  // the table printed on stdout
std::string summaryJson(const RunSummary& summary);    // the same as a JSON document

}  // namespace collide::scene
