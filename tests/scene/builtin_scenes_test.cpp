// Every built-in scene goes through the loader and runs; the reference scenes are built as
// reference-scenes.md specifies.
#include <collide/scene/builtin_scenes.h>
#include <collide/scene/reference_scenes.h>
#include <collide/scene/runner.h>

#include "builtin_scene_runs.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace collide::scene {
namespace {

class EveryBuiltinScene : public testing::TestWithParam<std::string> {};

TEST_P(EveryBuiltinScene, LoadsAndRunsTenSteps) {
  const std::string& name = GetParam();
  const Scene scene = loadBuiltinScene(name);
  RunOptions options;
  options.steps = 10;
  const RunSummary s = runScene(scene, options);
  EXPECT_EQ(s.steps, 10);
  EXPECT_EQ(s.staticBodies + s.kinematicBodies + s.dynamicBodies, int(scene.bodies.size()));
  EXPECT_TRUE(std::isfinite(s.kineticEnergy));
  // The export is the same document: its text, parsed as a file's, builds the very same world (the
  // loader reads the generated document without that text).
  const Scene fromText = parseScene(builtinSceneJson(name), scene.source);
  ASSERT_EQ(fromText.bodies.size(), scene.bodies.size());
  EXPECT_TRUE(buildWorld(fromText).world.saveSnapshot() == buildWorld(scene).world.saveSnapshot());
}

INSTANTIATE_TEST_SUITE_P(BuiltinScenes, EveryBuiltinScene, testing::ValuesIn(builtinScenesSteppedHere()),
                         sceneTestName);

TEST(BuiltinScenes, UnknownNameIsAnError) {
  EXPECT_FALSE(isBuiltinScene("no-such-scene"));
  EXPECT_THROW(loadBuiltinScene("no-such-scene"), Error);
}

TEST(BuiltinScenes, ReferenceCounts) {
  EXPECT_EQ(loadBuiltinScene("pile").bodies.size(), 4096u + 1u);
  EXPECT_EQ(loadBuiltinScene("rain").bodies.size(), 8000u + 5u);
  EXPECT_EQ(loadBuiltinScene("rain-jittered").bodies.size(), 8000u + 5u);
  EXPECT_EQ(loadBuiltinScene("pyramid").bodies.size(), 465u + 1u);
  EXPECT_EQ(loadBuiltinScene("billiards").bodies.size(), 16u + 5u);
}

// rain-jittered is R2 with each sphere moved sideways by up to 4 cm: the same heights, the sideways
// offsets spread over (-4, 4) cm (a draw below float resolution at 6 m leaves a coordinate as it
// was, so "moved" allows a few), and every sphere still 2 cm clear of its lattice neighbours
// (radius 0.25, spacing 0.6), so nothing starts overlapping.
TEST(BuiltinScenes, JitteredRainMovesEverySphereSidewaysWithinItsCell) {
  const Scene exact = loadBuiltinScene("rain");
  const Scene jittered = loadBuiltinScene("rain-jittered");
  ASSERT_EQ(exact.bodies.size(), jittered.bodies.size());
  std::size_t moved = 0;
  float lowest = 0.0f, highest = 0.0f;
  for (std::size_t i = 5; i < exact.bodies.size(); ++i) {
    const Vec3 a = exact.bodies[i].def.position, b = jittered.bodies[i].def.position;
    EXPECT_EQ(a.y, b.y);
    EXPECT_LE(std::abs(b.x - a.x), 0.04f + 1e-6f);
    EXPECT_LE(std::abs(b.z - a.z), 0.04f + 1e-6f);
    moved += (a.x != b.x || a.z != b.z) ? 1 : 0;
    lowest = std::min({lowest, b.x - a.x, b.z - a.z});
    highest = std::max({highest, b.x - a.x, b.z - a.z});
  }
  EXPECT_GE(moved, exact.bodies.size() - 5 - 2);
  EXPECT_LT(lowest, -0.039f);
  EXPECT_GT(highest, 0.039f);
  // Lattice order: x fastest, then z, then y; neighbours along x and z in one layer.
  const auto at = [&](int x, int y, int z) { return jittered.bodies[5 + x + 20 * z + 400 * y].def.position; };
  for (int y = 0; y < 20; ++y) {
    for (int z = 0; z < 20; ++z) {
      for (int x = 0; x < 20; ++x) {
        if (x + 1 < 20) {
          EXPECT_GE(glm::length(at(x + 1, y, z) - at(x, y, z)), 0.52f);
        }
        if (z + 1 < 20) {
          EXPECT_GE(glm::length(at(x, y, z + 1) - at(x, y, z)), 0.52f);
        }
      }
    }
  }
}

TEST(BuiltinScenes, PyramidCubesTouchExactly) {
  const Scene s = loadBuiltinScene("pyramid");
  // Row 0 spans x = -14.5 .. 14.5 at y = 0.5; the top cube sits at (0, 29.5, 0).
  EXPECT_EQ(s.bodies[1].def.position, Vec3(-14.5f, 0.5f, 0.0f));
  EXPECT_EQ(s.bodies.back().def.position, Vec3(0.0f, 29.5f, 0.0f));
  EXPECT_FLOAT_EQ(*s.bodies.back().def.mass, 1.0f);
}

TEST(BuiltinScenes, BilliardRackTouches) {
  const Scene s = loadBuiltinScene("billiards");
  // Bodies 6.. are the rack; neighbours in a row are 2R apart, rows sqrt(3)R apart.
  const float r = 0.028575f;
  const Vec3 apex = s.bodies[6].def.position, second = s.bodies[7].def.position,
             third = s.bodies[8].def.position;
  EXPECT_NEAR(glm::length(second - apex), 2 * r, 1e-6f);
  EXPECT_NEAR(glm::length(third - second), 2 * r, 1e-6f);
  EXPECT_EQ(s.bodies[5].def.linearVelocity, Vec3(6, 0, 0));
}

// The terrain scene's hulls are built from terrainHullPoints() (the points a Bullet-side builder
// reuses): every hull vertex is one of its body's generating points, bit for bit, at length 0.5, and
// the body sits at terrainHullPosition of its lattice cell.
TEST(BuiltinScenes, TerrainHullsAreTheExposedPoints) {
  const Scene s = loadBuiltinScene("terrain");
  ASSERT_EQ(s.bodies.size(), 2001u);
  EXPECT_EQ(s.bodies[0].def.shape.mesh().triangles().size(), 20000u);
  const auto hulls = terrainHullPoints();
  ASSERT_EQ(hulls.size(), 2000u);
  for (std::size_t i = 1; i < s.bodies.size(); i += 97) {
    SCOPED_TRACE(s.bodies[i].def.name);
    const auto& points = hulls[i - 1];
    for (const Vec3& v : s.bodies[i].def.shape.convexHull().vertices()) {
      EXPECT_NEAR(glm::length(v), 0.5f, 1e-5f);
      EXPECT_NE(std::find(points.begin(), points.end(), v), points.end()) << v.x << " " << v.y << " " << v.z;
    }
    const int cell = int(i) - 1;
    EXPECT_EQ(s.bodies[i].def.position, terrainHullPosition(cell / 100, (cell / 20) % 5, cell % 20));
  }
  // The lattice's corners: spacing 1.5 centred on x = z = 0, lowest layer at y = 3.
  EXPECT_EQ(terrainHullPosition(0, 0, 0), Vec3(-14.25f, 3.0f, -14.25f));
  EXPECT_EQ(terrainHullPosition(19, 4, 19), Vec3(14.25f, 9.0f, 14.25f));
  EXPECT_DOUBLE_EQ(terrainHeight(0.0, 7.0), 0.0);
}

// reference-scenes.md's std::normal_distribution(0,1) is the double distribution: the first point
// is the first three double draws of mt19937(42), normalised to 0.5 (float draws give other values).
TEST(BuiltinScenes, TerrainPointsAreDoubleDraws) {
  std::mt19937 rng(42);
  std::normal_distribution<double> gauss;
  const double x = gauss(rng);
  const double y = gauss(rng);
  const double z = gauss(rng);
  const double scale = 0.5 / std::sqrt(x * x + y * y + z * z);
  const Vec3 first = terrainHullPoints()[0][0];
  EXPECT_EQ(first, Vec3(float(x * scale), float(y * scale), float(z * scale)));
  // The float distribution draws other numbers from the same engine (it takes 32 bits a value).
  std::mt19937 rngFloat(42);
  std::normal_distribution<float> gaussFloat;
  EXPECT_NE(gaussFloat(rngFloat), float(x));
}

TEST(BuiltinScenes, ReferenceScenesByIdOrName) {
  ASSERT_EQ(referenceScenes().size(), 5u);
  EXPECT_EQ(referenceScenes()[4].id, "R4");
  EXPECT_EQ(referenceScenes()[4].builtin, "terrain");
  for (const ReferenceScene& r : referenceScenes()) EXPECT_TRUE(isBuiltinScene(r.builtin));
  EXPECT_EQ(loadReferenceScene("R3").bodies.size(), loadReferenceScene("pyramid").bodies.size());
  EXPECT_EQ(loadReferenceScene("B1").source, "builtin:billiards");
  try {
    loadReferenceScene("R9");
    ADD_FAILURE() << "R9 was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("unknown reference scene \"R9\""), std::string::npos);
  }
}

// The chain scene's rigid links (rope and net) keep their lengths within 1 % from 1 s to 2 s: the
// rope swings throughout, the net has landed on the ball (at about 0.7 s) and must drape over it.
// The landing itself stretches net links by up to about 7 % for a few steps (the centre stops at
// once while the rim still falls at 6 m/s; the rigid joints are soft constraints, see
// docs/architecture.md, "Distance constraints"), so the first second is not asserted.
TEST(BuiltinScenes, ChainLinksHoldTheirLength) {
  const Scene scene = loadBuiltinScene("chain");
  EXPECT_EQ(scene.constraints.size(), 10u + 2u * 7u * 6u);
  SceneWorld sw = buildWorld(scene);
  float worst = 0.0f;
  for (int step = 1; step <= 120; ++step) {
    sw.world.step(scene.dt);
    if (step < 60) continue;
    for (const JointId link : sw.constraints) {
      const float length = sw.world.constraintLength(link);
      worst = std::max(worst, std::abs(sw.world.constraintCurrentLength(link) - length) / length);
    }
  }
  EXPECT_LT(worst, 0.01f);
  // The net's centre knot rests on top of the ball (radius 0.4 on the ground, knot radius 0.06).
  std::size_t centre = 0;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    if (scene.bodies[i].def.name == "net_3_3") centre = i;
  }
  ASSERT_NE(centre, 0u);
  EXPECT_NEAR(sw.world.transform(sw.bodies[centre]).position.y, 0.86f, 0.02f);
  // The rope swung: its last particle started 30 degrees out on the +x side of the hook (x = -1.25).
  EXPECT_LT(sw.world.transform(sw.bodies[11]).position.x, -1.5f);
  // Sleeping is on: by 3 s the draped net (its rim on the ground) sleeps, the swinging rope does not.
  for (int step = 120; step < 180; ++step) sw.world.step(scene.dt);
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    if (scene.bodies[i].def.type != BodyType::Dynamic) continue;
    const bool net = scene.bodies[i].def.name.starts_with("net_");
    EXPECT_EQ(sw.world.isAwake(sw.bodies[i]), !net) << scene.bodies[i].def.name;
  }
}

// Every proxy type comes to rest on the ground, the ramp or each other: the boxes, hulls and k-DOPs
// on their faces, the round shapes (spheres, cylinders on their side, ellipsoids) by their rolling
// resistance. At 10 s no body moves faster than 1 cm/s or turns faster than 0.05 rad/s.
TEST(BuiltinScenes, EveryProxyInTheProxiesSceneComesToRest) {
  const Scene scene = loadBuiltinScene("proxies");
  SceneWorld sw = buildWorld(scene);
  for (int step = 0; step < 600; ++step) sw.world.step(scene.dt);
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    if (scene.bodies[i].def.type != BodyType::Dynamic) continue;
    SCOPED_TRACE(scene.bodies[i].def.name);
    EXPECT_LT(glm::length(sw.world.linearVelocity(sw.bodies[i])), 0.01f);
    EXPECT_LT(glm::length(sw.world.angularVelocity(sw.bodies[i])), 0.05f);
    EXPECT_GT(sw.world.transform(sw.bodies[i]).position.y, 0.0f);  // above the ground
  }
}

// The tunneling scene shows what continuous detection covers: a shot tunnels when, between two
// steps, it crosses its plate's plane (x = 0; the plates are 0.02 thick) inside the plate's face.
// Nothing tunnels through a static plate, flagged ccd or not (lanes 0 and 1); through a kinematic
// plate, only the shots without the flag do (lanes 2 and 3: all four, see docs/ccd.md), which shows
// what the flag adds. A deflected shot may slide off the plate's edge and cross x = 0 outside the
// face: that is not tunneling.
TEST(BuiltinScenes, NothingTunnelsThroughStaticPlatesAndBulletsThroughNone) {
  const Scene scene = loadBuiltinScene("tunneling");
  SceneWorld sw = buildWorld(scene);
  struct Shot {
    std::size_t body;
    Vec3 plateCentre;
    Vec3 previous;
    bool tunneled = false;
  };
  std::vector<Shot> shots;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodyDef& def = scene.bodies[i].def;
    if (def.type != BodyType::Dynamic) continue;
    const std::string lane = def.name.substr(def.name.find('_') + 1);  // "ccd_2", "no_ccd_0"
    const auto plate = std::find_if(scene.bodies.begin(), scene.bodies.end(),
                                    [&](const Body& b) { return b.def.name == "plate_" + lane; });
    ASSERT_NE(plate, scene.bodies.end()) << def.name;
    shots.push_back({i, plate->def.position, def.position});
  }
  for (int step = 0; step < scene.steps; ++step) {
    sw.world.step(scene.dt);
    for (Shot& shot : shots) {
      const Vec3 p = sw.world.transform(sw.bodies[shot.body]).position;
      if (shot.previous.x < 0.0f && p.x >= 0.0f) {
        const Vec3 crossing =
            shot.previous + (p - shot.previous) * (-shot.previous.x / (p.x - shot.previous.x));
        const Vec3 offset = crossing - shot.plateCentre;
        if (std::abs(offset.y) < 0.6f && std::abs(offset.z) < 0.6f) shot.tunneled = true;
      }
      shot.previous = p;
    }
  }
  int withCcd = 0, throughKinematic = 0;
  for (const Shot& shot : shots) {
    const BodyDef& def = scene.bodies[shot.body].def;
    const bool kinematicPlate = def.name.back() == '2' || def.name.back() == '3';
    if (def.ccd) ++withCcd;
    if (def.ccd || !kinematicPlate) {
      EXPECT_FALSE(shot.tunneled) << def.name;
    } else {
      throughKinematic += shot.tunneled ? 1 : 0;
    }
  }
  EXPECT_EQ(withCcd, 8);
  EXPECT_EQ(throughKinematic, 4);
}

}  // namespace
}  // namespace collide::scene

namespace collide::scene {
namespace {

// The world's mechanical energy: kinetic plus the potential of gravity (m g h of each dynamic body).
double mechanicalEnergy(const SceneWorld& sw, const Vec3& gravity) {
  double potential = 0.0;
  for (BodyId id : sw.bodies) {
    if (!sw.world.isValid(id) || sw.world.type(id) != BodyType::Dynamic) continue;
    potential -= double(sw.world.mass(id)) * glm::dot(gravity, sw.world.centerOfMass(id));
  }
  return sw.world.kineticEnergy() + potential;
}

// The deepest penetration between any two bodies (brute force over every pair).
float deepestPenetration(const SceneWorld& sw, std::string* where) {
  float deepest = 0.0f;
  for (std::size_t i = 0; i < sw.bodies.size(); ++i) {
    for (std::size_t j = i + 1; j < sw.bodies.size(); ++j) {
      const World& w = sw.world;
      if (w.type(sw.bodies[i]) == BodyType::Static && w.type(sw.bodies[j]) == BodyType::Static) continue;
      Manifold m;
      if (!collide(w.shape(sw.bodies[i]), w.transform(sw.bodies[i]), w.shape(sw.bodies[j]),
                   w.transform(sw.bodies[j]), m))
        continue;
      if (m.maxDepth() > deepest) {
        deepest = m.maxDepth();
        if (where) *where = w.name(sw.bodies[i]) + " in " + w.name(sw.bodies[j]);
      }
    }
  }
  return deepest;
}

// The lecture's revert (slide 10): a body that would penetrate goes back to its last valid position.
// In the built-in `revert` drop no body ends a step inside another (deeper than the linear slop, the
// tolerance every contact has), and the mechanical energy never grows: the response may only take
// energy out.
TEST(BuiltinScenes, RevertLeavesNoBodyInsideAnotherAndAddsNoEnergy) {
  const Scene scene = loadBuiltinScene("revert");
  SceneWorld sw = buildWorld(scene);
  const float slop = scene.world.contact.linearSlop;
  double energy = mechanicalEnergy(sw, scene.world.gravity);
  const double scale = energy;
  ASSERT_LE(deepestPenetration(sw, nullptr), 0.0f);  // the drop starts with every body apart
  for (int step = 1; step <= scene.steps; ++step) {
    sw.world.step(scene.dt);
    const double now = mechanicalEnergy(sw, scene.world.gravity);
    EXPECT_LE(now, energy + 1e-4 * scale) << "step " << step;
    energy = now;
    std::string where;
    const float deepest = deepestPenetration(sw, &where);
    EXPECT_LE(deepest, slop + 1e-4f) << "step " << step << ": " << where << " by " << deepest;
  }
}

}  // namespace
}  // namespace collide::scene
