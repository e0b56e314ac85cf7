#include "renderer.h"

#include <collide/error.h>

#include <glm/gtc/type_ptr.hpp>

#include <cstddef>
#include <string>

namespace collide::viewer {
namespace {

constexpr const char* kMeshVertexShader = R"(#version 330 core
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in mat4 aModel;  // locations 2 to 5
layout(location = 6) in vec4 aColour;
uniform mat4 uViewProjection;
out vec3 vNormal;
out vec3 vWorld;
out vec4 vColour;
void main() {
  vec4 world = aModel * vec4(aPosition, 1.0);
  vWorld = world.xyz;
  // Rotation and uniform scale only, so the model matrix turns normals correctly once normalised.
  vNormal = mat3(aModel) * aNormal;
  vColour = aColour;
  gl_Position = uViewProjection * world;
}
)";

constexpr const char* kMeshFragmentShader = R"(#version 330 core
in vec3 vNormal;
in vec3 vWorld;
in vec4 vColour;
uniform vec3 uLightDirection;  // towards which the light travels
out vec4 fragColour;
void main() {
  vec3 n = normalize(vNormal);
  if (!gl_FrontFacing) n = -n;  // meshes are two-sided surfaces
  vec3 albedo = vColour.rgb;
  if (vColour.a < 0.5) {  // a 1 m checkerboard, so that the ground shows scale and motion
    vec3 cell = floor(vWorld + 1e-3);
    albedo *= mod(cell.x + cell.y + cell.z, 2.0) < 1.0 ? 1.0 : 0.85;
  }
  float diffuse = max(dot(n, -uLightDirection), 0.0);
  float sky = 0.5 + 0.5 * n.y;  // a little hemisphere light so that shadowed faces keep their shape
  fragColour = vec4(albedo * (0.18 + 0.22 * sky + 0.65 * diffuse), 1.0);
}
)";

constexpr const char* kLineVertexShader = R"(#version 330 core
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aColour;
uniform mat4 uViewProjection;
out vec3 vColour;
void main() {
  vColour = aColour;
  gl_Position = uViewProjection * vec4(aPosition, 1.0);
}
)";

constexpr const char* kLineFragmentShader = R"(#version 330 core
in vec3 vColour;
out vec4 fragColour;
void main() { fragColour = vec4(vColour, 1.0); }
)";

GLuint compileShader(GLenum stage, const char* source) {
  const GLuint shader = glCreateShader(stage);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    glGetShaderInfoLog(shader, sizeof(log), nullptr, log);
    glDeleteShader(shader);
    throw Error(std::string("viewer: shader does not compile: ") + log);
  }
  return shader;
}

GLuint linkProgram(const char* vertexSource, const char* fragmentSource) {
  const GLuint vertex = compileShader(GL_VERTEX_SHADER, vertexSource);
  const GLuint fragment = compileShader(GL_FRAGMENT_SHADER, fragmentSource);
  const GLuint program = glCreateProgram();
  glAttachShader(program, vertex);
  glAttachShader(program, fragment);
  glLinkProgram(program);
  glDeleteShader(vertex);
  glDeleteShader(fragment);
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    glGetProgramInfoLog(program, sizeof(log), nullptr, log);
    glDeleteProgram(program);
    throw Error(std::string("viewer: shader program does not link: ") + log);
  }
  return program;
}

}  // namespace

Renderer::Renderer() {
  meshProgram_ = linkProgram(kMeshVertexShader, kMeshFragmentShader);
  lineProgram_ = linkProgram(kLineVertexShader, kLineFragmentShader);
  glGenVertexArrays(1, &lineVao_);
  glGenBuffers(1, &lineBuffer_);
  glBindVertexArray(lineVao_);
  glBindBuffer(GL_ARRAY_BUFFER, lineBuffer_);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(LineVertex),
                        reinterpret_cast<void*>(offsetof(LineVertex, position)));
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(LineVertex),
                        reinterpret_cast<void*>(offsetof(LineVertex, colour)));
  glBindVertexArray(0);
}

Renderer::~Renderer() {
  clearMeshes();
  glDeleteBuffers(1, &lineBuffer_);
  glDeleteVertexArrays(1, &lineVao_);
  glDeleteProgram(lineProgram_);
  glDeleteProgram(meshProgram_);
}

int Renderer::addMesh(const DrawMesh& mesh) {
  GpuMesh gpu;
  gpu.vertexCount = static_cast<GLsizei>(mesh.vertices.size());
  glGenVertexArrays(1, &gpu.vao);
  glGenBuffers(1, &gpu.vertexBuffer);
  glGenBuffers(1, &gpu.instanceBuffer);
  glBindVertexArray(gpu.vao);
  glBindBuffer(GL_ARRAY_BUFFER, gpu.vertexBuffer);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(mesh.vertices.size() * sizeof(MeshVertex)),
               mesh.vertices.data(), GL_STATIC_DRAW);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(MeshVertex),
                        reinterpret_cast<void*>(offsetof(MeshVertex, position)));
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(MeshVertex),
                        reinterpret_cast<void*>(offsetof(MeshVertex, normal)));
  // Per-instance attributes: the model matrix as four columns, then the colour.
  glBindBuffer(GL_ARRAY_BUFFER, gpu.instanceBuffer);
  for (int column = 0; column < 4; ++column) {
    glEnableVertexAttribArray(2 + column);
    glVertexAttribPointer(2 + column, 4, GL_FLOAT, GL_FALSE, sizeof(Instance),
                          reinterpret_cast<void*>(offsetof(Instance, model) + column * sizeof(glm::vec4)));
    glVertexAttribDivisor(2 + column, 1);
  }
  glEnableVertexAttribArray(6);
  glVertexAttribPointer(6, 4, GL_FLOAT, GL_FALSE, sizeof(Instance),
                        reinterpret_cast<void*>(offsetof(Instance, colour)));
  glVertexAttribDivisor(6, 1);
  glBindVertexArray(0);
  meshes_.push_back(gpu);
  return static_cast<int>(meshes_.size()) - 1;
}

void Renderer::clearMeshes() {
  for (GpuMesh& mesh : meshes_) {
    glDeleteBuffers(1, &mesh.vertexBuffer);
    glDeleteBuffers(1, &mesh.instanceBuffer);
    glDeleteVertexArrays(1, &mesh.vao);
  }
  meshes_.clear();
}

void Renderer::drawMeshes(const std::vector<std::vector<Instance>>& instances,
                          const glm::mat4& viewProjection, const Vec3& lightDirection) {
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);  // meshes and planes are seen from both sides
  glUseProgram(meshProgram_);
  glUniformMatrix4fv(glGetUniformLocation(meshProgram_, "uViewProjection"), 1, GL_FALSE,
                     glm::value_ptr(viewProjection));
  glUniform3fv(glGetUniformLocation(meshProgram_, "uLightDirection"), 1, glm::value_ptr(lightDirection));
  for (std::size_t i = 0; i < instances.size() && i < meshes_.size(); ++i) {
    if (instances[i].empty()) continue;
    const GpuMesh& mesh = meshes_[i];
    glBindBuffer(GL_ARRAY_BUFFER, mesh.instanceBuffer);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(instances[i].size() * sizeof(Instance)),
                 instances[i].data(), GL_STREAM_DRAW);
    glBindVertexArray(mesh.vao);
    glDrawArraysInstanced(GL_TRIANGLES, 0, mesh.vertexCount, static_cast<GLsizei>(instances[i].size()));
  }
  glBindVertexArray(0);
}

void Renderer::drawLines(const std::vector<LineVertex>& lines, const glm::mat4& viewProjection) {
  if (lines.empty()) return;
  // Debug lines show through the bodies: contacts sit inside the surfaces they join.
  glDisable(GL_DEPTH_TEST);
  glUseProgram(lineProgram_);
  glUniformMatrix4fv(glGetUniformLocation(lineProgram_, "uViewProjection"), 1, GL_FALSE,
                     glm::value_ptr(viewProjection));
  glBindVertexArray(lineVao_);
  glBindBuffer(GL_ARRAY_BUFFER, lineBuffer_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(lines.size() * sizeof(LineVertex)), lines.data(),
               GL_STREAM_DRAW);
  glDrawArrays(GL_LINES, 0, static_cast<GLsizei>(lines.size()));
  glBindVertexArray(0);
  glEnable(GL_DEPTH_TEST);
}

}  // namespace collide::viewer
