#include "engines.h"

#include <chrono>
#include <ctime>

namespace collide::bench {

std::string_view toString(Engine engine) { return engine == Engine::Collide ? "collide" : "Bullet"; }

double processCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

EngineRun runCollide(const scene::Scene& scene, int steps) {
  using Clock = std::chrono::steady_clock;
  EngineRun run;
  const auto buildStart = Clock::now();
  scene::SceneWorld sw = scene::buildWorld(scene);
  run.buildMs = std::chrono::duration<double, std::milli>(Clock::now() - buildStart).count();

  const double cpuStart = processCpuSeconds();
  const auto start = Clock::now();
  for (int i = 0; i < steps; ++i) sw.world.step(scene.dt);
  const double wallMs = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
  const double cpuMs = 1e3 * (processCpuSeconds() - cpuStart);
  run.internalSteps = steps;
  run.wallMsPerStep = steps > 0 ? wallMs / steps : 0.0;
  run.cpuMsPerStep = steps > 0 ? cpuMs / steps : 0.0;

  run.poses.resize(scene.bodies.size());
  run.masses.resize(scene.bodies.size(), 0.0);
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodyId id = sw.bodies[i];
    const Transform t = sw.world.transform(id);
    run.poses[i] = {t.position, t.rotation, sw.world.linearVelocity(id)};
    run.masses[i] = sw.world.mass(id);
  }
  return run;
}

QueryRun queryCollide(const scene::Scene& scene, int steps, const QueryBatch& batch, int repeats) {
  scene::SceneWorld sw = scene::buildWorld(scene);
  for (int i = 0; i < steps; ++i) sw.world.step(scene.dt);
  QueryRun run;
  run.rayDistances.assign(batch.rays.size(), kMiss);
  run.sweepFractions.assign(batch.sweeps.size(), kMiss);
  const double rayStart = processCpuSeconds();
  for (int r = 0; r < repeats; ++r) {
    for (std::size_t k = 0; k < batch.rays.size(); ++k) {
      if (const auto hit = sw.world.castRay(batch.rays[k])) run.rayDistances[k] = hit->distance;
    }
  }
  run.rayCpuSeconds = processCpuSeconds() - rayStart;
  const Shape sphere(Sphere{batch.sweepRadius});
  const double sweepStart = processCpuSeconds();
  for (int r = 0; r < repeats; ++r) {
    for (std::size_t k = 0; k < batch.sweeps.size(); ++k) {
      const SweepQuery& q = batch.sweeps[k];
      if (const auto hit = sw.world.castShape(sphere, Transform{q.from}, q.translation))
        run.sweepFractions[k] = hit->fraction;
    }
  }
  run.sweepCpuSeconds = processCpuSeconds() - sweepStart;
  return run;
}

}  // namespace collide::bench
