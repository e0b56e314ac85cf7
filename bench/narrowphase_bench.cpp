// Narrow-phase speed: nanoseconds per pair test, per pair type, and our GJK against libccd's on
// the same 32-vertex polytopes through the same support function.
#include <benchmark/benchmark.h>
#include <collide/narrowphase.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "narrowphase/convex_distance.h"
#include "narrowphase/convex_support.h"
#include "narrowphase/gjk.h"
#include "narrowphase/pair_functions.h"

#if defined(COLLIDE_HAVE_CCD)
#include <ccd/ccd.h>
#endif
#if defined(COLLIDE_HAVE_FCL)
#include <fcl/narrowphase/detail/convexity_based_algorithm/gjk_libccd.h>
#endif
#if defined(COLLIDE_BENCH_WITH_BULLET)
#include <BulletCollision/CollisionDispatch/btBoxBoxDetector.h>
#include <BulletCollision/CollisionShapes/btBoxShape.h>
#endif

using namespace collide;

namespace {

constexpr int kPairs = 256;

Quat randomRotation(std::mt19937& rng) {
  std::normal_distribution<float> n(0.0f, 1.0f);
  return glm::normalize(Quat(n(rng), n(rng), n(rng), n(rng)));
}

struct Placed {
  Shape a, b;
  Transform ta, tb;
};

// Pairs at centre distances spread around touching, so that about half collide.
std::vector<Placed> makePairs(const Shape& a, const Shape& b, float reach) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::vector<Placed> pairs;
  for (int i = 0; i < kPairs; ++i) {
    const Vec3 direction = glm::normalize(Vec3(unit(rng), unit(rng), unit(rng)) + Vec3(1e-3f));
    const Transform ta{Vec3(0.0f), randomRotation(rng), 1.0f};
    const Transform tb{direction * reach * (0.8f + 0.4f * (0.5f + 0.5f * unit(rng))), randomRotation(rng),
                       1.0f};
    pairs.push_back({a, b, ta, tb});
  }
  return pairs;
}

void runCollide(benchmark::State& state, const Shape& a, const Shape& b, float reach) {
  const std::vector<Placed> pairs = makePairs(a, b, reach);
  Manifold m;
  std::size_t i = 0;
  for (auto _ : state) {
    const Placed& p = pairs[i++ & (kPairs - 1)];
    benchmark::DoNotOptimize(collide::collide(p.a, p.ta, p.b, p.tb, m));
    benchmark::ClobberMemory();
  }
}

void BM_SphereSphereKernel(benchmark::State& state) {
  // The table's function itself, without the public entry's validation and dispatch.
  const std::vector<Placed> pairs = makePairs(Sphere{0.5f}, Sphere{0.4f}, 0.9f);
  Manifold m;
  std::size_t i = 0;
  for (auto _ : state) {
    const Placed& p = pairs[i++ & (kPairs - 1)];
    benchmark::DoNotOptimize(detail::collideSphereSphere(p.a, p.ta, p.b, p.tb, 0.0f, m));
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_SphereSphereKernel);

void BM_CollideSphereSphere(benchmark::State& s) { runCollide(s, Sphere{0.5f}, Sphere{0.4f}, 0.9f); }
void BM_CollideSphereCapsule(benchmark::State& s) { runCollide(s, Sphere{0.5f}, Capsule{0.3f, 0.5f}, 1.3f); }
void BM_CollideSphereBox(benchmark::State& s) { runCollide(s, Sphere{0.5f}, Box{Vec3(0.4f)}, 1.1f); }
void BM_CollideCapsuleCapsule(benchmark::State& s) {
  runCollide(s, Capsule{0.3f, 0.5f}, Capsule{0.3f, 0.5f}, 1.2f);
}
void BM_CollideCapsuleBox(benchmark::State& s) { runCollide(s, Capsule{0.3f, 0.5f}, Box{Vec3(0.4f)}, 1.3f); }
void BM_CollidePlaneBox(benchmark::State& s) { runCollide(s, Plane{}, Box{Vec3(0.4f)}, 0.6f); }
void BM_CollideBoxBoxSat(benchmark::State& s) { runCollide(s, Box{Vec3(0.4f)}, Box{Vec3(0.5f)}, 1.4f); }
// The generic entry on the same pairs, for comparison with SAT.
void BM_BoxBoxGjkEpaKernel(benchmark::State& state) {
  const std::vector<Placed> pairs = makePairs(Box{Vec3(0.4f)}, Box{Vec3(0.5f)}, 1.4f);
  Manifold m;
  std::size_t i = 0;
  for (auto _ : state) {
    const Placed& p = pairs[i++ & (kPairs - 1)];
    benchmark::DoNotOptimize(detail::collideConvexGeneric(p.a, p.ta, p.b, p.tb, 0.0f, m));
    benchmark::ClobberMemory();
  }
}
// A box resting face-down on a larger box, slightly wobbling: four clipped points.
std::vector<Placed> makeRestingBoxPairs() {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::vector<Placed> pairs;
  for (int i = 0; i < kPairs; ++i) {
    const Quat wobble =
        glm::angleAxis(glm::radians(0.5f * unit(rng)), glm::normalize(Vec3(unit(rng), 1e-3f, unit(rng))));
    pairs.push_back({Box{Vec3(3.0f, 0.5f, 3.0f)}, Box{Vec3(0.5f)}, Transform{},
                     Transform{Vec3(0.5f * unit(rng), 0.99f, 0.5f * unit(rng)), wobble, 1.0f}});
  }
  return pairs;
}

template <detail::CollideFunction F>
void runKernel(benchmark::State& state, const std::vector<Placed>& pairs, float margin = 0.0f) {
  Manifold m;
  std::size_t i = 0;
  int points = 0;
  for (auto _ : state) {
    const Placed& p = pairs[i++ & (kPairs - 1)];
    benchmark::DoNotOptimize(F(p.a, p.ta, p.b, p.tb, margin, m));
    points += m.count;
    benchmark::ClobberMemory();
  }
  state.counters["points_per_pair"] =
      benchmark::Counter(double(points) / double(std::max<std::size_t>(i, 1)));
}

void BM_CollideBoxOnBoxResting(benchmark::State& state) {
  const std::vector<Placed> pairs = makeRestingBoxPairs();
  Manifold m;
  std::size_t i = 0;
  for (auto _ : state) {
    const Placed& p = pairs[i++ & (kPairs - 1)];
    benchmark::DoNotOptimize(collide::collide(p.a, p.ta, p.b, p.tb, m));
    benchmark::ClobberMemory();
  }
}
// The box-specific kernel (the table's box–box cell) and the generic polyhedron SAT on the same
// pairs: resting (four points) and random (about half touching).
void BM_BoxBoxRestingFastKernel(benchmark::State& s) {
  runKernel<detail::collideBoxBox>(s, makeRestingBoxPairs());
}
void BM_BoxBoxRestingGenericSatKernel(benchmark::State& s) {
  runKernel<detail::collidePolyhedra>(s, makeRestingBoxPairs());
}
void BM_BoxBoxRandomFastKernel(benchmark::State& s) {
  runKernel<detail::collideBoxBox>(s, makePairs(Box{Vec3(0.4f)}, Box{Vec3(0.5f)}, 1.4f));
}
void BM_BoxBoxRandomGenericSatKernel(benchmark::State& s) {
  runKernel<detail::collidePolyhedra>(s, makePairs(Box{Vec3(0.4f)}, Box{Vec3(0.5f)}, 1.4f));
}
BENCHMARK(BM_BoxBoxRestingFastKernel);
BENCHMARK(BM_BoxBoxRestingGenericSatKernel);
BENCHMARK(BM_BoxBoxRandomFastKernel);
BENCHMARK(BM_BoxBoxRandomGenericSatKernel);

#if defined(COLLIDE_BENCH_WITH_BULLET)
// Bullet's box–box (btBoxBoxDetector, ODE's dBoxBox: 15 axes, then clipping, up to four points)
// on the same pairs, with a result that only counts the points.
struct CountingResult : btDiscreteCollisionDetectorInterface::Result {
  int points = 0;
  void setShapeIdentifiersA(int, int) override {}
  void setShapeIdentifiersB(int, int) override {}
  void addContactPoint(const btVector3&, const btVector3&, btScalar) override { ++points; }
};

btTransform toBulletTransform(const Transform& t) {
  return btTransform(btQuaternion(t.rotation.x, t.rotation.y, t.rotation.z, t.rotation.w),
                     btVector3(t.position.x, t.position.y, t.position.z));
}

void runBullet(benchmark::State& state, const std::vector<Placed>& pairs) {
  std::vector<btBoxShape> shapesA, shapesB;
  std::vector<btDiscreteCollisionDetectorInterface::ClosestPointInput> inputs(pairs.size());
  shapesA.reserve(pairs.size());
  shapesB.reserve(pairs.size());
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const Vec3 a = pairs[k].a.box().halfExtents, b = pairs[k].b.box().halfExtents;
    shapesA.emplace_back(btVector3(a.x, a.y, a.z));
    shapesB.emplace_back(btVector3(b.x, b.y, b.z));
    inputs[k].m_transformA = toBulletTransform(pairs[k].ta);
    inputs[k].m_transformB = toBulletTransform(pairs[k].tb);
  }
  CountingResult result;
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t k = i++ & (kPairs - 1);
    btBoxBoxDetector detector(&shapesA[k], &shapesB[k]);
    detector.getClosestPoints(inputs[k], result, nullptr);
    benchmark::ClobberMemory();
  }
  state.counters["points_per_pair"] =
      benchmark::Counter(double(result.points) / double(std::max<std::size_t>(i, 1)));
}
void BM_BulletBoxBoxResting(benchmark::State& s) { runBullet(s, makeRestingBoxPairs()); }
void BM_BulletBoxBoxRandom(benchmark::State& s) {
  runBullet(s, makePairs(Box{Vec3(0.4f)}, Box{Vec3(0.5f)}, 1.4f));
}
BENCHMARK(BM_BulletBoxBoxResting);
BENCHMARK(BM_BulletBoxBoxRandom);
#endif
// Hulls of 24 random points on a sphere (about 14 faces each).
void BM_CollideHullHullSat(benchmark::State& s) {
  std::mt19937 rng(3);
  std::normal_distribution<float> n(0.0f, 1.0f);
  auto hull = [&] {
    std::vector<Vec3> points(24);
    for (Vec3& p : points) p = 0.5f * glm::normalize(Vec3(n(rng), n(rng), n(rng)));
    return Shape(ConvexHull::fromPoints(points));
  };
  runCollide(s, hull(), hull(), 1.0f);
}
void BM_CollideEllipsoidCylinderGjkEpa(benchmark::State& s) {
  runCollide(s, Ellipsoid{Vec3(0.5f, 0.3f, 0.4f)}, Cylinder{0.4f, 0.5f}, 1.2f);
}
BENCHMARK(BM_CollideSphereSphere);
BENCHMARK(BM_CollideSphereCapsule);
BENCHMARK(BM_CollideSphereBox);
BENCHMARK(BM_CollideCapsuleCapsule);
BENCHMARK(BM_CollideCapsuleBox);
BENCHMARK(BM_CollidePlaneBox);
BENCHMARK(BM_CollideBoxBoxSat);
BENCHMARK(BM_BoxBoxGjkEpaKernel);
BENCHMARK(BM_CollideBoxOnBoxResting);
BENCHMARK(BM_CollideHullHullSat);
BENCHMARK(BM_CollideEllipsoidCylinderGjkEpa);

// ---- R4's pairs (reference-scenes.md): 12-point hulls on the sine terrain and on each other ----
//
// The terrain mesh and the hull generator of R4, built here as the scene library builds them; each
// hull is placed resting: turned at random, its lowest point sunk 0.005 (the linear slop) into the
// terrain under it, or onto another hull along a random direction, sunk 0.005 along the pair's
// GJK normal. Through the table's functions (no validation), with R4's speculative margin order
// (0.02).

TriangleMesh r4Terrain() {
  constexpr int kQuads = 100;
  std::vector<Vec3> vertices;
  std::vector<MeshTriangle> triangles;
  for (int j = 0; j <= kQuads; ++j) {
    for (int i = 0; i <= kQuads; ++i) {
      const double x = i - kQuads / 2.0, z = j - kQuads / 2.0;
      vertices.emplace_back(float(x), float(0.5 * std::sin(0.3 * x) * std::cos(0.3 * z)), float(z));
    }
  }
  const auto at = [&](int i, int j) { return static_cast<std::uint32_t>(j * (kQuads + 1) + i); };
  for (int j = 0; j < kQuads; ++j) {
    for (int i = 0; i < kQuads; ++i) {
      triangles.push_back({{at(i, j), at(i, j + 1), at(i + 1, j)}});
      triangles.push_back({{at(i + 1, j), at(i, j + 1), at(i + 1, j + 1)}});
    }
  }
  return TriangleMesh::fromTriangles(std::move(vertices), std::move(triangles));
}

std::vector<Shape> r4Hulls(int count) {
  std::mt19937 rng(42);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::vector<Shape> hulls;
  for (int h = 0; h < count; ++h) {
    std::vector<Vec3> points(12);
    for (Vec3& p : points) {
      const double x = gauss(rng);
      const double y = gauss(rng);
      const double z = gauss(rng);
      const double scale = 0.5 / std::sqrt(x * x + y * y + z * z);
      p = Vec3(float(x * scale), float(y * scale), float(z * scale));
    }
    hulls.push_back(Shape(ConvexHull::fromPoints(points)));
  }
  return hulls;
}

constexpr float kR4Margin = 0.02f;

std::vector<Placed> makeHullsOnTerrain() {
  const Shape terrain(r4Terrain());
  const std::vector<Shape> hulls = r4Hulls(kPairs);
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::vector<Placed> pairs;
  for (int i = 0; i < kPairs; ++i) {
    Transform pose{Vec3(20.0f * unit(rng), 0.0f, 20.0f * unit(rng)), randomRotation(rng), 1.0f};
    const Vec3 down = glm::conjugate(pose.rotation) * Vec3(0.0f, -1.0f, 0.0f);
    const Vec3 lowest = pose.applyToPoint(support(hulls[i], down));
    const Ray ray{Vec3(lowest.x, 10.0f, lowest.z), Vec3(0.0f, -1.0f, 0.0f), 100.0f};
    const float ground = rayCast(terrain, Transform{}, ray)->point.y;
    pose.position.y += ground - lowest.y - 0.005f;
    pairs.push_back({terrain, hulls[i], Transform{}, pose});
  }
  return pairs;
}

std::vector<Placed> makeHullsOnHulls() {
  const std::vector<Shape> hulls = r4Hulls(2 * kPairs);
  std::mt19937 rng(10);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::vector<Placed> pairs;
  for (int i = 0; i < kPairs; ++i) {
    const Transform ta{Vec3(0.0f), randomRotation(rng), 1.0f};
    const Vec3 direction = glm::normalize(Vec3(unit(rng), 1.0f + unit(rng), unit(rng)));
    Transform tb{2.0f * direction, randomRotation(rng), 1.0f};
    const DistanceResult d = distance(hulls[2 * i], ta, hulls[2 * i + 1], tb);
    tb.position -= (d.distance + 0.005f) * d.normal;
    pairs.push_back({hulls[2 * i], hulls[2 * i + 1], ta, tb});
  }
  return pairs;
}

void BM_R4HullOnTerrain(benchmark::State& s) {
  runKernel<detail::collideMeshConvex>(s, makeHullsOnTerrain(), kR4Margin);
}
void BM_R4HullOnHull(benchmark::State& s) {
  runKernel<detail::collidePolyhedra>(s, makeHullsOnHulls(), kR4Margin);
}
BENCHMARK(BM_R4HullOnTerrain);
BENCHMARK(BM_R4HullOnHull);

// ---- GJK on 32-vertex convex hulls (hulls of 32 random points on a sphere), separated pairs ----
//
// Every variant runs on the same pairs and the same support functions as libccd: a ConvexHull's
// support or, for the "Points" variants, our scan over the 32 points. "Cold" calls start from
// nothing; "Warm" calls pass a GjkCache per pair while the pair moves a little
// between visits (B turns 1° and slides 0.005 per visit, 16 visits per pair), as in a simulation
// step. libccd 2.1 has no distance query and no warm start: its GJK yes/no test is the peer.

constexpr int kFrames = 16;

struct HullPairs {
  std::vector<Shape> hulls;
  std::vector<std::vector<Vec3>> clouds;
  // [pair][frame]
  std::vector<detail::ConvexSupport> a, b, pointsA, pointsB;
};

HullPairs makeHullPairs() {
  std::mt19937 rng(7);
  std::normal_distribution<float> n(0.0f, 1.0f);
  HullPairs pairs;
  pairs.clouds.resize(2 * kPairs);
  pairs.hulls.reserve(2 * kPairs);
  for (auto& cloud : pairs.clouds) {
    for (int i = 0; i < 32; ++i) cloud.push_back(0.5f * glm::normalize(Vec3(n(rng), n(rng), n(rng))));
    pairs.hulls.push_back(Shape(ConvexHull::fromPoints(cloud)));
  }
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  for (int i = 0; i < kPairs; ++i) {
    const Vec3 direction = glm::normalize(Vec3(unit(rng), unit(rng), unit(rng)) + Vec3(1e-3f));
    const Transform ta{Vec3(0.0f), randomRotation(rng), 1.0f};
    const Quat rb = randomRotation(rng);
    const Vec3 spin = glm::normalize(Vec3(unit(rng), unit(rng), unit(rng)) + Vec3(1e-3f));
    const Vec3 slide = glm::normalize(Vec3(unit(rng), unit(rng), unit(rng)) + Vec3(1e-3f));
    for (int f = 0; f < kFrames; ++f) {
      // Apart by about 0.2 at frame 0.
      const Transform tb{direction * 1.2f + 0.005f * float(f) * slide,
                         glm::angleAxis(glm::radians(1.0f * float(f)), spin) * rb, 1.0f};
      pairs.a.push_back(detail::makeConvexSupport(pairs.hulls[2 * i], ta));
      pairs.b.push_back(detail::makeConvexSupport(pairs.hulls[2 * i + 1], tb));
      pairs.pointsA.push_back(detail::makePointsSupport(pairs.clouds[2 * i].data(), 32, ta));
      pairs.pointsB.push_back(detail::makePointsSupport(pairs.clouds[2 * i + 1].data(), 32, tb));
    }
  }
  return pairs;
}

// Visit order: all pairs at frame 0, then all at frame 1, ...
std::size_t visit(std::size_t i) {
  const std::size_t pair = i % kPairs;
  const std::size_t frame = (i / kPairs) % kFrames;
  return pair * kFrames + frame;
}

void BM_GjkDistanceHull32Cold(benchmark::State& state) {
  const HullPairs pairs = makeHullPairs();
  std::size_t i = 0;
  double sum = 0.0, iterations = 0.0;
  for (auto _ : state) {
    const std::size_t k = visit(i++);
    detail::ConvexSupport a = pairs.a[k], b = pairs.b[k];
    const detail::GjkResult result = detail::gjkDistance(a, b);
    benchmark::DoNotOptimize(result);
    sum += result.distance;
    iterations += result.iterations;
  }
  state.counters["mean_distance"] = benchmark::Counter(sum / double(std::max<std::size_t>(i, 1)));
  state.counters["iterations"] = benchmark::Counter(iterations / double(std::max<std::size_t>(i, 1)));
}
BENCHMARK(BM_GjkDistanceHull32Cold);

void BM_GjkDistanceHull32Warm(benchmark::State& state) {
  const HullPairs pairs = makeHullPairs();
  std::vector<detail::GjkCache> caches(kPairs);
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t pair = i % kPairs;
    const std::size_t k = visit(i++);
    detail::ConvexSupport a = pairs.a[k], b = pairs.b[k];
    benchmark::DoNotOptimize(detail::gjkDistance(a, b, 1e30f, &caches[pair]));
  }
}
BENCHMARK(BM_GjkDistanceHull32Warm);

void BM_GjkIntersectHull32Cold(benchmark::State& state) {
  // The same GJK as a yes/no test: bound 0 stops as soon as a separating plane is found, the work
  // libccd's ccdGJKIntersect does.
  const HullPairs pairs = makeHullPairs();
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t k = visit(i++);
    detail::ConvexSupport a = pairs.a[k], b = pairs.b[k];
    benchmark::DoNotOptimize(detail::gjkDistance(a, b, 0.0f));
  }
}
BENCHMARK(BM_GjkIntersectHull32Cold);

void BM_GjkDistancePoints32Cold(benchmark::State& state) {
  const HullPairs pairs = makeHullPairs();
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t k = visit(i++);
    benchmark::DoNotOptimize(detail::gjkDistance(pairs.pointsA[k], pairs.pointsB[k]));
  }
}
BENCHMARK(BM_GjkDistancePoints32Cold);

void BM_GjkDistancePoints32Warm(benchmark::State& state) {
  const HullPairs pairs = makeHullPairs();
  std::vector<detail::GjkCache> caches(kPairs);
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t pair = i % kPairs;
    const std::size_t k = visit(i++);
    benchmark::DoNotOptimize(detail::gjkDistance(pairs.pointsA[k], pairs.pointsB[k], 1e30f, &caches[pair]));
  }
}
BENCHMARK(BM_GjkDistancePoints32Warm);

#if defined(COLLIDE_HAVE_CCD)
void ccdSupport(const void* object, const ccd_vec3_t* direction, ccd_vec3_t* out) {
  const auto& s = *static_cast<const detail::ConvexSupport*>(object);
  const Vec3 p = s.supportCore(Vec3(direction->v[0], direction->v[1], direction->v[2]));
  for (int i = 0; i < 3; ++i) out->v[i] = p[i];
}

ccd_t makeCcd() {
  ccd_t ccd;
  CCD_INIT(&ccd);
  ccd.support1 = ccdSupport;
  ccd.support2 = ccdSupport;
  ccd.max_iterations = 100;
  return ccd;
}

void BM_LibccdGjkIntersectHull32(benchmark::State& state) {
  const HullPairs pairs = makeHullPairs();
  const ccd_t ccd = makeCcd();
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t k = visit(i++);
    detail::ConvexSupport a = pairs.a[k], b = pairs.b[k];
    benchmark::DoNotOptimize(ccdGJKIntersect(&a, &b, &ccd));
  }
}
BENCHMARK(BM_LibccdGjkIntersectHull32);

void BM_LibccdGjkIntersectPoints32(benchmark::State& state) {
  const HullPairs pairs = makeHullPairs();
  const ccd_t ccd = makeCcd();
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t k = visit(i++);
    benchmark::DoNotOptimize(ccdGJKIntersect(&pairs.pointsA[k], &pairs.pointsB[k], &ccd));
  }
}
BENCHMARK(BM_LibccdGjkIntersectPoints32);

#if defined(COLLIDE_HAVE_FCL)
// libccd's GJK as a distance query: FCL's extension of it (fcl::detail::GJKDistance: libccd's
// intersection GJK, then its distance iterations from that simplex), with FCL's default tolerance
// (1e-6) and the same support function.
template <bool kPoints>
void runLibccdDistance(benchmark::State& state) {
  const HullPairs pairs = makeHullPairs();
  std::size_t i = 0;
  double sum = 0.0;
  for (auto _ : state) {
    const std::size_t k = visit(i++);
    detail::ConvexSupport a = kPoints ? pairs.pointsA[k] : pairs.a[k];
    detail::ConvexSupport b = kPoints ? pairs.pointsB[k] : pairs.b[k];
    double distance = 0.0;
    fcl::Vector3d p1, p2;
    benchmark::DoNotOptimize(
        fcl::detail::GJKDistance<double>(&a, ccdSupport, &b, ccdSupport, 1000, 1e-6, &distance, &p1, &p2));
    sum += distance;
  }
  state.counters["mean_distance"] = benchmark::Counter(sum / double(std::max<std::size_t>(i, 1)));
}
void BM_LibccdGjkDistanceHull32(benchmark::State& s) { runLibccdDistance<false>(s); }
void BM_LibccdGjkDistancePoints32(benchmark::State& s) { runLibccdDistance<true>(s); }
BENCHMARK(BM_LibccdGjkDistanceHull32);
BENCHMARK(BM_LibccdGjkDistancePoints32);
#endif
#endif

}  // namespace
