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

// CPU time of this process, seconds.
double processCpuSeconds();

}  // namespace collide::bench
