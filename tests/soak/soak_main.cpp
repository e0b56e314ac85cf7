// The soak test: a pile of unit cubes (R1 of docs/benchmarks.md, or its lower corner) stepped for a
// long time, checking after every step what a long-running game needs from the world:
//   - no non-finite value in any body's position, rotation or velocities;
//   - no body below the ground: the ground box's top face is y = 0, and a cube whose lowest corner
//     is more than kSunk below it has gone through (the solver's allowed penetration, the linear
//     slop, is 5 mm; a tenth of the cube's size is twenty times that);
//   - memory flat: the resident set size after the warm-up (the pile has landed and every buffer
//     has grown to its working size) and at the end differ by less than kRssGrowth. A leak of even
//     a few bytes per contact per step would exceed it over thousands of steps.
//
// Usage: collide_soak [--side K] [--steps N] [--warmup W]
//   --side K    cubes per lattice side (16: the full R1 pile of 4,096; 8: its 512-cube corner)
//   --steps N   steps in all (default 2000)
//   --warmup W  the step after which the baseline RSS is taken (default min(1000, N / 2))
// Exit code 0 when every check held, 1 otherwise (with the first failure on stderr).
#include <collide/scene/builtin_scenes.h>
#include <collide/scene/scene.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>
#include <string_view>

#include <unistd.h>

namespace {

using namespace collide;

constexpr float kSunk = 0.1f;        // m below y = 0 (see above)
constexpr double kRssGrowth = 0.03;  // relative, between the warm-up and the end

// Resident set size in bytes (Linux: /proc/self/statm, second field, in pages).
long residentBytes() {
  std::ifstream statm("/proc/self/statm");
  long total = 0, resident = 0;
  statm >> total >> resident;
  return resident * ::sysconf(_SC_PAGESIZE);
}

int parseInt(std::string_view text, std::string_view what) {
  int value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || value < 1) {
    throw Error("soak: " + std::string(what) + " must be an integer >= 1, got \"" + std::string(text) + "\"");
  }
  return value;
}

bool finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// R1's cubes are named box_X_Y_Z with X, Y, Z in [0, 16); keep the K x K x K lattice corner.
scene::Scene pile(int side) {
  scene::Scene s = scene::loadBuiltinScene("pile");
  std::erase_if(s.bodies, [side](const scene::Body& b) {
    int x = 0, y = 0, z = 0;
    if (std::sscanf(b.def.name.c_str(), "box_%d_%d_%d", &x, &y, &z) != 3) return false;  // the ground
    return x >= side || y >= side || z >= side;
  });
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    int side = 16, steps = 2000, warmup = -1;
    for (int i = 1; i < argc; ++i) {
      const std::string_view arg = argv[i];
      if (i + 1 >= argc) throw Error("soak: " + std::string(arg) + " needs a value");
      if (arg == "--side")
        side = parseInt(argv[++i], "--side");
      else if (arg == "--steps")
        steps = parseInt(argv[++i], "--steps");
      else if (arg == "--warmup")
        warmup = parseInt(argv[++i], "--warmup");
      else
        throw Error("soak: unknown option " + std::string(arg));
    }
    if (side > 16) throw Error("soak: --side must be <= 16, got " + std::to_string(side));
    if (warmup < 0) warmup = std::min(1000, steps / 2);
    if (warmup >= steps) throw Error("soak: --warmup must be < --steps");

    const scene::Scene s = pile(side);
    scene::SceneWorld sw = scene::buildWorld(s);
    std::cout << "soak: " << s.bodies.size() - 1 << " cubes, " << steps << " steps, RSS baseline after step "
              << warmup << "\n";

    const auto start = std::chrono::steady_clock::now();
    long baseline = 0;
    float deepest = 0.0f;
    for (int step = 1; step <= steps; ++step) {
      sw.world.step(s.dt);
      for (std::size_t i = 0; i < sw.bodies.size(); ++i) {
        const BodyId id = sw.bodies[i];
        if (sw.world.type(id) != BodyType::Dynamic) continue;
        const Transform t = sw.world.transform(id);
        const Quat& q = t.rotation;
        if (!finite(t.position) || !std::isfinite(q.x + q.y + q.z + q.w) ||
            !finite(sw.world.linearVelocity(id)) || !finite(sw.world.angularVelocity(id))) {
          std::cerr << "FAIL step " << step << ": " << s.bodies[i].def.name << " has a non-finite state\n";
          return 1;
        }
        const float bottom = worldBounds(sw.world.shape(id), t).min.y;
        deepest = std::min(deepest, bottom);
        if (bottom < -kSunk) {
          std::cerr << "FAIL step " << step << ": " << s.bodies[i].def.name
                    << " is below the ground, lowest point y = " << bottom << "\n";
          return 1;
        }
      }
      if (step == warmup) baseline = residentBytes();
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const long end = residentBytes();
    const double growth = static_cast<double>(end - baseline) / static_cast<double>(baseline);
    std::cout << "soak: " << seconds * 1000.0 / steps << " ms/step, deepest point y = " << deepest
              << " m, RSS " << baseline / 1024 << " KiB after step " << warmup << ", " << end / 1024
              << " KiB at the end (" << growth * 100.0 << " %)\n";
    if (std::abs(growth) > kRssGrowth) {
      std::cerr << "FAIL: memory is not flat: RSS changed by " << growth * 100.0 << " % (limit "
                << kRssGrowth * 100.0 << " %)\n";
      return 1;
    }
    std::cout << "soak: pass\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << e.what() << "\n";
    return 2;
  }
}
