// JsonNode (scene/src/json_node.h): a value with its path. Paths name the field in every message,
// and a node costs the same memory at any depth, so that reading a deeply nested document is linear
// in its depth.
#include "json_node.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <malloc.h>

#include <string>
#include <vector>

namespace collide::scene {
namespace {

using ::testing::HasSubstr;

std::string failure(const JsonNode& node, const std::string& message) {
  try {
    node.fail(message);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(JsonNode, PathsNameObjectFieldsAndArrayElements) {
  const std::string source = "s.json";
  const Json document = Json::parse(R"({"bodies": [{"shape": {"points": [[0, 1, 2], [3, 4, 5]]}}], "": 1})");
  const JsonNode root(document, source);
  EXPECT_EQ(root.path(), "");
  const JsonNode point = root.at("bodies").elements()[0].at("shape").at("points").elements()[1];
  EXPECT_EQ(point.path(), "bodies[0].shape.points[1]");
  EXPECT_EQ(point.elements()[2].path(), "bodies[0].shape.points[1][2]");
  EXPECT_EQ(failure(point.elements()[2], "must be > 5, got 5"),
            "s.json: bodies[0].shape.points[1][2]: must be > 5, got 5");
  EXPECT_THAT(failure(root.at(""), "odd"), HasSubstr("s.json: : odd"));  // an empty key is a key
  try {
    (void)root.at("bodies").elements()[0].at("mass");
    ADD_FAILURE() << "a missing field must throw";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "s.json: bodies[0].mass: missing required field");
  }
}

// Heap bytes in use (glibc's count; 0 where a sanitizer replaces the allocator).
std::size_t heapInUse() {
  const struct mallinfo2 info = mallinfo2();
  return info.uordblks + info.hblkhd;
}

// The parser keeps a node alive at every level it descends through (the compound recursion keeps
// several), so a node holding its whole path as a string makes depth d cost d^2 / 2 path lengths:
// 5 GB at 10,000 levels of compounds. Shared path steps keep it linear.
TEST(JsonNode, NodesAtEveryLevelOfADeepDocumentTakeLinearMemory) {
  constexpr int kDepth = 20'000;
  Json document = 0;
  for (int i = 0; i < kDepth; ++i) {
    Json level = Json::object();
    level["children"] = std::move(document);
    document = std::move(level);
  }
  const std::string source = "deep.json";
  std::vector<JsonNode> levels;
  levels.reserve(kDepth + 1);
  levels.emplace_back(document, source);
  const std::size_t before = heapInUse();
  for (int i = 0; i < kDepth; ++i) levels.push_back(levels.back().at("children"));
  const std::size_t used = heapInUse() - before;
  // Steps of about 100 bytes each; whole paths would take 20,000 x 120 KB / 2 = 1.2 GB.
  EXPECT_LT(used, std::size_t(kDepth) * 256) << "bytes for " << kDepth << " levels";
  const std::string path = levels.back().path();
  EXPECT_EQ(path.size(), std::size_t(kDepth) * 9 - 1);  // "children" and a dot a level
  EXPECT_EQ(path.substr(0, 18), "children.children.");
  EXPECT_TRUE(levels.back().value().is_number());
}

}  // namespace
}  // namespace collide::scene
