#include "json_node.h"

#include <cmath>
#include <limits>

namespace collide::scene {

namespace {

std::string typeName(const Json& v) {
  if (v.is_number()) return "a number";
  if (v.is_string()) return "a string";
  if (v.is_boolean()) return "a boolean";
  if (v.is_null()) return "null";
  if (v.is_array()) return "an array";
  return "an object";
}

}  // namespace

std::string JsonNode::path() const {
  std::vector<const Step*> steps;
  for (const Step* s = step_.get(); s != nullptr; s = s->parent.get()) steps.push_back(s);
  std::string out;
  for (auto it = steps.rbegin(); it != steps.rend(); ++it) {
    const Step& s = **it;
    if (s.element) {
      out += '[';
      out += std::to_string(s.index);
      out += ']';
    } else {
      if (!out.empty()) out += '.';
      out += s.key;
    }
  }
  return out;
}

std::string JsonNode::childPath(std::string_view key) const {
  const std::string here = path();
  return (here.empty() ? "" : here + ".") + std::string(key);
}

JsonNode JsonNode::child(const Json& value, std::string key) const {
  return JsonNode(value, std::make_shared<const Step>(Step{step_, false, 0, std::move(key)}), source_);
}

void JsonNode::fail(const std::string& message) const {
  throw Error(*source_ + ": " + path() + ": " + message);
}

std::string JsonNode::shown() const {
  if (value_->is_number_float() && !std::isfinite(value_->get<double>())) return "a number out of range";
  std::string text = value_->dump();
  if (text.size() > 60) text = text.substr(0, 57) + "...";
  return text;
}

void JsonNode::expectObject(std::initializer_list<std::string_view> known) const {
  if (!value_->is_object()) fail("must be an object, got " + typeName(*value_));
  for (const auto& [key, unused] : value_->items()) {
    bool ok = false;
    for (std::string_view k : known) ok = ok || k == key;
    if (ok) continue;
    std::string list;
    for (std::string_view k : known) list += (list.empty() ? "" : ", ") + std::string(k);
    throw Error(*source_ + ": " + childPath(key) + ": unknown field (expected " + list + ")");
  }
}

bool JsonNode::has(std::string_view key) const { return value_->is_object() && value_->contains(key); }

std::optional<JsonNode> JsonNode::find(std::string_view key) const {
  if (!has(key)) return std::nullopt;
  return child(value_->at(std::string(key)), std::string(key));
}

JsonNode JsonNode::at(std::string_view key) const {
  if (auto node = find(key)) return *node;
  throw Error(*source_ + ": " + childPath(key) + ": missing required field");
}

std::vector<JsonNode> JsonNode::elements() const {
  if (!value_->is_array()) fail("must be an array, got " + typeName(*value_));
  std::vector<JsonNode> out;
  out.reserve(value_->size());
  for (std::size_t i = 0; i < value_->size(); ++i) {
    out.push_back(JsonNode((*value_)[i], std::make_shared<const Step>(Step{step_, true, i, {}}), source_));
  }
  return out;
}

bool JsonNode::boolean() const {
  if (!value_->is_boolean()) fail("must be true or false, got " + shown());
  return value_->get<bool>();
}

std::string JsonNode::string() const {
  if (!value_->is_string()) fail("must be a string, got " + shown());
  return value_->get<std::string>();
}

float JsonNode::number() const {
  if (!value_->is_number()) fail("must be a number, got " + shown());
  const double v = value_->get<double>();
  // JSON has no NaN or infinity, but "1e999" parses to infinity and 1e39 overflows a float.
  if (!std::isfinite(v) || std::abs(v) > std::numeric_limits<float>::max()) {
    fail("must be a finite number within float range, got " + shown());
  }
  return static_cast<float>(v);
}

float JsonNode::positive() const {
  const float v = number();
  if (!(v > 0.0f)) fail("must be > 0, got " + shown());
  return v;
}

float JsonNode::nonNegative() const {
  const float v = number();
  if (!(v >= 0.0f)) fail("must be >= 0, got " + shown());
  return v;
}

float JsonNode::unitInterval() const {
  const float v = number();
  if (!(v >= 0.0f && v <= 1.0f)) fail("must be in [0, 1], got " + shown());
  return v;
}

std::uint32_t JsonNode::bits() const {
  if (!value_->is_number_integer()) fail("must be an integer, got " + shown());
  if (!value_->is_number_unsigned() || value_->get<std::uint64_t>() > 0xFFFFFFFFull)
    fail("must be from 0 to 4294967295 (32 bits), got " + shown());
  return static_cast<std::uint32_t>(value_->get<std::uint64_t>());
}

int JsonNode::integer(int minimum, int maximum) const {
  if (!value_->is_number_integer()) fail("must be an integer, got " + shown());
  if (value_->is_number_unsigned() && value_->get<std::uint64_t>() > std::uint64_t(maximum)) {
    fail((maximum == std::numeric_limits<int>::max() ? "is too large"
                                                     : "must be <= " + std::to_string(maximum)) +
         ", got " + shown());
  }
  const auto v = value_->get<std::int64_t>();
  if (v < minimum) fail("must be >= " + std::to_string(minimum) + ", got " + shown());
  if (v > maximum) {
    fail((maximum == std::numeric_limits<int>::max() ? "is too large"
                                                     : "must be <= " + std::to_string(maximum)) +
         ", got " + shown());
  }
  return static_cast<int>(v);
}

Vec3 JsonNode::vec3() const {
  const auto items = elements();
  if (items.size() != 3) fail("must be [x, y, z], got " + shown());
  return {items[0].number(), items[1].number(), items[2].number()};
}

Vec3 JsonNode::positiveVec3() const {
  const auto items = elements();
  if (items.size() != 3) fail("must be [x, y, z], got " + shown());
  return {items[0].positive(), items[1].positive(), items[2].positive()};
}

Quat JsonNode::quaternion() const {
  const auto items = elements();
  if (items.size() != 4) fail("must be a quaternion [x, y, z, w], got " + shown());
  const Quat q(items[3].number(), items[0].number(), items[1].number(), items[2].number());
  const float length = glm::length(q);
  if (!std::isfinite(length) || std::abs(length - 1.0f) > 1e-3f) {
    fail("must be a unit quaternion [x, y, z, w], got " + shown() + " (length " + std::to_string(length) +
         ")");
  }
  return glm::normalize(q);
}

}  // namespace collide::scene
