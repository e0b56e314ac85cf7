// `collide fit MESH.obj` (lecture, slide 52, "choosing geometric proxies"): every bounding volume
// fitted to the mesh's points, with how tight it is (volume over the convex hull's), the memory it
// takes and what one test costs: a point-containment test and a ray cast, each timed over a short
// loop of random queries around the mesh.
#include "commands.h"

#include <collide/bounding.h>
#include <collide/scene/obj_file.h>

#include <chrono>
#include <cstdio>
#include <random>

using namespace collide;

namespace {

// Nanoseconds per call of `test` over the queries, best of three passes (the machine is shared).
template <class Query, class Test>
double nanosecondsPerTest(const std::vector<Query>& queries, Test&& test, int& sink) {
  double best = 1e300;
  for (int pass = 0; pass < 3; ++pass) {
    const auto start = std::chrono::steady_clock::now();
    for (const Query& q : queries) sink += test(q) ? 1 : 0;
    const double ns =
        std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start).count();
    best = std::min(best, ns / double(queries.size()));
  }
  return best;
}

}  // namespace

int fitCommand(const std::string& meshPath) {
  const scene::ObjMesh mesh = scene::readObjFile(meshPath);
  const std::vector<ProxyFit> fits = fitAllProxies(mesh.vertices);
  const Aabb box = boundingBox(mesh.vertices);
  const Vec3 centre = 0.5f * (box.min + box.max), half = 0.5f * (box.max - box.min);
  const float reach = 2.0f * glm::length(half) + 1e-3f;

  // Points in the box grown by a quarter on each side; rays from a sphere around it towards
  // random points inside the box.
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::vector<Vec3> points(4096);
  for (Vec3& p : points) p = centre + 1.25f * half * Vec3(unit(rng), unit(rng), unit(rng));
  std::vector<Ray> rays(4096);
  for (Ray& r : rays) {
    Vec3 direction(unit(rng), unit(rng), unit(rng));
    if (glm::length(direction) < 1e-3f) direction = Vec3(1, 0, 0);
    const Vec3 origin = centre + reach * glm::normalize(direction);
    const Vec3 target = centre + half * Vec3(unit(rng), unit(rng), unit(rng));
    r = Ray{origin, glm::normalize(target - origin), 2.0f * reach};
  }

  std::printf("%s: %zu vertices, %zu triangles\n\n", meshPath.c_str(), mesh.vertices.size(),
              mesh.triangles.size());
  std::printf("%-12s %12s %10s %10s %12s %10s\n", "proxy", "volume", "tightness", "bytes", "point ns",
              "ray ns");
  int sink = 0;
  for (const ProxyFit& fit : fits) {
    const double pointNs = nanosecondsPerTest(
        points, [&](const Vec3& p) { return containsPoint(fit.shape, fit.transform, p); }, sink);
    const double rayNs = nanosecondsPerTest(
        rays, [&](const Ray& r) { return rayCast(fit.shape, fit.transform, r).has_value(); }, sink);
    std::printf("%-12s %12.5g %10.3f %10zu %12.1f %10.1f\n", fit.name.c_str(), fit.volume, fit.tightness,
                fit.bytes, pointNs, rayNs);
  }
  std::printf(
      "\ntightness: volume / convex hull volume (1 is the hull itself). Costs: best of 3 passes over\n"
      "4096 random queries; %d of them hit (printed so the loops are not optimised away).\n",
      sink);
  return 0;
}
