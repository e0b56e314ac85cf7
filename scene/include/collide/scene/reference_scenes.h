// The reference scenes of the benchmarks (reference-scenes.md: B1 billiards, R1 pile, R2 rain,
// R3 pyramid, R4 terrain) for code that builds them in another engine (bench/, the Bullet
// comparison): each scene's full body list is loadBuiltinScene(builtin) (or loadReferenceScene(id)),
// the very Scene `collide run` steps, and the R4 generator is exposed so its hull points can be
// reproduced or checked without parsing JSON.
#pragma once

#include <collide/scene/scene.h>

#include <array>
#include <span>
#include <string_view>
#include <vector>

namespace collide::scene {

struct ReferenceScene {
  std::string_view id;       // "B1", "R1", ..., as reference-scenes.md names them
  std::string_view builtin;  // the built-in scene: "billiards", "pile", ...
};

std::span<const ReferenceScene> referenceScenes();
// The reference scene by id ("R4") or built-in name ("terrain"). Throws collide::Error otherwise.
Scene loadReferenceScene(std::string_view idOrName);

// ---- R4, convex hulls on a sine terrain. ----
inline constexpr int kTerrainQuads = 100;  // 100 x 100 quads of 1 m, centred on the origin
inline constexpr int kTerrainLatticeX = 20, kTerrainLatticeY = 5, kTerrainLatticeZ = 20;
inline constexpr int kTerrainHullPoints = 12;

// The terrain's height y = 0.5 sin(0.3 x) cos(0.3 z) at its vertices (the mesh interpolates it
// linearly in between).
double terrainHeight(double x, double z);

// The centre of the lattice cell (x, y, z), x in [0, 20), y in [0, 5), z in [0, 20): spacing 1.5,
// centred on x = z = 0, lowest layer at y = 3.
Vec3 terrainHullPosition(int x, int y, int z);

// The points of the 2,000 hulls in lattice order (x outermost, then y, then z; scene body
// 1 + (x * 5 + y) * 20 + z): one std::mt19937 seeded 42, for each point three
// std::normal_distribution<double>(0, 1) draws in separate statements (x, then y, then z),
// normalised in double to length 0.5, then rounded to float. These are exactly the points of the
// terrain scene's convex_hull shapes (written with 9 significant digits, which read back as the
// same floats); each body's shape is their hull.
std::vector<std::array<Vec3, kTerrainHullPoints>> terrainHullPoints();

}  // namespace collide::scene
