// Scene -> World. The World validates again (it is the API boundary for code too); here its
// messages get the scene field in front ("constraints[2]: distance constraint: ...").
#include <collide/scene/scene.h>

#include <cstddef>
#include <map>
#include <string>

namespace collide::scene {

namespace {

JointId createJoint(World& world, const Constraint& c, BodyId a, BodyId b) {
  const Vec3 anchor = c.anchor.value_or(Vec3(0.0f));
  switch (c.type) {
    case JointType::Distance: {
      DistanceConstraintDef def{.a = a, .b = b};
      def.localAnchorA = c.anchorA;
      def.localAnchorB = c.anchorB;
      def.length = c.length;
      def.compliance = c.compliance;
      if (c.softness.hertz > 0.0f) def.spring = {true, c.softness.hertz, c.softness.dampingRatio, 0.0f};
      def.limits = c.limits;
      def.collideConnected = c.collideConnected;
      def.breakForce = c.breakForce;
      return world.createDistanceConstraint(def);
    }
    case JointType::Ball: {
      BallJointDef def{.a = a, .b = b, .anchor = anchor, .collideConnected = c.collideConnected};
      def.softness = c.softness;
      def.breakForce = c.breakForce;
      def.frictionTorque = c.friction;
      return world.createBallJoint(def);
    }
    case JointType::Hinge: {
      HingeJointDef def{.a = a, .b = b, .anchor = anchor, .axis = c.axis};
      def.limits = c.limits;
      def.motor = c.motor;
      def.collideConnected = c.collideConnected;
      def.softness = c.softness;
      def.breakForce = c.breakForce;
      def.breakTorque = c.breakTorque;
      def.frictionTorque = c.friction;
      return world.createHingeJoint(def);
    }
    case JointType::Slider: {
      SliderJointDef def{.a = a, .b = b, .anchor = anchor, .axis = c.axis};
      def.limits = c.limits;
      def.motor = c.motor;
      def.collideConnected = c.collideConnected;
      def.softness = c.softness;
      def.breakForce = c.breakForce;
      def.breakTorque = c.breakTorque;
      def.frictionForce = c.friction;
      return world.createSliderJoint(def);
    }
    case JointType::Fixed: {
      FixedJointDef def{.a = a, .b = b, .anchor = c.anchor, .collideConnected = c.collideConnected};
      def.linearSoftness = c.softness;
      def.angularSoftness = c.softness;
      def.breakForce = c.breakForce;
      def.breakTorque = c.breakTorque;
      return world.createFixedJoint(def);
    }
    case JointType::Cone: {
      ConeJointDef def{.a = a, .b = b, .anchor = anchor, .axis = c.axis, .swingLimit = c.swing};
      def.twistLimits = c.limits;
      def.collideConnected = c.collideConnected;
      def.softness = c.softness;
      def.breakForce = c.breakForce;
      def.breakTorque = c.breakTorque;
      def.frictionTorque = c.friction;
      return world.createConeJoint(def);
    }
  }
  throw Error("unknown joint type");
}

}  // namespace

SceneWorld buildWorld(const Scene& scene) {
  std::optional<World> world;
  try {
    world.emplace(scene.world);
  } catch (const Error& e) {
    throw Error(scene.source + ": settings: " + e.what());
  }
  SceneWorld out{std::move(*world), {}, {}};
  out.world.reserveBodies(scene.bodies.size());  // bounded by the loader's kMaxBodies
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
    try {
      out.constraints.push_back(createJoint(out.world, c, body(c.a, "a"), body(c.b, "b")));
    } catch (const Error& e) {
      throw Error(scene.source + ": " + field + ": " + e.what());
    }
  }
  return out;
}

namespace {

template <typename T>
std::size_t vectorBytes(const std::vector<T>& v) {
  return v.capacity() * sizeof(T);
}
// A string's heap block: none while it fits in the string itself.
std::size_t stringBytes(const std::string& s) {
  return s.capacity() > std::string().capacity() ? s.capacity() + 1 : 0;
}

}  // namespace

std::size_t sceneMemoryBytes(const Scene& scene, const SceneWorld& world) {
  // A std::map node: the value and three links and a colour, rounded to pointers.
  constexpr std::size_t kMapNodeOverhead = 4 * sizeof(void*);
  std::size_t bytes = vectorBytes(scene.bodies) + vectorBytes(scene.constraints) +
                      vectorBytes(scene.objFiles) + vectorBytes(world.bodies) +
                      vectorBytes(world.constraints);
  for (const Body& body : scene.bodies)
    bytes += stringBytes(body.material) + stringBytes(body.def.name) + vectorBytes(body.def.parts);
  for (const Constraint& constraint : scene.constraints)
    bytes += stringBytes(constraint.name) + stringBytes(constraint.a) + stringBytes(constraint.b);
  for (const auto& [name, material] : scene.materials)
    bytes += sizeof(std::pair<const std::string, Material>) + kMapNodeOverhead + stringBytes(name);
  for (const std::filesystem::path& path : scene.objFiles) bytes += stringBytes(path.native());
  return bytes;
}

Vec3 CharacterPath::nextVelocity(const Character& character, float dt) {
  const Vec3 up = character.def().up;
  while (next_ < character_->path.size()) {
    const SceneCharacter::Waypoint& waypoint = character_->path[next_];
    Vec3 toward = waypoint.to - character.footPosition();
    toward -= glm::dot(toward, up) * up;
    const float distance = glm::length(toward);
    // Reached when within a step's walk (or 5 cm): on to the next.
    if (distance <= std::max(0.05f, waypoint.speed * dt)) {
      ++next_;
      jumped_ = false;
      continue;
    }
    Vec3 velocity = toward * (waypoint.speed / distance);
    if (waypoint.jump > 0.0f && !jumped_ && character.isOnGround()) {
      velocity += waypoint.jump * up;
      jumped_ = true;
    }
    return velocity;
  }
  return Vec3(0.0f);
}

}  // namespace collide::scene
