// Ray casts and world-bound updates per proxy type, through the public Shape API. Each benchmark
// casts a fixed set of random rays (fixed seed) against the shape under a random transform; to add
// a proxy, add one line to kShapes.
#include <collide/shapes.h>

#include <benchmark/benchmark.h>

#include <functional>
#include <random>
#include <vector>

namespace {

using namespace collide;

struct ShapeEntry {
  const char* name;
  std::function<Shape()> make;
};

const std::vector<ShapeEntry> kShapes = {
    {"sphere", [] { return Shape(Sphere{0.7f}); }},
    {"capsule",
     [] {
       return Shape(Capsule{0.4f, 0.9f});
     }},
    {"plane",
     [] {
       return Shape(Plane{glm::normalize(Vec3(0.3f, 1.0f, -0.2f)), 0.5f});
     }},
    {"box", [] { return Shape(Box{Vec3(0.3f, 0.8f, 1.2f)}); }},
    {"ellipsoid", [] { return Shape(Ellipsoid{Vec3(1.2f, 0.5f, 0.8f)}); }},
    {"cylinder",
     [] {
       return Shape(Cylinder{0.6f, 0.9f});
     }},
};

constexpr int kRays = 1024;
constexpr int kTransforms = 1024;

Vec3 randomUnit(std::mt19937& rng) {
  std::normal_distribution<float> n(0.0f, 1.0f);
  return glm::normalize(Vec3(n(rng), n(rng), n(rng)));
}

Transform randomTransform(std::mt19937& rng) {
  std::uniform_real_distribution<float> position(-5.0f, 5.0f), scale(0.3f, 3.0f);
  std::normal_distribution<float> n(0.0f, 1.0f);
  return {Vec3(position(rng), position(rng), position(rng)),
          glm::normalize(Quat(n(rng), n(rng), n(rng), n(rng))), scale(rng)};
}

// Rays from a sphere of radius 10 around the shape towards points 0.6 (scaled) from its centre:
// most hit, some graze past.
void rayCasts(benchmark::State& state, const ShapeEntry& entry) {
  std::mt19937 rng(42);
  const Shape shape = entry.make();
  const Transform transform = randomTransform(rng);
  std::vector<Ray> rays;
  for (int i = 0; i < kRays; ++i) {
    const Vec3 origin = transform.position + 10.0f * randomUnit(rng);
    const Vec3 target = transform.position + 0.6f * transform.scale * randomUnit(rng);
    rays.push_back(Ray{origin, glm::normalize(target - origin), 100.0f});
  }
  int hits = 0;
  for (auto _ : state) {
    for (const Ray& ray : rays) {
      const std::optional<RayHit> hit = rayCast(shape, transform, ray);
      hits += hit.has_value();
      benchmark::DoNotOptimize(hit);
    }
  }
  state.SetItemsProcessed(state.iterations() * kRays);
  state.counters["hit_fraction"] = double(hits) / double(state.iterations() * kRays);
}

void worldBoundsUpdate(benchmark::State& state, const ShapeEntry& entry) {
  std::mt19937 rng(43);
  const Shape shape = entry.make();
  std::vector<Transform> transforms;
  for (int i = 0; i < kTransforms; ++i) transforms.push_back(randomTransform(rng));
  for (auto _ : state) {
    for (const Transform& t : transforms) benchmark::DoNotOptimize(worldBounds(shape, t));
  }
  state.SetItemsProcessed(state.iterations() * kTransforms);
}

const bool kRegistered = [] {
  for (const ShapeEntry& entry : kShapes) {
    benchmark::RegisterBenchmark((std::string("RayCast/") + entry.name).c_str(), rayCasts, entry);
    benchmark::RegisterBenchmark((std::string("WorldBounds/") + entry.name).c_str(), worldBoundsUpdate,
                                 entry);
  }
  return true;
}();

}  // namespace
