// The two engines of collide_vs_bullet, each building one scene::Scene and stepping it: collide
// through the scene library's own buildWorld (the very bodies `collide run` makes), Bullet 3.24
// through a translation of the same Scene (bullet_engine.cpp), so both start from one description.
#pragma once

#include "figures.h"

#include <collide/scene/scene.h>

#include <string_view>
#include <vector>

namespace collide::bench {

enum class Engine { Collide, Bullet };
std::string_view toString(Engine engine);

struct EngineRun {
  double buildMs = 0.0;         // wall time to build the world from the Scene
  double wallMsPerStep = 0.0;   // wall time of the stepping loop / steps
  double cpuMsPerStep = 0.0;    // process CPU time of the stepping loop / steps
  int internalSteps = 0;        // steps the engine says it took (Bullet: internal tick callbacks)
  std::vector<BodyPose> poses;  // per scene body, after the last step
  std::vector<double> masses;   // per scene body, the engine's mass (0 for static bodies)
};

// Build the scene in collide and take `steps` steps of scene.dt.
EngineRun runCollide(const scene::Scene& scene, int steps);

// Build the same scene in Bullet (btDiscreteDynamicsWorld, btDbvtBroadphase, sequential impulse
// solver, default settings; deactivation disabled) and take `steps` calls of
// stepSimulation(dt, 1, dt): exactly one internal step each. Throws collide::Error for what the
// translation does not support (shape types, material combinations Bullet's product rule cannot
// reproduce). Defined only when Bullet is available.
EngineRun runBullet(const scene::Scene& scene, int steps);

// The query benchmark (collide_query_vs_bullet): the same rays and sphere sweeps asked of both
// engines' worlds of one scene.
struct SweepQuery {
  Vec3 from{0.0f};
  Vec3 translation{0.0f};
};
struct QueryBatch {
  std::vector<Ray> rays;  // unit directions, finite maxDistance
  std::vector<SweepQuery> sweeps;
  float sweepRadius = 0.25f;
};
inline constexpr float kMiss = -1.0f;
struct QueryRun {
  std::vector<float> rayDistances;    // per ray: the closest hit's distance, kMiss for none
  std::vector<float> sweepFractions;  // per sweep: the first contact's fraction, kMiss for none
  double rayCpuSeconds = 0.0;         // all rays, `repeats` times
  double sweepCpuSeconds = 0.0;
};
// Build the scene, take `steps` steps, then ask every ray (castRay / rayTest with the closest-hit
// callback) and every sweep (castShape / convexSweepTest of a sphere), `repeats` times over.
QueryRun queryCollide(const scene::Scene& scene, int steps, const QueryBatch& batch, int repeats);
QueryRun queryBullet(const scene::Scene& scene, int steps, const QueryBatch& batch, int repeats);

// CPU time of this process, seconds.
double processCpuSeconds();

}  // namespace collide::bench
