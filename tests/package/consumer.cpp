// Built against the installed collide package by the package_consumer test, and as a subproject by
// the subproject tests (add_subdirectory: a game compiled with -fno-exceptions -fno-rtti, collide
// with COLLIDE_EXCEPTIONS=OFF).
#include <collide/collide.h>

#include <cmath>
#include <cstdio>
#include <cstring>

namespace {
int gErrors = 0;
}  // namespace

int main() {
  using namespace collide;
  const Shape hull = ConvexHull::fromPoints(std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}});
  const float volume = massProperties(hull, 1.0f).volume;  // a corner tetrahedron: 1/6
  std::printf("tetrahedron volume %.6f\n", volume);
  if (std::abs(volume - 1.0f / 6.0f) >= 1e-5f) return 1;
  if (exceptionsEnabled()) return 0;
  // Without exceptions bad input reaches the game's handler, and the call's result says so.
  setErrorHandler([](const char* message, void*) {
    ++gErrors;
    std::printf("handler: %s\n", message);
  });
  World world;
  BodyDef def;
  def.linearDamping = -1.0f;
  const BodyId refused = world.createBody(def);
  const bool reported = gErrors == 1 && refused.isNull() && world.bodyCount() == 0 &&
                        std::strstr(lastError(), "linearDamping") != nullptr;
  return reported ? 0 : 2;
}
