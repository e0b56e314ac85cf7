// A JSON value together with its path in the document ("bodies[3].shape.radius"), so that every
// check can say which field is wrong and what it holds. Jolt-style validation: bad input becomes a
// collide::Error with a message, never a crash or a silently defaulted value.
//
// The path is a chain of steps shared with the parent node and spelled out only for a message, so a
// node costs the same at any depth: reading a document nested d levels deep takes memory and time
// linear in d (a copied path string per node would make both quadratic).
#pragma once

#include <collide/error.h>
#include <collide/math.h>

#include <nlohmann/json.hpp>

#include <initializer_list>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace collide::scene {

using Json = nlohmann::json;

// A JSON document from text, with the scene files' limits (depth, numbers within float range, no
// NUL byte): Error "SOURCE: malformed JSON at line L, column C: ..." or "SOURCE: PATH: ..." for what
// the limits refuse.
Json parseDocument(std::string_view text, const std::string& source);

class JsonNode {
 public:
  // The document's root (its path is empty); `source` prefixes every message and must outlive the
  // node.
  JsonNode(const Json& value, const std::string& source) : value_(&value), source_(&source) {}

  const Json& value() const { return *value_; }
  std::string path() const;  // "bodies[3].shape.radius"; empty for the root

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
  float number() const;                                                           // a finite float
  float positive() const;                                                         // > 0
  float nonNegative() const;                                                      // >= 0
  float unitInterval() const;                                                     // in [0, 1]
  int integer(int minimum, int maximum = std::numeric_limits<int>::max()) const;  // in [minimum, maximum]
  std::uint32_t bits() const;  // an integer in [0, 2^32 - 1]: layer and mask bits
  Vec3 vec3() const;
  Vec3 positiveVec3() const;  // every component > 0
  Quat quaternion() const;    // [x, y, z, w], unit length (within 1e-3), returned normalised

 private:
  struct Step {
    std::shared_ptr<const Step> parent;  // null: a field of the root
    bool element = false;                // an array element, else an object's field
    std::size_t index = 0;               // the element's index
    std::string key;                     // the field's key
  };
  JsonNode(const Json& value, std::shared_ptr<const Step> step, const std::string* source)
      : value_(&value), step_(std::move(step)), source_(source) {}
  JsonNode child(const Json& value, std::string key) const;
  std::string childPath(std::string_view key) const;  // the path of a field of this object

  const Json* value_;
  std::shared_ptr<const Step> step_;  // null for the root
  const std::string* source_;
};

}  // namespace collide::scene
