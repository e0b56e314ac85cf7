// Wavefront OBJ meshes through tinyobjloader, with the checks it leaves out: tinyobjloader reads a
// coordinate it cannot parse ("nan", "inf", "1.5x", a missing one) as 0, which silently changes the
// mesh, and triangulates polygons by ear clipping in time quadratic in their size. So the text is
// scanned first: every number of a "v" line must be a finite float, every "f" line's vertices valid
// indices, polygons and the whole mesh within the limits of collide/scene/limits.h.
#include <collide/scene/limits.h>
#include <collide/scene/obj_file.h>

#include "file_text.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>

#include <tiny_obj_loader.h>

namespace collide::scene {

namespace {

bool isBlank(char c) { return c == ' ' || c == '\t'; }

// The token as written, quoted and cut short, printable.
std::string quoted(std::string_view token) {
  std::string out = "\"";
  for (std::size_t i = 0; i < token.size() && i < 40; ++i) {
    const auto c = static_cast<unsigned char>(token[i]);
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
    } else {
      static const char* const hex = "0123456789abcdef";
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  return out + (token.size() > 40 ? "...\"" : "\"");
}

// An optional sign, then what std::from_chars reads, all of the token.
bool parseNumber(std::string_view token, double& value) {
  std::string_view digits = token;
  if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);
  if (digits.empty() || digits.front() == '+') return false;
#if defined(__cpp_lib_to_chars)
  const char* end = digits.data() + digits.size();
  const auto [ptr, ec] = std::from_chars(digits.data(), end, value);
  if (ptr != end) return false;
  if (ec == std::errc::result_out_of_range) {
    // Too large or too small for a double: strtod says which (infinity, or a value near zero).
    value = std::strtod(std::string(digits).c_str(), nullptr);
    return true;
  }
  return ec == std::errc();
#else
  // A standard library without from_chars for doubles (emscripten's libc++ 14): strtod, held to
  // what from_chars reads (no leading space, no hexadecimal).
  if (std::isspace(static_cast<unsigned char>(digits.front())) ||
      digits.find_first_of("xX") != std::string_view::npos)
    return false;
  const std::string text(digits);
  char* stop = nullptr;
  value = std::strtod(text.c_str(), &stop);
  return stop == text.c_str() + text.size();
#endif
}

bool parseIndex(std::string_view token, long long& value) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty() || token.front() == '+') return false;
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, value);
  return ec == std::errc() && ptr == end;
}

// The line's tokens after its keyword, up to a comment.
std::vector<std::string_view> tokens(std::string_view rest) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < rest.size()) {
    while (i < rest.size() && isBlank(rest[i])) ++i;
    if (i == rest.size() || rest[i] == '#') break;
    const std::size_t start = i;
    while (i < rest.size() && !isBlank(rest[i])) ++i;
    out.push_back(rest.substr(start, i - start));
  }
  return out;
}

// Lines end at "\n", "\r\n" or "\r" and at a NUL byte, as tinyobjloader reads them; a line is a
// vertex ("v x y z [w]" or "v x y z r g b") or a face ("f v1 v2 v3 ...", each vertex "v", "v/vt",
// "v//vn" or "v/vt/vn") when its keyword, after leading blanks, is followed by a blank. Returns the
// text tinyobjloader is to read: the vertices and faces checked here, every other line made a comment
// (its first character '#', so the line numbers stay). collide reads only the geometry, and
// tinyobjloader converts the numbers of the other lines unchecked (a skin weight's joint of 1e300
// to int, a normal's 1e300 to float: undefined behaviour, found by obj_fuzzer).
std::string checkedGeometry(std::string_view text, const std::string& who) {
  std::string geometry(text);
  std::size_t triangles = 0;
  std::size_t lineNumber = 0;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find_first_of("\r\n", pos);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(pos, end - pos);
    pos = end + (end + 1 < text.size() && text[end] == '\r' && text[end + 1] == '\n' ? 2 : 1);
    ++lineNumber;
    line = line.substr(0, line.find('\0'));
    std::size_t start = 0;
    while (start < line.size() && isBlank(line[start])) ++start;
    line.remove_prefix(start);
    if (line.size() < 2 || !isBlank(line[1]) || (line[0] != 'v' && line[0] != 'f')) {
      if (!line.empty()) geometry[static_cast<std::size_t>(line.data() - text.data())] = '#';
      continue;
    }
    const std::string where = who + ":" + std::to_string(lineNumber) + ": ";
    const std::vector<std::string_view> items = tokens(line.substr(2));
    if (line[0] == 'v') {
      for (std::string_view token : items) {
        double value = 0.0;
        if (!parseNumber(token, value))
          throw Error(where + "vertex coordinate " + quoted(token) + " is not a number");
        if (!std::isfinite(value))
          throw Error(where + "vertex coordinate " + quoted(token) + " is not a finite number");
        if (std::abs(value) > std::numeric_limits<float>::max()) {
          throw Error(where + "vertex coordinate " + quoted(token) +
                      " is not a finite number within float range");
        }
      }
      if (items.size() < 3) {
        throw Error(where + "a vertex needs x, y and z, got " + std::to_string(items.size()) + " number" +
                    (items.size() == 1 ? "" : "s"));
      }
      continue;
    }
    for (std::string_view item : items) {
      // "v", "v/vt", "v//vn", "v/vt/vn": the vertex index is required, the others are optional.
      std::size_t part = 0;
      std::string_view rest = item;
      while (true) {
        const std::size_t slash = rest.find('/');
        const std::string_view number = rest.substr(0, slash);
        long long index = 0;
        const bool required = part == 0;
        if ((required || !number.empty()) && !parseIndex(number, index)) {
          throw Error(where + "face vertex " + quoted(item) + " is not an index (v, v/vt, v//vn or v/vt/vn)");
        }
        if (required && index == 0) {
          throw Error(where + "face vertex " + quoted(item) +
                      ": vertex indices start at 1 (or count back from -1), got 0");
        }
        if (slash == std::string_view::npos) break;
        rest.remove_prefix(slash + 1);
        if (++part == 3) throw Error(where + "face vertex " + quoted(item) + " has more than three indices");
      }
    }
    if (items.size() > kMaxObjFaceVertices) {
      throw Error(where + "a face of " + std::to_string(items.size()) + " vertices, more than the limit of " +
                  std::to_string(kMaxObjFaceVertices));
    }
    if (items.size() >= 3) triangles += items.size() - 2;
    if (triangles > kMaxMeshTriangles) {
      throw Error(who + ": more than " + std::to_string(kMaxMeshTriangles) +
                  " triangles (the limit), reached at line " + std::to_string(lineNumber));
    }
  }
  return geometry;
}

}  // namespace

ObjMesh readObjFile(const std::filesystem::path& path) {
  const std::string who = "OBJ file " + path.string();
  return parseObj(readFileText(path, kMaxObjFileBytes, who), who);
}

ObjMesh parseObj(std::string_view text, std::string_view name) {
  const std::string who(name);
  const std::string geometry = checkedGeometry(text, who);
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromString(geometry, /*mtl_text=*/"", config)) {
    std::string why = reader.Error();
    while (!why.empty() && (why.back() == '\n' || why.back() == '\r')) why.pop_back();
    throw Error(who + ": " + (why.empty() ? "cannot be parsed" : why));
  }
  ObjMesh mesh;
  const auto& coordinates = reader.GetAttrib().vertices;
  for (std::size_t i = 0; i + 2 < coordinates.size(); i += 3) {
    mesh.vertices.emplace_back(coordinates[i], coordinates[i + 1], coordinates[i + 2]);
    // The scan above lets only finite coordinates through; this holds whatever tinyobjloader does.
    if (!std::isfinite(coordinates[i]) || !std::isfinite(coordinates[i + 1]) ||
        !std::isfinite(coordinates[i + 2])) {
      throw Error(who + ": vertex " + std::to_string(i / 3 + 1) + " is not finite");
    }
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
