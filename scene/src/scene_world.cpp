// Scene -> World. The World validates again (it is the API boundary for code too); here its
// messages get the scene field in front, and what the World does not do yet is refused by name.
#include <collide/scene/scene.h>

namespace collide::scene {

SceneWorld buildWorld(const Scene& scene) {
  std::optional<World> world;
  try {
    world.emplace(scene.world);
  } catch (const Error& e) {
    const std::string field = scene.world.sleeping ? "settings.sleeping" : "settings";
    throw Error(scene.source + ": " + field + ": " + e.what());
  }
  if (!scene.constraints.empty()) {
    // Parsed and validated (names, anchors, length, compliance); the World has no joints yet.
    throw Error(scene.source + ": constraints[0]: distance constraints are not supported yet by the World");
  }
  SceneWorld out{std::move(*world), {}};
  out.bodies.reserve(scene.bodies.size());
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    try {
      out.bodies.push_back(out.world.createBody(scene.bodies[i].def));
    } catch (const Error& e) {
      throw Error(scene.source + ": bodies[" + std::to_string(i) + "]: " + e.what());
    }
  }
  return out;
}

}  // namespace collide::scene
