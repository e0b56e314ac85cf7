// The built-in scenes the per-scene tests step, and for how long. Each per-scene test is one
// gtest per scene (a value-parameterised suite over builtinScenesSteppedHere()), so ctest and the
// sanitized stage's shards spread the scenes over the cores, and a failure names its scene.
#pragma once

#include <collide/scene/builtin_scenes.h>

#include <gtest/gtest.h>

#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace collide::scene {

// Steps per scene: 120 (two seconds at 60 Hz) unless the scene is one of the big reference scenes,
// whose first contacts come earlier than that and whose steps cost tens of ms (docs/benchmarks.md).
inline int stepsFor(std::string_view name) {
  static const std::map<std::string, int, std::less<>> kShorter = {
      {"pile", 30},    {"rain", 40},       {"rain-jittered", 40}, {"terrain", 60},
      {"pyramid", 60}, {"joint-grid", 10}, {"ragdoll-pile", 30},  {"large-pile", 2}};
  const auto it = kShorter.find(name);
  return it == kShorter.end() ? 120 : it->second;
}

// large-pile's 100,000 bodies and joint-grid's 19,800 joints cost minutes under the sanitizers and
// in Debug: the per-scene tests step them in the reference build only (GCC's Release build, the
// README's test command and CI's first stage), where they take seconds. The joints' code runs under
// the sanitizers in the other joint scenes (pendulum, bridge, ragdolls, machine, ragdoll-pile).
inline bool stepsInThisBuild(std::string_view scene) {
#ifdef COLLIDE_REFERENCE_BUILD
  (void)scene;
  return true;
#else
  return scene != "large-pile" && scene != "joint-grid";
#endif
}

inline std::vector<std::string> builtinScenesSteppedHere() {
  std::vector<std::string> names;
  for (const BuiltinScene& builtin : builtinScenes()) {
    if (stepsInThisBuild(builtin.name)) names.emplace_back(builtin.name);
  }
  return names;
}

// The scenes the snapshot round trip steps (scene/snapshot_test.cpp): in the reference build every
// one; under the sanitizers and in Debug not the big reference scenes as well (their thousands of
// bodies take a minute of the sanitized run, and the smaller scenes hold every shape type, joint
// type and response the snapshot code reads and writes).
inline std::vector<std::string> snapshotScenesHere() {
  std::vector<std::string> names;
  for (std::string& name : builtinScenesSteppedHere()) {
#ifndef COLLIDE_REFERENCE_BUILD
    if (name == "pile" || name == "rain" || name == "rain-jittered" || name == "terrain" ||
        name == "ragdoll-pile")
      continue;
#endif
    names.push_back(std::move(name));
  }
  return names;
}

// A gtest name for a scene's test ("rain-jittered" -> "rain_jittered": names take letters, digits
// and underscores only).
inline std::string sceneTestName(const testing::TestParamInfo<std::string>& info) {
  std::string name = info.param;
  for (char& c : name) {
    if (c == '-') c = '_';
  }
  return name;
}

}  // namespace collide::scene
