// `collide bench SCENE`: collide alone on any scene (built-in or file), the world rebuilt for every
// run and stepped at the scene's dt, after --warmup untimed steps; prints each run's ms per step and
// the median, and the median of each stage's wall time (StageTimes) over the runs. The comparison
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
  if (arguments.warmup > 0) std::printf("each run takes %d untimed steps first\n", arguments.warmup);
  std::vector<double> cpu, wall;
  std::vector<std::vector<double>> stageMs(std::size(StageTimes::kStages));
  WorldMemory memory;
  std::size_t sceneMemory = 0;
  for (int run = 0; run < arguments.runs; ++run) {
    scene::SceneWorld sw = scene::buildWorld(loaded);
    for (int i = 0; i < arguments.warmup; ++i) sw.world.step(loaded.dt);
    const StageTimes before = sw.world.totalStats().time;
    const double cpuStart = cpuSeconds();
    const auto start = Clock::now();
    for (int i = 0; i < steps; ++i) sw.world.step(loaded.dt);
    const double wallMs = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    const double cpuMs = 1e3 * (cpuSeconds() - cpuStart);
    const double perStep = steps > 0 ? 1.0 / steps : 0.0;
    cpu.push_back(cpuMs * perStep);
    wall.push_back(wallMs * perStep);
    const StageTimes after = sw.world.totalStats().time;
    for (std::size_t k = 0; k < stageMs.size(); ++k) {
      const auto seconds = StageTimes::kStages[k].seconds;
      stageMs[k].push_back(1e3 * (after.*seconds - before.*seconds) * perStep);
    }
    std::printf("run %d: %.3f ms/step (cpu), %.3f ms/step (wall)\n", run + 1, cpu.back(), wall.back());
    memory = sw.world.memoryUse();  // every run's world is built and stepped alike
    sceneMemory = scene::sceneMemoryBytes(loaded, sw);
  }
  const double medianWall = median(wall);
  std::printf("median: %.3f ms/step (cpu), %.3f ms/step (wall)\n", median(cpu), medianWall);
  // Each stage's median over the runs, and its share of the median step's wall time.
  std::printf("%-20s %10s %8s\n", "stage (median)", "ms/step", "share");
  for (std::size_t k = 0; k < stageMs.size(); ++k) {
    const double ms = median(stageMs[k]);
    const double share = medianWall > 0.0 ? 100.0 * ms / medianWall : 0.0;
    std::printf("%-20s %10.3f %7.1f%%\n", StageTimes::kStages[k].label, ms, share);
  }
  // What the world holds after its steps (WorldMemory), and per body of the scene.
  const double bodies = loaded.bodies.empty() ? 1.0 : double(loaded.bodies.size());
  std::printf("%-20s %10s %8s %10s\n", "heap after the run", "MB", "share", "B/body");
  const double worldBytes = double(memory.total());
  for (const WorldMemory::Category& category : WorldMemory::kCategories) {
    const double bytes = double(memory.*category.bytes);
    std::printf("%-20s %10.3f %7.1f%% %10.0f\n", category.label, bytes / 1e6,
                worldBytes > 0.0 ? 100.0 * bytes / worldBytes : 0.0, bytes / bodies);
  }
  std::printf("%-20s %10.3f %8s %10.0f\n", "world", worldBytes / 1e6, "", worldBytes / bodies);
  std::printf("%-20s %10.3f %8s %10.0f\n", "scene", double(sceneMemory) / 1e6, "",
              double(sceneMemory) / bodies);
  return 0;
}
