// The commands of the `collide` tool, one file each; command_line.cpp wires them to the command line.
#pragma once

#include <collide/scene/scene.h>

#include <optional>
#include <string>
#include <vector>

// A scene file, or else a built-in scene of that name (`collide run` and `collide bench`).
collide::scene::Scene loadSceneArgument(const std::string& argument,
                                        const collide::scene::LoadOptions& options);

// `collide`: one proxy of every type and what it answers.
int printProxyTable();

struct RunArguments {
  std::string scene = "billiards";  // a file or a built-in name
  std::optional<int> steps;
  std::string record;
  int every = 1;
  std::string events;
  std::string json;
  bool allowOutsidePaths = false;  // LoadOptions::allowOutsidePaths
  std::optional<int> threads;      // the world's workers, over the scene's settings.workers
  std::string snapshot;            // RunOptions::snapshotPath
  int snapshotAt = 0;
  std::string fromSnapshot;  // RunOptions::fromSnapshotPath
};
// `collide run`: runs a scene and prints the summary. Returns 0, or kExitFaults when the world's
// fault guard froze a body during the run (the summary and every output are written all the same).
inline constexpr int kExitFaults = 2;
int runCommand(const RunArguments& arguments);

struct BenchArguments {
  std::string scene = "pyramid";  // a file or a built-in name
  int runs = 3;
  std::optional<int> steps;
  int warmup = 0;  // steps taken before the timed ones, in every run
  bool allowOutsidePaths = false;
  std::optional<int> threads;
};
// `collide bench`: times collide alone on a scene, ms per step, median over runs.
int benchCommand(const BenchArguments& arguments);

// `collide scenes [--export NAME]`.
int scenesCommand(const std::string& exportName);

// `collide fit MESH.obj`: every proxy fitted to the mesh's points, with tightness, memory and cost.
int fitCommand(const std::string& meshPath);

struct QueryArguments {
  std::string scene;  // a file or a built-in name
  int steps = 0;
  std::vector<std::string> ray;      // X,Y,Z DX,DY,DZ
  std::vector<std::string> cast;     // SHAPE.json X,Y,Z DX,DY,DZ
  std::vector<std::string> overlap;  // SHAPE.json X,Y,Z
  bool all = false;                  // every hit of the ray or cast, not only the closest
  bool allowOutsidePaths = false;
};
// `collide query SCENE`: after `steps` steps, one ray, shape cast or overlap; a JSON line per hit,
// nearest first ({"body", "part", "fraction", "distance", "point", "normal"}; overlaps: body, part).
int queryCommand(const QueryArguments& arguments);
