// The folder of the scene tests' data files (tests/scene/data), set by CMake.
#pragma once

#include <string>

namespace collide::test {

inline const std::string kSceneData = COLLIDE_SCENE_TEST_DATA;

}  // namespace collide::test
