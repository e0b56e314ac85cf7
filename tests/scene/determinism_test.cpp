// Determinism (docs/determinism.md): the same scene run twice in one process gives bit-identical
// final states, for every built-in scene. The step has no hidden state (no global caches, no
// pointer-ordered containers, no threads), so a second World built from the same Scene must follow
// the first bit for bit. The runs are long enough for contacts to form, so the broad phase, the
// contact cache and the solver's warm start are all in play.
#include <collide/scene/builtin_scenes.h>
#include <collide/scene/runner.h>

#include "scenes_in_this_build.h"

#include <gtest/gtest.h>

#include <map>
#include <string>

namespace collide::scene {
namespace {

// Steps per scene: 120 (two seconds at 60 Hz) unless the scene is one of the big reference scenes,
// whose first contacts come earlier than that and whose steps cost tens of ms (docs/benchmarks.md).
int stepsFor(std::string_view name) {
  static const std::map<std::string, int, std::less<>> kShorter = {
      {"pile", 30},    {"rain", 40},       {"rain-jittered", 40}, {"terrain", 60},
      {"pyramid", 60}, {"joint-grid", 10}, {"ragdoll-pile", 30},  {"large-pile", 2}};
  const auto it = kShorter.find(name);
  return it == kShorter.end() ? 120 : it->second;
}

TEST(Determinism, EveryBuiltinSceneTwiceGivesTheSameState) {
  for (const BuiltinScene& builtin : builtinScenes()) {
    if (!stepsInThisBuild(builtin.name)) continue;
    SCOPED_TRACE(std::string(builtin.name));
    const Scene scene = loadBuiltinScene(builtin.name);
    RunOptions options;
    options.steps = stepsFor(builtin.name);
    const RunSummary first = runScene(scene, options);
    const RunSummary second = runScene(scene, options);
    // The runs must have exercised contacts or joints, or the comparison says little.
    EXPECT_TRUE(first.total.contactPairs > 0u || !scene.constraints.empty());
    EXPECT_EQ(first.stateHash, second.stateHash);
    EXPECT_EQ(first.total.contactPairs, second.total.contactPairs);
    EXPECT_EQ(first.contactEvents, second.contactEvents);
    EXPECT_EQ(first.brokenBodies, second.brokenBodies);
  }
}

// A scene reloaded from its exported document is the same scene: a fresh parse gives the same run.
TEST(Determinism, ReparsedSceneGivesTheSameState) {
  RunOptions options;
  options.steps = 120;
  const RunSummary fromBuiltin = runScene(loadBuiltinScene("billiards"), options);
  const RunSummary fromText = runScene(parseScene(builtinSceneJson("billiards"), "export"), options);
  EXPECT_EQ(fromBuiltin.stateHash, fromText.stateHash);
}

}  // namespace
}  // namespace collide::scene
