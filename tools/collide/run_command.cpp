// `collide run SCENE` and `collide scenes`: scene files and built-in scenes through the scene
// library (scene/), the summary on stdout, a progress bar on stderr when it is a terminal.
#include "commands.h"

#include <collide/scene/builtin_scenes.h>
#include <collide/scene/runner.h>

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <utility>

using namespace collide;

scene::Scene loadSceneArgument(const std::string& argument, const scene::LoadOptions& options) {
  // A file wins over a built-in of the same name; something path-like that does not exist is a
  // missing file, anything else an unknown built-in (whose message lists the built-ins).
  const std::filesystem::path path(argument);
  const bool pathLike = path.has_parent_path() || path.has_extension();
  return std::filesystem::exists(path) || pathLike ? scene::loadSceneFile(path, options)
                                                   : scene::loadBuiltinScene(argument);
}

int runCommand(const RunArguments& arguments) {
  scene::Scene loaded = loadSceneArgument(
      arguments.scene, scene::LoadOptions{.allowOutsidePaths = arguments.allowOutsidePaths});
  if (arguments.threads) loaded.world.workerCount = *arguments.threads;
  scene::RunOptions options;
  options.steps = arguments.steps;
  options.recordPath = arguments.record;
  options.recordEvery = arguments.every;
  options.eventsPath = arguments.events;
  options.summaryPath = arguments.json;
  options.snapshotPath = arguments.snapshot;
  options.snapshotAt = arguments.snapshotAt;
  options.fromSnapshotPath = arguments.fromSnapshot;
  options.progress = isatty(STDERR_FILENO) != 0;
  const scene::RunSummary summary = scene::runScene(std::move(loaded), options);
  std::printf("%s", scene::formatSummary(summary).c_str());
  if (!summary.faults.empty()) {
    // The outputs are written, but the run did not simulate every body to the end: a script that
    // only reads the exit code must not take it for a clean run.
    std::fprintf(stderr,
                 "collide: %zu %s frozen by the fault guard (state no longer finite); see the summary\n",
                 summary.faults.size(), summary.faults.size() == 1 ? "body was" : "bodies were");
    return kExitFaults;
  }
  return 0;
}

int scenesCommand(const std::string& exportName) {
  if (!exportName.empty()) {
    std::printf("%s", scene::builtinSceneJson(exportName).c_str());
    return 0;
  }
  for (const scene::BuiltinScene& s : scene::builtinScenes()) {
    std::printf("%-16s %.*s\n", std::string(s.name).c_str(), int(s.description.size()), s.description.data());
  }
  return 0;
}
