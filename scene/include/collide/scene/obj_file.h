// Wavefront OBJ meshes (through tinyobjloader): the vertices and triangles of every shape in the
// file, polygons triangulated. Used by mesh shapes with "file" and by `collide fit`.
#pragma once

#include <collide/shapes.h>

#include <filesystem>
#include <string_view>
#include <vector>

namespace collide::scene {

struct ObjMesh {
  std::vector<Vec3> vertices;
  std::vector<MeshTriangle> triangles;
};

// Throws collide::Error when the file cannot be read or parsed, or holds no triangles; when it is not
// a regular file (a directory, a device, a FIFO) or is larger than kMaxObjFileBytes
// (collide/scene/limits.h); and for everything parseObj refuses.
ObjMesh readObjFile(const std::filesystem::path& path);

// The same for the text of an OBJ file; `name` names it in error messages. Only geometry is read:
// materials (mtllib, usemtl) do not matter to a collision mesh and are ignored. Stricter than
// tinyobjloader, which reads what it cannot parse as 0: every number of a vertex line must be a
// finite float and a vertex needs x, y and z ("NAME:LINE: vertex coordinate "nan" is not a finite
// number"); a face's vertices must be indices (not 0); a face has at most kMaxObjFaceVertices
// vertices and the mesh at most kMaxMeshTriangles triangles once triangulated.
ObjMesh parseObj(std::string_view text, std::string_view name);

}  // namespace collide::scene
