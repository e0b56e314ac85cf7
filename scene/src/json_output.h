// Numbers for the JSON outputs: floats written with the 9 significant digits that round-trip a
// float, rather than the 17 of the double they are widened to.
#pragma once

#include <collide/math.h>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstdlib>

namespace collide::scene {

inline nlohmann::json jsonNumber(float value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", static_cast<double>(value));
  return std::strtod(text, nullptr);
}
inline nlohmann::json jsonVec3(const Vec3& v) { return {jsonNumber(v.x), jsonNumber(v.y), jsonNumber(v.z)}; }
// glTF order [x, y, z, w], as scene files.
inline nlohmann::json jsonQuat(const Quat& q) {
  return {jsonNumber(q.x), jsonNumber(q.y), jsonNumber(q.z), jsonNumber(q.w)};
}

}  // namespace collide::scene
