// The reference scenes of the benchmarks (reference-scenes.md), built exactly as specified there so
// that collide and its peer run the same thing: B1 billiards, R1 pile, R2 rain, R3 pyramid and R4
// terrain.
#include "builtin_scene_parts.h"

#include <collide/scene/builtin_scenes.h>
#include <collide/scene/reference_scenes.h>

#include <cmath>
#include <random>

namespace collide::scene {

std::span<const ReferenceScene> referenceScenes() {
  static constexpr std::array<ReferenceScene, 5> kScenes = {
      {{"B1", "billiards"}, {"R1", "pile"}, {"R2", "rain"}, {"R3", "pyramid"}, {"R4", "terrain"}}};
  return kScenes;
}

Scene loadReferenceScene(std::string_view idOrName) {
  for (const ReferenceScene& r : referenceScenes()) {
    if (r.id == idOrName || r.builtin == idOrName) return loadBuiltinScene(r.builtin);
  }
  throw Error("unknown reference scene \"" + std::string(idOrName) +
              "\" (expected B1, R1, R2, R3, R4 or billiards, pile, rain, pyramid, terrain)");
}

double terrainHeight(double x, double z) { return 0.5 * std::sin(0.3 * x) * std::cos(0.3 * z); }

Vec3 terrainHullPosition(int x, int y, int z) {
  return Vec3(static_cast<float>((x - (kTerrainLatticeX - 1) / 2.0) * 1.5), static_cast<float>(3.0 + y * 1.5),
              static_cast<float>((z - (kTerrainLatticeZ - 1) / 2.0) * 1.5));
}

// reference-scenes.md writes std::normal_distribution(0,1), whose RealType defaults to double: the
// draws and the normalisation are in double so that any other builder following the text gets the
// same floats.
std::vector<std::array<Vec3, kTerrainHullPoints>> terrainHullPoints() {
  std::vector<std::array<Vec3, kTerrainHullPoints>> hulls(kTerrainLatticeX * kTerrainLatticeY *
                                                          kTerrainLatticeZ);
  std::mt19937 rng(42);
  std::normal_distribution<double> gauss(0.0, 1.0);
  for (auto& hull : hulls) {
    for (Vec3& point : hull) {
      const double px = gauss(rng);
      const double py = gauss(rng);
      const double pz = gauss(rng);
      const double scale = 0.5 / std::sqrt(px * px + py * py + pz * pz);
      point = Vec3(static_cast<float>(px * scale), static_cast<float>(py * scale),
                   static_cast<float>(pz * scale));
    }
  }
  return hulls;
}

}  // namespace collide::scene

namespace collide::scene::builtin {

// B1, the lecture's shot: 15 balls racked in a touching triangle, the cue ball sent at 6 m/s into
// the apex, cushions as static boxes around a 2.54 x 1.27 table.
Json billiards() {
  constexpr double kRadius = 0.028575, kMass = 0.17, kLength = 2.54, kWidth = 1.27;
  Json doc = referenceDocument();
  // min: ball-ball bounce 0.95, ball-cushion 0.8, ball-cloth 0.
  doc["settings"]["bounciness_combine"] = "min";
  doc["materials"] = {{"ball", {{"bounciness", num(0.95)}, {"friction", num(0.5)}}},
                      {"cloth", {{"bounciness", 0}, {"friction", num(0.5)}}},
                      {"cushion", {{"bounciness", num(0.8)}, {"friction", num(0.5)}}}};
  Json& bodies = doc["bodies"];
  Json table =
      body("table", "static", {{"type", "plane"}, {"normal", vec(0, 1, 0)}, {"distance", 0}}, vec(0, 0, 0));
  table["material"] = "cloth";
  bodies.push_back(table);
  // Cushions: 5 cm square rails just outside the playing area.
  constexpr double kRail = 0.05;
  const auto cushion = [&](const std::string& name, Json shape, const Json& position) {
    Json c = body(name, "static", std::move(shape), position);
    c["material"] = "cushion";
    bodies.push_back(c);
  };
  cushion("cushion_north", box(kLength / 2 + 2 * kRail, kRail, kRail), vec(0, kRail, kWidth / 2 + kRail));
  cushion("cushion_south", box(kLength / 2 + 2 * kRail, kRail, kRail), vec(0, kRail, -kWidth / 2 - kRail));
  cushion("cushion_east", box(kRail, kRail, kWidth / 2), vec(kLength / 2 + kRail, kRail, 0));
  cushion("cushion_west", box(kRail, kRail, kWidth / 2), vec(-kLength / 2 - kRail, kRail, 0));
  const auto ball = [&](const std::string& name, double x, double z) {
    Json b = body(name, "dynamic", sphere(kRadius), vec(x, kRadius, z));
    b["mass"] = num(kMass);
    b["material"] = "ball";
    return b;
  };
  Json cue = ball("cue", -kLength / 4, 0);
  cue["velocity"] = vec(6, 0, 0);
  bodies.push_back(cue);
  // The rack: row r has r + 1 balls, rows sqrt(3) R apart, so neighbours touch.
  int number = 1;
  for (int row = 0; row < 5; ++row) {
    for (int i = 0; i <= row; ++i) {
      const double x = kLength / 4 + row * std::sqrt(3.0) * kRadius;
      const double z = (i - row / 2.0) * 2.0 * kRadius;
      bodies.push_back(ball("ball_" + std::to_string(number++), x, z));
    }
  }
  return doc;
}

// Unit cubes of 1 kg on the ground in an nx x ny x nz lattice, spacing 1.1, centred on the origin in
// x and z, the lowest layer's centres at y = lowestY.
static Json cubeLattice(int nx, int ny, int nz, double lowestY) {
  Json doc = referenceDocument();
  Json& bodies = doc["bodies"];
  bodies.push_back(groundBox());
  for (int y = 0; y < ny; ++y) {
    for (int z = 0; z < nz; ++z) {
      for (int x = 0; x < nx; ++x) {
        Json b = body("box_" + std::to_string(x) + "_" + std::to_string(y) + "_" + std::to_string(z),
                      "dynamic", box(0.5, 0.5, 0.5),
                      vec((x - (nx - 1) / 2.0) * 1.1, lowestY + y * 1.1, (z - (nz - 1) / 2.0) * 1.1));
        b["mass"] = 1;
        b["friction"] = num(0.5);
        bodies.push_back(b);
      }
    }
  }
  return doc;
}

// R1: 4,096 unit cubes in a 16 x 16 x 16 lattice, spacing 1.1, lowest layer at y = 1.
Json pile() { return cubeLattice(16, 16, 16, 1.0); }

// The step at scale (docs/threads.md, "At scale"): 100,000 unit cubes in a 100 x 10 x 100 lattice,
// spacing 1.1, the lowest layer resting on the ground, so that contacts start with the first step.
Json largePile() { return cubeLattice(100, 10, 100, 0.5); }

// R2: 8,000 spheres (radius 0.25) in a 20 x 20 x 20 lattice, spacing 0.6, into an open container of
// four static walls enclosing x, z in [-7, 7], 10 high, 0.5 thick. `jitter` (m) moves each sphere by
// up to that much in x and z (a fixed seed), so that the columns of the exact lattice topple and
// heap in every engine, as they do in Bullet's rounding only; 0 is R2 as specified.
Json rain(double jitter) {
  Json doc = referenceDocument();
  Json& bodies = doc["bodies"];
  bodies.push_back(groundBox());
  const auto wall = [&](const std::string& name, Json shape, const Json& position) {
    Json w = body(name, "static", std::move(shape), position);
    w["friction"] = num(0.5);
    bodies.push_back(w);
  };
  wall("wall_east", box(0.25, 5, 7.5), vec(7.25, 5, 0));
  wall("wall_west", box(0.25, 5, 7.5), vec(-7.25, 5, 0));
  wall("wall_north", box(7.5, 5, 0.25), vec(0, 5, 7.25));
  wall("wall_south", box(7.5, 5, 0.25), vec(0, 5, -7.25));
  std::mt19937 random(2);
  // The offsets from the generator's raw integers, so that every standard library gives the same.
  const auto offset = [&] { return jitter * (2.0 * (random() / 4294967295.0) - 1.0); };
  for (int y = 0; y < 20; ++y) {
    for (int z = 0; z < 20; ++z) {
      for (int x = 0; x < 20; ++x) {
        const double dx = jitter > 0.0 ? offset() : 0.0;
        const double dz = jitter > 0.0 ? offset() : 0.0;
        Json b =
            body("sphere_" + std::to_string(x) + "_" + std::to_string(y) + "_" + std::to_string(z), "dynamic",
                 sphere(0.25), vec((x - 9.5) * 0.6 + dx, 1.0 + y * 0.6, (z - 9.5) * 0.6 + dz));
        b["mass"] = 1;
        b["friction"] = num(0.5);
        bodies.push_back(b);
      }
    }
  }
  return doc;
}

// R3: 465 unit cubes in rows of 30, 29, ..., 1 in the x-y plane, exactly touching.
Json pyramid() {
  Json doc = referenceDocument();
  Json& bodies = doc["bodies"];
  bodies.push_back(groundBox());
  for (int row = 0; row < 30; ++row) {
    const int count = 30 - row;
    for (int i = 0; i < count; ++i) {
      Json b = body("cube_" + std::to_string(row) + "_" + std::to_string(i), "dynamic", box(0.5, 0.5, 0.5),
                    vec(i - (count - 1) / 2.0, 0.5 + row, 0));
      b["mass"] = 1;
      b["friction"] = num(0.5);
      bodies.push_back(b);
    }
  }
  return doc;
}

// R4: 2,000 convex hulls on a static sine terrain; the hull points and positions as
// reference_scenes.h gives them.
Json terrain() {
  Json doc = referenceDocument();
  Json& bodies = doc["bodies"];
  constexpr int kQuads = kTerrainQuads;
  Json vertices = Json::array(), triangles = Json::array();
  for (int j = 0; j <= kQuads; ++j) {
    for (int i = 0; i <= kQuads; ++i) {
      const double x = i - kQuads / 2.0, z = j - kQuads / 2.0;
      vertices.push_back(vec(x, terrainHeight(x, z), z));
    }
  }
  const auto at = [&](int i, int j) { return j * (kQuads + 1) + i; };
  for (int j = 0; j < kQuads; ++j) {
    for (int i = 0; i < kQuads; ++i) {
      // Counter-clockwise seen from above (+y): the front faces up.
      triangles.push_back({at(i, j), at(i, j + 1), at(i + 1, j)});
      triangles.push_back({at(i + 1, j), at(i, j + 1), at(i + 1, j + 1)});
    }
  }
  Json ground = body("terrain", "static",
                     {{"type", "mesh"}, {"vertices", vertices}, {"triangles", triangles}}, vec(0, 0, 0));
  ground["friction"] = num(0.5);
  bodies.push_back(ground);

  const auto hulls = terrainHullPoints();
  std::size_t next = 0;
  for (int x = 0; x < kTerrainLatticeX; ++x) {
    for (int y = 0; y < kTerrainLatticeY; ++y) {
      for (int z = 0; z < kTerrainLatticeZ; ++z) {
        Json points = Json::array();
        for (const Vec3& point : hulls[next++]) points.push_back(jsonVec3(point));
        Json b =
            body("hull_" + std::to_string(x) + "_" + std::to_string(y) + "_" + std::to_string(z), "dynamic",
                 {{"type", "convex_hull"}, {"points", points}}, jsonVec3(terrainHullPosition(x, y, z)));
        b["mass"] = 1;
        b["friction"] = num(0.5);
        bodies.push_back(b);
      }
    }
  }
  return doc;
}

}  // namespace collide::scene::builtin
