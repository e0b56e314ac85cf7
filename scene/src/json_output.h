// Numbers for the JSON outputs: floats written with the fewest digits (at most 9) that round-trip
// the float, rather than the 17 of the double they are widened to.
#pragma once

#include <collide/math.h>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstdlib>

namespace collide::scene {

inline nlohmann::json jsonNumber(float value) {
  // The shortest of 6..9 significant digits that reads back as the same float (0.6f as 0.6).
  char text[32];
  for (int digits = 6; digits <= 9; ++digits) {
    std::snprintf(text, sizeof text, "%.*g", digits, static_cast<double>(value));
    if (std::strtof(text, nullptr) == value) break;
  }
  return std::strtod(text, nullptr);
}
inline nlohmann::json jsonVec3(const Vec3& v) { return {jsonNumber(v.x), jsonNumber(v.y), jsonNumber(v.z)}; }
// glTF order [x, y, z, w], as scene files.
inline nlohmann::json jsonQuat(const Quat& q) {
  return {jsonNumber(q.x), jsonNumber(q.y), jsonNumber(q.z), jsonNumber(q.w)};
}

}  // namespace collide::scene
