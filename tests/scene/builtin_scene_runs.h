// Which built-in scenes the per-scene loops step in this build.
#pragma once

#include <string_view>

namespace collide::scene {

// large-pile's 100,000 bodies cost minutes under the sanitizers and in Debug: the loops over every
// built-in scene step it in the reference build only (GCC's Release build, the README's test
// command and CI's first stage), where it takes seconds.
inline bool stepsInThisBuild(std::string_view scene) {
#ifdef COLLIDE_REFERENCE_BUILD
  (void)scene;
  return true;
#else
  return scene != "large-pile";
#endif
}

}  // namespace collide::scene
