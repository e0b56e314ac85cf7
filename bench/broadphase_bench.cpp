// Broad-phase benchmarks: N boxes doing a random walk inside a cube sized so that each box overlaps
// on average 0.05 others (a few per cent of the boxes are in a pair). One step = update every box,
// then find the pairs. Also 10,000 closest-hit ray casts over the 100,000-box scene. The same
// workload runs on Bullet's btDbvtBroadphase when Bullet is available.
#include <collide/broadphase.h>

#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#ifdef COLLIDE_BENCH_WITH_BULLET
#include <BulletCollision/BroadphaseCollision/btDbvtBroadphase.h>
#include <BulletCollision/BroadphaseCollision/btOverlappingPairCache.h>
#endif

using namespace collide;

namespace {

constexpr float kHalfSize = 0.5f;
constexpr float kStepSize = 0.05f;  // per axis per step: half the tree's margin
constexpr int kRayCount = 10000;

// Random walk of N boxes. The cube's side L makes the expected number of partners per box
// N (4h)³ / L³ equal 0.05.
struct Workload {
  explicit Workload(int n) : rng(1234), side(4.0f * kHalfSize * std::cbrt(static_cast<float>(n) / 0.05f)) {
    std::uniform_real_distribution<float> position(kHalfSize, side - kHalfSize);
    centers.resize(n);
    for (Vec3& c : centers) c = Vec3(position(rng), position(rng), position(rng));
  }
  void step() {
    std::uniform_real_distribution<float> jitter(-kStepSize, kStepSize);
    for (Vec3& c : centers) {
      c += Vec3(jitter(rng), jitter(rng), jitter(rng));
      c = glm::clamp(c, Vec3(kHalfSize), Vec3(side - kHalfSize));
    }
  }
  Aabb box(int i) const { return Aabb::fromCenterHalfExtents(centers[i], Vec3(kHalfSize)); }
  std::vector<Ray> rays() {
    std::uniform_real_distribution<float> position(0.0f, side), direction(-1.0f, 1.0f);
    std::vector<Ray> out(kRayCount);
    for (Ray& r : out) {
      r.origin = Vec3(position(rng), position(rng), position(rng));
      r.direction = glm::normalize(Vec3(direction(rng), direction(rng), direction(rng)));
      r.maxDistance = 0.25f * side;
    }
    return out;
  }

  std::mt19937 rng;
  float side;
  std::vector<Vec3> centers;
};

void stepCollide(benchmark::State& state, BroadPhaseType type) {
  const int n = static_cast<int>(state.range(0));
  Workload workload(n);
  BroadPhaseSettings settings;
  settings.type = type;
  auto bp = createBroadPhase(settings);
  std::vector<ProxyId> ids(n);
  for (int i = 0; i < n; ++i) ids[i] = bp->add({workload.box(i)});
  Array<ProxyPair> pairs;
  bp->findPairs(pairs);
  std::uint64_t kept = 0, steps = 0, tests = 0;
  for (auto _ : state) {
    state.PauseTiming();
    workload.step();  // the motion itself is not the broad phase's cost
    state.ResumeTiming();
    for (int i = 0; i < n; ++i) bp->update(ids[i], workload.box(i));
    const BroadPhaseStats& stats = bp->findPairs(pairs);
    kept += stats.keptPairs;
    tests += stats.boxTests;
    ++steps;
  }
  state.counters["boxTests"] = static_cast<double>(tests) / static_cast<double>(steps);
  state.counters["pairs"] = static_cast<double>(kept) / static_cast<double>(steps);
  state.counters["potential"] = static_cast<double>(bp->lastStats().potentialPairs);
}

void rayCollide(benchmark::State& state, BroadPhaseType type) {
  const int n = static_cast<int>(state.range(0));
  Workload workload(n);
  BroadPhaseSettings settings;
  settings.type = type;
  auto bp = createBroadPhase(settings);
  for (int i = 0; i < n; ++i) bp->add({workload.box(i)});
  Array<ProxyPair> pairs;
  bp->findPairs(pairs);
  const std::vector<Ray> rays = workload.rays();
  std::uint64_t hits = 0;
  for (auto _ : state) {
    for (const Ray& ray : rays) hits += bp->rayCastClosest(ray).has_value() ? 1 : 0;
  }
  state.counters["hitFraction"] =
      static_cast<double>(hits) / static_cast<double>(state.iterations() * kRayCount);
}

#ifdef COLLIDE_BENCH_WITH_BULLET

btVector3 toBullet(const Vec3& v) { return {v.x, v.y, v.z}; }

struct BulletScene {
  explicit BulletScene(const Workload& workload) {
    const int n = static_cast<int>(workload.centers.size());
    proxies.resize(n);
    for (int i = 0; i < n; ++i) {
      const Aabb box = workload.box(i);
      proxies[i] =
          broadphase.createProxy(toBullet(box.min), toBullet(box.max), 0, nullptr,
                                 btBroadphaseProxy::DefaultFilter, btBroadphaseProxy::AllFilter, nullptr);
    }
    broadphase.calculateOverlappingPairs(nullptr);
  }
  btDbvtBroadphase broadphase;
  std::vector<btBroadphaseProxy*> proxies;
};

void stepBullet(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  Workload workload(n);
  BulletScene scene(workload);
  std::uint64_t kept = 0, steps = 0;
  for (auto _ : state) {
    state.PauseTiming();
    workload.step();
    state.ResumeTiming();
    for (int i = 0; i < n; ++i) {
      const Aabb box = workload.box(i);
      scene.broadphase.setAabb(scene.proxies[i], toBullet(box.min), toBullet(box.max), nullptr);
    }
    scene.broadphase.calculateOverlappingPairs(nullptr);
    kept += static_cast<std::uint64_t>(scene.broadphase.getOverlappingPairCache()->getNumOverlappingPairs());
    ++steps;
  }
  state.counters["pairs"] = static_cast<double>(kept) / static_cast<double>(steps);
}

// Closest box along the ray. Bullet's dbvt ray test does not clip the ray while it runs, so the
// callback sees every box on the ray and keeps the nearest (its own slab test, like ours).
struct ClosestBoxCallback : btBroadphaseRayCallback {
  btVector3 from;
  float best = 0.0f;
  bool hit = false;
  bool process(const btBroadphaseProxy* proxy) override {
    float tMin = 0.0f, tMax = m_lambda_max;
    for (int i = 0; i < 3; ++i) {
      float t0 = (proxy->m_aabbMin[i] - from[i]) * m_rayDirectionInverse[i];
      float t1 = (proxy->m_aabbMax[i] - from[i]) * m_rayDirectionInverse[i];
      if (t0 > t1) std::swap(t0, t1);
      tMin = std::max(tMin, t0);
      tMax = std::min(tMax, t1);
    }
    if (tMin <= tMax && (!hit || tMin < best)) {
      best = tMin;
      hit = true;
    }
    return true;
  }
};

void rayBullet(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  Workload workload(n);
  BulletScene scene(workload);
  const std::vector<Ray> rays = workload.rays();
  std::uint64_t hits = 0;
  for (auto _ : state) {
    for (const Ray& ray : rays) {
      ClosestBoxCallback callback;
      const btVector3 from = toBullet(ray.origin);
      const btVector3 to = toBullet(ray.origin + ray.maxDistance * ray.direction);
      const btVector3 direction = toBullet(ray.direction);
      callback.from = from;
      for (int i = 0; i < 3; ++i) {
        callback.m_rayDirectionInverse[i] = direction[i] == 0.0f ? BT_LARGE_FLOAT : 1.0f / direction[i];
      }
      callback.m_signs[0] = callback.m_rayDirectionInverse[0] < 0.0f;
      callback.m_signs[1] = callback.m_rayDirectionInverse[1] < 0.0f;
      callback.m_signs[2] = callback.m_rayDirectionInverse[2] < 0.0f;
      callback.m_lambda_max = ray.maxDistance;
      scene.broadphase.rayTest(from, to, callback);
      hits += callback.hit ? 1 : 0;
    }
  }
  state.counters["hitFraction"] =
      static_cast<double>(hits) / static_cast<double>(state.iterations() * kRayCount);
}

#endif

void sizes(benchmark::internal::Benchmark* b, int largest) {
  for (int n : {1000, 3000, 10000, 30000, 100000}) {
    if (n <= largest) b->Arg(n);
  }
  b->Unit(benchmark::kMillisecond)->MinTime(1.0);
}

}  // namespace

BENCHMARK_CAPTURE(stepCollide, tree, BroadPhaseType::Tree)->Apply([](auto* b) { sizes(b, 100000); });
BENCHMARK_CAPTURE(stepCollide, sap, BroadPhaseType::SweepAndPrune)->Apply([](auto* b) { sizes(b, 100000); });
BENCHMARK_CAPTURE(stepCollide, grid, BroadPhaseType::Grid)->Apply([](auto* b) { sizes(b, 100000); });
BENCHMARK_CAPTURE(stepCollide, brute, BroadPhaseType::BruteForce)->Apply([](auto* b) { sizes(b, 5000); });
#ifdef COLLIDE_BENCH_WITH_BULLET
BENCHMARK(stepBullet)->Apply([](auto* b) { sizes(b, 100000); });
#endif

BENCHMARK_CAPTURE(rayCollide, tree, BroadPhaseType::Tree)->Arg(100000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(rayCollide, grid, BroadPhaseType::Grid)->Arg(100000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(rayCollide, sap, BroadPhaseType::SweepAndPrune)->Arg(10000)->Unit(benchmark::kMillisecond);
#ifdef COLLIDE_BENCH_WITH_BULLET
BENCHMARK(rayBullet)->Arg(100000)->Unit(benchmark::kMillisecond);
#endif
