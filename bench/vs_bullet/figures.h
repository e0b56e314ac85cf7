// What collide_vs_bullet reports for one run of one engine on one scene: the timings, the memory
// and the stability figures of reference-scenes.md. The figures are computed by one function from
// the bodies' final poses, whichever engine produced them, so both engines are judged alike.
#pragma once

#include <collide/math.h>
#include <collide/scene/scene.h>

#include <vector>

namespace collide::bench {

// A body's final state in collide's convention: the pose of the shape's origin (not the centre of
// mass) and the velocity of the centre of mass.
struct BodyPose {
  Vec3 origin{0.0f};
  Quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
  Vec3 linearVelocity{0.0f};
};

struct Figures {
  int staticBodies = 0;
  int dynamicBodies = 0;
  double dynamicMass = 0.0;  // kg, summed over the dynamic bodies as the engine holds them
  // The dynamic body that started highest (R3: the top cube): final minus initial position.
  int topBody = -1;
  Vec3 topDisplacement{0.0f};
  double meanSpeed = 0.0;  // m/s, of the dynamic bodies' centres of mass at the end
  double maxSpeed = 0.0;
  double lowestPointY = 0.0;  // the lowest point of any dynamic convex body (its support along -y)
  // Scenes with a static triangle mesh (R4): dynamic bodies whose lowest point lies below the mesh
  // surface straight under that point, and by how much the deepest one does.
  bool hasTerrain = false;
  int belowTerrain = 0;              // by any amount
  int belowTerrainBy1cm = 0;         // by more than 1 cm
  double deepestBelowTerrain = 0.0;  // m, >= 0
  bool finite = true;                // every pose and velocity finite
};

// `poses[i]` belongs to scene.bodies[i] (static bodies are ignored); `masses[i]` is the engine's
// mass of that body (0 for static ones).
Figures computeFigures(const scene::Scene& scene, const std::vector<BodyPose>& poses,
                       const std::vector<double>& masses);

}  // namespace collide::bench
