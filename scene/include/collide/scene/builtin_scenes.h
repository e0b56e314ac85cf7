// The built-in scenes of `collide run NAME`: the reference scenes of docs/benchmarks (B1 billiards,
// R1 pile, R2 rain, R3 pyramid, R4 terrain) and demonstrations (proxies, revert, breakable, chain). Each is
// generated as scene JSON, so it goes through parseScene like a file does and can be exported.
#pragma once

#include <collide/scene/scene.h>

#include <string>
#include <string_view>
#include <vector>

namespace collide::scene {

struct BuiltinScene {
  std::string_view name;
  std::string_view description;
};

std::vector<BuiltinScene> builtinScenes();
bool isBuiltinScene(std::string_view name);
// The scene document (pretty-printed JSON). Throws collide::Error for an unknown name.
std::string builtinSceneJson(std::string_view name);
// The built-in scene through parseScene (source "builtin:NAME"). Throws Error for an unknown name.
Scene loadBuiltinScene(std::string_view name);

}  // namespace collide::scene
