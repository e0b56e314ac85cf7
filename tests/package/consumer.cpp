// Built against the installed collide package by the package_consumer test.
#include <collide/collide.h>

#include <cmath>
#include <cstdio>

int main() {
  using namespace collide;
  const Shape hull = ConvexHull::fromPoints(std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}});
  const float volume = massProperties(hull, 1.0f).volume;  // a corner tetrahedron: 1/6
  std::printf("tetrahedron volume %.6f\n", volume);
  return std::abs(volume - 1.0f / 6.0f) < 1e-5f ? 0 : 1;
}
