// Collision filtering: groups, layers and masks against a table of expectations, the pair filter,
// constraints that keep their bodies apart, and filters changed at run time. A box is dropped on
// another resting on the ground: it rests on it if the pair collides, and falls through to the ground
// if not.
#include "support/collide_error.h"
#include "support/world_helpers.h"

#include <gtest/gtest.h>

#include <vector>

namespace collide {
namespace {

using test::boxBody;

using test::kDt;

struct Filter {
  std::uint32_t layer = 1;
  std::uint32_t mask = kAllLayers;
  std::int32_t group = 0;
};

struct Drop {
  World world;
  BodyId lower, upper;
  Drop(const Filter& lowerFilter, const Filter& upperFilter) {
    BodyDef ground = test::groundBox();
    ground.layer = kAllLayers;  // the ground takes both boxes whatever their layers
    world.createBody(ground);
    BodyDef a = boxBody(Vec3(0.0f, 0.5f, 0.0f), Vec3(0.5f), 1.0f);
    a.layer = lowerFilter.layer;
    a.mask = lowerFilter.mask | 1u;  // and both boxes take the ground
    a.group = lowerFilter.group;
    BodyDef b = boxBody(Vec3(0.0f, 1.6f, 0.0f), Vec3(0.5f), 1.0f);
    b.layer = upperFilter.layer;
    b.mask = upperFilter.mask | 1u;
    b.group = upperFilter.group;
    lower = world.createBody(a);
    upper = world.createBody(b);
  }
  // Whether the upper box ends resting on the lower one (else it fell through to the ground).
  bool rests(int steps = 60) {
    for (int i = 0; i < steps; ++i) world.step(kDt);
    return world.transform(upper).position.y > 1.4f;
  }
};

TEST(Filtering, GroupsLayersAndMasksFollowTheTable) {
  // How a pair that does not collide is refused: by the masks, which the bodies' broad-phase
  // proxies carry, so that the broad phase never keeps the pair; or by a negative group, which the
  // filters rule out after the broad phase, every step it keeps the pair (filteredPairs).
  enum class Refused { No, InBroadPhase, ByFilters };
  struct Row {
    const char* what;
    Filter lower, upper;
    Refused refused;
  };
  const std::vector<Row> table = {
      {"defaults", {}, {}, Refused::No},
      {"the lower's mask leaves out the upper's layer",
       {2, ~4u, 0},
       {4, kAllLayers, 0},
       Refused::InBroadPhase},
      {"the upper's mask leaves out the lower's layer",
       {2, kAllLayers, 0},
       {4, ~2u, 0},
       Refused::InBroadPhase},
      {"layers in each other's masks", {2, 4, 0}, {4, 2, 0}, Refused::No},
      {"the same positive group overrides the masks", {2, 0, 7}, {4, 0, 7}, Refused::No},
      {"the same negative group overrides the masks",
       {2, kAllLayers, -7},
       {4, kAllLayers, -7},
       Refused::ByFilters},
      {"different positive groups: the masks decide", {2, kAllLayers, 1}, {4, kAllLayers, 2}, Refused::No},
      {"different negative groups: the masks decide (allow)",
       {2, kAllLayers, -1},
       {4, kAllLayers, -2},
       Refused::No},
      {"different negative groups: the masks decide (refuse)",
       {2, ~4u, -1},
       {4, kAllLayers, -2},
       Refused::InBroadPhase},
      // A positive group collides whatever the masks say, so its proxy pairs with every layer: the
      // filters refuse the pair.
      {"one in a group, one not: the masks decide", {2, ~4u, 5}, {4, kAllLayers, 0}, Refused::ByFilters},
  };
  for (const Row& row : table) {
    Drop drop(row.lower, row.upper);
    EXPECT_EQ(drop.rests(), row.refused == Refused::No) << row.what;
    EXPECT_EQ(drop.world.lastStats().filteredPairs, row.refused == Refused::ByFilters ? 1u : 0u) << row.what;
  }
}

TEST(Filtering, ThePairFilterHasTheLastWord) {
  {
    Drop drop({}, {});
    std::vector<std::pair<BodyId, BodyId>> asked;
    drop.world.setPairFilter([&](BodyId a, BodyId b) {
      asked.emplace_back(a, b);
      return !((a == drop.lower && b == drop.upper) || (a == drop.upper && b == drop.lower));
    });
    EXPECT_FALSE(drop.rests());
    bool sawThePair = false;
    for (const auto& [a, b] : asked)
      sawThePair = sawThePair || (a == drop.lower && b == drop.upper) || (a == drop.upper && b == drop.lower);
    EXPECT_TRUE(sawThePair);
  }
  {
    Drop drop({}, {});
    drop.world.setPairFilter([](BodyId, BodyId) { return true; });
    EXPECT_TRUE(drop.rests());
    drop.world.setPairFilter({});  // none
    EXPECT_TRUE(drop.rests());
  }
  {
    // It is asked only about pairs the groups and masks allow.
    Drop drop({2, ~4u, 0}, {4, kAllLayers, 0});
    drop.world.setPairFilter([](BodyId, BodyId) { return true; });
    EXPECT_FALSE(drop.rests());
  }
}

TEST(Filtering, AConstraintCanKeepItsBodiesApart) {
  for (const bool collideConnected : {true, false}) {
    Drop drop({}, {});
    DistanceConstraintDef joint;
    joint.a = drop.lower;
    joint.b = drop.upper;
    joint.compliance = 1e3f;  // a spring too weak to matter: only the filter differs
    joint.collideConnected = collideConnected;
    drop.world.createDistanceConstraint(joint);
    EXPECT_EQ(drop.rests(), collideConnected) << "collideConnected " << collideConnected;
  }
  // Two such constraints: with one of them destroyed the other still keeps the bodies apart;
  // with both destroyed, nothing does.
  for (const bool destroyBoth : {false, true}) {
    Drop drop({}, {});
    DistanceConstraintDef joint;
    joint.a = drop.lower;
    joint.b = drop.upper;
    joint.compliance = 1e3f;
    joint.collideConnected = false;
    const JointId first = drop.world.createDistanceConstraint(joint);
    const JointId second = drop.world.createDistanceConstraint(joint);
    drop.world.destroyConstraint(first);
    if (destroyBoth) drop.world.destroyConstraint(second);
    EXPECT_EQ(drop.rests(), destroyBoth) << "destroyBoth " << destroyBoth;
    EXPECT_EQ(drop.world.lastStats().filteredPairs, destroyBoth ? 0u : 1u);
  }
}

TEST(Filtering, AFilterChangedAtRunTimeCountsFromTheNextStep) {
  Drop drop({}, {});
  ASSERT_TRUE(drop.rests());
  // The lower box to layer 2, the upper to layer 4 with a mask that leaves out 2.
  drop.world.setCollisionFilter(drop.lower, 2, kAllLayers, 0);
  drop.world.setCollisionFilter(drop.upper, 4, ~2u, 0);
  EXPECT_EQ(drop.world.layer(drop.upper), 4u);
  EXPECT_EQ(drop.world.mask(drop.lower), kAllLayers);
  EXPECT_EQ(drop.world.group(drop.upper), 0);
  EXPECT_FALSE(drop.rests(120));  // the contact ends and the box falls through
  // The queries' masks see the new layers: a ray down through both finds the one of its mask.
  const Ray down{Vec3(0.0f, 10.0f, 0.0f), Vec3(0.0f, -1.0f, 0.0f)};
  ASSERT_TRUE(drop.world.castRay(down, 4).has_value());
  EXPECT_EQ(drop.world.castRay(down, 4)->body, drop.upper);
  EXPECT_EQ(drop.world.castRay(down, 2)->body, drop.lower);
  EXPECT_COLLIDE_ERROR(drop.world.setCollisionFilter(BodyId{}, 1, 1, 0));
}

}  // namespace
}  // namespace collide
