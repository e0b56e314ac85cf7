// The commands of the `collide` tool, one file each; main.cpp wires them to the command line.
#pragma once

#include <optional>
#include <string>

// `collide`: one proxy of every type and what it answers.
int printProxyTable();

struct RunArguments {
  std::string scene = "billiards";  // a file or a built-in name
  std::optional<int> steps;
  std::string record;
  int every = 1;
  std::string events;
  std::string json;
};
// `collide run`: runs a scene and prints the summary.
int runCommand(const RunArguments& arguments);

// `collide scenes [--export NAME]`.
int scenesCommand(const std::string& exportName);

// `collide fit MESH.obj`: every proxy fitted to the mesh's points, with tightness, memory and cost.
int fitCommand(const std::string& meshPath);
