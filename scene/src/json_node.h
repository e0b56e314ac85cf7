// A JSON value together with its path in the document ("bodies[3].shape.radius"), so that every
// check can say which field is wrong and what it holds. Jolt-style validation: bad input becomes a
// collide::Error with a message, never a crash or a silently defaulted value.
#pragma once

#include <collide/error.h>
#include <collide/math.h>

#include <nlohmann/json.hpp>

#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace collide::scene {

using Json = nlohmann::json;

class JsonNode {
 public:
  JsonNode(const Json& value, std::string path, const std::string& source)
      : value_(&value), path_(std::move(path)), source_(&source) {}

  const Json& value() const { return *value_; }
  const std::string& path() const { return path_; }

  // Throws Error("SOURCE: PATH: message").
  [[noreturn]] void fail(const std::string& message) const;
  // The value as it was written (strings quoted), for "got ..." in messages.
  std::string shown() const;

  // ---- Objects. ----
  // Checks that this is an object whose keys are all in `known`.
  void expectObject(std::initializer_list<std::string_view> known) const;
  bool has(std::string_view key) const;
  JsonNode at(std::string_view key) const;  // throws "missing required field"
  std::optional<JsonNode> find(std::string_view key) const;

  // ---- Arrays. ----
  std::vector<JsonNode> elements() const;  // throws unless an array

  // ---- Scalars, each checked for type and range. ----
  bool boolean() const;
  std::string string() const;
  float number() const;            // a finite float
  float positive() const;          // > 0
  float nonNegative() const;       // >= 0
  float unitInterval() const;      // in [0, 1]
  int integer(int minimum) const;  // an integer >= minimum
  Vec3 vec3() const;
  Vec3 positiveVec3() const;  // every component > 0
  Quat quaternion() const;    // [x, y, z, w], unit length (within 1e-3), returned normalised

 private:
  const Json* value_;
  std::string path_;
  const std::string* source_;
};

}  // namespace collide::scene
