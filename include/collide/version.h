// The library's version (semantic versioning: a new minor version may add to the API, a new major
// version may change it). CMake reads the project's version from this file, so it is the one place
// where the number is written; CHANGELOG.md lists what each version holds.
#pragma once

#define COLLIDE_VERSION_MAJOR 0
#define COLLIDE_VERSION_MINOR 1
#define COLLIDE_VERSION_PATCH 0

#define COLLIDE_VERSION_TEXT_(major, minor, patch) #major "." #minor "." #patch
#define COLLIDE_VERSION_TEXT(major, minor, patch) COLLIDE_VERSION_TEXT_(major, minor, patch)

namespace collide {
inline constexpr int kVersionMajor = COLLIDE_VERSION_MAJOR;
inline constexpr int kVersionMinor = COLLIDE_VERSION_MINOR;
inline constexpr int kVersionPatch = COLLIDE_VERSION_PATCH;
inline constexpr const char* kVersion =
    COLLIDE_VERSION_TEXT(COLLIDE_VERSION_MAJOR, COLLIDE_VERSION_MINOR, COLLIDE_VERSION_PATCH);
}  // namespace collide
