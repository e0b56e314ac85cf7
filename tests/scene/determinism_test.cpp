// Determinism (docs/determinism.md): the same scene run twice in one process gives bit-identical
// final states, for every built-in scene. The step has no hidden state (no global caches, no
// pointer-ordered containers, no result that depends on which worker ran an item), so a second
// World built from the same Scene must follow the first bit for bit. The runs are long enough for contacts to
// form, so the broad phase, the contact cache and the solver's warm start are all in play.
#include <collide/scene/builtin_scenes.h>
#include <collide/scene/runner.h>

#include "builtin_scene_runs.h"

#include <gtest/gtest.h>

#include <string>

namespace collide::scene {
namespace {

class DeterminismOfEveryScene : public testing::TestWithParam<std::string> {};

TEST_P(DeterminismOfEveryScene, TwiceGivesTheSameState) {
  const std::string& name = GetParam();
  const Scene scene = loadBuiltinScene(name);
  RunOptions options;
  options.steps = stepsFor(name);
  const RunSummary first = runScene(scene, options);
  const RunSummary second = runScene(scene, options);
  // The runs must have exercised contacts or joints, or the comparison says little.
  EXPECT_TRUE(first.total.contactPairs > 0u || !scene.constraints.empty());
  EXPECT_EQ(first.stateHash, second.stateHash);
  EXPECT_EQ(first.total.contactPairs, second.total.contactPairs);
  EXPECT_EQ(first.contactEvents, second.contactEvents);
  EXPECT_EQ(first.brokenBodies, second.brokenBodies);
}

INSTANTIATE_TEST_SUITE_P(BuiltinScenes, DeterminismOfEveryScene,
                         testing::ValuesIn(builtinScenesSteppedHere()), sceneTestName);

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
