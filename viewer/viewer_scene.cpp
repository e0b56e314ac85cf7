#include "viewer_scene.h"

#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string_view>

namespace collide::viewer {
namespace {

glm::mat4 toMatrix(const Transform& transform) {
  glm::mat4 m = glm::mat4_cast(transform.rotation);
  m[0] *= transform.scale;
  m[1] *= transform.scale;
  m[2] *= transform.scale;
  m[3] = glm::vec4(transform.position, 1.0f);
  return m;
}

// Primitives with equal parameters share a mesh; polyhedra and meshes are shared by pointer.
std::string meshKey(const Shape& shape) {
  char key[160];
  switch (shape.type()) {
    case ShapeType::Sphere:
      std::snprintf(key, sizeof(key), "sphere %a", shape.sphere().radius);
      break;
    case ShapeType::Capsule:
      std::snprintf(key, sizeof(key), "capsule %a %a", shape.capsule().radius, shape.capsule().halfHeight);
      break;
    case ShapeType::Cylinder:
      std::snprintf(key, sizeof(key), "cylinder %a %a", shape.cylinder().radius, shape.cylinder().halfHeight);
      break;
    case ShapeType::Box: {
      const Vec3 h = shape.box().halfExtents;
      std::snprintf(key, sizeof(key), "box %a %a %a", h.x, h.y, h.z);
      break;
    }
    case ShapeType::Ellipsoid: {
      const Vec3 r = shape.ellipsoid().radii;
      std::snprintf(key, sizeof(key), "ellipsoid %a %a %a", r.x, r.y, r.z);
      break;
    }
    case ShapeType::Plane: {
      const Plane& p = shape.plane();
      std::snprintf(key, sizeof(key), "plane %a %a %a %a", p.normal.x, p.normal.y, p.normal.z, p.distance);
      break;
    }
    case ShapeType::ConvexHull:
      std::snprintf(key, sizeof(key), "hull %p", static_cast<const void*>(&shape.convexHull()));
      break;
    case ShapeType::Kdop:
      std::snprintf(key, sizeof(key), "kdop %p", static_cast<const void*>(&shape.kdop()));
      break;
    case ShapeType::Mesh:
      std::snprintf(key, sizeof(key), "mesh %p", static_cast<const void*>(&shape.mesh()));
      break;
    case ShapeType::Compound:
      key[0] = '\0';
      break;
  }
  return key;
}

// A calm palette for dynamic bodies; static ones are grey, kinematic ones blue-grey.
glm::vec4 bodyColour(BodyType type, ShapeType shape, std::size_t index) {
  static constexpr float kPalette[][3] = {{0.90f, 0.55f, 0.30f}, {0.35f, 0.65f, 0.90f}, {0.55f, 0.80f, 0.40f},
                                          {0.90f, 0.80f, 0.35f}, {0.75f, 0.50f, 0.85f}, {0.90f, 0.45f, 0.50f},
                                          {0.40f, 0.80f, 0.75f}};
  if (shape == ShapeType::Plane) return {0.62f, 0.64f, 0.66f, 0.0f};  // checkerboard
  if (type == BodyType::Static) return {0.60f, 0.60f, 0.62f, 0.0f};   // checkerboard: ground shows scale
  if (type == BodyType::Kinematic) return {0.50f, 0.58f, 0.72f, 1.0f};
  // A multiplicative hash spreads neighbouring bodies (a pyramid's cubes) over the palette.
  const std::size_t pick = (index * 2654435761u >> 7) % std::size(kPalette);
  return {kPalette[pick][0], kPalette[pick][1], kPalette[pick][2], 1.0f};
}

}  // namespace

ViewerScene::ViewerScene(scene::Scene scene, scene::SceneWorld built, Renderer& renderer)
    : scene_(std::move(scene)),
      renderer_(renderer),
      built_(std::make_unique<scene::SceneWorld>(std::move(built))) {
  std::vector<float> radii, staticRadii, masses;
  for (std::size_t i = 0; i < built_->bodies.size(); ++i) {
    const BodyId id = built_->bodies[i];
    const Shape& shape = built_->world.shape(id);
    addBody(id, bodyColour(built_->world.type(id), shape.type(), i));
    if (built_->world.type(id) == BodyType::Dynamic) masses.push_back(built_->world.mass(id));
    if (shape.type() == ShapeType::Plane) continue;
    const Aabb box = worldBounds(shape, built_->world.transform(id));
    (built_->world.type(id) == BodyType::Static ? staticRadii : radii)
        .push_back(0.5f * glm::length(box.max - box.min));
  }
  for (const scene::SceneCharacter& character : scene_.characters) {
    characters_.emplace_back(character.def);
    paths_.emplace_back(character);
    std::vector<DrawnBody::Part> parts;
    addParts(Shape(Capsule{character.def.radius, character.def.halfHeight}), glm::mat4(1.0f), parts);
    characterParts_.push_back(parts.front());
  }
  // The median moving body's bounding radius (a static one's if nothing moves).
  std::vector<float>& sizes = radii.empty() ? staticRadii : radii;
  if (!sizes.empty()) {
    std::nth_element(sizes.begin(), sizes.begin() + sizes.size() / 2, sizes.end());
    typicalRadius_ = sizes[sizes.size() / 2];
  }
  // The median dynamic body's weight over a step, shared by four contact points: the impulse drawn
  // as long as the typical radius.
  if (!masses.empty()) {
    std::nth_element(masses.begin(), masses.begin() + masses.size() / 2, masses.end());
    typicalImpulse_ = 0.25f * masses[masses.size() / 2] * 9.81f * scene_.dt;
  }
}

void ViewerScene::addBody(BodyId id, const glm::vec4& colour) {
  DrawnBody body;
  body.id = id;
  addParts(built_->world.shape(id), glm::mat4(1.0f), body.parts);
  body.colour = colour;
  bodies_.push_back(std::move(body));
}

void ViewerScene::addParts(const Shape& shape, const glm::mat4& local, std::vector<DrawnBody::Part>& parts) {
  if (shape.type() == ShapeType::Compound) {
    for (const Compound::Child& child : shape.compound().children()) {
      addParts(child.shape, local * toMatrix(child.transform), parts);
    }
    return;
  }
  const std::string key = meshKey(shape);
  auto found = meshKeys_.find(key);
  if (found == meshKeys_.end()) found = meshKeys_.emplace(key, renderer_.addMesh(shapeMesh(shape))).first;
  parts.push_back({found->second, local});
}

BodyId ViewerScene::shoot(const Ray& ray, const SphereShot& shot) {
  if (shots_.size() >= kMaxShots) {
    const BodyId oldest = shots_.front();
    shots_.pop_front();
    if (world().isValid(oldest)) world().destroyBody(oldest);
    std::erase_if(bodies_, [&](const DrawnBody& body) { return body.id == oldest; });
  }
  const BodyId id = shootSphere(world(), ray, shot);
  shots_.push_back(id);
  addBody(id, {0.95f, 0.95f, 0.90f, 1.0f});  // off-white: no scene body has it
  return id;
}

double ViewerScene::step() {
  const auto start = std::chrono::steady_clock::now();
  built_->world.step(scene_.dt);
  for (std::size_t i = 0; i < characters_.size(); ++i) {
    const Vec3 walk = i == 0 && drive_ ? *drive_ : paths_[i].nextVelocity(characters_[i], scene_.dt);
    characters_[i].update(built_->world, walk, scene_.dt);
  }
  const auto stop = std::chrono::steady_clock::now();
  ++steps_;
  return std::chrono::duration<double, std::milli>(stop - start).count();
}

std::size_t ViewerScene::showRecordedFrame(const scene::RecordedFrame& frame) {
  std::unordered_map<std::string_view, DrawnBody*> byName;
  for (DrawnBody& body : bodies_) {
    body.hidden = true;
    if (world().isValid(body.id)) byName.emplace(world().name(body.id), &body);
  }
  std::size_t unknown = 0;
  for (const scene::RecordedBody& recorded : frame.bodies) {
    const auto found = byName.find(recorded.name);
    if (found == byName.end()) {
      ++unknown;
      continue;
    }
    DrawnBody& body = *found->second;
    body.hidden = false;
    World& w = world();
    w.setTransform(body.id, recorded.position, recorded.rotation, false);  // for the debug lines
    body.replayPose = Transform{recorded.position, recorded.rotation, w.transform(body.id).scale};
    body.replayAwake = recorded.awake;
  }
  steps_ = frame.step;
  showCharacters_ = false;
  return unknown;
}

void ViewerScene::applySettings(const WorldDef& def, float dt) {
  if (!(dt > 0.0f) || !std::isfinite(dt)) throw Error("viewer: the time step must be finite and > 0");
  built_->world.setDef(def);
  scene_.world = def;
  scene_.dt = dt;
}

Aabb ViewerScene::bounds() const {
  // The moving bodies are what the scene is about: frame them, unless there are none (a large
  // static ground would otherwise shrink them to a few pixels).
  bool anyMoving = false;
  for (const DrawnBody& body : bodies_) {
    anyMoving = anyMoving || (world().isValid(body.id) && world().type(body.id) != BodyType::Static);
  }
  Aabb box = Aabb::empty();
  for (const DrawnBody& body : bodies_) {
    if (!world().isValid(body.id)) continue;
    if (anyMoving && world().type(body.id) == BodyType::Static) continue;
    const Shape& shape = world().shape(body.id);
    if (shape.type() == ShapeType::Plane) continue;
    const Aabb b = worldBounds(shape, world().transform(body.id));
    box.min = glm::min(box.min, b.min);
    box.max = glm::max(box.max, b.max);
  }
  if (box.min.x > box.max.x) return {Vec3(-5.0f), Vec3(5.0f)};
  return box;
}

glm::vec4 ViewerScene::drawnColour(const DrawnBody& body) const {
  // Resting bodies are drawn darker, so that sleeping islands show.
  const bool awake = body.replayAwake.value_or(world().isAwake(body.id));
  const bool dimmed = world().type(body.id) == BodyType::Dynamic && !awake;
  return dimmed ? glm::vec4(glm::vec3(body.colour) * 0.6f, body.colour.a) : body.colour;
}

std::vector<std::vector<Instance>> ViewerScene::instances(int meshCount) const {
  std::vector<std::vector<Instance>> out(static_cast<std::size_t>(meshCount));
  for (const DrawnBody& body : bodies_) {
    if (!world().isValid(body.id) || body.hidden) continue;
    const glm::mat4 model = toMatrix(body.replayPose.value_or(world().transform(body.id)));
    const glm::vec4 colour = drawnColour(body);
    for (const DrawnBody::Part& part : body.parts) {
      if (part.mesh < meshCount)
        out[static_cast<std::size_t>(part.mesh)].push_back({model * part.local, colour});
    }
  }
  // The characters: upright capsules.
  for (std::size_t i = 0; showCharacters_ && i < characters_.size(); ++i) {
    const Character& character = characters_[i];
    const DrawnBody::Part& part = characterParts_[i];
    const Vec3 y(0.0f, 1.0f, 0.0f), up = character.def().up;
    const Quat stand = glm::dot(y, up) < -0.999999f
                           ? Quat(0.0f, 1.0f, 0.0f, 0.0f)
                           : glm::normalize(Quat(1.0f + glm::dot(y, up), glm::cross(y, up)));
    if (part.mesh < meshCount)
      out[static_cast<std::size_t>(part.mesh)].push_back(
          {toMatrix(Transform{character.position(), stand, 1.0f}) * part.local, kCharacterColour});
  }
  return out;
}

namespace {

// The library's debug drawing into the renderer's line list.
class LineRecorder : public collide::DebugDraw {
 public:
  explicit LineRecorder(std::vector<LineVertex>& lines) : lines_(lines) {}
  void drawLine(const Vec3& from, const Vec3& to, const DebugColor& color) override {
    lines_.push_back({from, color});
    lines_.push_back({to, color});
  }

 private:
  std::vector<LineVertex>& lines_;
};

}  // namespace

std::vector<LineVertex> ViewerScene::debugLines(const DebugLines& options) const {
  std::vector<LineVertex> lines;
  DebugDrawOptions draw;
  draw.shapes = false;  // the bodies are drawn shaded
  draw.bounds = options.aabbs;
  draw.broadPhase = options.broadPhaseNodes;
  draw.staticTree = options.staticTree;
  draw.firstDepth = options.firstDepth;
  draw.lastDepth = options.lastDepth;
  draw.contacts = options.contacts;
  draw.joints = options.joints;
  // Sized by the bodies: a 30 cm normal hides a billiard ball and vanishes next to a house.
  draw.normalLength = 0.6f * typicalRadius_;
  draw.impulseScale = typicalRadius_ / typicalImpulse_;
  LineRecorder recorder(lines);
  world().draw(recorder, draw);
  if (options.pairs) addPairLines(lines);
  return lines;
}

int ViewerScene::broadPhaseDepth() const {
  int deepest = 0;
  world().broadPhase().visitNodes(
      [&](const BroadPhaseNode& node) { deepest = std::max(deepest, node.depth); });
  return deepest;
}

void ViewerScene::addPairLines(std::vector<LineVertex>& lines) const {
  // A line joins the two bodies' centres; a static body's end is the point of its box nearest the
  // other body's centre instead, since a plane has no centre and a ground's is far below.
  const Vec3 colour(0.95f, 0.35f, 0.95f);
  for (const BodyPair& pair : world().broadPhasePairs()) {
    const Vec3 a = world().centerOfMass(pair.a), b = world().centerOfMass(pair.b);
    const auto end = [&](BodyId id, const Vec3& centre, const Vec3& other) {
      if (world().type(id) != BodyType::Static) return centre;
      const Aabb box = worldBounds(world().shape(id), world().transform(id));
      return glm::clamp(other, box.min, box.max);
    };
    lines.push_back({end(pair.a, a, b), colour});
    lines.push_back({end(pair.b, b, a), colour});
  }
}

}  // namespace collide::viewer
