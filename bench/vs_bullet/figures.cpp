#include "figures.h"

#include <collide/shapes.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace collide::bench {

namespace {

bool finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// The lowest point of a convex shape under a pose: its support point along -y.
Vec3 lowestPoint(const Shape& shape, const BodyPose& pose, float scale) {
  const Vec3 down = glm::conjugate(pose.rotation) * Vec3(0.0f, -1.0f, 0.0f);
  return pose.origin + pose.rotation * (scale * support(shape, down));
}

}  // namespace

Figures computeFigures(const scene::Scene& scene, const std::vector<BodyPose>& poses,
                       const std::vector<double>& masses) {
  Figures f;
  std::vector<Transform> terrains;
  std::vector<const Shape*> terrainShapes;
  float topY = -std::numeric_limits<float>::infinity();
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodyDef& def = scene.bodies[i].def;
    if (def.type != BodyType::Dynamic) {
      ++f.staticBodies;
      if (def.shape.type() == ShapeType::Mesh) {
        terrains.push_back({def.position, def.rotation, def.scale});
        terrainShapes.push_back(&def.shape);
      }
      continue;
    }
    if (def.position.y > topY) {
      topY = def.position.y;
      f.topBody = static_cast<int>(i);
    }
  }
  f.hasTerrain = !terrains.empty();
  f.lowestPointY = std::numeric_limits<double>::infinity();
  double speedSum = 0.0;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodyDef& def = scene.bodies[i].def;
    if (def.type != BodyType::Dynamic) continue;
    ++f.dynamicBodies;
    f.dynamicMass += masses[i];
    const BodyPose& pose = poses[i];
    if (!finite(pose.origin) || !finite(pose.linearVelocity)) {
      f.finite = false;
      continue;
    }
    const double speed = glm::length(pose.linearVelocity);
    speedSum += speed;
    f.maxSpeed = std::max(f.maxSpeed, speed);
    if (!def.parts.empty() || !def.shape.isConvex()) continue;
    const Vec3 low = lowestPoint(def.shape, pose, def.scale);
    f.lowestPointY = std::min(f.lowestPointY, static_cast<double>(low.y));
    // The terrain straight under the lowest point: a ray down from well above it.
    for (std::size_t t = 0; t < terrains.size(); ++t) {
      const Ray ray{Vec3(low.x, low.y + 100.0f, low.z), Vec3(0.0f, -1.0f, 0.0f), 1000.0f};
      const std::optional<RayHit> hit = rayCast(*terrainShapes[t], terrains[t], ray);
      if (!hit) continue;
      const double depth = static_cast<double>(hit->point.y) - low.y;
      if (depth > 0.0) ++f.belowTerrain;
      if (depth > 0.01) ++f.belowTerrainBy1cm;
      f.deepestBelowTerrain = std::max(f.deepestBelowTerrain, depth);
    }
  }
  if (f.dynamicBodies > 0) f.meanSpeed = speedSum / f.dynamicBodies;
  if (f.topBody >= 0) f.topDisplacement = poses[f.topBody].origin - scene.bodies[f.topBody].def.position;
  return f;
}

}  // namespace collide::bench
