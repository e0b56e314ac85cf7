// The collide command line (CLI11): the proxy table, the pair table, scene runs and timings, the
// built-in scenes and proxy fitting. Errors print "collide: message" and exit non-zero.
#include "command_line.h"

#include "commands.h"

#include <collide/collide.h>
#include <collide/scene/limits.h>

#include <CLI/CLI.hpp>

#include <charconv>
#include <cstdio>
#include <exception>
#include <string>

namespace {

// Runs of `collide bench`: each rebuilds the world, so a thousand is already hours on a big scene.
constexpr int kMaxRuns = 1000;

// A whole number within [low, high], checked before CLI11 converts it, so that a wrong value gets one
// short line: "--steps: must be a whole number from 0 to 10000000, got abc".
CLI::Validator wholeNumber(long long low, long long high) {
  const std::string range = std::to_string(low) + " to " + std::to_string(high);
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        long long value = 0;
        const char* end = text.data() + text.size();
        const auto [stop, error] = std::from_chars(text.data(), end, value);
        if (text.empty() || error != std::errc() || stop != end || value < low || value > high)
          return "must be a whole number from " + range + ", got " + text;
        return "";
      },
      "from " + range);
}

}  // namespace

int runCollide(int argc, const char* const* argv) try {
  CLI::App app{"collide: collision detection and response for 3D games"};
  app.set_version_flag("--version", collide::kVersion);
  app.require_subcommand(0, 1);

  CLI::App* pairs = app.add_subcommand("pairs", "print the narrow phase's pair table");

  RunArguments run;
  CLI::App* runApp = app.add_subcommand("run", "run a scene file or a built-in scene and print a summary");
  runApp->add_option("scene", run.scene, "scene file (collide-scene/1 JSON) or built-in name")
      ->capture_default_str();
  runApp->add_option("--steps", run.steps, "steps to take (default: the scene's settings.steps)")
      ->check(wholeNumber(0, collide::scene::kMaxSteps));
  CLI::Option* record = runApp->add_option("--record", run.record, "write the frames to this JSON file");
  runApp->add_option("--every", run.every, "record a frame every K steps (and the last)")
      ->check(wholeNumber(1, collide::scene::kMaxSteps))
      ->needs(record)
      ->capture_default_str();
  runApp->add_option("--events", run.events, "write contact events to this JSON Lines file");
  runApp->add_option("--json", run.json, "write the summary to this JSON file");
  runApp->add_flag("--allow-outside-paths", run.allowOutsidePaths,
                   "let the scene read OBJ files outside its folder (absolute, \"..\", links leading out)");
  runApp
      ->add_option("--threads", run.threads,
                   "step with this many workers (default: the scene's settings.workers, 1)")
      ->check(wholeNumber(1, collide::kMaxWorkers));
  CLI::Option* snapshot = runApp->add_option("--snapshot", run.snapshot,
                                             "write a world snapshot to this file (after --snapshot-at)");
  runApp
      ->add_option("--snapshot-at", run.snapshotAt,
                   "the step after which the snapshot is taken (0: before the first)")
      ->check(wholeNumber(0, collide::scene::kMaxSteps))
      ->needs(snapshot)
      ->capture_default_str();
  runApp->add_option("--from-snapshot", run.fromSnapshot,
                     "start from this world snapshot of the same scene instead of its initial state");

  BenchArguments bench;
  CLI::App* benchApp =
      app.add_subcommand("bench", "time collide alone on a scene: ms per step, median over runs");
  benchApp->add_option("scene", bench.scene, "scene file (collide-scene/1 JSON) or built-in name")
      ->capture_default_str();
  benchApp->add_option("--runs", bench.runs, "runs, each on a freshly built world")
      ->check(wholeNumber(1, kMaxRuns))
      ->capture_default_str();
  benchApp->add_option("--steps", bench.steps, "steps per run (default: the scene's settings.steps)")
      ->check(wholeNumber(1, collide::scene::kMaxSteps));
  benchApp
      ->add_option("--warmup", bench.warmup,
                   "steps each run takes before the timed ones (a settled pile, not its first fall)")
      ->check(wholeNumber(0, collide::scene::kMaxSteps))
      ->capture_default_str();
  benchApp->add_flag("--allow-outside-paths", bench.allowOutsidePaths,
                     "let the scene read OBJ files outside its folder (absolute, \"..\", links leading out)");
  benchApp
      ->add_option("--threads", bench.threads,
                   "step with this many workers (default: the scene's settings.workers, 1)")
      ->check(wholeNumber(1, collide::kMaxWorkers));

  std::string exportName;
  CLI::App* scenes = app.add_subcommand("scenes", "list the built-in scenes, or export one as JSON");
  scenes->add_option("--export", exportName, "write this built-in scene's JSON to stdout");

  std::string meshPath;
  CLI::App* fit = app.add_subcommand("fit", "fit every proxy type to a mesh's points and compare them");
  fit->add_option("mesh", meshPath, "a Wavefront OBJ file")->required();

  QueryArguments query;
  CLI::App* queryApp = app.add_subcommand(
      "query",
      "after N steps, cast a ray or a shape, or overlap a shape; one JSON line per hit, nearest first");
  queryApp->add_option("scene", query.scene, "scene file (collide-scene/1 JSON) or built-in name")
      ->required();
  queryApp->add_option("--steps", query.steps, "steps to take first")
      ->check(wholeNumber(0, collide::scene::kMaxSteps))
      ->capture_default_str();
  CLI::Option* ray =
      queryApp->add_option("--ray", query.ray, "a ray from X,Y,Z along DX,DY,DZ (its length is the reach)")
          ->expected(2)
          ->type_name("X,Y,Z DX,DY,DZ");
  CLI::Option* cast =
      queryApp
          ->add_option("--cast", query.cast, "the shape of a JSON file placed at X,Y,Z swept along DX,DY,DZ")
          ->expected(3)
          ->type_name("SHAPE.json X,Y,Z DX,DY,DZ");
  CLI::Option* overlapOption =
      queryApp
          ->add_option("--overlap", query.overlap,
                       "the bodies the shape of a JSON file placed at X,Y,Z overlaps")
          ->expected(2)
          ->type_name("SHAPE.json X,Y,Z");
  ray->excludes(cast)->excludes(overlapOption);
  cast->excludes(overlapOption);
  queryApp->add_flag("--all", query.all,
                     "every hit of the ray or cast, nearest first (default: the closest)");
  queryApp->add_flag("--allow-outside-paths", query.allowOutsidePaths,
                     "let the scene read OBJ files outside its folder (absolute, \"..\", links leading out)");

  CLI11_PARSE(app, argc, argv);
  if (pairs->parsed()) {
    std::printf("%s", collide::describePairTable().c_str());
    return 0;
  }
  if (runApp->parsed()) return runCommand(run);
  if (benchApp->parsed()) return benchCommand(bench);
  if (scenes->parsed()) return scenesCommand(exportName);
  if (fit->parsed()) return fitCommand(meshPath);
  if (queryApp->parsed()) return queryCommand(query);
  return printProxyTable();
} catch (const std::exception& e) {
  std::fprintf(stderr, "collide: %s\n", e.what());
  return 1;
}
