// Characters in scene files (docs/scene-format.md, "characters") and the built-in character scene:
// the fields reach the CharacterDef, bad ones are refused naming the field, and `collide run`
// walks the player along its path to the end.
#include <collide/scene/builtin_scenes.h>
#include <collide/scene/runner.h>
#include <collide/scene/scene.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

namespace collide::scene {
namespace {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

std::string document(const std::string& character) {
  return R"({"format": "collide-scene/1", "bodies": [{"name": "ground", "type": "static", "shape": )"
         R"({"type": "plane", "normal": [0, 1, 0], "distance": 0}}], "characters": [)" +
         character + "]}";
}

TEST(SceneCharacters, FieldsReachTheCharacterDef) {
  const Scene scene = parseScene(document(R"({"name": "npc", "position": [1, 1, 2], "radius": 0.4,
      "half_height": 0.5, "max_slope": 0.6, "max_step_height": 0.25, "skin_width": 0.03, "push_force": 100,
      "mass": 60, "mask": 3, "path": [{"to": [5, 0, 2], "speed": 1.5}, {"to": [5, 0, 6], "jump": 4}]})"),
                                 "s.json");
  ASSERT_EQ(scene.characters.size(), 1u);
  const SceneCharacter& c = scene.characters.front();
  EXPECT_EQ(c.name, "npc");
  EXPECT_EQ(c.def.position, Vec3(1, 1, 2));
  EXPECT_FLOAT_EQ(c.def.radius, 0.4f);
  EXPECT_FLOAT_EQ(c.def.halfHeight, 0.5f);
  EXPECT_FLOAT_EQ(c.def.maxSlope, 0.6f);
  EXPECT_FLOAT_EQ(c.def.maxStepHeight, 0.25f);
  EXPECT_FLOAT_EQ(c.def.skinWidth, 0.03f);
  EXPECT_FLOAT_EQ(c.def.pushForce, 100.0f);
  EXPECT_FLOAT_EQ(c.def.mass, 60.0f);
  EXPECT_EQ(c.def.filter.mask, 3u);
  EXPECT_EQ(c.def.gravity, Vec3(0.0f, -9.81f, 0.0f)) << "the scene's gravity";
  ASSERT_EQ(c.path.size(), 2u);
  EXPECT_FLOAT_EQ(c.path[0].speed, 1.5f);
  EXPECT_FLOAT_EQ(c.path[1].jump, 4.0f);
}

TEST(SceneCharacters, BadFieldsAreRefusedNamingThem) {
  const auto refused = [](const std::string& character, const std::string& message) {
    EXPECT_THAT([&] { parseScene(document(character), "s.json"); }, ThrowsMessage<Error>(HasSubstr(message)))
        << character;
  };
  refused(R"({"name": "a", "position": [0, 1, 0], "radius": -1})", "s.json: characters[0].radius: ");
  refused(R"({"name": "a", "position": [0, 1, 0], "max_slope": 2})", "characters[0].max_slope: must be in (0, pi/2)");
  refused(R"({"name": "a"})", "characters[0].position: missing required field");
  refused(R"({"name": "a", "position": [0, 1, 0], "wings": 2})", "characters[0].wings: unknown field");
  refused(R"({"name": "a", "position": [0, 1, 0], "path": [{"to": [1, 0, 0], "speed": 0}]})",
          "characters[0].path[0].speed: ");
  refused(R"({"name": "a", "position": [0, 1, 0]}, {"name": "a", "position": [2, 1, 0]})",
          "characters[1].name: duplicate name");
}

TEST(SceneCharacters, ThePlayerWalksItsPathOntoTheTurntable) {
  const Scene scene = loadBuiltinScene("character");
  const RunSummary summary = runScene(scene);
  ASSERT_EQ(summary.characters.size(), 1u);
  const RunSummary::CharacterEnd& player = summary.characters.front();
  EXPECT_EQ(player.waypointsReached, player.waypoints) << "up the stairs, down the ramp, through the crates, "
                                                          "over the kerb, onto the disc";
  EXPECT_EQ(player.ground, GroundState::OnGround);
  // On the turntable (centre (-6, 0.2, 0), radius 2.5), its feet on the disc's top.
  EXPECT_LT(glm::length(Vec3(player.position.x + 6.0f, 0.0f, player.position.z)), 2.5f);
  EXPECT_NEAR(player.position.y, 0.2f, 0.05f);
}

}  // namespace
}  // namespace collide::scene
