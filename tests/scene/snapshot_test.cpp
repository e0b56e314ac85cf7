// World snapshots (World::saveSnapshot / loadSnapshot, docs/snapshots.md): a world loaded from a
// snapshot continues bit-identically to the one that saved it, in every built-in scene; the same
// state gives the same bytes; and what is not a snapshot of this build, or not whole, is refused by
// name without changing the world.
#include <collide/scene/builtin_scenes.h>
#include <collide/scene/runner.h>
#include <collide/scene/scene.h>

#include "builtin_scene_runs.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <vector>

namespace collide::scene {
namespace {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

// A world loaded from `snapshot`, with the saved world's ids (they stay valid), for stateHash.
SceneWorld loaded(const SceneWorld& saved, const std::vector<std::uint8_t>& snapshot, int workers = 1) {
  WorldDef def;
  def.workerCount = workers;
  SceneWorld copy{World(def), saved.bodies, saved.constraints};
  copy.world.loadSnapshot(snapshot);
  return copy;
}

// Saved after `before` steps, then both worlds step `after` more: the same state, bit for bit, and the
// loaded world saves the bytes it was loaded from.
void expectContinuesIdentically(const std::string& name, int before, int after, int workers = 1) {
  const Scene scene = loadBuiltinScene(name);
  SceneWorld original = buildWorld(scene);
  const float dt = scene.dt;
  for (int i = 0; i < before; ++i) original.world.step(dt);
  const std::vector<std::uint8_t> snapshot = original.world.saveSnapshot();
  SceneWorld restored = loaded(original, snapshot, workers);
  EXPECT_EQ(restored.world.saveSnapshot(), snapshot) << "loaded, then saved: other bytes";
  EXPECT_EQ(stateHash(restored), stateHash(original)) << "right after loading";
  for (int i = 0; i < after; ++i) {
    original.world.step(dt);
    restored.world.step(dt);
  }
  EXPECT_EQ(stateHash(restored), stateHash(original))
      << name << ": saved at step " << before << ", compared at " << before + after;
  EXPECT_EQ(restored.world.saveSnapshot(), original.world.saveSnapshot());
}

class SnapshotOfEveryScene : public testing::TestWithParam<std::string> {};

// Every built-in scene: saved once its first contacts are made, both worlds stepped as long again.
TEST_P(SnapshotOfEveryScene, ContinuesBitIdentically) {
  const int steps = stepsFor(GetParam());
  expectContinuesIdentically(GetParam(), steps, steps);
}

INSTANTIATE_TEST_SUITE_P(BuiltinScenes, SnapshotOfEveryScene, testing::ValuesIn(snapshotScenesHere()),
                         sceneTestName);

// The long run: saved at step 100, both to 400, in the scenes of joints, sleep, impacts and stacks.
TEST(Snapshot, SavedAtStep100TheWorldsAgreeAtStep400) {
  for (const char* name : {"ragdolls", "bridge", "billiards", "chain", "machine"}) {
    SCOPED_TRACE(name);
    expectContinuesIdentically(name, 100, 300);
  }
}

TEST(Snapshot, LoadsIntoAWorldOfAnotherWorkerCount) {
  expectContinuesIdentically("ragdolls", 60, 60, 3);
  expectContinuesIdentically("pyramid", 30, 30, 2);
}

TEST(Snapshot, TheSameStateGivesTheSameBytes) {
  SceneWorld a = buildWorld(loadBuiltinScene("proxies"));
  SceneWorld b = buildWorld(loadBuiltinScene("proxies"));
  for (int i = 0; i < 60; ++i) {
    a.world.step(1.0f / 60.0f);
    b.world.step(1.0f / 60.0f);
  }
  EXPECT_EQ(a.world.saveSnapshot(), b.world.saveSnapshot());
  EXPECT_EQ(a.world.saveSnapshot(), a.world.saveSnapshot());
}

TEST(Snapshot, TheLoadingWorldKeepsItsCallbacks) {
  SceneWorld original = buildWorld(loadBuiltinScene("pyramid"));
  const std::vector<std::uint8_t> snapshot = original.world.saveSnapshot();
  World world;
  int filtered = 0;
  world.setPairFilter([&](BodyId, BodyId) {
    ++filtered;
    return true;
  });
  world.loadSnapshot(snapshot);
  world.step(1.0f / 60.0f);
  EXPECT_GT(filtered, 0) << "the pair filter set before loading still runs";
}

// ---- What is refused. ----

// The payload's checksum made right again after a change, as a crafted snapshot would have it.
void resign(std::vector<std::uint8_t>& snapshot) {
  constexpr std::size_t kHeader = 8 + 4 + 4 + 8 + 8 + 8;
  std::uint64_t hash = 0xcbf29ce484222325ull;
  for (std::size_t i = kHeader; i < snapshot.size(); ++i) hash = (hash ^ snapshot[i]) * 0x100000001b3ull;
  std::memcpy(snapshot.data() + kHeader - 8, &hash, 8);
}

std::vector<std::uint8_t> ragdollSnapshot() {
  SceneWorld sw = buildWorld(loadBuiltinScene("ragdolls"));
  for (int i = 0; i < 40; ++i) sw.world.step(1.0f / 60.0f);
  return sw.world.saveSnapshot();
}

TEST(Snapshot, WhatIsNotAWholeSnapshotOfThisBuildIsRefusedByName) {
  const std::vector<std::uint8_t> good = ragdollSnapshot();
  World world;
  const auto refusedWith = [&](std::vector<std::uint8_t> bytes, const std::string& message) {
    EXPECT_THAT([&] { world.loadSnapshot(bytes); }, ThrowsMessage<Error>(HasSubstr(message))) << message;
  };
  refusedWith({}, "not a collide world snapshot");
  refusedWith(std::vector<std::uint8_t>(good.begin() + 1, good.end()), "not a collide world snapshot");
  std::vector<std::uint8_t> bytes = good;
  bytes[8] = 9;  // the format version
  refusedWith(bytes, "format version 9");
  bytes = good;
  bytes[16] ^= 0x40;  // the layout fingerprint
  refusedWith(bytes, "with other fields than this build");
  bytes = good;
  bytes.resize(bytes.size() - 100);
  refusedWith(bytes, "truncated or padded");
  bytes = good;
  bytes[bytes.size() / 2] ^= 0x01;
  refusedWith(bytes, "corrupt: its checksum does not match");
  // Crafted, with the checksum made right: the contents are checked field by field and as a whole.
  bytes = good;
  bytes.resize(bytes.size() - 7);
  std::uint64_t size = bytes.size() - 40;
  std::memcpy(bytes.data() + 24, &size, 8);
  resign(bytes);
  refusedWith(bytes, "truncated: the payload ends inside it");
  EXPECT_EQ(world.bodyCount(), 0u) << "a refused snapshot changes nothing";
}

// Random changes to the contents, the checksum made right each time: each snapshot is taken or
// refused with an Error, never a crash (the sanitized build runs this too), and a world refused one
// is the world it was.
TEST(Snapshot, CraftedContentsAreTakenOrRefusedNeverACrash) {
  const std::vector<std::uint8_t> good = ragdollSnapshot();
  SceneWorld keeper = buildWorld(loadBuiltinScene("billiards"));
  const std::uint64_t before = stateHash(keeper);
  std::mt19937 rng(7);
  std::uniform_int_distribution<std::size_t> at(40, good.size() - 1);
  std::uniform_int_distribution<int> byte(0, 255);
  int taken = 0, refused = 0;
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<std::uint8_t> bytes = good;
    for (int changes = 1 + trial % 4; changes > 0; --changes)
      bytes[at(rng)] = static_cast<std::uint8_t>(byte(rng));
    resign(bytes);
    World world;
    try {
      world.loadSnapshot(bytes);
      ++taken;
      for (int i = 0; i < 3; ++i) world.step(1.0f / 60.0f);
    } catch (const Error& e) {
      ++refused;
      EXPECT_THAT(e.what(), ::testing::StartsWith("snapshot: "));
    }
    try {
      keeper.world.loadSnapshot(bytes.size() > 60 ? std::vector<std::uint8_t>(bytes.begin(), bytes.end() - 1)
                                                  : bytes);
    } catch (const Error&) {
    }
  }
  EXPECT_GT(refused, 0);
  EXPECT_GT(taken, 0) << "a changed float is still a world";
  EXPECT_EQ(stateHash(keeper), before) << "refused snapshots left the world as it was";
}

}  // namespace
}  // namespace collide::scene
