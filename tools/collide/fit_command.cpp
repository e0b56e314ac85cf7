// `collide fit MESH.obj` (lecture, slide 52, "choosing geometric proxies"): every bounding volume
// fitted to the mesh's points, with how tight it is (volume over the convex hull's), the memory it
// takes and what one test costs: a point-containment test and a ray cast, each timed over random
// queries around the mesh.
//
// Huge inputs: a mesh wider than kMaxFitExtent is refused, naming its size, before anything is
// fitted; the points are fitted about the centre of their box, so that a mesh far from the origin is
// fitted with the precision its coordinates have rather than failing inside a fitter; the cost of a
// test is measured on up to 4096 queries, fewer when a pass would take longer than kPassBudget (a
// million-vertex hull takes milliseconds a ray), so the timing takes well under a second whatever
// the mesh. Stages that take long on a large mesh say so on stderr.
#include "commands.h"

#include <collide/bounding.h>
#include <collide/scene/obj_file.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>

using namespace collide;

namespace {

using Clock = std::chrono::steady_clock;

constexpr std::size_t kQueries = 4096;
constexpr double kPassBudget = 0.02;             // s: one pass of one measure
constexpr std::size_t kLargeVertices = 100'000;  // progress on stderr from here
constexpr std::uintmax_t kLargeFileBytes = 8u << 20;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Nanoseconds per call of `test`, best of three passes (the machine is shared). The first pass runs
// the queries in doubling blocks until they are all done or the pass has taken kPassBudget; the
// other two run as many. `used` is how many queries each pass ran.
template <class Query, class Test>
double nanosecondsPerTest(const std::vector<Query>& queries, Test&& test, int& sink, std::size_t& used) {
  used = 0;
  const auto start = Clock::now();
  for (std::size_t block = 1; used < queries.size(); block *= 2) {
    const std::size_t end = std::min(queries.size(), used + block);
    for (; used < end; ++used) sink += test(queries[used]) ? 1 : 0;
    if (secondsSince(start) >= kPassBudget) break;
  }
  double best = 1e9 * secondsSince(start) / double(used);
  for (int pass = 1; pass < 3; ++pass) {
    const auto passStart = Clock::now();
    for (std::size_t i = 0; i < used; ++i) sink += test(queries[i]) ? 1 : 0;
    best = std::min(best, 1e9 * secondsSince(passStart) / double(used));
  }
  return best;
}

// Refuses a mesh wider than the fitters take, naming the file and the size (a 1e38 m mesh would
// overflow every volume, and the rays around it).
void requireFittableSize(const std::string& meshPath, const Aabb& box) {
  const Vec3 extent = box.max - box.min;
  const float widest = std::max({extent.x, extent.y, extent.z});
  if (!(widest <= kMaxFitExtent)) {
    char message[256];
    std::snprintf(message, sizeof message,
                  "%s: the mesh spans %.3g m along an axis; collide fit takes meshes up to %.3g m across, "
                  "whose proxies' volumes stay finite in float",
                  meshPath.c_str(), double(widest), double(kMaxFitExtent));
    throw Error(message);
  }
}

}  // namespace

int fitCommand(const std::string& meshPath) {
  std::error_code sizeError;
  const std::uintmax_t fileBytes = std::filesystem::file_size(meshPath, sizeError);
  const bool largeFile = !sizeError && fileBytes > kLargeFileBytes;
  auto start = Clock::now();
  if (largeFile)
    std::fprintf(stderr, "collide fit: reading %s (%.0f MB)...\n", meshPath.c_str(), fileBytes / 1e6);
  const scene::ObjMesh mesh = scene::readObjFile(meshPath);
  const bool large = mesh.vertices.size() >= kLargeVertices;
  if (largeFile) std::fprintf(stderr, "collide fit: read in %.1f s\n", secondsSince(start));

  const Aabb box = boundingBox(mesh.vertices);
  requireFittableSize(meshPath, box);
  // Fitted about the box's centre: tightness, memory and costs do not depend on where the mesh is,
  // and coordinates near the origin keep the fitters' arithmetic (and Qhull's merge tolerance) at
  // the precision of the mesh's size rather than of its distance from the origin.
  const Vec3 centre = 0.5f * box.min + 0.5f * box.max,
             half = 0.5f * (box.max - box.min);  // no overflow at 3e38
  std::vector<Vec3> points(mesh.vertices.size());
  std::transform(mesh.vertices.begin(), mesh.vertices.end(), points.begin(),
                 [&](const Vec3& v) { return v - centre; });

  start = Clock::now();
  if (large) {
    std::fprintf(stderr,
                 "collide fit: fitting 9 proxies to %zu points (the convex hull takes most of it)...\n",
                 points.size());
  }
  std::vector<ProxyFit> fits;
  try {
    fits = fitAllProxies(points);
  } catch (const Error& e) {
    // Far from the origin, float coordinates are far apart: a small mesh there may have lost its
    // shape when it was read, which is what the fitter found.
    const float far = std::max({std::abs(box.min.x), std::abs(box.min.y), std::abs(box.min.z),
                                std::abs(box.max.x), std::abs(box.max.y), std::abs(box.max.z)});
    const float spacing = std::nextafter(far, INFINITY) - far;
    std::string context;
    if (spacing > 1e-3f * 2.0f * std::max({half.x, half.y, half.z})) {
      char text[256];
      std::snprintf(
          text, sizeof text,
          " (the mesh is %.3g m across at %.3g m from the origin, where float coordinates are %.3g m "
          "apart: move it towards the origin)",
          2.0 * std::max({half.x, half.y, half.z}), double(far), double(spacing));
      context = text;
    }
    throw Error(meshPath + ": " + e.what() + context);
  }
  if (large) std::fprintf(stderr, "collide fit: fitted in %.1f s\n", secondsSince(start));
  const float reach = 2.0f * glm::length(half) + 1e-3f;

  // Points in the box grown by a quarter on each side; rays from a sphere around it towards
  // random points inside the box.
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::vector<Vec3> queryPoints(kQueries);
  for (Vec3& p : queryPoints) p = 1.25f * half * Vec3(unit(rng), unit(rng), unit(rng));
  std::vector<Ray> rays(kQueries);
  for (Ray& r : rays) {
    Vec3 direction(unit(rng), unit(rng), unit(rng));
    if (glm::length(direction) < 1e-3f) direction = Vec3(1, 0, 0);
    const Vec3 origin = reach * glm::normalize(direction);
    const Vec3 target = half * Vec3(unit(rng), unit(rng), unit(rng));
    r = Ray{origin, glm::normalize(target - origin), 2.0f * reach};
  }

  std::printf("%s: %zu vertices, %zu triangles\n", meshPath.c_str(), mesh.vertices.size(),
              mesh.triangles.size());
  std::printf("box: centre (%.6g, %.6g, %.6g), size %.6g x %.6g x %.6g; proxies fitted about its centre\n\n",
              double(centre.x), double(centre.y), double(centre.z), double(2.0f * half.x),
              double(2.0f * half.y), double(2.0f * half.z));
  std::printf("%-12s %12s %10s %10s %12s %10s\n", "proxy", "volume", "tightness", "bytes", "point ns",
              "ray ns");
  start = Clock::now();
  if (large) std::fprintf(stderr, "collide fit: timing point tests and ray casts...\n");
  int sink = 0;
  std::string sampled;  // the measures that ran fewer queries than kQueries
  for (const ProxyFit& fit : fits) {
    std::size_t pointQueries = 0, rayQueries = 0;
    const double pointNs = nanosecondsPerTest(
        queryPoints, [&](const Vec3& p) { return containsPoint(fit.shape, fit.transform, p); }, sink,
        pointQueries);
    const double rayNs = nanosecondsPerTest(
        rays, [&](const Ray& r) { return rayCast(fit.shape, fit.transform, r).has_value(); }, sink,
        rayQueries);
    std::printf("%-12s %12.5g %10.3f %10zu %12.1f %10.1f\n", fit.name.c_str(), fit.volume, fit.tightness,
                fit.bytes, pointNs, rayNs);
    if (pointQueries < kQueries || rayQueries < kQueries) {
      sampled += (sampled.empty() ? "" : ", ") + fit.name + " " + std::to_string(pointQueries) +
                 " points and " + std::to_string(rayQueries) + " rays";
    }
  }
  if (large) std::fprintf(stderr, "collide fit: timed in %.1f s\n", secondsSince(start));
  std::printf(
      "\ntightness: volume / convex hull volume (1 is the hull itself). Costs: best of 3 passes over\n"
      "%zu random queries; %d of them hit (printed so the loops are not optimised away).\n",
      kQueries, sink);
  if (!sampled.empty()) {
    std::printf("Fewer queries where a pass would take more than %.0f ms: %s.\n", kPassBudget * 1e3,
                sampled.c_str());
  }
  return 0;
}
