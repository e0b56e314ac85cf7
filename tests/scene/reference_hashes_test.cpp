// Reference state hashes: every built-in scene, stepped for stepsFor(scene) steps
// (builtin_scene_runs.h, as the determinism test steps it), ends in the state recorded here. Refactoring the
// step (moving code between files and layers, splitting functions, renaming) must keep every hash; a change
// that means to change the physics updates this table in the same commit and says why there.
//
// A hash holds for one build only (docs/determinism.md, "Its limits"): these are GCC's Release
// build on x86-64, the build of the README's test command and of CI's first stage. Other builds
// (the sanitized clang -O1 one, Debug) skip the comparison; their runs are still compared with
// each other by DeterminismOfEveryScene.TwiceGivesTheSameState. Every build compares each
// scene's runs at several worker counts with its run at one (kWorkerCounts; large-pile in the
// reference build only).
#include <collide/scene/builtin_scenes.h>
#include <collide/scene/runner.h>

#include "builtin_scene_runs.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

namespace collide::scene {
namespace {

struct ReferenceRun {
  std::string_view scene;
  std::uint64_t stateHash;
};

constexpr ReferenceRun kReferenceRuns[] = {
    {"billiards", 0x72ce044392ccc8d0},      {"pile", 0x5c4ce0fd6d05ace3},
    {"rain", 0xdface9156540e385},           {"rain-jittered", 0xe3486d671c6ec022},
    {"pyramid", 0x740868d17186d5b5},        {"terrain", 0x1b7588b4d6446760},
    {"proxies", 0xeeaf803d7014a034},        {"revert", 0xb3ef4055efa0bcdf},
    {"revert-project", 0xad04b72d62555a76}, {"revert-soft", 0x947cd53baaa59032},
    {"breakable", 0x48e3d966f1d1186c},      {"chain", 0x32cbd4d6a4bb1ebf},
    {"tunneling", 0xa9851618eb31fa67},      {"pendulum", 0x3103546b80f70646},
    {"bridge", 0xa1a3c113fd69f59b},         {"ragdolls", 0x3787fbe7f03e5bb5},
    {"machine", 0xc70c01c589203282},        {"joint-grid", 0x59cf60525bfbd3b9},
    {"ragdoll-pile", 0x267f0b556ff9d603},   {"large-pile", 0xdc38a4a372127d4f},
    {"character", 0xcfcb44a29ffb3652},
};

std::string hex(std::uint64_t value) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(value));
  return text;
}

TEST(ReferenceHashes, EveryBuiltinSceneHasATableEntry) {
  for (const BuiltinScene& builtin : builtinScenes()) {
    bool found = false;
    for (const ReferenceRun& run : kReferenceRuns) found = found || run.scene == builtin.name;
    EXPECT_TRUE(found) << "no reference hash for built-in scene " << builtin.name;
  }
}

TEST(ReferenceHashes, EveryBuiltinSceneEndsInItsRecordedState) {
#ifndef COLLIDE_REFERENCE_BUILD
  GTEST_SKIP() << "the recorded hashes are those of GCC's Release build on x86-64";
#endif
  for (const ReferenceRun& run : kReferenceRuns) {
    SCOPED_TRACE(std::string(run.scene));
    RunOptions options;
    options.steps = stepsFor(run.scene);
    const RunSummary summary = runScene(loadBuiltinScene(run.scene), options);
    EXPECT_EQ(hex(summary.stateHash), hex(run.stateHash));
  }
}

// The step's parallel stages split their work so that no item depends on who ran it: at every
// worker count, each scene ends in the state it ends in on one (in every build).
// The reference build tries 2, 3, 4 and 8 workers. The sanitized and other builds, five to ten times
// slower, try 3 (ranges that do not split evenly) and 8 (more workers than cores, and for the small
// scenes more than ranges): under the sanitizers the point is the memory and the races of the
// threaded stages, which both counts reach.
#ifdef COLLIDE_REFERENCE_BUILD
constexpr int kWorkerCounts[] = {2, 3, 4, 8};
#else
constexpr int kWorkerCounts[] = {3, 8};
#endif

class WorkerCountsOfEveryScene : public testing::TestWithParam<std::string> {};

TEST_P(WorkerCountsOfEveryScene, EndInTheStateOfOneWorker) {
  const std::string& name = GetParam();
  RunOptions options;
  options.steps = stepsFor(name);
  const Scene scene = loadBuiltinScene(name);
  const std::uint64_t oneWorker = runScene(scene, options).stateHash;
  for (const int workers : kWorkerCounts) {
    SCOPED_TRACE(std::to_string(workers) + " workers");
    Scene threaded = scene;
    threaded.world.workerCount = workers;
    EXPECT_EQ(hex(runScene(threaded, options).stateHash), hex(oneWorker));
  }
}

INSTANTIATE_TEST_SUITE_P(BuiltinScenes, WorkerCountsOfEveryScene,
                         testing::ValuesIn(builtinScenesSteppedHere()), sceneTestName);

}  // namespace
}  // namespace collide::scene
