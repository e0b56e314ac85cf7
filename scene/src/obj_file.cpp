#include <collide/scene/limits.h>
#include <collide/scene/obj_file.h>

#include "file_text.h"

#include <string>

#include <tiny_obj_loader.h>

namespace collide::scene {

ObjMesh readObjFile(const std::filesystem::path& path) {
  const std::string who = "OBJ file " + path.string();
  return parseObj(readFileText(path, kMaxObjFileBytes, who), who);
}

ObjMesh parseObj(std::string_view text, std::string_view name) {
  const std::string who(name);
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromString(std::string(text), /*mtl_text=*/"", config)) {
    std::string why = reader.Error();
    while (!why.empty() && (why.back() == '\n' || why.back() == '\r')) why.pop_back();
    throw Error(who + ": " + (why.empty() ? "cannot be parsed" : why));
  }
  ObjMesh mesh;
  const auto& coordinates = reader.GetAttrib().vertices;
  for (std::size_t i = 0; i + 2 < coordinates.size(); i += 3) {
    mesh.vertices.emplace_back(coordinates[i], coordinates[i + 1], coordinates[i + 2]);
  }
  for (const auto& shape : reader.GetShapes()) {
    const auto& indices = shape.mesh.indices;
    for (std::size_t i = 0; i + 2 < indices.size(); i += 3) {
      MeshTriangle t;
      for (int k = 0; k < 3; ++k) {
        const int v = indices[i + k].vertex_index;
        if (v < 0 || static_cast<std::size_t>(v) >= mesh.vertices.size()) {
          throw Error(who + ": vertex index " + std::to_string(v) + " out of range (" +
                      std::to_string(mesh.vertices.size()) + " vertices)");
        }
        t.v[k] = static_cast<std::uint32_t>(v);
      }
      mesh.triangles.push_back(t);
    }
  }
  if (mesh.triangles.empty()) throw Error(who + ": no triangles");
  return mesh;
}

}  // namespace collide::scene
