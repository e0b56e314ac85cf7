// Built against the installed collide package with its scene component (find_package(collide
// COMPONENTS scene)) by the package_consumer test: a built-in scene loaded and stepped.
#include <collide/scene/builtin_scenes.h>
#include <collide/scene/scene.h>

#include <cstdio>

int main() {
  using namespace collide;
  const scene::Scene billiards = scene::loadBuiltinScene("billiards");
  scene::SceneWorld loaded = scene::buildWorld(billiards);
  for (int i = 0; i < 10; ++i) loaded.world.step(1.0f / 60.0f);
  std::printf("billiards: %zu bodies stepped\n", loaded.bodies.size());
  return loaded.bodies.size() == 21 ? 0 : 1;  // 16 balls, the table and its four cushions
}
