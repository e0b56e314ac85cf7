// The scene loader: every field of docs/scene-format.md lands where it should, and each class of
// bad input is refused with a message naming the field path and the value.
#include <collide/scene/scene.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "support/scene_data.h"

namespace collide::scene {
namespace {

using ::testing::HasSubstr;

using collide::test::kSceneData;

// The message of the Error that parsing `text` throws ("" if it does not throw).
std::string sceneParseError(const std::string& text) {
  try {
    parseScene(text, "test.json", kSceneData);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// A one-body scene around `body`.
std::string withBody(const std::string& body) {
  return R"({"format": "collide-scene/1", "bodies": [)" + body + "]}";
}

TEST(SceneParser, EveryFieldReachesTheScene) {
  const Scene s = loadSceneFile(kSceneData + "/every_field.json");
  EXPECT_EQ(s.world.gravity, Vec3(0.5f, -9.5f, 0.25f));
  EXPECT_FLOAT_EQ(s.dt, 0.01f);
  EXPECT_EQ(s.steps, 42);
  EXPECT_EQ(s.world.substeps, 6);
  EXPECT_EQ(s.world.broadPhase.type, BroadPhaseType::SweepAndPrune);
  EXPECT_FALSE(s.world.ccd);  // the engine default is true
  EXPECT_FALSE(s.world.sleeping);
  EXPECT_TRUE(s.world.persistEvents);                            // the engine default is false
  EXPECT_FLOAT_EQ(s.world.contact.restitutionThreshold, 0.25f);  // the engine default is 1 m/s
  EXPECT_EQ(s.world.bouncinessCombine, CombineRule::Multiply);
  EXPECT_EQ(s.world.frictionCombine, CombineRule::Min);
  EXPECT_EQ(s.world.impactModel, ImpactModel::Interpolated);
  EXPECT_EQ(s.world.frictionModel, FrictionModel::Viscous);
  EXPECT_EQ(s.world.penetrationResponse, PenetrationResponse::Revert);

  ASSERT_EQ(s.materials.size(), 2u);
  EXPECT_EQ(s.materials.at("felt"), (Material{0.1f, 0.4f, 800.0f, 0.02f}));
  EXPECT_EQ(s.materials.at("steel"), (Material{std::nullopt, 0.3f, std::nullopt, std::nullopt}));

  ASSERT_EQ(s.bodies.size(), 11u);
  const BodyDef& ground = s.bodies[0].def;
  EXPECT_EQ(ground.name, "ground");
  EXPECT_EQ(ground.type, BodyType::Static);
  ASSERT_EQ(ground.shape.type(), ShapeType::Plane);
  EXPECT_EQ(ground.shape.plane().normal, Vec3(0, 1, 0));
  EXPECT_FLOAT_EQ(ground.shape.plane().distance, -0.5f);

  const Body& ball = s.bodies[1];
  EXPECT_EQ(ball.def.type, BodyType::Dynamic);
  EXPECT_FLOAT_EQ(ball.def.shape.sphere().radius, 0.5f);
  EXPECT_EQ(ball.def.position, Vec3(1, 2, 3));
  // [x, y, z, w] = [0, 0.6, 0, 0.8]: glm stores (w, x, y, z).
  EXPECT_FLOAT_EQ(ball.def.rotation.y, 0.6f);
  EXPECT_FLOAT_EQ(ball.def.rotation.w, 0.8f);
  EXPECT_FLOAT_EQ(ball.def.scale, 2.0f);
  EXPECT_EQ(ball.def.linearVelocity, Vec3(1, 0, -1));
  EXPECT_EQ(ball.def.angularVelocity, Vec3(0, 3, 0));
  ASSERT_TRUE(ball.def.mass.has_value());
  EXPECT_FLOAT_EQ(*ball.def.mass, 1.5f);
  EXPECT_EQ(ball.material, "felt");
  EXPECT_FLOAT_EQ(ball.def.bounciness, 0.9f);          // its own value over the material's 0.1
  EXPECT_FLOAT_EQ(ball.def.friction, 0.4f);            // the material's
  EXPECT_FLOAT_EQ(ball.def.rollingResistance, 0.02f);  // the material's
  EXPECT_TRUE(ball.def.ccd);
  EXPECT_FALSE(ball.def.sensor);
  EXPECT_EQ(ball.def.userData, 1u);

  const Body& crate = s.bodies[2];
  EXPECT_EQ(crate.def.type, BodyType::Kinematic);
  EXPECT_EQ(crate.def.shape.box().halfExtents, Vec3(0.5f, 0.25f, 0.125f));
  EXPECT_TRUE(crate.def.sensor);
  EXPECT_FLOAT_EQ(crate.def.friction, 0.3f);
  EXPECT_FLOAT_EQ(crate.def.bounciness, 0.0f);  // neither the body nor steel says: the default
  EXPECT_EQ(crate.def.layer, 6u);
  EXPECT_EQ(crate.def.mask, 0xFFFFFFFFu);
  EXPECT_EQ(crate.def.group, -3);
  EXPECT_EQ(ball.def.layer, 1u);  // the defaults
  EXPECT_EQ(ball.def.mask, kAllLayers);
  EXPECT_EQ(ball.def.group, 0);

  const Body& pill = s.bodies[3];
  EXPECT_FLOAT_EQ(pill.def.shape.capsule().radius, 0.2f);
  EXPECT_FLOAT_EQ(pill.def.shape.capsule().halfHeight, 0.3f);
  EXPECT_FALSE(pill.def.mass.has_value());
  EXPECT_FLOAT_EQ(pill.def.density, 2000.0f);
  EXPECT_FLOAT_EQ(pill.def.friction, 0.7f);
  EXPECT_FLOAT_EQ(pill.def.rollingResistance, 0.005f);
  EXPECT_FLOAT_EQ(crate.def.rollingResistance, 0.0f);  // neither the body nor steel says
  ASSERT_TRUE(pill.breakImpulse.has_value());
  EXPECT_FLOAT_EQ(*pill.breakImpulse, 12.5f);

  EXPECT_FLOAT_EQ(s.bodies[4].def.shape.cylinder().radius, 0.3f);
  EXPECT_FLOAT_EQ(s.bodies[4].def.shape.cylinder().halfHeight, 0.4f);
  EXPECT_EQ(s.bodies[5].def.shape.ellipsoid().radii, Vec3(0.3f, 0.4f, 0.5f));
  // The hull of a corner tetrahedron plus an inner point: 4 vertices, volume 1/6.
  EXPECT_EQ(s.bodies[6].def.shape.convexHull().vertices().size(), 4u);
  EXPECT_NEAR(s.bodies[6].def.shape.convexHull().volume(), 1.0f / 6.0f, 1e-6f);
  EXPECT_EQ(s.bodies[7].def.shape.kdop().k(), 14);
  EXPECT_EQ(s.bodies[8].def.shape.mesh().triangles().size(), 1u);
  // The OBJ cube: 6 quads triangulated, closed, volume 1.
  const TriangleMesh& objCube = s.bodies[9].def.shape.mesh();
  EXPECT_EQ(objCube.triangles().size(), 12u);
  EXPECT_TRUE(objCube.isClosed());
  EXPECT_NEAR(objCube.volume(), 1.0f, 1e-5f);
  const Compound& dumbbell = s.bodies[10].def.shape.compound();
  ASSERT_EQ(dumbbell.children().size(), 3u);
  EXPECT_EQ(dumbbell.children()[0].transform.position, Vec3(-0.6f, 0, 0));
  EXPECT_FLOAT_EQ(dumbbell.children()[1].transform.rotation.z, 0.6f);
  EXPECT_FLOAT_EQ(dumbbell.children()[2].shape.sphere().radius, 0.3f);

  ASSERT_EQ(s.constraints.size(), 1u);
  const Constraint& c = s.constraints[0];
  EXPECT_EQ(c.a, "ball");
  EXPECT_EQ(c.b, "crate");
  ASSERT_TRUE(c.anchorA.has_value() && c.anchorB.has_value());
  EXPECT_EQ(*c.anchorA, Vec3(0, 0.5f, 0));
  EXPECT_EQ(*c.anchorB, Vec3(0.1f, 0, 0));
  ASSERT_TRUE(c.length.has_value());
  EXPECT_FLOAT_EQ(*c.length, 2.5f);
  EXPECT_FLOAT_EQ(c.compliance, 0.001f);
  EXPECT_FALSE(c.collideConnected);
}

TEST(SceneParser, BodiesReachTheWorld) {
  const Scene s = loadSceneFile(kSceneData + "/every_field.json");
  SceneWorld sw = buildWorld(s);
  ASSERT_EQ(sw.bodies.size(), s.bodies.size());
  EXPECT_EQ(sw.world.def().penetrationResponse, PenetrationResponse::Revert);
  EXPECT_FALSE(sw.world.def().ccd);
  EXPECT_EQ(sw.world.name(sw.bodies[1]), "ball");
  EXPECT_FLOAT_EQ(sw.world.mass(sw.bodies[1]), 1.5f);
  // Density 2000 on a capsule r 0.2, half height 0.3: pi r^2 (2 hh + 4/3 r) * 2000.
  const float pi = 3.14159265f;
  EXPECT_NEAR(sw.world.mass(sw.bodies[3]), pi * 0.04f * (0.6f + 0.8f / 3.0f) * 2000.0f, 1e-2f);
  EXPECT_EQ(sw.world.transform(sw.bodies[9]).position, Vec3(25, 3, 0));
  EXPECT_EQ(sw.world.linearVelocity(sw.bodies[1]), Vec3(1, 0, -1));
  ASSERT_EQ(sw.constraints.size(), 1u);
  EXPECT_EQ(sw.world.constraintCount(), 1u);
  EXPECT_FLOAT_EQ(sw.world.constraintLength(sw.constraints[0]), 2.5f);
}

TEST(SceneParser, GravityScaleAndDampingReachTheWorld) {
  const Scene s = parseScene(withBody(R"({"name": "b", "type": "dynamic", "gravity_scale": -0.5,
      "linear_damping": 0.25, "angular_damping": 2, "shape": {"type": "sphere", "radius": 1}})"));
  ASSERT_EQ(s.bodies.size(), 1u);
  EXPECT_EQ(s.bodies[0].def.gravityScale, -0.5f);
  EXPECT_EQ(s.bodies[0].def.linearDamping, 0.25f);
  EXPECT_EQ(s.bodies[0].def.angularDamping, 2.0f);
  SceneWorld sw = buildWorld(s);
  const BodyId b = sw.world.bodies().front();
  EXPECT_EQ(sw.world.gravityScale(b), -0.5f);
  EXPECT_EQ(sw.world.linearDamping(b), 0.25f);
  EXPECT_EQ(sw.world.angularDamping(b), 2.0f);
  EXPECT_THAT(sceneParseError(withBody(R"({"name": "b", "type": "dynamic", "angular_damping": -1,
      "shape": {"type": "sphere", "radius": 1}})")),
              HasSubstr("bodies[0].angular_damping: must be >= 0, got -1"));
  EXPECT_THAT(sceneParseError(withBody(R"({"name": "b", "type": "dynamic", "gravity_scale": "heavy",
      "shape": {"type": "sphere", "radius": 1}})")),
              HasSubstr("bodies[0].gravity_scale: must be a number"));
}

TEST(SceneParser, PartsTakeTheBodysValuesThenTheirOwn) {
  const Scene s = parseScene(R"({"format": "collide-scene/1",
      "materials": {"ice": {"friction": 0.02, "density": 900}},
      "bodies": [{"name": "b", "type": "dynamic", "friction": 0.8, "layer": 3, "position": [0, 2, 0],
        "parts": [
          {"shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5]}, "position": [-1, 0, 0]},
          {"shape": {"type": "sphere", "radius": 0.5}, "position": [1, 0, 0], "material": "ice",
           "bounciness": 0.5, "group": -2},
          {"shape": {"type": "sphere", "radius": 1}, "sensor": true, "density": 0, "mask": 4}]}]})");
  ASSERT_EQ(s.bodies.size(), 1u);
  const std::vector<PartDef>& parts = s.bodies[0].def.parts;
  ASSERT_EQ(parts.size(), 3u);
  EXPECT_EQ(parts[0].position, Vec3(-1.0f, 0.0f, 0.0f));
  EXPECT_EQ(parts[0].material.friction, 0.8f);  // the body's
  EXPECT_EQ(parts[0].layer, 3u);
  EXPECT_EQ(parts[1].material.friction, 0.02f);  // the material's
  EXPECT_EQ(parts[1].density, 900.0f);
  EXPECT_EQ(parts[1].material.bounciness, 0.5f);  // its own
  EXPECT_EQ(parts[1].group, -2);
  EXPECT_TRUE(parts[2].sensor);
  EXPECT_EQ(parts[2].density, 0.0f);
  EXPECT_EQ(parts[2].mask, 4u);
  SceneWorld sw = buildWorld(s);
  const BodyId b = sw.world.bodies().front();
  EXPECT_EQ(sw.world.partCount(b), 3u);
  // 1000 kg of box and 900 kg/m^3 of a 0.5 m ball; the sensor weighs nothing.
  const float ball = 900.0f * 4.0f / 3.0f * 3.14159265f * 0.125f;
  EXPECT_NEAR(sw.world.mass(b), 1000.0f + ball, 1e-2f);
  EXPECT_TRUE(sw.world.partIsSensor(b, 2));

  EXPECT_THAT(
      sceneParseError(withBody(R"({"name": "b", "type": "dynamic", "shape": {"type": "sphere", "radius": 1},
      "parts": [{"shape": {"type": "sphere", "radius": 1}}]})")),
      HasSubstr("bodies[0].parts: give shape or parts, not both"));
  EXPECT_THAT(sceneParseError(withBody(R"({"name": "b", "type": "dynamic", "parts": []})")),
              HasSubstr("bodies[0].parts: must hold at least one part"));
  EXPECT_THAT(sceneParseError(withBody(R"({"name": "b", "type": "dynamic",
      "parts": [{"shape": {"type": "sphere", "radius": 1}, "frictoin": 1}]})")),
              HasSubstr("bodies[0].parts[0]"));
  EXPECT_THAT(sceneParseError(withBody(R"({"name": "b", "type": "static",
      "parts": [{"shape": {"type": "plane", "normal": [0, 1, 0], "distance": 0}}]})")),
              HasSubstr("bodies[0].parts[0].shape: a plane cannot be a part"));
  EXPECT_THAT(sceneParseError(withBody(R"({"name": "b", "type": "dynamic",
      "parts": [{"shape": {"type": "sphere", "radius": 1}, "density": 0}]})")),
              HasSubstr("bodies[0].parts: a dynamic body needs a part with density > 0"));
  EXPECT_THAT(sceneParseError(withBody(R"({"name": "b", "type": "dynamic"})")), HasSubstr("shape"));
}

TEST(SceneParser, DefaultsAreTheEngines) {
  const Scene s = parseScene(R"({"format": "collide-scene/1"})");
  const WorldDef defaults;
  EXPECT_EQ(s.world.gravity, defaults.gravity);
  EXPECT_EQ(s.world.substeps, defaults.substeps);
  EXPECT_FLOAT_EQ(s.dt, 1.0f / 60.0f);
  EXPECT_EQ(s.steps, 600);
  EXPECT_TRUE(s.bodies.empty());
}

TEST(SceneParserErrors, MalformedJsonGivesLineAndColumn) {
  const std::string message =
      sceneParseError("{ \"format\": \"collide-scene/1\",\n  \"bodies\": [ { \"name\": 1 ]\n}");
  EXPECT_THAT(message, HasSubstr("test.json: malformed JSON at line 2, column 27"));
}

TEST(SceneParserErrors, NegativeSizeNamesThePathAndValue) {
  EXPECT_THAT(
      sceneParseError(withBody(R"({"name": "a", "type": "static", "shape": {"type": "sphere", "radius": 1}},
      {"name": "b", "type": "dynamic", "shape": {"type": "sphere", "radius": -1}})")),
      HasSubstr("test.json: bodies[1].shape.radius: must be > 0, got -1"));
  EXPECT_THAT(sceneParseError(withBody(R"({"name": "b", "type": "dynamic", "shape": {"type": "box",
      "half_extents": [1, 0, 1]}})")),
              HasSubstr("bodies[0].shape.half_extents[1]: must be > 0, got 0"));
  EXPECT_THAT(sceneParseError(withBody(R"({"name": "b", "type": "dynamic", "rolling_resistance": -0.01,
      "shape": {"type": "sphere", "radius": 1}})")),
              HasSubstr("bodies[0].rolling_resistance: must be >= 0, got -0.01"));
}

TEST(SceneParserErrors, WrongTypeNamesTheField) {
  EXPECT_THAT(sceneParseError(withBody(
                  R"({"name": "b", "type": "dynamic", "shape": {"type": "sphere", "radius": "big"}})")),
              HasSubstr("bodies[0].shape.radius: must be a number, got \"big\""));
  EXPECT_THAT(sceneParseError(R"({"format": "collide-scene/1", "settings": {"sleeping": 1}})"),
              HasSubstr("settings.sleeping: must be true or false, got 1"));
  EXPECT_THAT(sceneParseError(R"({"format": "collide-scene/1", "settings": {"steps": 2.5}})"),
              HasSubstr("settings.steps: must be an integer, got 2.5"));
  EXPECT_THAT(sceneParseError(R"({"format": "collide-scene/1", "bodies": {}})"),
              HasSubstr("bodies: must be an array, got an object"));
  EXPECT_THAT(sceneParseError(withBody(R"({"name": "b", "type": "dynamic", "position": [1, 2],
      "shape": {"type": "sphere", "radius": 1}})")),
              HasSubstr("bodies[0].position: must be [x, y, z], got [1,2]"));
}

TEST(SceneParserErrors, LayerAndMaskAre32Bits) {
  EXPECT_THAT(sceneParseError(withBody(R"({"name": "b", "type": "dynamic", "mask": 4294967296,
      "shape": {"type": "sphere", "radius": 1}})")),
              HasSubstr("bodies[0].mask: must be from 0 to 4294967295 (32 bits), got 4294967296"));
  EXPECT_THAT(sceneParseError(withBody(R"({"name": "b", "type": "dynamic", "layer": -1,
      "shape": {"type": "sphere", "radius": 1}})")),
              HasSubstr("bodies[0].layer: must be from 0 to 4294967295 (32 bits), got -1"));
  EXPECT_THAT(sceneParseError(withBody(R"({"name": "b", "type": "dynamic", "group": 1.5,
      "shape": {"type": "sphere", "radius": 1}})")),
              HasSubstr("bodies[0].group: must be an integer, got 1.5"));
}

TEST(SceneParserErrors, MissingRequiredField) {
  EXPECT_THAT(sceneParseError(withBody(R"({"name": "b", "type": "dynamic"})")),
              HasSubstr("bodies[0].shape: missing required field"));
  EXPECT_THAT(sceneParseError(
                  withBody(R"({"name": "b", "type": "dynamic", "shape": {"type": "capsule", "radius": 1}})")),
              HasSubstr("bodies[0].shape.half_height: missing required field"));
  EXPECT_THAT(sceneParseError(R"({"bodies": []})"), HasSubstr("test.json: format: missing required field"));
}

TEST(SceneParserErrors, UnknownFieldIsRefused) {
  EXPECT_THAT(sceneParseError(
                  withBody(R"({"name": "b", "type": "dynamic", "shape": {"type": "sphere", "radus": 1}})")),
              HasSubstr("bodies[0].shape.radus: unknown field (expected type, radius)"));
  EXPECT_THAT(sceneParseError(R"({"format": "collide-scene/1", "settings": {"gravty": [0, 0, 0]}})"),
              HasSubstr("settings.gravty: unknown field"));
  EXPECT_THAT(sceneParseError(R"({"format": "collide-scene/1", "extra": 1})"),
              HasSubstr("test.json: extra: unknown field"));
}

TEST(SceneParserErrors, UnknownNames) {
  EXPECT_THAT(sceneParseError(
                  withBody(R"({"name": "b", "type": "dynamic", "shape": {"type": "spere", "radius": 1}})")),
              HasSubstr("bodies[0].shape.type: unknown shape type \"spere\""));
  EXPECT_THAT(sceneParseError(
                  withBody(R"({"name": "b", "type": "dynamc", "shape": {"type": "sphere", "radius": 1}})")),
              HasSubstr("bodies[0].type: unknown body type \"dynamc\""));
  EXPECT_THAT(sceneParseError(withBody(R"({"name": "b", "type": "dynamic", "material": "wood",
      "shape": {"type": "sphere", "radius": 1}})")),
              HasSubstr("bodies[0].material: unknown material \"wood\""));
  EXPECT_THAT(sceneParseError(R"({"format": "collide-scene/1", "settings": {"broadphase": "octree"}})"),
              HasSubstr("settings.broadphase: broad phase: unknown type \"octree\""));
  EXPECT_THAT(sceneParseError(R"({"format": "collide-scene/1", "settings": {"friction_model": "sticky"}})"),
              HasSubstr("settings.friction_model: "));
  EXPECT_THAT(sceneParseError(R"({"format": "collide-scene/1", "bodies": [
      {"name": "b", "type": "dynamic", "shape": {"type": "sphere", "radius": 1}}],
      "constraints": [{"type": "distance", "a": "b", "b": "nobody"}]})"),
              HasSubstr("constraints[0].b: unknown body \"nobody\""));
  EXPECT_THAT(sceneParseError(R"({"format": "collide-scene/2"})"),
              HasSubstr("format: must be \"collide-scene/1\", got \"collide-scene/2\""));
}

// JSON has no NaN or infinity: "1e999" parses to infinity, and 1e39 overflows a float.
TEST(SceneParserErrors, HugeNumbersAreNotFinite) {
  EXPECT_THAT(
      sceneParseError(
          withBody(R"({"name": "b", "type": "dynamic", "shape": {"type": "sphere", "radius": 1e999}})")),
      HasSubstr("bodies[0].shape.radius: must be a finite number within float range, got 1e999 (line 1"));
  EXPECT_THAT(sceneParseError(R"({"format": "collide-scene/1", "settings": {"gravity": [0, -1e999, 0]}})"),
              HasSubstr("settings.gravity[1]: must be a finite number within float range, got -1e999"));
  EXPECT_THAT(sceneParseError(R"({"format": "collide-scene/1", "settings": {"gravity": [0, -1e39, 0]}})"),
              HasSubstr("settings.gravity[1]: must be a finite number within float range, got -1e+39"));
  EXPECT_THAT(sceneParseError(R"({"format": "collide-scene/1", "settings": {"dt": "NaN"}})"),
              HasSubstr("settings.dt: must be a number, got \"NaN\""));
}

TEST(SceneParserErrors, OutOfRangeValues) {
  EXPECT_THAT(sceneParseError(withBody(R"({"name": "b", "type": "dynamic", "bounciness": 1.5,
      "shape": {"type": "sphere", "radius": 1}})")),
              HasSubstr("bodies[0].bounciness: must be in [0, 1], got 1.5"));
  EXPECT_THAT(sceneParseError(R"({"format": "collide-scene/1", "settings": {"substeps": 0}})"),
              HasSubstr("settings.substeps: must be >= 1, got 0"));
  EXPECT_THAT(sceneParseError(R"({"format": "collide-scene/1", "settings": {"restitution_threshold": -1}})"),
              HasSubstr("settings.restitution_threshold: must be"));
  EXPECT_THAT(sceneParseError(withBody(R"({"name": "b", "type": "dynamic", "rotation": [0, 0, 0, 2],
      "shape": {"type": "sphere", "radius": 1}})")),
              HasSubstr("bodies[0].rotation: must be a unit quaternion"));
  EXPECT_THAT(sceneParseError(withBody(R"({"name": "b", "type": "dynamic",
      "shape": {"type": "kdop", "k": 10, "points": [[0,0,0],[1,0,0],[0,1,0],[0,0,1]]}})")),
              HasSubstr("bodies[0].shape.k: must be 6, 14, 18 or 26, got 10"));
}

TEST(SceneParserErrors, ShapesTheLibraryRefuses) {
  // Coplanar hull points: Qhull's refusal with the field in front.
  EXPECT_THAT(sceneParseError(withBody(R"({"name": "b", "type": "dynamic",
      "shape": {"type": "convex_hull", "points": [[0,0,0],[1,0,0],[0,1,0],[1,1,0]]}})")),
              HasSubstr("bodies[0].shape.points: "));
  EXPECT_THAT(sceneParseError(withBody(R"({"name": "b", "type": "static",
      "shape": {"type": "mesh", "vertices": [[0,0,0],[1,0,0],[0,0,1]], "triangles": [[0, 1, 3]]}})")),
              HasSubstr("bodies[0].shape.triangles[0][2]: vertex index out of range (3 vertices), got 3"));
  EXPECT_THAT(sceneParseError(withBody(R"({"name": "b", "type": "dynamic",
      "shape": {"type": "plane", "normal": [0, 1, 0], "distance": 0}})")),
              HasSubstr("bodies[0].shape: a plane can only be on a static body, got a dynamic body"));
  EXPECT_THAT(sceneParseError(withBody(
                  R"({"name": "b", "type": "static", "shape": {"type": "mesh", "file": "missing.obj"}})")),
              HasSubstr("bodies[0].shape.file: OBJ file "));
  EXPECT_THAT(sceneParseError(withBody(R"({"name": "b", "type": "dynamic",
      "shape": {"type": "compound", "children": []}})")),
              HasSubstr("bodies[0].shape.children: a compound needs at least one child"));
}

TEST(SceneParserErrors, DuplicateNames) {
  EXPECT_THAT(
      sceneParseError(withBody(R"({"name": "b", "type": "static", "shape": {"type": "sphere", "radius": 1}},
      {"name": "b", "type": "static", "shape": {"type": "sphere", "radius": 1}})")),
      HasSubstr("bodies[1].name: duplicate name \"b\" (also bodies[0])"));
}

TEST(SceneParserErrors, ParticleIsADynamicSphereWithoutSpin) {
  EXPECT_THAT(sceneParseError(withBody(R"({"name": "p", "type": "static", "particle": true,
      "shape": {"type": "sphere", "radius": 0.1}})")),
              HasSubstr("bodies[0].particle: a particle must be a dynamic body, got a static body"));
  EXPECT_THAT(sceneParseError(withBody(R"({"name": "p", "type": "dynamic", "particle": true,
      "shape": {"type": "box", "half_extents": [0.1, 0.1, 0.1]}})")),
              HasSubstr("bodies[0].particle: a particle's shape must be a sphere, got box"));
  EXPECT_THAT(sceneParseError(withBody(R"({"name": "p", "type": "dynamic", "particle": true,
      "angular_velocity": [0, 1, 0], "shape": {"type": "sphere", "radius": 0.1}})")),
              HasSubstr("bodies[0].angular_velocity: a particle has no angular velocity, got [0,1,0]"));
  EXPECT_THAT(sceneParseError(withBody(R"({"name": "p", "type": "dynamic", "particle": "yes",
      "shape": {"type": "sphere", "radius": 0.1}})")),
              HasSubstr("bodies[0].particle: must be true or false, got \"yes\""));
  // A particle cannot turn: an anchor off its centre has no lever.
  EXPECT_THAT(
      sceneParseError(R"({"format": "collide-scene/1", "bodies": [
      {"name": "hook", "type": "static", "shape": {"type": "sphere", "radius": 0.1}},
      {"name": "p", "type": "dynamic", "particle": true, "shape": {"type": "sphere", "radius": 0.1},
       "position": [0, -1, 0]}],
      "constraints": [{"type": "distance", "a": "hook", "b": "p", "anchor_b": [0.1, 0, 0]}]})"),
      HasSubstr("constraints[0].anchor_b: a particle's anchor must be its centre [0, 0, 0], got [0.1,0,0]"));
}

TEST(SceneParser, ParticleReachesTheWorld) {
  const Scene s = parseScene(withBody(R"({"name": "p", "type": "dynamic", "particle": true,
      "shape": {"type": "sphere", "radius": 0.1}, "mass": 0.5})"));
  ASSERT_EQ(s.bodies.size(), 1u);
  EXPECT_TRUE(s.bodies[0].def.particle);
  const SceneWorld sw = buildWorld(s);
  EXPECT_TRUE(sw.world.isParticle(sw.bodies[0]));
  EXPECT_FLOAT_EQ(sw.world.mass(sw.bodies[0]), 0.5f);
}

// The JSON parser's whole explanation, after the line and column: "NaN", random bytes or a
// truncated file each say what is wrong, bytes that do not print escaped.
TEST(SceneParserErrors, MalformedJsonKeepsTheParsersExplanation) {
  EXPECT_THAT(sceneParseError(R"({"format": "collide-scene/1", "settings": {"dt": NaN}})"),
              HasSubstr("test.json: malformed JSON at line 1, column 50: syntax error while parsing value - "
                        "invalid literal; last read: '\"dt\": N'"));
  EXPECT_THAT(sceneParseError(R"({"format": "collide-scene/1", "bodies": [{"name": "a")"),
              HasSubstr("test.json: malformed JSON at line 1, column 54: syntax error while parsing object - "
                        "unexpected end of input; expected '}'"));
  EXPECT_THAT(sceneParseError("\x89PNG\r\n\x1a\n"),
              HasSubstr("test.json: malformed JSON at line 1, column 1: syntax error while parsing value - "
                        "invalid literal; last read: '\\x89'"));
  EXPECT_THAT(sceneParseError(""),
              HasSubstr("test.json: malformed JSON at line 1, column 1: syntax error while parsing "
                        "value - unexpected end of input; expected '[', '{', or a literal"));
  // nlohmann's parser takes a NUL byte for the end of the text, which would hide what follows it.
  EXPECT_THAT(sceneParseError(std::string(R"({"format": "collide-scene/1"})") + '\0' + R"(, "bodies": 7})"),
              HasSubstr("test.json: malformed JSON at line 1, column 30: a NUL byte (JSON text has none)"));
}

// nlohmann's parser keeps the last of two equal keys; the scene loader refuses them.
TEST(SceneParserErrors, DuplicateKeysAreRefused) {
  EXPECT_THAT(sceneParseError(withBody(R"({"name": "b", "type": "dynamic",
      "shape": {"type": "sphere", "radius": 1, "radius": 2}})")),
              HasSubstr("test.json: bodies[0].shape.radius: duplicate key: an object holds each key once"));
  EXPECT_THAT(sceneParseError(R"({"format": "collide-scene/1", "format": "collide-scene/1"})"),
              HasSubstr("test.json: format: duplicate key"));
  EXPECT_THAT(
      sceneParseError(R"({"format": "collide-scene/1", "materials": {"felt": {}, "wood": {}, "felt": {}}})"),
      HasSubstr("test.json: materials.felt: duplicate key"));
  // The same key in different objects is no duplicate.
  EXPECT_EQ(parseScene(withBody(R"({"name": "b", "type": "dynamic", "position": [0, 1, 0],
      "shape": {"type": "compound", "children": [{"shape": {"type": "sphere", "radius": 1}, "position": [0, 0, 0]},
                                                  {"shape": {"type": "sphere", "radius": 1}, "position": [1, 0, 0]}]}})"))
                .bodies.size(),
            1u);
}

// nlohmann parses any depth, but copying, printing and freeing a value recurse: [[[...]]] a hundred
// thousand deep would overflow the stack when an error message prints it.
TEST(SceneParserErrors, JsonNestingIsLimited) {
  const std::string deep = std::string(100'000, '[') + std::string(100'000, ']');
  const std::string message = sceneParseError(
      R"({"format": "collide-scene/1", "bodies": [{"name": "b", "type": "dynamic", "position": )" + deep +
      R"(, "shape": {"type": "sphere", "radius": 1}}]})");
  EXPECT_THAT(message, HasSubstr("test.json: bodies[0].position[0][0][0]"));
  EXPECT_THAT(message, HasSubstr(": arrays and objects nest more than 256 levels deep (the limit)"));
  // 256 levels are parsed (then refused for what they hold).
  EXPECT_THAT(sceneParseError(R"({"format": "collide-scene/1", "x": )" + std::string(255, '[') +
                              std::string(255, ']') + "}"),
              HasSubstr("test.json: x: unknown field"));
}

// `levels` compounds around a sphere, each the only child of the one above.
std::string nestedCompounds(int levels) {
  std::string shape = R"({"type": "sphere", "radius": 0.5})";
  for (int i = 0; i < levels; ++i) shape = R"({"type": "compound", "children": [{"shape": )" + shape + "}]}";
  return withBody(R"({"name": "b", "type": "dynamic", "shape": )" + shape + "}");
}

TEST(SceneParser, CompoundsNestUpToTheLimit) {
  const Scene s = parseScene(nestedCompounds(64));
  const Shape* shape = &s.bodies.at(0).def.shape;
  for (int i = 0; i < 64; ++i) {
    ASSERT_EQ(shape->type(), ShapeType::Compound) << "level " << i;
    shape = &shape->compound().children()[0].shape;
  }
  EXPECT_FLOAT_EQ(shape->sphere().radius, 0.5f);
  const SceneWorld sw = buildWorld(s);
  EXPECT_NEAR(sw.world.mass(sw.bodies[0]), 1000.0f * 4.0f / 3.0f * 3.14159265f * 0.125f, 0.1f);

  std::string path = "bodies[0].shape";
  for (int i = 0; i < 64; ++i) path += ".children[0].shape";
  EXPECT_THAT(sceneParseError(nestedCompounds(65)),
              HasSubstr("test.json: " + path + ": compounds nest more than 64 levels deep (the limit)"));
}

TEST(SceneParserErrors, SettingsWithinTheirLimits) {
  // One step of a billion substeps would not end; a step of 1e30 s overflows every position.
  EXPECT_THAT(sceneParseError(R"({"format": "collide-scene/1", "settings": {"substeps": 1000000000}})"),
              HasSubstr("test.json: settings.substeps: must be <= 64, got 1000000000"));
  EXPECT_THAT(
      sceneParseError(R"({"format": "collide-scene/1", "settings": {"substeps": 18446744073709551615}})"),
      HasSubstr("settings.substeps: must be <= 64, got 18446744073709551615"));
  EXPECT_THAT(sceneParseError(R"({"format": "collide-scene/1", "settings": {"dt": 1e30}})"),
              HasSubstr("test.json: settings.dt: must be at most 1 s, got 1e+30"));
  EXPECT_THAT(sceneParseError(R"({"format": "collide-scene/1", "settings": {"dt": 1.5}})"),
              HasSubstr("settings.dt: must be at most 1 s, got 1.5"));
  EXPECT_THAT(sceneParseError(R"({"format": "collide-scene/1", "settings": {"steps": 10000001}})"),
              HasSubstr("test.json: settings.steps: must be <= 10000000, got 10000001"));
  const Scene s = parseScene(
      R"({"format": "collide-scene/1", "settings": {"substeps": 64, "dt": 1, "steps": 10000000}})");
  EXPECT_EQ(s.world.substeps, 64);
  EXPECT_EQ(s.dt, 1.0f);
  EXPECT_EQ(s.steps, 10'000'000);
}

TEST(SceneParserErrors, BodiesAndTrianglesWithinTheirLimits) {
  // Counted before any is read.
  std::string bodies = "0";
  for (int i = 0; i < 1'000'000; ++i) bodies += ",0";
  EXPECT_THAT(sceneParseError(R"({"format": "collide-scene/1", "bodies": [)" + bodies + "]}"),
              HasSubstr("test.json: bodies: holds 1000001 bodies, more than the limit of 1000000"));
  std::string triangles = "0";
  for (int i = 0; i < 4'000'000; ++i) triangles += ",0";
  EXPECT_THAT(
      sceneParseError(withBody(R"({"name": "m", "type": "static", "shape": {"type": "mesh",
      "vertices": [[0, 0, 0], [1, 0, 0], [0, 0, 1]], "triangles": [)" +
                               triangles + "]}}")),
      HasSubstr(
          "test.json: bodies[0].shape.triangles: holds 4000001 triangles, more than the limit of 4000000"));
}

TEST(SceneParserErrors, MassOutsideFloatRangeNamesTheMass) {
  const auto massBody = [](const std::string& mass) {
    return withBody(R"({"name": "b", "type": "dynamic", "shape": {"type": "sphere", "radius": 1}, "mass": )" +
                    mass + "}");
  };
  EXPECT_THAT(sceneParseError(massBody("1e39")),
              HasSubstr("test.json: bodies[0].mass: must be a finite number within float range, got 1e+39"));
  EXPECT_THAT(sceneParseError(massBody("1e999")),
              HasSubstr("test.json: bodies[0].mass: must be a finite number within float range, got 1e999"));
  EXPECT_THAT(sceneParseError(massBody("1e-50")),
              HasSubstr("test.json: bodies[0].mass: must be > 0, got 1e-50"));
  // Within float range but more than a 1 m sphere's inertia can carry in float: the World refuses
  // it, naming the mass.
  try {
    buildWorld(parseScene(massBody("3e38"), "test.json"));
    ADD_FAILURE() << "3e38 kg on a 1 m sphere must be refused";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(),
                HasSubstr("test.json: bodies[0]: body \"b\": mass: mass properties not representable in "
                          "float with mass 3e+38"));
  }
}

}  // namespace
}  // namespace collide::scene
