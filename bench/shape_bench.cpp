// Ray casts and world-bound updates per proxy type, through the public Shape API. Each benchmark
// casts a fixed set of random rays (fixed seed) against the shape under a random transform; to add
// a proxy, add one line to kShapes.
#include <collide/shapes.h>

#include <benchmark/benchmark.h>

#include <cmath>
#include <functional>
#include <random>
#include <vector>

namespace {

using namespace collide;

struct ShapeEntry {
  const char* name;
  std::function<Shape()> make;
};

// Points on a sphere, from a fixed seed: a typical rock-like hull.
std::vector<Vec3> spherePoints(int count, float radius) {
  std::mt19937 rng(5);
  std::normal_distribution<float> gauss(0.0f, 1.0f);
  std::vector<Vec3> points;
  for (int i = 0; i < count; ++i) {
    const float x = gauss(rng);
    const float y = gauss(rng);
    const float z = gauss(rng);
    points.push_back(radius * glm::normalize(Vec3(x, y, z)));
  }
  return points;
}

// A wavy n x n grid of quads (2 n² triangles) spanning [-1, 1]² in x and z.
TriangleMesh gridMesh(int n) {
  std::vector<Vec3> vertices;
  std::vector<MeshTriangle> triangles;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const float x = -1.0f + 2.0f * float(i) / float(n), z = -1.0f + 2.0f * float(j) / float(n);
      vertices.emplace_back(x, 0.2f * std::sin(3.0f * x) * std::cos(3.0f * z), z);
    }
  }
  auto index = [n](int i, int j) { return std::uint32_t(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      triangles.push_back({{index(i, j), index(i, j + 1), index(i + 1, j)}});
      triangles.push_back({{index(i + 1, j), index(i, j + 1), index(i + 1, j + 1)}});
    }
  }
  return TriangleMesh::fromTriangles(std::move(vertices), std::move(triangles));
}

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
    {"hull32", [] { return Shape(ConvexHull::fromPoints(spherePoints(32, 1.0f))); }},
    {"kdop18", [] { return Shape(Kdop::fromPoints(18, spherePoints(32, 1.0f))); }},
    {"mesh_grid_2k", [] { return Shape(gridMesh(32)); }},
    {"compound3",
     [] {
       std::vector<Compound::Child> children;
       children.push_back({Sphere{0.4f}, Transform{Vec3(-0.8f, 0, 0)}});
       children.push_back({Box{Vec3(0.4f, 0.2f, 0.2f)}, Transform{}});
       children.push_back({Capsule{0.2f, 0.3f}, Transform{Vec3(0.8f, 0, 0)}});
       return Shape(Compound::fromChildren(std::move(children)));
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
