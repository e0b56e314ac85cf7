// The viewer's drawing: shaded meshes, instanced (one draw call per distinct shape, with a model
// matrix and a colour per body), and coloured lines for debug drawing. One directional light.
#pragma once

#include "gl.h"
#include "shape_meshes.h"

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include <vector>

namespace collide::viewer {

struct Instance {
  glm::mat4 model;
  // rgb; alpha 0 asks for a checkerboard in world space (the ground plane), 1 for a plain colour.
  glm::vec4 colour;
};

struct LineVertex {
  Vec3 position;
  Vec3 colour;
};

class Renderer {
 public:
  Renderer();  // needs a current OpenGL 3.3 core context; throws Error if a shader fails
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Uploads a mesh once; the id indexes draw()'s per-mesh instance lists.
  int addMesh(const DrawMesh& mesh);
  void clearMeshes();
  int meshCount() const { return static_cast<int>(meshes_.size()); }

  // instances[i] are the placements of mesh i this frame.
  void drawMeshes(const std::vector<std::vector<Instance>>& instances, const glm::mat4& viewProjection,
                  const Vec3& lightDirection);
  void drawLines(const std::vector<LineVertex>& lines, const glm::mat4& viewProjection);

 private:
  struct GpuMesh {
    GLuint vao = 0;
    GLuint vertexBuffer = 0;
    GLuint instanceBuffer = 0;
    GLsizei vertexCount = 0;
  };
  GLuint meshProgram_ = 0;
  GLuint lineProgram_ = 0;
  GLuint lineVao_ = 0;
  GLuint lineBuffer_ = 0;
  std::vector<GpuMesh> meshes_;
};

}  // namespace collide::viewer
