// The library used directly: a world, a ground, a few bodies dropped on it, their positions printed
// every half second. Build it against the installed package (examples/CMakeLists.txt).
#include <collide/collide.h>

#include <cstdio>
#include <vector>

int main() {
  using namespace collide;
  World world;  // gravity (0, -9.81, 0), 6 substeps, a dynamic-tree broad phase

  BodyDef ground;
  ground.type = BodyType::Static;
  ground.shape = Box{Vec3(10.0f, 0.5f, 10.0f)};  // top face at y = 0
  ground.position = Vec3(0.0f, -0.5f, 0.0f);
  ground.name = "ground";
  world.createBody(ground);

  std::vector<BodyId> bodies;
  const Shape shapes[] = {Sphere{0.5f}, Box{Vec3(0.4f)}, Capsule{0.3f, 0.4f}};
  const char* names[] = {"ball", "crate", "pill"};
  for (int i = 0; i < 3; ++i) {
    BodyDef def;  // dynamic, density 1000, friction 0.5
    def.shape = shapes[i];
    def.position = Vec3(1.5f * float(i - 1), 2.0f + float(i), 0.0f);
    def.name = names[i];
    bodies.push_back(world.createBody(def));
  }

  for (int step = 1; step <= 120; ++step) {
    world.step(1.0f / 60.0f);
    if (step % 30 != 0) continue;
    std::printf("t = %.2f s:", step / 60.0);
    for (BodyId id : bodies) {
      const Vec3 p = world.transform(id).position;
      std::printf("  %s (%.2f, %.2f, %.2f)", world.name(id).c_str(), p.x, p.y, p.z);
    }
    std::printf("\n");
  }
  // After two seconds everything rests on the ground: the ball's centre is one radius up.
  const float ballHeight = world.transform(bodies[0]).position.y;
  return ballHeight > 0.45f && ballHeight < 0.55f ? 0 : 1;
}
