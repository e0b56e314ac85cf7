// The character mover (collide/character.h) held to the numbers a game expects of one: it walks
// flat ground at the speed asked without rising or sinking, climbs stairs up to its step height and
// no higher, stands on a walkable slope and slides down a steep one, rides moving and turning
// platforms, stops still in a corner, never ends inside geometry, pushes what it can and is pushed
// by what moves into it, and crouches only where it can stand up again.
#include <collide/character.h>
#include <collide/world.h>

#include "support/collide_error.h"
#include "support/test_random.h"
#include "support/world_helpers.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace collide {
namespace {

using test::kDt;

BodyId staticBox(World& world, const Vec3& center, const Vec3& half,
                 const Quat& rotation = Quat(1, 0, 0, 0)) {
  BodyDef def;
  def.type = BodyType::Static;
  def.shape = Shape(Box{half});
  def.position = center;
  def.rotation = rotation;
  return world.createBody(def);
}

// A character standing on the ground (y = 0) at x, z: its feet a skin above the floor.
CharacterDef standingAt(float x, float z, float groundHeight = 0.0f) {
  CharacterDef def;
  def.position = Vec3(x, groundHeight + def.skinWidth + def.radius + def.halfHeight, z);
  return def;
}

// Steps the world, then the character, as a game's frame does.
void frame(World& world, Character& character, const Vec3& walk) {
  world.step(kDt);
  character.update(world, walk, kDt);
}

float feetHeight(const Character& c) { return c.footPosition().y; }

TEST(Character, WalksFlatGroundAtTheSpeedAskedWithoutRisingOrSinking) {
  World world;
  world.createBody(test::groundBox());
  Character character(standingAt(0.0f, 0.0f));
  const float startY = character.position().y;
  float worstDrift = 0.0f;
  for (int i = 0; i < 120; ++i) {
    frame(world, character, Vec3(5.0f, 0.0f, 0.0f));
    worstDrift = std::max(worstDrift, std::abs(character.position().y - startY));
    ASSERT_EQ(character.groundState(), GroundState::OnGround) << "frame " << i;
  }
  EXPECT_NEAR(character.position().x, 10.0f, 0.1f);  // 5 m/s for 2 s, within 1 %
  EXPECT_LT(worstDrift, 1e-3f);
  EXPECT_NEAR(character.velocity().x, 5.0f, 0.05f);
}

// halfHeight 0 (the def allows it, and setHalfHeight crouches to it) is a capsule of no length: the
// mover is then a sphere, and walks as one instead of being refused (a Capsule's halfHeight must be
// > 0).
TEST(Character, ASegmentOfLengthZeroWalksAsASphere) {
  World world;
  world.createBody(test::groundBox());
  CharacterDef def;
  def.halfHeight = 0.0f;
  def.position = Vec3(0.0f, def.skinWidth + def.radius, 0.0f);
  Character character(def);
  for (int i = 0; i < 60; ++i) {
    ASSERT_NO_COLLIDE_ERROR(frame(world, character, Vec3(2.0f, 0.0f, 0.0f))) << "frame " << i;
  }
  EXPECT_EQ(character.groundState(), GroundState::OnGround);
  EXPECT_NEAR(character.position().x, 2.0f, 0.05f);  // 2 m/s for 1 s
  EXPECT_NEAR(feetHeight(character), 0.0f, def.skinWidth + 1e-3f);
}

// Stairs of `rise` per step, 0.5 m deep, from x = 2 on, up to 5 steps.
void buildStairs(World& world, float rise) {
  for (int step = 0; step < 5; ++step) {
    const float top = rise * float(step + 1);
    staticBox(world, Vec3(2.0f + 0.5f * float(step) + 0.25f + 2.5f, 0.5f * top, 0.0f),
              Vec3(0.25f + 2.5f, 0.5f * top, 2.0f));
  }
}

TEST(Character, ClimbsStepsUpToItsStepHeightAndNoHigher) {
  for (const float rise : {0.3f, 0.4f}) {
    World world;
    world.createBody(test::groundBox());
    buildStairs(world, rise);
    CharacterDef def = standingAt(0.0f, 0.0f);
    def.maxStepHeight = 0.35f;
    Character character(def);
    for (int i = 0; i < 240; ++i) frame(world, character, Vec3(2.0f, 0.0f, 0.0f));
    if (rise <= def.maxStepHeight) {
      EXPECT_NEAR(feetHeight(character), 5.0f * rise + def.skinWidth, 0.05f) << "a rise of " << rise;
      EXPECT_GT(character.position().x, 4.5f);
      EXPECT_TRUE(character.isOnGround());
    } else {
      EXPECT_LT(feetHeight(character), 0.1f) << "a rise of " << rise << " m is no step";
      EXPECT_LT(character.position().x, 2.0f);
    }
  }
}

TEST(Character, WalksDownStairsWithoutLeavingThem) {
  World world;
  world.createBody(test::groundBox());
  buildStairs(world, 0.3f);
  // On the top step, walking back down.
  Character character(standingAt(5.0f, 0.0f, 1.5f));
  int airborne = 0;
  for (int i = 0; i < 180; ++i) {
    frame(world, character, Vec3(-1.5f, 0.0f, 0.0f));
    if (!character.isOnGround()) ++airborne;
  }
  EXPECT_LT(feetHeight(character), 0.05f);
  EXPECT_LT(character.position().x, 1.5f);
  EXPECT_LE(airborne, 2) << "down a step the character keeps to the stairs";
}

// A 60 m ramp at `degrees`, falling towards -x, its top face through the origin.
void buildRamp(World& world, float degrees) {
  const Quat tilt = glm::angleAxis(glm::radians(degrees), Vec3(0.0f, 0.0f, 1.0f));
  staticBox(world, tilt * Vec3(0.0f, -0.5f, 0.0f), Vec3(30.0f, 0.5f, 3.0f), tilt);
}

TEST(Character, StandsOnAWalkableSlopeAndSlidesDownASteepOne) {
  for (const float degrees : {30.0f, 50.0f}) {
    World world;
    buildRamp(world, degrees);
    CharacterDef def;
    def.maxSlope = glm::radians(45.0f);
    // Above the ramp's surface at the origin, dropped onto it.
    def.position = Vec3(0.0f, def.radius + def.halfHeight + 0.3f, 0.0f);
    Character character(def);
    for (int i = 0; i < 30; ++i) frame(world, character, Vec3(0.0f));
    const Vec3 settled = character.position();
    for (int i = 0; i < 120; ++i) frame(world, character, Vec3(0.0f));
    const float moved = glm::length(character.position() - settled);
    if (degrees < 45.0f) {
      EXPECT_EQ(character.groundState(), GroundState::OnGround);
      EXPECT_LT(moved, 0.01f) << "stands on " << degrees << " degrees";
    } else {
      EXPECT_EQ(character.groundState(), GroundState::Sliding);
      EXPECT_GT(moved, 1.0f) << "slides down " << degrees << " degrees";
      EXPECT_LT(character.position().y, settled.y - 0.5f);
    }
  }
}

BodyId kinematicBox(World& world, const Vec3& center, const Vec3& half) {
  BodyDef def;
  def.type = BodyType::Kinematic;
  def.shape = Shape(Box{half});
  def.position = center;
  return world.createBody(def);
}

TEST(Character, RidesAMovingAndATurningPlatform) {
  {
    World world;
    world.createBody(test::groundBox());
    const BodyId platform = kinematicBox(world, Vec3(0.0f, 1.0f, 0.0f), Vec3(2.0f, 0.25f, 2.0f));
    world.setLinearVelocity(platform, Vec3(2.0f, 0.0f, 0.0f));
    Character character(standingAt(0.5f, 0.5f, 1.25f));
    for (int i = 0; i < 10; ++i) frame(world, character, Vec3(0.0f));
    const Vec3 offset = character.position() - world.transform(platform).position;
    for (int i = 0; i < 300; ++i) frame(world, character, Vec3(0.0f));
    const Vec3 drift = character.position() - world.transform(platform).position - offset;
    EXPECT_LT(glm::length(drift), 0.01f) << "on a platform at 2 m/s for 5 s";
    EXPECT_EQ(character.groundBody(), platform);
    EXPECT_NEAR(character.groundVelocity().x, 2.0f, 1e-3f);
  }
  {
    World world;
    const BodyId platform = kinematicBox(world, Vec3(0.0f, 0.0f, 0.0f), Vec3(4.0f, 0.25f, 4.0f));
    world.setAngularVelocity(platform, Vec3(0.0f, 1.0f, 0.0f));
    Character character(standingAt(2.0f, 0.0f, 0.25f));
    for (int i = 0; i < 10; ++i) frame(world, character, Vec3(0.0f));
    const Transform start = world.transform(platform);
    const Vec3 local = start.inverseApplyToPoint(character.position());
    for (int i = 0; i < 300; ++i) frame(world, character, Vec3(0.0f));
    const Vec3 now = world.transform(platform).inverseApplyToPoint(character.position());
    EXPECT_LT(glm::length(now - local), 0.01f) << "on a platform turning at 1 rad/s for 5 s";
  }
}

TEST(Character, StopsWithoutJitterInACornerOfTwoWalls) {
  World world;
  world.createBody(test::groundBox());
  // Two walls meeting at 45 degrees at the origin, the character walking into the corner.
  const float half = glm::radians(22.5f);
  for (const float side : {-1.0f, 1.0f}) {
    const Quat turn = glm::angleAxis(side * half, Vec3(0.0f, 1.0f, 0.0f));
    staticBox(world, turn * Vec3(2.0f, 1.0f, side * 0.1f), Vec3(2.0f, 1.0f, 0.1f), turn);
  }
  Character character(standingAt(4.0f, 0.0f));
  for (int i = 0; i < 120; ++i) frame(world, character, Vec3(-3.0f, 0.0f, 0.0f));
  float worst = 0.0f;
  for (int i = 0; i < 60; ++i) {
    const Vec3 before = character.position();
    frame(world, character, Vec3(-3.0f, 0.0f, 0.0f));
    worst = std::max(worst, glm::length(character.position() - before));
  }
  EXPECT_LT(worst, 1e-3f) << "walking into the corner, the character is still";
  EXPECT_LT(character.position().x, 4.0f);
}

// A sine terrain (R4's formula) and a mesh room with a ramp, a step and a pillar.
Shape sineTerrain(int n) {
  std::vector<Vec3> vertices;
  std::vector<MeshTriangle> triangles;
  const float offset = 0.5f * float(n);
  for (int z = 0; z <= n; ++z) {
    for (int x = 0; x <= n; ++x) {
      const float px = float(x) - offset, pz = float(z) - offset;
      vertices.emplace_back(px, 0.5f * std::sin(0.3f * px) * std::cos(0.3f * pz), pz);
    }
  }
  const auto index = [&](int x, int z) { return static_cast<std::uint32_t>(z * (n + 1) + x); };
  for (int z = 0; z < n; ++z) {
    for (int x = 0; x < n; ++x) {
      triangles.push_back({{index(x, z), index(x, z + 1), index(x + 1, z + 1)}});
      triangles.push_back({{index(x, z), index(x + 1, z + 1), index(x + 1, z)}});
    }
  }
  return Shape(TriangleMesh::fromTriangles(std::move(vertices), std::move(triangles)));
}

// The twelve triangles of a box's surface, facing out.
void addBoxTriangles(std::vector<Vec3>& vertices, std::vector<MeshTriangle>& triangles, const Vec3& center,
                     const Vec3& half) {
  const auto base = static_cast<std::uint32_t>(vertices.size());
  for (int i = 0; i < 8; ++i)
    vertices.push_back(center +
                       Vec3(i & 1 ? half.x : -half.x, i & 2 ? half.y : -half.y, i & 4 ? half.z : -half.z));
  // Corners by bits (x, y, z); each face's quad counter-clockwise seen from outside.
  const std::uint32_t faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                     {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  for (const auto& f : faces) {
    triangles.push_back({{base + f[0], base + f[1], base + f[2]}});
    triangles.push_back({{base + f[0], base + f[2], base + f[3]}});
  }
}

// How deep the character overlaps static geometry (0 when clear).
float worstOverlap(const World& world, const Character& character) {
  float worst = 0.0f;
  for (const Character::Plane& plane : character.planesNear(world, character.position(), 0.0f))
    worst = std::max(worst, -plane.gap);
  return worst;
}

TEST(Character, RandomMovesThroughTerrainAndAMeshLevelNeverEndInsideGeometry) {
  World world;
  BodyDef terrain;
  terrain.type = BodyType::Static;
  terrain.shape = sineTerrain(40);
  world.createBody(terrain);
  // The level: one static triangle mesh of a room's walls around the terrain, a pillar, a step and
  // a low beam (a level as a game's editor exports it), and the same pillar, step and beam mirrored
  // as static boxes.
  std::vector<Vec3> vertices;
  std::vector<MeshTriangle> triangles;
  for (const float side : {-1.0f, 1.0f}) {
    addBoxTriangles(vertices, triangles, Vec3(side * 20.5f, 2.0f, 0.0f), Vec3(0.5f, 3.0f, 21.0f));
    addBoxTriangles(vertices, triangles, Vec3(0.0f, 2.0f, side * 20.5f), Vec3(21.0f, 3.0f, 0.5f));
  }
  addBoxTriangles(vertices, triangles, Vec3(3.0f, 1.0f, 3.0f), Vec3(0.5f, 2.0f, 0.5f));
  addBoxTriangles(vertices, triangles, Vec3(-4.0f, 0.5f, 2.0f), Vec3(2.0f, 0.3f, 2.0f));
  addBoxTriangles(vertices, triangles, Vec3(0.0f, 2.3f, -5.0f), Vec3(3.0f, 0.2f, 1.0f));
  BodyDef level;
  level.type = BodyType::Static;
  level.shape = Shape(TriangleMesh::fromTriangles(std::move(vertices), std::move(triangles)));
  const BodyId levelBody = world.createBody(level);
  staticBox(world, Vec3(-3.0f, 1.0f, -3.0f), Vec3(0.5f, 2.0f, 0.5f));
  staticBox(world, Vec3(4.0f, 0.5f, -2.0f), Vec3(2.0f, 0.3f, 2.0f));
  staticBox(world, Vec3(0.0f, 2.3f, 5.0f), Vec3(3.0f, 0.2f, 1.0f));
  Character character(standingAt(0.0f, 0.0f, 1.0f));
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> speed(-6.0f, 6.0f);
  std::uniform_int_distribution<int> dice(0, 19);
  Vec3 walk(0.0f);
  float worst = 0.0f;
  int framesTouchingLevel = 0;
  for (int i = 0; i < 1000; ++i) {
    if (i % 15 == 0) walk = Vec3(speed(rng), 0.0f, speed(rng));
    const Vec3 jump = dice(rng) == 0 && character.isOnGround() ? Vec3(0.0f, 5.0f, 0.0f) : Vec3(0.0f);
    frame(world, character, walk + jump);
    worst = std::max(worst, worstOverlap(world, character));
    ASSERT_TRUE(isFinite(character.position()));
    for (const CharacterContact& contact : character.contacts())
      framesTouchingLevel += contact.body == levelBody;
  }
  EXPECT_GT(framesTouchingLevel, 20) << "the walk meets the mesh level's walls and blocks";
  EXPECT_LT(worst, 2e-3f) << "the deepest the character ever sank into the level (m)";
  EXPECT_LT(std::abs(character.position().x), 20.0f);
  EXPECT_LT(std::abs(character.position().z), 20.0f);
}

TEST(Character, PushesALightBoxAndIsBlockedByAHeavyOne) {
  for (const float mass : {10.0f, 10000.0f}) {
    World world;
    world.createBody(test::groundBox());
    const BodyId box = world.createBody(test::boxBody(Vec3(2.0f, 0.5f, 0.0f), Vec3(0.5f), mass));
    Character character(standingAt(0.0f, 0.0f));
    bool pushedOnce = false;
    for (int i = 0; i < 180; ++i) {
      frame(world, character, Vec3(2.0f, 0.0f, 0.0f));
      for (const CharacterContact& contact : character.contacts())
        pushedOnce = pushedOnce || (contact.body == box && contact.pushed);
    }
    const float moved = world.transform(box).position.x - 2.0f;
    EXPECT_TRUE(pushedOnce);
    if (mass < 100.0f) {
      EXPECT_GT(moved, 1.0f) << "a 10 kg box is pushed along";
    } else {
      EXPECT_LT(moved, 0.05f) << "a 10 t box stays";
      EXPECT_LT(character.position().x, 1.3f) << "and stops the character";
    }
    EXPECT_LT(worstOverlap(world, character), 2e-3f);
  }
}

TEST(Character, IsPushedByAKinematicWallMovingIntoIt) {
  World world;
  world.createBody(test::groundBox());
  const BodyId wall = kinematicBox(world, Vec3(-1.0f, 1.0f, 0.0f), Vec3(0.2f, 1.0f, 2.0f));
  world.setLinearVelocity(wall, Vec3(1.0f, 0.0f, 0.0f));
  Character character(standingAt(0.0f, 0.0f));
  float worst = 0.0f;
  for (int i = 0; i < 180; ++i) {
    frame(world, character, Vec3(0.0f));
    worst = std::max(worst, worstOverlap(world, character));
  }
  EXPECT_GT(character.position().x, 1.5f) << "3 s at 1 m/s from 1 m behind";
  EXPECT_LT(worst, 0.03f) << "it keeps out of the wall within a step's motion";
}

TEST(Character, CrouchesAnywhereAndStandsOnlyWhereThereIsRoom) {
  World world;
  world.createBody(test::groundBox());
  staticBox(world, Vec3(3.0f, 1.6f, 0.0f), Vec3(1.0f, 0.2f, 2.0f));  // a beam 1.4 m above the floor
  Character character(standingAt(0.0f, 0.0f));
  frame(world, character, Vec3(0.0f));
  ASSERT_TRUE(character.setHalfHeight(world, 0.2f));  // crouched: 1 m tall
  for (int i = 0; i < 90; ++i) frame(world, character, Vec3(2.0f, 0.0f, 0.0f));
  EXPECT_GT(character.position().x, 2.5f) << "crouched, it passes under the beam";
  ASSERT_LT(character.position().x, 3.8f);
  const Vec3 under = character.position();
  EXPECT_FALSE(character.setHalfHeight(world, 0.6f)) << "no room to stand under the beam";
  EXPECT_EQ(character.position(), under);
  EXPECT_FLOAT_EQ(character.halfHeight(), 0.2f);
  for (int i = 0; i < 60; ++i) frame(world, character, Vec3(2.0f, 0.0f, 0.0f));
  EXPECT_TRUE(character.setHalfHeight(world, 0.6f)) << "past the beam it stands up";
  EXPECT_NEAR(character.footPosition().y, under.y - 0.5f, 0.01f) << "its feet where they were";
}

TEST(Character, ReportsTheWallItWalksInto) {
  World world;
  world.createBody(test::groundBox());
  const BodyId wall = staticBox(world, Vec3(2.0f, 1.0f, 0.0f), Vec3(0.2f, 1.0f, 2.0f));
  Character character(standingAt(0.0f, 0.0f));
  bool touched = false;
  for (int i = 0; i < 90; ++i) {
    frame(world, character, Vec3(3.0f, 0.0f, 0.0f));
    for (const CharacterContact& contact : character.contacts()) {
      if (contact.body != wall) continue;
      touched = true;
      EXPECT_NEAR(contact.normal.x, -1.0f, 1e-3f);
      EXPECT_FALSE(contact.pushed);
    }
  }
  EXPECT_TRUE(touched);
  EXPECT_NEAR(character.position().x, 1.8f - 0.3f - 0.02f, 2e-3f) << "a skin short of the wall";
}

TEST(Character, BadDefinitionsAreRefusedNamingTheField) {
  const auto refused = [](CharacterDef def, const char* field) {
    EXPECT_THAT([&] { Character c(def); }, ::collide::test::ReportsError(::testing::HasSubstr(field)))
        << field;
  };
  CharacterDef def;
  def.radius = 0.0f;
  refused(def, "radius");
  def = {};
  def.halfHeight = -1.0f;
  refused(def, "halfHeight");
  def = {};
  def.maxSlope = 2.0f;
  refused(def, "maxSlope");
  def = {};
  def.up = Vec3(0.0f);
  refused(def, "up");
  def = {};
  def.position = Vec3(std::nanf(""), 0.0f, 0.0f);
  refused(def, "position");
  def = {};
  def.skinWidth = 0.0f;
  refused(def, "skinWidth");
  World world;
  Character character(CharacterDef{});
  EXPECT_THAT([&] { character.update(world, Vec3(0.0f), 0.0f); },
              ::collide::test::ReportsError(::testing::HasSubstr("dt must be finite and > 0")));
}

}  // namespace
}  // namespace collide
