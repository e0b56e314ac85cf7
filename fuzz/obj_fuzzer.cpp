// OBJ loader fuzzer: the text of an OBJ file, as the scene loader and `collide fit` read it,
// through collide::scene::parseObj (tinyobjloader underneath), then into a TriangleMesh, its mass
// properties when it is closed, and every fitted proxy of `collide fit`.
//
// Allowed: a mesh, or collide::Error with a message (unparsable text, an index out of range, no
// triangles, a non-finite coordinate, a zero-area triangle, a flat point set). A finding: a crash,
// a sanitizer report, another exception, an error without a message, a mesh whose triangles name
// vertices that do not exist, or a vertex that is not finite, in the parsed OBJ or in the
// TriangleMesh built from it (what tinyobjloader makes of "nan" or "inf" must be refused, not
// passed on).
#include <collide/bounding.h>
#include <collide/scene/obj_file.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace collide;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    scene::ObjMesh obj = scene::parseObj(text, "fuzz.obj");
    if (obj.triangles.empty()) std::abort();  // documented: "no triangles" is an Error
    for (const Vec3& v : obj.vertices) {
      if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) std::abort();
    }
    for (const MeshTriangle& t : obj.triangles) {
      for (const std::uint32_t v : t.v) {
        if (v >= obj.vertices.size()) std::abort();
      }
    }
    // Keep each input cheap: the fitters are O(n log n) and up, the hull goes through Qhull.
    if (obj.vertices.size() > 256) return 0;
    const std::vector<Vec3> vertices = obj.vertices;
    const TriangleMesh mesh = TriangleMesh::fromTriangles(std::move(obj.vertices), std::move(obj.triangles));
    // The mesh the loader's output becomes, as a scene's mesh body gets it: finite too.
    for (const Vec3& v : mesh.vertices()) {
      if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) __builtin_trap();
    }
    if (mesh.isClosed()) {
      try {
        (void)massProperties(Shape(mesh), 1000.0f);
      } catch (const Error& e) {
        if (std::string_view(e.what()).empty()) std::abort();
      }
    }
    (void)fitAllProxies(vertices);
  } catch (const Error& e) {
    if (std::string_view(e.what()).empty()) std::abort();  // an error must say what is wrong
  }
  return 0;
}
