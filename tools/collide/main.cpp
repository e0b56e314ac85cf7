// The collide command line (CLI11): the proxy table, the pair table, scene runs and timings, the
// built-in scenes and proxy fitting. Errors print "collide: message" and exit non-zero.
#include "commands.h"

#include <collide/collide.h>

#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>

int main(int argc, char** argv) try {
  CLI::App app{"collide: collision detection and response for 3D games"};
  app.set_version_flag("--version", collide::kVersion);
  app.require_subcommand(0, 1);

  CLI::App* pairs = app.add_subcommand("pairs", "print the narrow phase's pair table");

  RunArguments run;
  CLI::App* runApp = app.add_subcommand("run", "run a scene file or a built-in scene and print a summary");
  runApp->add_option("scene", run.scene, "scene file (collide-scene/1 JSON) or built-in name")
      ->capture_default_str();
  runApp->add_option("--steps", run.steps, "steps to take (default: the scene's settings.steps)")
      ->check(CLI::NonNegativeNumber);
  CLI::Option* record = runApp->add_option("--record", run.record, "write the frames to this JSON file");
  runApp->add_option("--every", run.every, "record a frame every K steps (and the last)")
      ->check(CLI::PositiveNumber)
      ->needs(record)
      ->capture_default_str();
  runApp->add_option("--events", run.events, "write contact events to this JSON Lines file");
  runApp->add_option("--json", run.json, "write the summary to this JSON file");

  BenchArguments bench;
  CLI::App* benchApp =
      app.add_subcommand("bench", "time collide alone on a scene: ms per step, median over runs");
  benchApp->add_option("scene", bench.scene, "scene file (collide-scene/1 JSON) or built-in name")
      ->capture_default_str();
  benchApp->add_option("--runs", bench.runs, "runs, each on a freshly built world")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  benchApp->add_option("--steps", bench.steps, "steps per run (default: the scene's settings.steps)")
      ->check(CLI::PositiveNumber);

  std::string exportName;
  CLI::App* scenes = app.add_subcommand("scenes", "list the built-in scenes, or export one as JSON");
  scenes->add_option("--export", exportName, "write this built-in scene's JSON to stdout");

  std::string meshPath;
  CLI::App* fit = app.add_subcommand("fit", "fit every proxy type to a mesh's points and compare them");
  fit->add_option("mesh", meshPath, "a Wavefront OBJ file")->required();

  CLI11_PARSE(app, argc, argv);
  if (pairs->parsed()) {
    std::printf("%s", collide::describePairTable().c_str());
    return 0;
  }
  if (runApp->parsed()) return runCommand(run);
  if (benchApp->parsed()) return benchCommand(bench);
  if (scenes->parsed()) return scenesCommand(exportName);
  if (fit->parsed()) return fitCommand(meshPath);
  return printProxyTable();
} catch (const std::exception& e) {
  std::fprintf(stderr, "collide: %s\n", e.what());
  return 1;
}
