// Values written into error messages the way the API's messages show them: "got -1",
// "got (0, nan, 0)".
#pragma once

#include <collide/math.h>

#include <sstream>
#include <string>

namespace collide::detail {

inline std::string formatFloat(float value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

inline std::string formatVec(const Vec3& v) {
  std::ostringstream out;
  out << "(" << v.x << ", " << v.y << ", " << v.z << ")";
  return out.str();
}

}  // namespace collide::detail
