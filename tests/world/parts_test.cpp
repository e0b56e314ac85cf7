// Bodies made of parts (docs/parts.md): the mass is the sum of the parts', each part's material,
// filter and sensor flag act on its own contacts, contacts and events name the parts, continuous
// collision and the queries go part by part, and parts come and go at run time.
#include "support/collide_error.h"
#include "support/test_random.h"
#include "support/world_helpers.h"

#include <collide/world.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>
#include <vector>

namespace collide {
namespace {

using test::kDt;

PartDef boxPart(const Vec3& position, const Vec3& half, float density = 1000.0f) {
  PartDef part;
  part.shape = Shape(Box{half});
  part.position = position;
  part.density = density;
  return part;
}

PartDef spherePart(const Vec3& position, float radius) {
  PartDef part;
  part.shape = Shape(Sphere{radius});
  part.position = position;
  return part;
}

// The inertia of a solid box of mass m and half extents h about its centre, box axes.
using test::boxInertia;

TEST(Parts, MassCentreAndInertiaAreTheSumOfTheParts) {
  // Two unit cubes side by side along x, densities 1000 and 3000: 1 kg and 3 kg per litre... a 1 m
  // cube weighs 1000 and 3000 kg. The centre sits at the mass-weighted mean of their centres; the
  // inertia is each cube's own plus m d^2 about the axes across the offset (parallel axes).
  World world(test::zeroGravityWorld());
  BodyDef def;
  def.position = Vec3(5.0f, 1.0f, 0.0f);
  def.parts = {boxPart(Vec3(-1.0f, 0.0f, 0.0f), Vec3(0.5f), 1000.0f),
               boxPart(Vec3(1.0f, 0.0f, 0.0f), Vec3(0.5f), 3000.0f)};
  const BodyId body = world.createBody(def);
  def.position.z = 10.0f;
  const BodyId twin = world.createBody(def);
  EXPECT_FLOAT_EQ(world.mass(body), 4000.0f);
  const Vec3 center = world.centerOfMass(body);
  EXPECT_NEAR(center.x, 5.0f + (-1000.0f + 3000.0f) / 4000.0f, 1e-5f);
  EXPECT_NEAR(center.y, 1.0f, 1e-6f);
  EXPECT_EQ(world.transform(body).position, Vec3(5.0f, 1.0f, 0.0f));  // the origin stays the origin
  EXPECT_EQ(world.partCount(body), 2u);

  // The inertia about the centre (x = 0.5 in the body frame): a torque about a principal axis for
  // one step gives w = tau dt / I about it, so a torque of I gives w = dt.
  const float c = 0.5f;
  const float izz = boxInertia(1000.0f, Vec3(0.5f))[2][2] + 1000.0f * (-1.0f - c) * (-1.0f - c) +
                    boxInertia(3000.0f, Vec3(0.5f))[2][2] + 3000.0f * (1.0f - c) * (1.0f - c);
  const float ixx = boxInertia(1000.0f, Vec3(0.5f))[0][0] + boxInertia(3000.0f, Vec3(0.5f))[0][0];
  world.applyTorque(body, Vec3(0.0f, 0.0f, izz));
  world.applyTorque(twin, Vec3(ixx, 0.0f, 0.0f));
  world.step(kDt);
  EXPECT_NEAR(world.angularVelocity(body).z, kDt, 1e-4f * kDt);
  EXPECT_NEAR(world.angularVelocity(twin).x, kDt, 1e-4f * kDt);
}

TEST(Parts, TheTableOfTheDocsStandsOnItsFourLegs) {
  // docs/parts.md's example: a top and four legs, placed with its feet 5 cm above the ground. It settles on
  // its four legs: four contacts, one per leg part (1 to 4), none for the top, and its mass is the five
  // parts' at 1000 kg/m^3.
  World world;
  world.createBody(test::groundBox());
  BodyDef table;
  table.position = Vec3(0.0f, 0.8f, 0.0f);
  PartDef top;
  top.shape = Box{Vec3(1.0f, 0.05f, 0.6f)};
  top.material.friction = 0.3f;
  table.parts.push_back(top);
  for (const Vec3 leg : {Vec3(-0.9f, -0.4f, -0.5f), Vec3(0.9f, -0.4f, -0.5f), Vec3(-0.9f, -0.4f, 0.5f),
                         Vec3(0.9f, -0.4f, 0.5f)}) {
    PartDef part;
    part.shape = Box{Vec3(0.05f, 0.35f, 0.05f)};
    part.position = leg;
    part.material.friction = 0.9f;
    table.parts.push_back(part);
  }
  const BodyId id = world.createBody(table);
  const float volume = 2.0f * 0.1f * 1.2f + 4.0f * (0.1f * 0.7f * 0.1f);
  EXPECT_NEAR(world.mass(id), 1000.0f * volume, 1e-2f);
  for (int s = 0; s < 120; ++s) world.step(kDt);
  std::set<std::uint32_t> parts;
  world.visitContacts(id, [&](const ContactData& c) { parts.insert(c.a == id ? c.partA : c.partB); });
  EXPECT_EQ(parts, (std::set<std::uint32_t>{1, 2, 3, 4}));
  EXPECT_NEAR(world.transform(id).position.y, 0.75f, 0.01f);  // the feet at 0.75 - 0.4 - 0.35 = 0
}

TEST(Parts, AGivenMassIsSharedByTheDensities) {
  World world(test::zeroGravityWorld());
  BodyDef def;
  def.mass = 10.0f;
  def.parts = {boxPart(Vec3(0.0f), Vec3(0.5f), 1.0f), boxPart(Vec3(0.0f, 2.0f, 0.0f), Vec3(0.5f), 3.0f)};
  const BodyId body = world.createBody(def);
  EXPECT_FLOAT_EQ(world.mass(body), 10.0f);
  EXPECT_NEAR(world.centerOfMass(body).y, 1.5f, 1e-5f);  // 2.5 kg at 0, 7.5 kg at 2
}

TEST(Parts, APartOfDensityZeroHasNoMass) {
  World world(test::zeroGravityWorld());
  BodyDef def;
  PartDef trigger = spherePart(Vec3(0.0f, 3.0f, 0.0f), 1.0f);
  trigger.density = 0.0f;
  trigger.sensor = true;
  def.parts = {boxPart(Vec3(0.0f), Vec3(0.5f)), trigger};
  const BodyId body = world.createBody(def);
  EXPECT_FLOAT_EQ(world.mass(body), 1000.0f);
  EXPECT_NEAR(world.centerOfMass(body).y, 0.0f, 1e-6f);
}

TEST(Parts, BadPartsAreRefusedNamingThePart) {
  World world;
  const auto message = [&](BodyDef def) {
    return ::collide::test::errorOf([&] { world.createBody(def); }).value_or("no error");
  };
  BodyDef def;
  def.name = "crate";
  def.parts = {boxPart(Vec3(0.0f), Vec3(0.5f)), boxPart(Vec3(0.0f), Vec3(0.5f))};
  def.parts[1].material.friction = -1.0f;
  EXPECT_NE(message(def).find("body \"crate\": parts[1]: friction must be finite and >= 0"),
            std::string::npos);
  def.parts[1] = boxPart(Vec3(0.0f), Vec3(0.5f));
  def.parts[1].shape = Shape(Plane{Vec3(0, 1, 0), 0.0f});
  EXPECT_NE(message(def).find("parts[1]: shape: a plane"), std::string::npos);
  def.parts[1] = boxPart(Vec3(NAN, 0.0f, 0.0f), Vec3(0.5f));
  EXPECT_NE(message(def).find("parts[1]: position must be finite"), std::string::npos);
  def.parts[1] = boxPart(Vec3(0.0f), Vec3(0.5f), -2.0f);
  EXPECT_NE(message(def).find("parts[1]: density must be finite and >= 0"), std::string::npos);
  def.parts[0].density = def.parts[1].density = 0.0f;
  EXPECT_NE(message(def).find("parts: a dynamic body needs a part with density > 0"), std::string::npos);
  def.parts = {boxPart(Vec3(0.0f), Vec3(0.5f))};
  def.particle = true;
  EXPECT_NE(message(def).find("parts: a particle"), std::string::npos);
  EXPECT_EQ(world.bodyCount(), 0u);
}

TEST(Parts, EachPairOfPartsTakesItsOwnMaterials) {
  // A plank of two box parts resting on the ground, friction 0.1 and 0.9, bounciness 0 and 1,
  // against ground friction 0.5 (Average) and bounciness 0 (Max): the pre-solve callback sees one
  // contact per part, with the combined values of that part.
  World world;
  BodyDef ground = test::groundBox();
  ground.friction = 0.5f;
  world.createBody(ground);
  BodyDef plank;
  plank.position = Vec3(0.0f, 0.25f, 0.0f);
  plank.parts = {boxPart(Vec3(-0.5f, 0.0f, 0.0f), Vec3(0.5f, 0.25f, 0.5f)),
                 boxPart(Vec3(0.5f, 0.0f, 0.0f), Vec3(0.5f, 0.25f, 0.5f))};
  plank.parts[0].material = {0.1f, 0.0f, 0.0f};
  plank.parts[1].material = {0.9f, 1.0f, 0.0f};
  const BodyId body = world.createBody(plank);
  std::vector<std::pair<float, ContactSettings>> seen;  // mean x of the manifold's points, settings
  world.setPreSolveCallback([&](BodyId, BodyId, const Manifold& m, ContactSettings& settings) {
    float x = 0.0f;
    for (int i = 0; i < m.count; ++i) x += m.points[i].midpoint().x / float(m.count);
    seen.push_back({x, settings});
    return true;
  });
  world.step(kDt);
  ASSERT_EQ(seen.size(), 2u);
  const auto byX = [](const auto& a, const auto& b) { return a.first < b.first; };
  std::sort(seen.begin(), seen.end(), byX);
  EXPECT_LT(seen[0].first, 0.0f);
  EXPECT_FLOAT_EQ(seen[0].second.friction, 0.3f);
  EXPECT_FLOAT_EQ(seen[0].second.bounciness, 0.0f);
  EXPECT_GT(seen[1].first, 0.0f);
  EXPECT_FLOAT_EQ(seen[1].second.friction, 0.7f);
  EXPECT_FLOAT_EQ(seen[1].second.bounciness, 1.0f);

  // A part's material set at run time counts from the next step.
  world.setPartMaterial(body, 0, {0.9f, 0.0f, 0.0f});
  EXPECT_EQ(world.partMaterial(body, 0), (BodyMaterial{0.9f, 0.0f, 0.0f}));
  seen.clear();
  world.step(kDt);
  ASSERT_EQ(seen.size(), 2u);
  std::sort(seen.begin(), seen.end(), byX);
  EXPECT_FLOAT_EQ(seen[0].second.friction, 0.7f);
  EXPECT_FLOAT_EQ(seen[1].second.friction, 0.7f);
}

TEST(Parts, ABouncyPartBouncesAndADeadOneDoesNot) {
  // A body of one sphere part dropped on the ground beside the body of that sphere, both of
  // bounciness b (Max with the ground's 0): they rise to the same height after the bounce, which
  // for b = 1 is most of the 1.5 m fall, and for b = 0 none of it. The part's material reaches the
  // impact as the body's does.
  for (const float bounciness : {1.0f, 0.0f}) {
    World world;
    world.createBody(test::groundBox());
    BodyDef ball = test::sphereBody(Vec3(-2.0f, 2.0f, 0.0f), 0.5f, 1.0f);
    ball.bounciness = bounciness;
    const BodyId shape = world.createBody(ball);
    ball.position.x = 2.0f;
    ball.parts = {spherePart(Vec3(0.0f), 0.5f)};
    ball.parts[0].material.bounciness = bounciness;
    const BodyId parts = world.createBody(ball);
    float highest[2] = {0.0f, 0.0f};
    bool bounced[2] = {false, false};
    for (int s = 0; s < 120; ++s) {
      world.step(kDt);
      for (int k = 0; k < 2; ++k) {
        const BodyId id = k == 0 ? shape : parts;
        if (world.linearVelocity(id).y > 0.0f) bounced[k] = true;
        if (bounced[k]) highest[k] = std::max(highest[k], world.transform(id).position.y);
      }
    }
    EXPECT_NEAR(highest[0], highest[1], 1e-3f) << "bounciness " << bounciness;
    if (bounciness == 1.0f) {
      EXPECT_GT(highest[1], 0.5f + 0.8f * 1.5f);
    } else {
      EXPECT_LT(highest[1], 0.52f);  // at rest on the ground, centre at 0.5
    }
  }
}

// The rule of docs/parts.md, written out as the table is built: groups first, then the masks.
bool expectedToCollide(const CollisionFilter& a, const CollisionFilter& b) {
  if (a.group != 0 && a.group == b.group) return a.group > 0;
  return (a.layer & b.mask) != 0 && (b.layer & a.mask) != 0;
}

TEST(Parts, PairsOfPartsFollowTheirOwnFilters) {
  // A static body and a dynamic one, four box parts each, every part of one overlapping every part
  // of the other: after a step, a contact exists for exactly the pairs of parts the filters allow.
  const CollisionFilter filters[] = {
      {1, kAllLayers, 0},  // everything
      {2, 1, 0},           // only layer 1
      {4, 0, 7},           // nothing by masks, but group 7
      {1, kAllLayers, -3}  // never its own group -3
  };
  World world(test::zeroGravityWorld());
  BodyDef wall;
  wall.type = BodyType::Static;
  BodyDef mover;
  mover.position = Vec3(0.0f, 0.9f, 0.0f);  // 0.1 m into the wall's parts
  for (const CollisionFilter& f : filters) {
    PartDef part = boxPart(Vec3(0.0f), Vec3(0.5f));
    part.layer = f.layer;
    part.mask = f.mask;
    part.group = f.group;
    wall.parts.push_back(part);
    mover.parts.push_back(part);
  }
  const BodyId a = world.createBody(wall);
  const BodyId b = world.createBody(mover);
  for (std::uint32_t i = 0; i < 4; ++i) EXPECT_EQ(world.partFilter(b, i), filters[i]);
  world.step(kDt);
  std::set<std::pair<std::uint32_t, std::uint32_t>> touching;  // (wall part, mover part)
  world.visitContacts([&](const ContactData& c) {
    touching.insert(c.a == a ? std::pair{c.partA, c.partB} : std::pair{c.partB, c.partA});
  });
  int expected = 0;
  for (std::uint32_t i = 0; i < 4; ++i) {
    for (std::uint32_t j = 0; j < 4; ++j) {
      const bool collides = expectedToCollide(filters[i], filters[j]);
      expected += collides;
      EXPECT_EQ(touching.count({i, j}), collides ? 1u : 0u) << "wall part " << i << ", mover part " << j;
    }
  }
  EXPECT_EQ(touching.size(), static_cast<std::size_t>(expected));
  EXPECT_GT(expected, 3);
  EXPECT_LT(expected, 16);

  // A part's filter changed at run time: part 3 of the mover now collides with nothing.
  world.setPartFilter(b, 3, {1, 0, 0});
  world.step(kDt);
  bool part3 = false;
  world.visitContacts([&](const ContactData& c) { part3 = part3 || (c.b == b ? c.partB : c.partA) == 3; });
  EXPECT_FALSE(part3);
}

TEST(Parts, ASensorPartReportsAndTheSolidPartStops) {
  // A static body: a floor part and, above it, a sensor part (a trigger zone). A ball falls through
  // the zone (sensor begin, then end, naming part 1) and lands on the floor (contact begin naming
  // part 0), at rest on it.
  World world;
  BodyDef zone;
  zone.type = BodyType::Static;
  PartDef trigger = boxPart(Vec3(0.0f, 2.0f, 0.0f), Vec3(2.0f, 0.5f, 2.0f));
  trigger.sensor = true;
  zone.parts = {boxPart(Vec3(0.0f, -0.5f, 0.0f), Vec3(10.0f, 0.5f, 10.0f)), trigger};
  const BodyId floor = world.createBody(zone);
  const BodyId ball = world.createBody(test::sphereBody(Vec3(0.0f, 4.0f, 0.0f), 0.25f, 1.0f));
  std::vector<SensorEvent> sensorEvents;
  std::vector<ContactEvent> contactEvents;
  for (int s = 0; s < 180; ++s) {
    world.step(kDt);
    for (const SensorEvent& e : world.sensorEvents()) sensorEvents.push_back(e);
    for (const ContactEvent& e : world.contactEvents()) contactEvents.push_back(e);
  }
  ASSERT_EQ(sensorEvents.size(), 2u);
  EXPECT_EQ(sensorEvents[0].type, SensorEvent::Type::Begin);
  EXPECT_EQ(sensorEvents[1].type, SensorEvent::Type::End);
  for (const SensorEvent& e : sensorEvents) {
    EXPECT_EQ(e.sensor, floor);
    EXPECT_EQ(e.sensorPart, 1u);
    EXPECT_EQ(e.visitor, ball);
    EXPECT_EQ(e.visitorPart, 0u);
  }
  ASSERT_GE(contactEvents.size(), 1u);
  EXPECT_EQ(contactEvents[0].type, ContactEvent::Type::Begin);
  EXPECT_EQ(contactEvents[0].a == floor ? contactEvents[0].partA : contactEvents[0].partB, 0u);
  EXPECT_NEAR(world.transform(ball).position.y, 0.25f, 0.01f);
  EXPECT_TRUE(world.partIsSensor(floor, 1));
  EXPECT_FALSE(world.partIsSensor(floor, 0));
}

TEST(Parts, ThePreSolveCallbackSeesThePartsAndDisablesOne) {
  // A level body of two parts, a floor (0) and a platform above it (1); the callback disables every
  // contact with the platform: a ball dropped on it falls through and lands on the floor.
  World world;
  BodyDef level;
  level.type = BodyType::Static;
  level.parts = {boxPart(Vec3(0.0f, -0.5f, 0.0f), Vec3(5.0f, 0.5f, 5.0f)),
                 boxPart(Vec3(0.0f, 2.0f, 0.0f), Vec3(2.0f, 0.1f, 2.0f))};
  const BodyId levelId = world.createBody(level);
  const BodyId ball = world.createBody(test::sphereBody(Vec3(0.0f, 4.0f, 0.0f), 0.25f, 1.0f));
  std::set<std::uint32_t> seen;
  world.setPreSolveCallback([&](BodyId a, BodyId, const Manifold&, ContactSettings& settings) {
    const std::uint32_t part = a == levelId ? settings.partA : settings.partB;
    seen.insert(part);
    settings.partA = settings.partB = 99;  // ignored
    return part != 1;
  });
  for (int s = 0; s < 180; ++s) world.step(kDt);
  EXPECT_EQ(seen, (std::set<std::uint32_t>{0, 1}));
  EXPECT_NEAR(world.transform(ball).position.y, 0.25f, 0.01f);
  world.visitContacts([&](const ContactData& c) { EXPECT_EQ(c.a == levelId ? c.partA : c.partB, 0u); });
}

TEST(Parts, ContinuousCollisionStopsEachSolidPartAndLetsAFilteredOnePass) {
  // A fast bar of two parts (a thin plate ahead, a box behind) shot at a thin static wall at
  // 200 m/s: it does not tunnel. With the plate filtered from the wall's layer, the plate passes and
  // the box behind it is what stops.
  for (const bool plateFiltered : {false, true}) {
    World world(test::zeroGravityWorld());
    BodyDef wall;
    wall.type = BodyType::Static;
    wall.shape = Shape(Box{Vec3(0.05f, 2.0f, 2.0f)});
    wall.position = Vec3(10.0f, 0.0f, 0.0f);
    wall.layer = 1;
    world.createBody(wall);
    BodyDef bar;
    bar.linearVelocity = Vec3(200.0f, 0.0f, 0.0f);
    bar.parts = {boxPart(Vec3(1.0f, 0.0f, 0.0f), Vec3(0.02f, 0.3f, 0.3f)),
                 boxPart(Vec3(-1.0f, 0.0f, 0.0f), Vec3(0.2f, 0.2f, 0.2f))};
    if (plateFiltered) bar.parts[0].layer = 2, bar.parts[0].mask = 2;
    const BodyId id = world.createBody(bar);
    float farthest = 0.0f;  // of the body origin (the bar rebounds from the wall)
    for (int s = 0; s < 10; ++s) {
      world.step(kDt);
      farthest = std::max(farthest, world.transform(id).position.x);
    }
    const float wallFace = 10.0f - 0.05f;
    if (!plateFiltered) {
      EXPECT_LT(farthest + 1.0f + 0.02f, wallFace + 0.01f) << "the plate went into the wall";
    } else {
      EXPECT_GT(farthest + 1.0f, 10.05f) << "the filtered plate was stopped";
      EXPECT_LT(farthest - 1.0f + 0.2f, wallFace + 0.01f) << "the box went into the wall";
    }
  }
}

// ---- Queries, part by part, against a brute force over every part of every body ----

std::vector<Shape> convexShapes() {
  return {Shape(Sphere{0.4f}), Shape(Box{Vec3(0.3f, 0.5f, 0.2f)}), Shape(Capsule{0.5f, 0.2f}),
          Shape(Cylinder{0.4f, 0.3f}), Shape(Ellipsoid{Vec3(0.5f, 0.3f, 0.2f)})};
}

struct QueryScene {
  World world{test::zeroGravityWorld()};
  std::vector<BodyId> bodies;
};

// Twenty bodies of two to four parts of every convex type, random poses, parts on layers 1 or 2.
void buildQueryScene(QueryScene& scene, std::mt19937& rng) {
  std::uniform_real_distribution<float> u(-4.0f, 4.0f);
  std::uniform_int_distribution<int> count(2, 4);
  const std::vector<Shape> shapes = convexShapes();
  for (int b = 0; b < 20; ++b) {
    BodyDef def;
    def.type = b % 3 == 0 ? BodyType::Static : BodyType::Dynamic;
    def.position = Vec3(u(rng), u(rng), u(rng));
    def.rotation = test::randomRotation(rng);
    def.scale = b % 4 == 0 ? 1.5f : 1.0f;
    const int n = count(rng);
    for (int p = 0; p < n; ++p) {
      PartDef part;
      part.shape = shapes[(b + p) % shapes.size()];
      part.position = 0.8f * test::randomInUnitBall(rng);
      part.rotation = test::randomRotation(rng);
      part.layer = (b + p) % 2 == 0 ? 1u : 2u;
      def.parts.push_back(part);
    }
    scene.bodies.push_back(scene.world.createBody(def));
  }
}

Transform partPose(const World& world, BodyId body, std::uint32_t part) {
  return world.transform(body) * world.partLocalPose(body, part);
}

TEST(PartQueries, RaysHitTheNearestPartTheFilterSees) {
  std::mt19937 rng(11);
  QueryScene scene;
  buildQueryScene(scene, rng);
  const World& world = scene.world;
  for (int r = 0; r < 300; ++r) {
    Ray ray;
    ray.origin = 8.0f * test::randomUnitVector(rng);
    ray.direction = glm::normalize(0.5f * test::randomInUnitBall(rng) - ray.origin);
    ray.maxDistance = 16.0f;
    QueryFilter filter;
    filter.mask = r % 3 == 0 ? 2u : kAllLayers;
    // Brute force: every part of every body the filter sees, the nearest hit of each body, with the
    // direction normalised as the world normalises it (grazing hits are sensitive to its last bit).
    Ray unit = ray;
    unit.direction = ray.direction / glm::length(ray.direction);
    std::vector<std::pair<float, std::pair<std::uint32_t, std::uint32_t>>> expected;
    for (const BodyId body : scene.bodies) {
      std::optional<std::pair<float, std::uint32_t>> best;
      for (std::uint32_t p = 0; p < world.partCount(body); ++p) {
        if ((world.partFilter(body, p).layer & filter.mask) == 0) continue;
        const auto hit = rayCast(world.partShape(body, p), partPose(world, body, p), unit);
        if (hit && (!best || hit->distance < best->first)) best = std::pair{hit->distance, p};
      }
      if (best) expected.push_back({best->first, {body.index, best->second}});
    }
    std::sort(expected.begin(), expected.end());
    const std::vector<RayCastResult> all = world.castRayAll(ray, filter);
    ASSERT_EQ(all.size(), expected.size()) << "ray " << r;
    for (std::size_t k = 0; k < all.size(); ++k) {
      EXPECT_EQ(all[k].distance, expected[k].first) << "ray " << r;
      EXPECT_EQ(all[k].body.index, expected[k].second.first) << "ray " << r;
      EXPECT_EQ(all[k].part, expected[k].second.second) << "ray " << r;
    }
    const std::optional<RayCastResult> closest = world.castRay(ray, filter);
    ASSERT_EQ(closest.has_value(), !expected.empty());
    if (closest) {
      EXPECT_EQ(closest->part, expected[0].second.second);
    }
  }
}

TEST(PartQueries, OverlapsListEveryPartTouched) {
  std::mt19937 rng(12);
  QueryScene scene;
  buildQueryScene(scene, rng);
  const World& world = scene.world;
  const Shape probe(Box{Vec3(0.8f, 0.6f, 0.7f)});
  int found = 0;
  for (int q = 0; q < 200; ++q) {
    const Transform pose{4.0f * test::randomInUnitBall(rng), test::randomRotation(rng), 1.0f};
    std::vector<std::pair<std::uint32_t, std::uint32_t>> expected;
    for (const BodyId body : scene.bodies) {
      for (std::uint32_t p = 0; p < world.partCount(body); ++p) {
        Manifold m;
        if (collide(probe, pose, world.partShape(body, p), partPose(world, body, p), m) &&
            m.maxDepth() >= 0.0f)
          expected.push_back({body.index, p});
      }
    }
    std::sort(expected.begin(), expected.end());
    std::vector<std::pair<std::uint32_t, std::uint32_t>> got;
    for (const OverlapResult& o : world.overlapShape(probe, pose)) got.push_back({o.body.index, o.part});
    EXPECT_EQ(got, expected) << "query " << q;
    found += static_cast<int>(got.size());
  }
  EXPECT_GT(found, 100);
}

TEST(PartQueries, ShapeCastsReachTheEarliestPart) {
  std::mt19937 rng(13);
  QueryScene scene;
  buildQueryScene(scene, rng);
  const World& world = scene.world;
  const Shape probe(Sphere{0.3f});
  ToiSettings settings;
  settings.targetSeparation = 0.0f;
  int hits = 0;
  for (int q = 0; q < 100; ++q) {
    const Transform start{9.0f * test::randomUnitVector(rng), Quat(1, 0, 0, 0), 1.0f};
    const Vec3 translation = -2.0f * start.position;
    Transform end = start;
    end.position += translation;
    const Sweep sweep = Sweep::between(start, end);
    std::optional<std::pair<float, std::pair<std::uint32_t, std::uint32_t>>> expected;
    for (const BodyId body : scene.bodies) {
      for (std::uint32_t p = 0; p < world.partCount(body); ++p) {
        const ToiResult toi = timeOfImpact(probe, sweep, world.partShape(body, p),
                                           Sweep::fixed(partPose(world, body, p)), settings);
        if (toi.state == ToiResult::State::Separated) continue;
        const float t = toi.state == ToiResult::State::Overlapping ? 0.0f : toi.t;
        const std::pair<float, std::pair<std::uint32_t, std::uint32_t>> candidate{t, {body.index, p}};
        if (!expected || candidate < *expected) expected = candidate;
      }
    }
    const std::optional<ShapeCastResult> hit = world.castShape(probe, start, translation);
    ASSERT_EQ(hit.has_value(), expected.has_value()) << "cast " << q;
    if (!hit) continue;
    ++hits;
    EXPECT_NEAR(hit->fraction, expected->first, 1e-5f) << "cast " << q;
    EXPECT_EQ(hit->body.index, expected->second.first) << "cast " << q;
    EXPECT_EQ(hit->part, expected->second.second) << "cast " << q;
  }
  EXPECT_GT(hits, 20);
}

// ---- Parts at run time ----

TEST(Parts, AddingAndRemovingAPartRecomputesTheMassAndKeepsTheOrigin) {
  World world(test::zeroGravityWorld());
  BodyDef def = test::boxBody(Vec3(1.0f, 2.0f, 3.0f), Vec3(0.5f), 8.0f);
  def.mass.reset();  // density 1000: 1000 kg
  def.friction = 0.25f;
  const BodyId body = world.createBody(def);
  world.setAngularVelocity(body, Vec3(0.0f, 0.0f, 1.0f));
  EXPECT_EQ(world.partCount(body), 1u);

  const std::uint32_t added = world.addPart(body, boxPart(Vec3(2.0f, 0.0f, 0.0f), Vec3(0.5f), 1000.0f));
  EXPECT_EQ(added, 1u);
  EXPECT_EQ(world.partCount(body), 2u);
  EXPECT_FLOAT_EQ(world.mass(body), 2000.0f);
  EXPECT_NEAR(world.centerOfMass(body).x, 2.0f, 1e-5f);
  EXPECT_EQ(world.transform(body).position, Vec3(1.0f, 2.0f, 3.0f));
  EXPECT_FLOAT_EQ(world.partMaterial(body, 0).friction, 0.25f);  // the shape became part 0
  // The body keeps turning about z at 1 rad/s: its new centre, 1 m from the old along x, moves at
  // w x r = 1 m/s along y.
  EXPECT_NEAR(world.linearVelocity(body).y, 1.0f, 1e-5f);

  world.removePart(body, 0);
  EXPECT_EQ(world.partCount(body), 1u);
  EXPECT_FLOAT_EQ(world.mass(body), 1000.0f);
  EXPECT_NEAR(world.centerOfMass(body).x, 3.0f, 1e-5f);
  EXPECT_EQ(world.partLocalPose(body, 0).position, Vec3(2.0f, 0.0f, 0.0f));

  EXPECT_COLLIDE_ERROR(world.removePart(body, 0));  // the last part stays
  EXPECT_COLLIDE_ERROR(world.removePart(body, 5));
  PartDef plane;
  plane.shape = Shape(Plane{Vec3(0, 1, 0), 0.0f});
  EXPECT_COLLIDE_ERROR(world.addPart(body, plane));
  EXPECT_EQ(world.partCount(body), 1u);
  EXPECT_FLOAT_EQ(world.mass(body), 1000.0f);
}

TEST(Parts, RemovingAPartEndsItsContactsAndNoOther) {
  // A plank of two parts resting on the ground: removing part 0 ends part 0's contact (an End event
  // with the next step) and the other contact goes on, now as part 0, with no end and no begin.
  World world;
  world.createBody(test::groundBox());
  BodyDef plank;
  plank.position = Vec3(0.0f, 0.25f, 0.0f);
  plank.parts = {boxPart(Vec3(-0.5f, 0.0f, 0.0f), Vec3(0.5f, 0.25f, 0.5f)),
                 boxPart(Vec3(0.5f, 0.0f, 0.0f), Vec3(0.5f, 0.25f, 0.5f))};
  const BodyId body = world.createBody(plank);
  world.step(kDt);
  int begins = 0;
  for (const ContactEvent& e : world.contactEvents()) begins += e.type == ContactEvent::Type::Begin;
  EXPECT_EQ(begins, 2);
  world.removePart(body, 0);
  world.step(kDt);
  std::vector<ContactEvent> events(world.contactEvents().begin(), world.contactEvents().end());
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].type, ContactEvent::Type::End);
  EXPECT_EQ(events[0].a == body ? events[0].partA : events[0].partB, 0u);
  int contacts = 0;
  world.visitContacts([&](const ContactData& c) {
    ++contacts;
    EXPECT_EQ(c.a == body ? c.partA : c.partB, 0u);
  });
  EXPECT_EQ(contacts, 1);
}

TEST(Parts, ABodyOfOnePartRestsAsTheBodyOfThatShape) {
  // The same box as a shape and as a single part, dropped side by side: they land and rest alike.
  World world;
  world.createBody(test::groundBox());
  BodyDef shape = test::boxBody(Vec3(-3.0f, 1.0f, 0.0f), Vec3(0.5f), 1.0f);
  shape.rotation = glm::angleAxis(0.3f, glm::normalize(Vec3(1.0f, 0.0f, 1.0f)));
  BodyDef parts = shape;
  parts.position.x = 3.0f;
  parts.parts = {boxPart(Vec3(0.0f), Vec3(0.5f))};
  const BodyId a = world.createBody(shape);
  const BodyId b = world.createBody(parts);
  for (int s = 0; s < 240; ++s) world.step(kDt);
  const Transform ta = world.transform(a), tb = world.transform(b);
  EXPECT_NEAR(ta.position.y, tb.position.y, 1e-3f);
  EXPECT_NEAR(ta.position.y, 0.5f, 0.01f);
  EXPECT_NEAR(ta.position.x + 3.0f, tb.position.x - 3.0f, 1e-3f);
  EXPECT_GT(std::abs(glm::dot(ta.rotation, tb.rotation)), 1.0f - 1e-4f);
}

}  // namespace
}  // namespace collide
