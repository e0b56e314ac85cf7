// Scene -> World. The World validates again (it is the API boundary for code too); here its
// messages get the scene field in front ("constraints[2]: distance constraint: ...").
#include <collide/scene/scene.h>

#include <map>

namespace collide::scene {

SceneWorld buildWorld(const Scene& scene) {
  std::optional<World> world;
  try {
    world.emplace(scene.world);
  } catch (const Error& e) {
    throw Error(scene.source + ": settings: " + e.what());
  }
  SceneWorld out{std::move(*world), {}, {}};
  out.bodies.reserve(scene.bodies.size());
  std::map<std::string, BodyId, std::less<>> byName;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    try {
      out.bodies.push_back(out.world.createBody(scene.bodies[i].def));
    } catch (const Error& e) {
      throw Error(scene.source + ": bodies[" + std::to_string(i) + "]: " + e.what());
    }
    byName.emplace(scene.bodies[i].def.name, out.bodies.back());
  }
  // After every body: a constraint's default length is the anchors' distance at load time.
  out.constraints.reserve(scene.constraints.size());
  for (std::size_t i = 0; i < scene.constraints.size(); ++i) {
    const Constraint& c = scene.constraints[i];
    const std::string field = "constraints[" + std::to_string(i) + "]";
    const auto body = [&](const std::string& name, const char* key) {
      const auto it = byName.find(name);
      if (it == byName.end())  // the parser checks names; a Scene built in code may not have
        throw Error(scene.source + ": " + field + "." + key + ": unknown body \"" + name + "\"");
      return it->second;
    };
    if (c.type == JointType::Ball) {
      try {
        out.constraints.push_back(
            out.world.createBallJoint({body(c.a, "a"), body(c.b, "b"), c.anchor, c.collideConnected}));
      } catch (const Error& e) {
        throw Error(scene.source + ": " + field + ": " + e.what());
      }
      continue;
    }
    DistanceConstraintDef def;
    def.a = body(c.a, "a");
    def.b = body(c.b, "b");
    def.localAnchorA = c.anchorA;
    def.localAnchorB = c.anchorB;
    def.length = c.length;
    def.compliance = c.compliance;
    def.collideConnected = c.collideConnected;
    try {
      out.constraints.push_back(out.world.createDistanceConstraint(def));
    } catch (const Error& e) {
      throw Error(scene.source + ": " + field + ": " + e.what());
    }
  }
  return out;
}

}  // namespace collide::scene
