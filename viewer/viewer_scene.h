// The scene the viewer shows: the scene library's World plus what drawing it needs (the meshes of
// its shapes, generated once, and a colour per body). Rebuilt from the Scene on restart.
#pragma once

#include "interaction.h"
#include "renderer.h"

#include <collide/character.h>
#include <collide/scene/recording.h>
#include <collide/scene/scene.h>

#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

namespace collide::viewer {

// What the viewer's debug lines show: the library's debug drawing (World::draw) of contacts, boxes,
// joints and the broad phase, and the broad phase's pairs.
struct DebugLines {
  bool contacts = false;  // touching contacts: points, normals and impulses (World::draw)
  bool aabbs = false;     // each body's world box
  // The broad phase's own boxes (BroadPhase::visitNodes): the tree's nodes from firstDepth to
  // lastDepth, coloured by depth, or the grid's occupied cells.
  bool broadPhaseNodes = false;
  bool staticTree = false;  // the static bodies' tree too (the ground's box is huge)
  int firstDepth = 0;
  int lastDepth = 64;
  bool pairs = false;  // the pairs the broad phase kept in the last step
  bool joints = true;  // each joint's anchors, axes and limits (World::draw)
};

class ViewerScene {
 public:
  // Takes the World built from the scene (scene::buildWorld) and uploads the meshes.
  ViewerScene(scene::Scene scene, scene::SceneWorld built, Renderer& renderer);

  const scene::Scene& scene() const { return scene_; }
  World& world() { return built_->world; }
  const World& world() const { return built_->world; }

  // One step of the scene's dt; returns the wall time it took in milliseconds.
  double step();
  // New world settings and time step, from the next step on (World::setDef). Throws Error for
  // settings the World refuses, and then changes nothing.
  void applySettings(const WorldDef& def, float dt);
  int stepCount() const { return steps_; }

  // The scene's characters (docs/character.md): each step walks them along their paths, or walks the
  // first at `drive` when the player drives it (WASD).
  const std::vector<Character>& characters() const { return characters_; }
  static constexpr glm::vec4 kCharacterColour{0.96f, 0.94f, 0.86f, 1.0f};  // off-white: no body has it
  bool charactersShown() const { return showCharacters_; }
  void drive(std::optional<Vec3> velocity) { drive_ = velocity; }
  bool driving() const { return drive_.has_value(); }

  // Replay (collide-viewer --replay): puts every recorded body where the frame has it (matched by
  // name; World::setTransform, nothing stepped) and hides the bodies the frame lacks (broken before
  // it). Returns how many of the frame's bodies the scene does not have (another scene's recording).
  std::size_t showRecordedFrame(const scene::RecordedFrame& frame);

  // Shoots a sphere along the ray and draws it from now on. The oldest shot is removed once there
  // are kMaxShots, so that shooting for a while does not slow the world down without end.
  static constexpr std::size_t kMaxShots = 64;
  BodyId shoot(const Ray& ray, const SphereShot& shot);
  std::size_t shotCount() const { return shots_.size(); }

  // A box around the moving bodies (every body but planes if none moves; around the origin when
  // that leaves nothing).
  Aabb bounds() const;

  struct DrawnBody {
    struct Part {
      int mesh = 0;
      glm::mat4 local{1.0f};  // the compound child's transform, identity for a simple shape
    };
    BodyId id;
    std::vector<Part> parts;
    glm::vec4 colour{1.0f};  // rgb; alpha 0 for a checkerboard (static bodies and planes)
    // Replay: hidden when not in the frame shown; otherwise drawn where the frame has it (exactly:
    // the world's pose, kept from the centre of mass, could differ in the last bit) and dimmed as
    // the frame says it slept.
    bool hidden = false;
    std::optional<Transform> replayPose;
    std::optional<bool> replayAwake;
  };
  // The bodies drawn, in scene order and then the shots; some may have been destroyed since.
  const std::vector<DrawnBody>& drawnBodies() const { return bodies_; }
  // The colour the body is drawn with this frame (darker while asleep).
  glm::vec4 drawnColour(const DrawnBody& body) const;

  // This frame's placements, one list per renderer mesh.
  std::vector<std::vector<Instance>> instances(int meshCount) const;
  std::vector<LineVertex> debugLines(const DebugLines& options) const;
  // The deepest node of the broad phase's structure (0 when it has none), for the depth sliders.
  int broadPhaseDepth() const;

 private:
  void addBody(BodyId id, const glm::vec4& colour);
  void addParts(const Shape& shape, const glm::mat4& local, std::vector<DrawnBody::Part>& parts);
  void addPairLines(std::vector<LineVertex>& lines) const;

  scene::Scene scene_;
  Renderer& renderer_;
  std::vector<Character> characters_;
  std::vector<scene::CharacterPath> paths_;
  std::vector<DrawnBody::Part> characterParts_;  // one capsule mesh per character
  std::optional<Vec3> drive_;
  bool showCharacters_ = true;  // not in a replay, which has no record of them
  std::unique_ptr<scene::SceneWorld> built_;
  std::vector<DrawnBody> bodies_;
  std::deque<BodyId> shots_;
  // Meshes shared by shapes with equal parameters (primitives) or the same polyhedron (pointer).
  std::unordered_map<std::string, int> meshKeys_;
  int steps_ = 0;
  float typicalRadius_ = 0.5f;   // of the scene's bodies: sizes the contact marks
  float typicalImpulse_ = 1.0f;  // N s, a typical body's share of its weight on a point over a step
};

}  // namespace collide::viewer
