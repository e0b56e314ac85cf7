// The scene the viewer shows: the scene library's World plus what drawing it needs (the meshes of
// its shapes, generated once, and a colour per body). Rebuilt from the Scene on restart.
#pragma once

#include "renderer.h"

#include <collide/scene/scene.h>

#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

namespace collide::viewer {

struct DebugDraw {
  bool contacts = false;  // contact points and normals (from the pre-solve callback)
  bool aabbs = false;     // each body's world box
};

class ViewerScene {
 public:
  // Builds the World and uploads the meshes. Throws collide::Error for a scene the World refuses.
  ViewerScene(scene::Scene scene, Renderer& renderer);

  const scene::Scene& scene() const { return scene_; }
  World& world() { return built_->world; }
  const World& world() const { return built_->world; }

  // One step of the scene's dt; returns the wall time it took in milliseconds.
  double step();
  int stepCount() const { return steps_; }

  // A box around the moving bodies (every body but planes if none moves; around the origin when
  // that leaves nothing).
  Aabb bounds() const;

  // This frame's placements, one list per renderer mesh.
  std::vector<std::vector<Instance>> instances(int meshCount) const;
  std::vector<LineVertex> debugLines(const DebugDraw& options) const;

 private:
  struct Part {
    int mesh = 0;
    glm::mat4 local{1.0f};  // the compound child's transform, identity for a simple shape
  };
  struct DrawnBody {
    BodyId id;
    std::vector<Part> parts;
    glm::vec4 colour{1.0f};
  };
  struct Contact {
    Vec3 point;
    Vec3 normal;
  };

  void addParts(const Shape& shape, const glm::mat4& local, Renderer& renderer, std::vector<Part>& parts);

  scene::Scene scene_;
  std::unique_ptr<scene::SceneWorld> built_;
  std::vector<DrawnBody> bodies_;
  // Meshes shared by shapes with equal parameters (primitives) or the same polyhedron (pointer).
  std::unordered_map<std::string, int> meshKeys_;
  std::shared_ptr<std::vector<Contact>> contacts_ = std::make_shared<std::vector<Contact>>();
  int steps_ = 0;
};

}  // namespace collide::viewer
