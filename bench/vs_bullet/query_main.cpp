// collide_query_vs_bullet: the world queries against Bullet 3.24's on the reference scenes (R1 pile,
// R4 terrain by default): the same closest-hit rays (World::castRay / btCollisionWorld::rayTest)
// and the same sphere sweeps (World::castShape / convexSweepTest), asked of each engine's world of
// one scene description, in one process, the engines taking turns run by run. Prints each engine's
// queries per CPU second, the time ratio collide / Bullet (median over the runs), and how far the
// answers agree (a cross-check: Bullet's hulls keep a collision margin, so their hits come a few
// centimetres early).
#include "engines.h"

#include <collide/error.h>
#include <collide/scene/builtin_scenes.h>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

using namespace collide;
using namespace collide::bench;

namespace {

// Where the action is: the dynamic bodies' region grown by 2 m (the grounds are far larger).
Aabb actionRegion(const scene::SceneWorld& sw) {
  Aabb region;
  for (const BodyId id : sw.bodies) {
    if (sw.world.type(id) != BodyType::Dynamic) continue;
    region.grow(worldBounds(sw.world.shape(id), sw.world.transform(id)));
  }
  return region.expanded(2.0f);
}

// Rays and sweeps as a game asks them: most from above, down into the region (picking, ground
// probes, a falling character), the rest across it between two random points (line of sight,
// bullets). Every ray and sweep starts outside every shape: Bullet does not report a start inside
// (collide reports distance 0), so such queries would compare nothing.
QueryBatch makeBatch(const scene::SceneWorld& sw, int rays, int sweeps, unsigned seed) {
  const Aabb region = actionRegion(sw);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const auto inside = [&] { return region.min + Vec3(u(rng), u(rng), u(rng)) * (region.max - region.min); };
  const float reach = 2.0f * glm::length(region.max - region.min);
  const auto segment = [&](int k, Vec3& from, Vec3& to) {
    to = inside();
    from = k % 10 < 7
               ? Vec3(to.x + 2.0f * (u(rng) - 0.5f), region.max.y + 5.0f, to.z + 2.0f * (u(rng) - 0.5f))
               : inside();
  };
  QueryBatch batch;
  const Shape sphere(Sphere{batch.sweepRadius});
  for (int k = 0; static_cast<int>(batch.rays.size()) < rays; ++k) {
    Vec3 from, to;
    segment(k, from, to);
    if (!sw.world.overlapPoint(from).empty() || glm::length(to - from) < 1e-3f) continue;
    batch.rays.push_back(Ray{from, glm::normalize(to - from), reach});
  }
  for (int k = 0; static_cast<int>(batch.sweeps.size()) < sweeps; ++k) {
    Vec3 from, to;
    segment(k, from, to);
    if (!sw.world.overlapShape(sphere, Transform{from}).empty()) continue;
    batch.sweeps.push_back({from, 1.5f * (to - from)});
  }
  return batch;
}

struct Agreement {
  int both = 0, neither = 0, onlyOne = 0, apart = 0;  // apart: both hit, beyond the tolerance
};

Agreement compare(const std::vector<float>& a, const std::vector<float>& b, const std::vector<float>& scale,
                  float tolerance) {
  Agreement g;
  for (std::size_t k = 0; k < a.size(); ++k) {
    const bool ha = a[k] != kMiss, hb = b[k] != kMiss;
    if (ha && hb) {
      ++g.both;
      if (std::abs(a[k] - b[k]) * scale[k] > tolerance) ++g.apart;
    } else if (!ha && !hb) {
      ++g.neither;
    } else {
      ++g.onlyOne;
    }
  }
  return g;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"collide_query_vs_bullet: rays and sphere sweeps in collide and in Bullet"};
  std::vector<std::string> scenes{"pile", "terrain"};
  int rays = 4000, sweeps = 1000, repeats = 3, runs = 3, steps = 0;
  app.add_option("--scene", scenes, "built-in scenes (default: pile terrain)");
  app.add_option("--rays", rays, "rays per batch")->check(CLI::PositiveNumber);
  app.add_option("--sweeps", sweeps, "sphere sweeps per batch")->check(CLI::PositiveNumber);
  app.add_option("--repeats", repeats, "times each batch is asked per run")->check(CLI::PositiveNumber);
  app.add_option("--runs", runs, "runs, the engines taking turns")->check(CLI::PositiveNumber);
  app.add_option("--steps", steps, "steps before the queries (0: the scene as built, both engines alike)")
      ->check(CLI::NonNegativeNumber);
  CLI11_PARSE(app, argc, argv);
  try {
    std::printf("%-10s %8s %14s %14s %8s %14s %14s %8s\n", "scene", "", "collide /s", "Bullet /s", "ratio",
                "both hit", "one only", "apart");
    for (const std::string& name : scenes) {
      const scene::Scene scene = scene::loadBuiltinScene(name);
      const QueryBatch batch = makeBatch(scene::buildWorld(scene), rays, sweeps, 7);
      std::vector<double> rayRatios, sweepRatios, rayRate[2], sweepRate[2];
      QueryRun last[2];
      for (int run = 0; run < runs; ++run) {
        for (int turn = 0; turn < 2; ++turn) {
          const int engine = (run + turn) % 2;  // 0 collide, 1 Bullet; who goes first alternates
          last[engine] = engine == 0 ? queryCollide(scene, steps, batch, repeats)
                                     : queryBullet(scene, steps, batch, repeats);
          rayRate[engine].push_back(rays * repeats / last[engine].rayCpuSeconds);
          sweepRate[engine].push_back(sweeps * repeats / last[engine].sweepCpuSeconds);
        }
        rayRatios.push_back(last[0].rayCpuSeconds / last[1].rayCpuSeconds);
        sweepRatios.push_back(last[0].sweepCpuSeconds / last[1].sweepCpuSeconds);
      }
      std::vector<float> rayScale(batch.rays.size(), 1.0f), sweepScale;
      for (const SweepQuery& q : batch.sweeps) sweepScale.push_back(glm::length(q.translation));
      if (std::getenv("COLLIDE_QUERY_DIFFS")) {
        for (std::size_t k = 0, shown = 0; k < batch.rays.size() && shown < 8; ++k) {
          const float a = last[0].rayDistances[k], b = last[1].rayDistances[k];
          if (a != kMiss && b != kMiss && std::abs(a - b) > 0.05f) {
            const scene::SceneWorld sw = scene::buildWorld(scene);
            float brute = kMiss;
            int which = -1;
            for (std::size_t i = 0; i < sw.bodies.size(); ++i) {
              const auto hit =
                  rayCast(sw.world.shape(sw.bodies[i]), sw.world.transform(sw.bodies[i]), batch.rays[k]);
              if (hit && (brute == kMiss || hit->distance < brute)) brute = hit->distance, which = int(i);
            }
            const Ray& ray = batch.rays[k];
            std::fprintf(stderr,
                         "ray %zu from (%.9g, %.9g, %.9g) along (%.9g, %.9g, %.9g): collide %.4f Bullet %.4f "
                         "brute %.4f body %d\n",
                         k, ray.origin.x, ray.origin.y, ray.origin.z, ray.direction.x, ray.direction.y,
                         ray.direction.z, a, b, brute, which);
            ++shown;
          }
        }
      }
      const Agreement r = compare(last[0].rayDistances, last[1].rayDistances, rayScale, 0.05f);
      const Agreement s = compare(last[0].sweepFractions, last[1].sweepFractions, sweepScale, 0.05f);
      std::printf("%-10s %8s %14.0f %14.0f %8.3f %14d %14d %8d\n", name.c_str(), "rays", median(rayRate[0]),
                  median(rayRate[1]), median(rayRatios), r.both, r.onlyOne, r.apart);
      std::printf("%-10s %8s %14.0f %14.0f %8.3f %14d %14d %8d\n", name.c_str(), "sweeps",
                  median(sweepRate[0]), median(sweepRate[1]), median(sweepRatios), s.both, s.onlyOne,
                  s.apart);
    }
    std::printf(
        "ratio: collide's CPU time / Bullet's for the same queries (median of %d runs); apart: both hit, "
        "more than 5 cm apart\n",
        runs);
  } catch (const Error& e) {
    std::fprintf(stderr, "collide_query_vs_bullet: %s\n", e.what());
    return 1;
  }
  return 0;
}
