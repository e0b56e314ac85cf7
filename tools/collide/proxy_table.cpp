// `collide` with no command: one proxy of every type, placed, and what each answers (mass
// properties, bounds, a ray cast and a point test), so a new user sees the library work end to end.
#include "commands.h"

#include <collide/collide.h>

#include <cstdio>
#include <exception>
#include <string>
#include <vector>

namespace {

using namespace collide;

std::vector<std::pair<std::string, Shape>> everyProxy() {
  std::vector<std::pair<std::string, Shape>> proxies;
  proxies.emplace_back("sphere r=0.5", Sphere{0.5f});
  proxies.emplace_back("capsule r=0.3 hh=0.5", Capsule{0.3f, 0.5f});
  proxies.emplace_back("plane y=0", Plane{Vec3(0, 1, 0), 0.0f});
  proxies.emplace_back("box 1x0.5x0.25", Box{Vec3(0.5f, 0.25f, 0.125f)});
  proxies.emplace_back("ellipsoid .6/.4/.3", Ellipsoid{Vec3(0.6f, 0.4f, 0.3f)});
  proxies.emplace_back("cylinder r=0.4 hh=0.5", Cylinder{0.4f, 0.5f});
  // An octahedron-ish gem: the hull of 6 axis points and a few others.
  const std::vector<Vec3> gem = {{0.5f, 0, 0}, {-0.5f, 0, 0}, {0, 0.7f, 0},       {0, -0.7f, 0},
                                 {0, 0, 0.5f}, {0, 0, -0.5f}, {0.3f, 0.3f, 0.3f}, {-0.3f, -0.3f, 0.3f}};
  proxies.emplace_back("convex hull (8 pts)", ConvexHull::fromPoints(gem));
  proxies.emplace_back("18-DOP of the same", Kdop::fromPoints(18, gem));
  // A closed unit cube as a triangle mesh.
  std::vector<Vec3> cube;
  for (int i = 0; i < 8; ++i)
    cube.emplace_back(i & 1 ? 0.5f : -0.5f, i & 2 ? 0.5f : -0.5f, i & 4 ? 0.5f : -0.5f);
  std::vector<MeshTriangle> faces = {{{0, 2, 1}}, {{1, 2, 3}}, {{4, 5, 6}}, {{5, 7, 6}},
                                     {{0, 1, 4}}, {{1, 5, 4}}, {{2, 6, 3}}, {{3, 6, 7}},
                                     {{0, 4, 2}}, {{2, 4, 6}}, {{1, 3, 5}}, {{3, 7, 5}}};
  proxies.emplace_back("mesh: closed cube", TriangleMesh::fromTriangles(cube, faces));
  std::vector<Compound::Child> dumbbell;
  dumbbell.push_back({Sphere{0.3f}, Transform{Vec3(-0.6f, 0, 0)}});
  dumbbell.push_back({Capsule{0.1f, 0.3f}, Transform{Vec3(0.0f), glm::angleAxis(kPi / 2, Vec3(0, 0, 1))}});
  dumbbell.push_back({Sphere{0.3f}, Transform{Vec3(0.6f, 0, 0)}});
  proxies.emplace_back("compound: dumbbell", Compound::fromChildren(std::move(dumbbell)));
  return proxies;
}

}  // namespace

int printProxyTable() {
  // Every proxy sits at (0, 1, 0), turned 30 degrees about z; a ray comes down the y axis.
  const Transform placement{Vec3(0, 1, 0), glm::angleAxis(kPi / 6, Vec3(0, 0, 1))};
  const Ray ray{Vec3(0.05f, 10.0f, 0.02f), Vec3(0, -1, 0), 100.0f};
  std::printf("collide %s: every geometric proxy, placed at (0,1,0) and turned 30 deg about z\n\n", kVersion);
  std::printf("%-24s %9s %9s %26s %22s %8s %9s %6s\n", "proxy", "volume", "mass kg", "inertia diag (kg m2)",
              "world AABB size", "bsphere", "ray hit y", "holds");
  for (const auto& [name, shape] : everyProxy()) {
    std::string volume = "inf", mass = "-", inertia = "-";
    if (shape.type() != ShapeType::Plane) {
      const MassProperties m = massProperties(shape, 1000.0f);
      volume = std::to_string(m.volume).substr(0, 7);
      mass = std::to_string(m.mass).substr(0, 7);
      char buffer[64];
      std::snprintf(buffer, sizeof buffer, "%.3f %.3f %.3f", m.inertia[0][0], m.inertia[1][1],
                    m.inertia[2][2]);
      inertia = buffer;
    }
    const Aabb box = worldBounds(shape, placement);
    char size[64];
    if (shape.type() == ShapeType::Plane)
      std::snprintf(size, sizeof size, "unbounded");
    else
      std::snprintf(size, sizeof size, "%.3f %.3f %.3f", box.max.x - box.min.x, box.max.y - box.min.y,
                    box.max.z - box.min.z);
    const BoundingSphere sphere = localBoundingSphere(shape);
    const auto hit = rayCast(shape, placement, ray);
    char hitText[32] = "miss";
    if (hit) std::snprintf(hitText, sizeof hitText, "%.4f", hit->point.y);
    const bool holdsCentre = containsPoint(shape, placement, placement.position);
    std::printf("%-24s %9s %9s %26s %22s %8.3f %9s %6s\n", name.c_str(), volume.c_str(), mass.c_str(),
                inertia.c_str(), size, shape.type() == ShapeType::Plane ? 0.0 : double(sphere.radius),
                hitText, holdsCentre ? "yes" : "no");
  }
  std::printf("\n'holds': the proxy contains its own placement point. Density 1000 kg/m3.\n");
  return 0;
}
