// Bad input in both builds (collide/error.h): with exceptions a collide::Error is thrown; without
// them the error handler hears the same message once per call, lastError() keeps it, nothing
// changes, and the call returns a result that says so.
#include <collide/collide.h>
#include <collide/error.h>

#include "support/collide_error.h"
#include "support/world_helpers.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>
#include <string>
#include <vector>

namespace collide {
namespace {

using ::testing::HasSubstr;

TEST(ErrorReporting, TheBuildSaysHowItReports) { EXPECT_EQ(exceptionsEnabled(), COLLIDE_EXCEPTIONS != 0); }

TEST(ErrorReporting, ABadBodyIsRefusedWholeWithItsFieldNamed) {
  World world;
  BodyDef def = test::boxBody(Vec3(0.0f), Vec3(0.5f), 1.0f);
  def.name = "crate";
  def.linearDamping = -1.0f;
  BodyId id{};
  const std::vector<std::string> messages = test::handledErrors([&] { id = world.createBody(def); });
  EXPECT_EQ(world.bodyCount(), 0u);
  EXPECT_TRUE(id.isNull());
  EXPECT_THAT([&] { world.createBody(def); },
              test::ReportsError("body \"crate\": linearDamping must be finite and >= 0, got -1"));
  if (!exceptionsEnabled()) {
    ASSERT_EQ(messages.size(), 1u);  // once per call, with the whole context
    EXPECT_EQ(messages[0], "body \"crate\": linearDamping must be finite and >= 0, got -1");
    EXPECT_EQ(std::string(lastError()), messages[0]);
  } else {
    EXPECT_TRUE(messages.empty());  // thrown instead
  }
  // The world goes on: a good body after a refused one.
  def.linearDamping = 0.0f;
  const BodyId good = world.createBody(def);
  EXPECT_TRUE(world.isValid(good));
  EXPECT_EQ(world.bodyCount(), 1u);
}

TEST(ErrorReporting, AFailureDeepInsideCarriesEveryLayersContext) {
  // The part's mass properties fail inside the body's: the message names the body, the part and
  // the shape, in both builds.
  World world;
  BodyDef def;
  def.name = "table";
  def.type = BodyType::Dynamic;
  PartDef top;
  top.shape = Shape(Box{Vec3(1e30f, 0.1f, 1e30f)});
  def.parts = {top};
  EXPECT_THAT([&] { world.createBody(def); }, test::ReportsError(HasSubstr("body \"table\": ")));
  EXPECT_EQ(world.bodyCount(), 0u);
}

TEST(ErrorReporting, StaleIdsAreReportedAndChangeNothing) {
  World world;
  const BodyId id = world.createBody(test::boxBody(Vec3(0.0f), Vec3(0.5f), 1.0f));
  world.destroyBody(id);
  EXPECT_THAT([&] { world.setLinearVelocity(id, Vec3(1.0f)); },
              test::ReportsError(HasSubstr("setLinearVelocity: invalid or stale body id")));
  EXPECT_THAT([&] { static_cast<void>(world.mass(id)); },
              test::ReportsError(HasSubstr("mass: invalid or stale")));
  if (!exceptionsEnabled()) {
    float mass = -1.0f;
    test::handledErrors([&] { mass = world.mass(id); });
    EXPECT_EQ(mass, 0.0f);  // a default body's
    std::uint32_t part = 0;
    test::handledErrors([&] { part = world.addPart(id, PartDef{}); });
    EXPECT_EQ(part, World::kNoPart);
  }
}

TEST(ErrorReporting, FactoriesReturnEmptyShapesThatTheWorldRefuses) {
  const std::vector<Vec3> flat = {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}, {1, 0, 1}};
  EXPECT_THAT([&] { ConvexHull::fromPoints(flat); }, test::ReportsError(HasSubstr("points are coplanar")));
  EXPECT_THAT([&] { TriangleMesh::fromTriangles({}, {}); },
              test::ReportsError(HasSubstr("mesh: needs at least one triangle")));
  if (exceptionsEnabled()) return;
  ConvexHull hull;
  test::handledErrors([&] { hull = ConvexHull::fromPoints(flat); });
  EXPECT_TRUE(hull.isEmpty());
  // A Shape of it is reported when made, and refused by whatever uses it, with the context.
  std::vector<std::string> messages;
  std::optional<Shape> shape;
  messages = test::handledErrors([&] { shape.emplace(std::move(hull)); });
  ASSERT_EQ(messages.size(), 1u);
  EXPECT_THAT(messages[0], HasSubstr("convex_hull: empty"));
  World world;
  BodyDef def;
  def.shape = *shape;
  BodyId id{};
  messages = test::handledErrors([&] { id = world.createBody(def); });
  EXPECT_TRUE(id.isNull());
  ASSERT_EQ(messages.size(), 1u);
  EXPECT_EQ(messages[0], "body: shape: convex_hull: empty (ConvexHull::fromPoints failed)");
  std::optional<ShapeCastResult> hit;
  messages = test::handledErrors([&] { hit = world.castShape(*shape, Transform{}, Vec3(1.0f)); });
  EXPECT_FALSE(hit.has_value());
  ASSERT_EQ(messages.size(), 1u);
  EXPECT_EQ(messages[0], "world: castShape: shape: convex_hull: empty (ConvexHull::fromPoints failed)");
}

TEST(ErrorReporting, ABadPrimitiveIsKeptReportedAndRefusedAgain) {
  EXPECT_THAT([] { Shape(Sphere{-1.0f}); },
              test::ReportsError("sphere: radius must be finite and > 0, got -1"));
  if (exceptionsEnabled()) return;
  std::optional<Shape> bad;
  test::handledErrors([&] { bad.emplace(Sphere{-1.0f}); });
  World world;
  BodyDef def;
  def.type = BodyType::Dynamic;
  def.shape = *bad;
  EXPECT_THAT([&] { world.createBody(def); },
              test::ReportsError("body: shape: sphere: radius must be finite and > 0, got -1"));
  EXPECT_THAT(
      [&] { world.overlapShape(*bad, Transform{}); },
      test::ReportsError("world: overlapShape: shape: sphere: radius must be finite and > 0, got -1"));
  EXPECT_EQ(world.bodyCount(), 0u);
}

TEST(ErrorReporting, ABadWorldDefinitionGivesNoWorldFromCreate) {
  WorldDef def;
  def.substeps = 0;
  EXPECT_THAT([&] { World::create(def); }, test::ReportsError("world: substeps must be 1 to 64, got 0"));
  if (exceptionsEnabled()) return;
  std::unique_ptr<World> world;
  test::handledErrors([&] { world = World::create(def); });
  EXPECT_EQ(world, nullptr);
  // The constructor, which cannot return nothing, takes the default definition instead.
  std::optional<World> fallback;
  test::handledErrors([&] { fallback.emplace(def); });
  EXPECT_EQ(fallback->def().substeps, WorldDef{}.substeps);
  def.substeps = 2;
  EXPECT_NE(World::create(def), nullptr);
}

TEST(ErrorReporting, ACorruptSnapshotLeavesTheWorldAsItWas) {
  World world;
  const BodyId id = world.createBody(test::boxBody(Vec3(0.0f, 2.0f, 0.0f), Vec3(0.5f), 1.0f));
  std::vector<std::uint8_t> bytes = world.saveSnapshot();
  world.step(1.0f / 60.0f);
  bytes[bytes.size() / 2] ^= 0x5a;
  EXPECT_THAT([&] { world.loadSnapshot(bytes); }, test::ReportsError(HasSubstr("snapshot: corrupt")));
  EXPECT_TRUE(world.isValid(id));
  EXPECT_LT(world.transform(id).position.y, 2.0f);  // still the stepped world
}

TEST(ErrorReporting, StaleJointIdsReadNoBody) {
  World world;
  world.createBody(test::groundBox());
  const BodyId a = world.createBody(test::sphereBody(Vec3(0.0f, 3.0f, 0.0f), 0.5f, 1.0f));
  const BodyId b = world.createBody(test::sphereBody(Vec3(0.0f, 2.0f, 0.0f), 0.5f, 1.0f));
  BallJointDef def;
  def.a = a;
  def.b = b;
  def.anchor = Vec3(0.0f, 2.5f, 0.0f);
  const JointId joint = world.createBallJoint(def);
  world.destroyConstraint(joint);
  EXPECT_THAT([&] { world.jointBodyA(joint); },
              test::ReportsError(HasSubstr("jointBodyA: invalid or stale")));
  EXPECT_THAT([&] { world.jointAnchorB(joint); },
              test::ReportsError(HasSubstr("jointAnchorB: invalid or stale")));
  EXPECT_THAT([&] { world.jointSpeed(joint); },
              test::ReportsError(HasSubstr("jointSpeed: invalid or stale")));
  if (exceptionsEnabled()) return;
  BodyId body = a;
  Vec3 anchor(1.0f);
  const std::vector<std::string> messages = test::handledErrors([&] {
    body = world.jointBodyA(joint);
    anchor = world.jointAnchorA(joint);
  });
  EXPECT_TRUE(body.isNull());  // not body 0 of the world
  EXPECT_EQ(anchor, Vec3(0.0f));
  EXPECT_EQ(messages.size(), 2u);
  // A world without bodies: nothing to read at all.
  World empty;
  float speed = 1.0f;
  test::handledErrors([&] { speed = empty.jointSpeed(JointId{0, 0}); });
  EXPECT_EQ(speed, 0.0f);
}

TEST(ErrorReporting, AStalePartGetterReportsOnce) {
  World world;
  const BodyId id = world.createBody(test::boxBody(Vec3(0.0f), Vec3(0.5f), 1.0f));
  world.destroyBody(id);
  EXPECT_THAT([&] { world.partMaterial(id, 3); },
              test::ReportsError(HasSubstr("partMaterial: invalid or stale")));
  if (!exceptionsEnabled()) {
    EXPECT_EQ(test::handledErrors([&] { world.partShape(id, 3); }).size(), 1u);
  }
}

TEST(ErrorReporting, FreeFunctionsRefuseAShapeFromAFailedFactory) {
  if (exceptionsEnabled()) GTEST_SKIP() << "with exceptions no such Shape can be made";
  const std::vector<Vec3> flat = {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}, {1, 0, 1}};
  std::optional<Shape> empty;
  test::handledErrors([&] { empty.emplace(ConvexHull::fromPoints(flat)); });
  const Shape ball(Sphere{1.0f});
  const Transform at{};
  Manifold manifold;
  const std::vector<std::pair<const char*, std::function<void()>>> calls = {
      {"localBounds", [&] { EXPECT_TRUE(localBounds(*empty).isEmpty()); }},
      {"worldBounds", [&] { EXPECT_TRUE(worldBounds(*empty, at).isEmpty()); }},
      {"support", [&] { EXPECT_EQ(support(*empty, Vec3(1.0f, 0.0f, 0.0f)), Vec3(0.0f)); }},
      {"massProperties", [&] { EXPECT_EQ(massProperties(*empty, 1.0f).mass, 0.0f); }},
      {"rayCast",
       [&] {
         EXPECT_FALSE(rayCast(*empty, at, Ray{Vec3(0.0f, 5.0f, 0.0f), Vec3(0, -1, 0), 10.0f}));
       }},
      {"containsPoint", [&] { EXPECT_FALSE(containsPoint(*empty, at, Vec3(0.1f))); }},
      {"collide", [&] { EXPECT_FALSE(collide::collide(*empty, at, ball, at, manifold)); }},
      {"overlap", [&] { EXPECT_FALSE(overlap(ball, at, *empty, at)); }},
      {"distance", [&] { static_cast<void>(distance(*empty, at, ball, at)); }},
  };
  for (const auto& call : calls) {
    const std::vector<std::string> messages = test::handledErrors(call.second);
    ASSERT_EQ(messages.size(), 1u) << call.first;
    EXPECT_EQ(messages[0], "convex_hull: empty (ConvexHull::fromPoints failed)") << call.first;
  }
}

TEST(ErrorReporting, ACompoundWithoutMassGivesNoPartialSum) {
  // An open mesh is a fine child of a static compound, which then has no mass properties.
  const Shape quad(TriangleMesh::fromTriangles({{0, 0, 0}, {1, 0, 0}, {1, 0, 1}}, {{{0, 2, 1}}}));
  const Shape compound(Compound::fromChildren({{Shape(Sphere{1.0f}), {}}, {quad, {{3, 0, 0}}}}));
  EXPECT_THAT([&] { massProperties(compound, 1.0f); }, test::ReportsError(HasSubstr("child 1 has no mass")));
  if (exceptionsEnabled()) return;
  MassProperties m;
  m.mass = -1.0f;
  const std::vector<std::string> messages = test::handledErrors([&] { m = massProperties(compound, 1.0f); });
  EXPECT_EQ(messages.size(), 1u);
  EXPECT_EQ(m.mass, 0.0f);  // not the sphere's alone
}

// A world with every kind of record a snapshot holds: shapes of each family, parts, contacts, joints.
void buildBusyWorld(World& world) {
  world.createBody(test::groundBox());
  const BodyId a = world.createBody(test::boxBody(Vec3(0.0f, 0.6f, 0.0f), Vec3(0.5f), 1.0f));
  const BodyId b = world.createBody(test::sphereBody(Vec3(0.0f, 1.8f, 0.0f), 0.5f, 1.0f));
  BodyDef hull;
  hull.type = BodyType::Dynamic;
  hull.position = Vec3(2.0f, 1.0f, 0.0f);
  hull.shape =
      Shape(ConvexHull::fromPoints(std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}}));
  world.createBody(hull);
  BodyDef table;
  table.type = BodyType::Dynamic;
  table.position = Vec3(-2.0f, 1.0f, 0.0f);
  PartDef top, leg;
  top.shape = Shape(Box{Vec3(0.5f, 0.05f, 0.5f)});
  leg.shape = Shape(Capsule{0.05f, 0.3f});
  leg.position = Vec3(0.0f, -0.35f, 0.0f);
  table.parts = {top, leg};
  world.createBody(table);
  BallJointDef ball;
  ball.a = a;
  ball.b = b;
  ball.anchor = Vec3(0.0f, 1.2f, 0.0f);
  world.createBallJoint(ball);
  for (int i = 0; i < 30; ++i) world.step(1.0f / 60.0f);
}

// Bytes of a snapshot whose contents were changed, with a checksum that matches them again (the
// header's layout: mark, format, library, layout, length, checksum), so that the reading itself
// meets the damage.
void resealSnapshot(std::vector<std::uint8_t>& bytes) {
  constexpr std::size_t kHeader = 40;
  const std::uint64_t length = bytes.size() - kHeader;
  std::uint64_t hash = 0xcbf29ce484222325ull;
  for (std::size_t i = kHeader; i < bytes.size(); ++i) hash = (hash ^ bytes[i]) * 0x100000001b3ull;
  std::memcpy(bytes.data() + 24, &length, sizeof length);
  std::memcpy(bytes.data() + 32, &hash, sizeof hash);
}

TEST(ErrorReporting, ASnapshotAskingForEndlessWorkIsRefused) {
  // A snapshot carries the world's settings, and a hostile one could ask each step for a billion
  // substeps or relax passes: a stalled program, not an error. The reader checks the loaded
  // definition as World's constructor does, so these are refused by name.
  WorldDef def;
  def.substeps = 37;
  def.contact.relaxPasses = 3;
  World source(def);
  buildBusyWorld(source);
  const std::vector<std::uint8_t> good = source.saveSnapshot();
  // The definition's substeps follow its gravity; its relax passes, the contact tuning's six floats.
  std::vector<std::uint8_t> marker(sizeof(float) * 3 + sizeof(int));
  std::memcpy(marker.data(), &def.gravity, sizeof(float) * 3);
  std::memcpy(marker.data() + sizeof(float) * 3, &def.substeps, sizeof(int));
  const auto at = std::search(good.begin() + 40, good.end(), marker.begin(), marker.end());
  ASSERT_NE(at, good.end()) << "the world definition's gravity and substeps";
  const std::size_t substepsAt = static_cast<std::size_t>(at - good.begin()) + sizeof(float) * 3;
  const auto refusedWith = [&](std::size_t offset, int value, const std::string& message) {
    std::vector<std::uint8_t> bytes = good;
    std::memcpy(bytes.data() + offset, &value, sizeof value);
    resealSnapshot(bytes);
    World target;
    EXPECT_THAT([&] { target.loadSnapshot(bytes); }, test::ReportsError(HasSubstr(message))) << value;
    EXPECT_EQ(target.bodyCount(), 0u);
  };
  refusedWith(substepsAt, kMaxSubsteps + 1, "substeps must be 1 to 64, got 65");
  refusedWith(substepsAt, 1'000'000'000, "substeps must be 1 to 64, got 1000000000");
  // The relax passes: the first 3 after the substeps (BroadPhaseSettings and the enums lie between).
  const int three = 3;
  const auto relax = std::search(good.begin() + static_cast<std::ptrdiff_t>(substepsAt) + 4, good.end(),
                                 reinterpret_cast<const std::uint8_t*>(&three),
                                 reinterpret_cast<const std::uint8_t*>(&three) + sizeof three);
  ASSERT_NE(relax, good.end());
  refusedWith(static_cast<std::size_t>(relax - good.begin()), kMaxRelaxPasses + 1,
              "relaxPasses out of range (must be 0 to 16), got 17");
  // The largest counts allowed still load and step.
  std::vector<std::uint8_t> bytes = good;
  std::memcpy(bytes.data() + substepsAt, &kMaxSubsteps, sizeof(int));
  resealSnapshot(bytes);
  World target;
  EXPECT_NO_COLLIDE_ERROR(target.loadSnapshot(bytes));
  EXPECT_EQ(target.def().substeps, kMaxSubsteps);
  target.step(1.0f / 60.0f);
}

TEST(ErrorReporting, DamagedSnapshotsAreRefusedOrLoadWithoutHarm) {
  // Every change a reader can meet mid-way (a flipped bit in any field, a count, an index, a cut
  // short payload): refused with an Error that leaves the world as it was, or, where the bytes
  // still make a world, loaded and stepped. In the build without exceptions this walks the reader's
  // failure paths, which go on reading zeros to the end instead of unwinding.
  World source;
  buildBusyWorld(source);
  const std::vector<std::uint8_t> good = source.saveSnapshot();
  std::mt19937 rng(20261206);
  int loaded = 0;
  for (int trial = 0; trial < 600; ++trial) {
    std::vector<std::uint8_t> bytes = good;
    const bool cut = trial % 4 == 3;
    if (cut) {
      bytes.resize(40 + std::uniform_int_distribution<std::size_t>(0, good.size() - 41)(rng));
    } else {
      for (int flips = 1 + trial % 3; flips > 0; --flips) {
        const std::size_t at = std::uniform_int_distribution<std::size_t>(40, bytes.size() - 1)(rng);
        bytes[at] ^= static_cast<std::uint8_t>(1u << std::uniform_int_distribution<int>(0, 7)(rng));
      }
    }
    resealSnapshot(bytes);
    World target;
    target.createBody(test::boxBody(Vec3(0.0f, 5.0f, 0.0f), Vec3(1.0f), 2.0f));
    const std::vector<std::uint8_t> before = target.saveSnapshot();
    const std::optional<std::string> error = test::errorOf([&] { target.loadSnapshot(bytes); });
    if (cut) {
      EXPECT_TRUE(error.has_value()) << "trial " << trial << ": a payload cut short was loaded";
    }
    if (error) {
      EXPECT_THAT(*error, HasSubstr("snapshot: ")) << "trial " << trial;
      ASSERT_EQ(target.saveSnapshot(), before) << "trial " << trial << ": " << *error;
    } else {
      ++loaded;
      for (int i = 0; i < 5; ++i) target.step(1.0f / 60.0f);
    }
  }
  RecordProperty("loaded", loaded);
}

}  // namespace
}  // namespace collide
