// Mass ratios: heavy bodies on light ones rest instead of pressing them into what is under them
// (support masses, src/dynamics/support_masses.h). Each scenario also runs with them off, where it
// collapses, so that the tests can fail.
#include "support/world_helpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace collide {
namespace {

using test::boxBody;
using test::groundBox;

using test::kDt;

WorldDef worldWithSupportMasses(bool on) {
  WorldDef def;
  def.contact.supportMasses = on;
  return def;
}

struct HeavyOnLight {
  float lightDeepestIntoGround = 0.0f;  // m below y = 0 of the light box's bottom, at its worst
  bool heavyPassedThrough = false;      // the heavy box's centre below the light one's, at any step
  float heavyRestHeight = 0.0f;         // the heavy box's centre at the end
  float lightRestHeight = 0.0f;
};

// A 1 kg box (1 m cube) rests on the ground; a 1,000 kg one of the same size is dropped on it from
// 1 m above, and the two are watched for 5 s.
HeavyOnLight dropHeavyOnLight(bool supportMasses) {
  World world(worldWithSupportMasses(supportMasses));
  world.createBody(groundBox());
  const BodyId light = world.createBody(boxBody(Vec3(0.0f, 0.5f, 0.0f), Vec3(0.5f), 1.0f));
  const BodyId heavy = world.createBody(boxBody(Vec3(0.0f, 2.5f, 0.0f), Vec3(0.5f), 1000.0f));
  HeavyOnLight result;
  for (int i = 0; i < 300; ++i) {
    world.step(kDt);
    const float lightY = world.transform(light).position.y;
    const float heavyY = world.transform(heavy).position.y;
    result.lightDeepestIntoGround = std::max(result.lightDeepestIntoGround, 0.5f - lightY);
    result.heavyPassedThrough = result.heavyPassedThrough || heavyY < lightY;
    result.heavyRestHeight = heavyY;
    result.lightRestHeight = lightY;
  }
  return result;
}

TEST(MassRatio, AThousandKilogramBoxDroppedOnAOneKilogramBoxRestsOnIt) {
  const HeavyOnLight r = dropHeavyOnLight(true);
  EXPECT_LT(r.lightDeepestIntoGround, 0.01f);
  EXPECT_FALSE(r.heavyPassedThrough);
  EXPECT_NEAR(r.lightRestHeight, 0.5f, 0.01f);
  EXPECT_NEAR(r.heavyRestHeight, 1.5f, 0.02f);
}

TEST(MassRatio, WithoutSupportMassesTheLightBoxIsPressedIntoTheGround) {
  const HeavyOnLight r = dropHeavyOnLight(false);
  EXPECT_GT(r.lightDeepestIntoGround, 0.05f);
}

// A 2,000 kg plank (4 m x 0.2 m x 1 m) dropped from 1 m onto two 1 kg boxes 3 m apart: each light
// box carries half the plank, neither is pressed into the ground, and the plank rests level on them.
TEST(MassRatio, AHeavyPlankOnTwoLightBoxesRestsOnThem) {
  World world;
  world.createBody(groundBox());
  const BodyId left = world.createBody(boxBody(Vec3(-1.5f, 0.5f, 0.0f), Vec3(0.5f), 1.0f));
  const BodyId right = world.createBody(boxBody(Vec3(1.5f, 0.5f, 0.0f), Vec3(0.5f), 1.0f));
  const BodyId plank = world.createBody(boxBody(Vec3(0.0f, 2.1f, 0.0f), Vec3(2.0f, 0.1f, 0.5f), 2000.0f));
  float deepest = 0.0f;
  for (int i = 0; i < 300; ++i) {
    world.step(kDt);
    for (const BodyId box : {left, right})
      deepest = std::max(deepest, 0.5f - world.transform(box).position.y);
  }
  EXPECT_LT(deepest, 0.01f);
  EXPECT_NEAR(world.transform(plank).position.y, 1.1f, 0.01f);
  const Vec3 along = world.transform(plank).rotation * Vec3(1.0f, 0.0f, 0.0f);
  EXPECT_LT(std::abs(along.y), 1e-3f);  // level
}

TEST(MassRatio, WithoutSupportMassesTheHeavyPlankPressesTheBoxesIntoTheGround) {
  WorldDef def;
  def.contact.supportMasses = false;
  World world(def);
  world.createBody(groundBox());
  const BodyId left = world.createBody(boxBody(Vec3(-1.5f, 0.5f, 0.0f), Vec3(0.5f), 1.0f));
  world.createBody(boxBody(Vec3(1.5f, 0.5f, 0.0f), Vec3(0.5f), 1.0f));
  world.createBody(boxBody(Vec3(0.0f, 2.1f, 0.0f), Vec3(2.0f, 0.1f, 0.5f), 2000.0f));
  float deepest = 0.0f;
  for (int i = 0; i < 300; ++i) {
    world.step(kDt);
    deepest = std::max(deepest, 0.5f - world.transform(left).position.y);
  }
  EXPECT_GT(deepest, 0.05f);
}

struct StackRun {
  float settledTop = 0.0f;     // the top box's height after 1 s
  float worstTopDrift = 0.0f;  // how far it strays from there over the next 10 s
};

// Thirty 1 m boxes, alternately 1 kg and 100 kg (the bottom one light), stacked on the ground.
StackRun alternatingStack(bool supportMasses) {
  World world(worldWithSupportMasses(supportMasses));
  world.createBody(groundBox());
  BodyId top;
  for (int i = 0; i < 30; ++i) {
    top =
        world.createBody(boxBody(Vec3(0.0f, 0.5f + float(i), 0.0f), Vec3(0.5f), i % 2 == 0 ? 1.0f : 100.0f));
  }
  for (int i = 0; i < 60; ++i) world.step(kDt);
  StackRun run;
  run.settledTop = world.transform(top).position.y;
  for (int i = 0; i < 600; ++i) {
    world.step(kDt);
    run.worstTopDrift = std::max(
        run.worstTopDrift, glm::length(world.transform(top).position - Vec3(0.0f, run.settledTop, 0.0f)));
  }
  return run;
}

TEST(MassRatio, AStackAlternatingOneAndAHundredKilogramsStands) {
  const StackRun run = alternatingStack(true);
  // Thirty contacts, each sagging a few millimetres into the next, as a uniform stack's do.
  EXPECT_NEAR(run.settledTop, 29.5f, 0.05f);
  EXPECT_LT(run.worstTopDrift, 0.05f);
}

TEST(MassRatio, WithoutSupportMassesTheAlternatingStackSinksIntoItself) {
  const StackRun run = alternatingStack(false);
  EXPECT_GT(29.5f - run.settledTop + run.worstTopDrift, 0.5f);
}

}  // namespace
}  // namespace collide
