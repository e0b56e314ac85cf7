// `collide bench SCENE`: collide alone on any scene (built-in or file), the world rebuilt for every
// run and stepped at the scene's dt; prints each run's ms per step and the median. The comparison
// with Bullet on the reference scenes is bench/vs_bullet (collide_vs_bullet), which needs Bullet.
#include "commands.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <vector>

using namespace collide;

namespace {

double cpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

int benchCommand(const BenchArguments& arguments) {
  using Clock = std::chrono::steady_clock;
  scene::Scene loaded = loadSceneArgument(
      arguments.scene, scene::LoadOptions{.allowOutsidePaths = arguments.allowOutsidePaths});
  if (arguments.threads) loaded.world.workerCount = *arguments.threads;
  const int steps = arguments.steps.value_or(loaded.steps);
  std::printf("scene %s: %zu bodies, %d steps of %.6g s, %d run(s), %d worker(s)\n", loaded.source.c_str(),
              loaded.bodies.size(), steps, static_cast<double>(loaded.dt), arguments.runs,
              loaded.world.workerCount);
  std::vector<double> cpu, wall;
  for (int run = 0; run < arguments.runs; ++run) {
    scene::SceneWorld sw = scene::buildWorld(loaded);
    const double cpuStart = cpuSeconds();
    const auto start = Clock::now();
    for (int i = 0; i < steps; ++i) sw.world.step(loaded.dt);
    const double wallMs = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    const double cpuMs = 1e3 * (cpuSeconds() - cpuStart);
    cpu.push_back(steps > 0 ? cpuMs / steps : 0.0);
    wall.push_back(steps > 0 ? wallMs / steps : 0.0);
    std::printf("run %d: %.3f ms/step (cpu), %.3f ms/step (wall)\n", run + 1, cpu.back(), wall.back());
  }
  std::printf("median: %.3f ms/step (cpu), %.3f ms/step (wall)\n", median(cpu), median(wall));
  return 0;
}
