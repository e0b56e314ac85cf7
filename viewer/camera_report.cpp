#include "camera_report.h"

#include <collide/error.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string_view>

namespace collide::viewer {
namespace {

std::string vec(const Vec3& v) {
  char text[96];
  std::snprintf(text, sizeof(text), "[%.9g, %.9g, %.9g]", v.x, v.y, v.z);
  return text;
}

// Scene body names come from files: escape what JSON needs escaped.
std::string quoted(std::string_view text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char escape[8];
      std::snprintf(escape, sizeof(escape), "\\u%04x", c);
      out += escape;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

}  // namespace

void writeCameraReport(const std::string& path, const OrbitCamera& camera, int width, int height,
                       const Vec3& background, const ViewerScene& scene) {
  const World& world = scene.world();
  std::ostringstream out;
  out << "{\n  \"width\": " << width << ", \"height\": " << height << ",\n";
  out << "  \"eye\": " << vec(camera.eye()) << ", \"target\": " << vec(camera.target)
      << ", \"up\": [0, 1, 0], \"fov_y\": " << camera.fovY << ",\n";
  out << "  \"background\": " << vec(background) << ",\n  \"bodies\": [";
  bool first = true;
  for (const ViewerScene::DrawnBody& body : scene.drawnBodies()) {
    if (!world.isValid(body.id)) continue;
    const Shape& shape = world.shape(body.id);
    const Transform transform = world.transform(body.id);
    const Aabb box = worldBounds(shape, transform);
    const glm::vec4 colour = scene.drawnColour(body);
    out << (first ? "\n" : ",\n") << "    {\"name\": " << quoted(world.name(body.id))
        << ", \"type\": " << quoted(toString(world.type(body.id)))
        << ", \"shape\": " << quoted(toString(shape.type()))
        << ", \"center\": " << vec(world.centerOfMass(body.id)) << ", \"min\": " << vec(box.min)
        << ", \"max\": " << vec(box.max) << ", \"rotation\": [" << transform.rotation.w << ", "
        << transform.rotation.x << ", " << transform.rotation.y << ", " << transform.rotation.z
        << "], \"colour\": " << vec(Vec3(colour)) << ", \"checker\": " << (colour.a < 0.5f ? "true" : "false")
        << "}";
    first = false;
  }
  // The characters, drawn as their capsules (not bodies of the World: type "character").
  for (std::size_t i = 0; scene.charactersShown() && i < scene.characters().size(); ++i) {
    const Character& character = scene.characters()[i];
    const Vec3 reach(character.def().radius + character.def().halfHeight);
    const Vec3 centre = character.position();
    out << (first ? "\n" : ",\n") << "    {\"name\": " << quoted(scene.scene().characters[i].name)
        << ", \"type\": \"character\", \"shape\": \"capsule\", \"center\": " << vec(centre)
        << ", \"min\": " << vec(centre - reach) << ", \"max\": " << vec(centre + reach)
        << ", \"rotation\": [1, 0, 0, 0], \"colour\": " << vec(Vec3(ViewerScene::kCharacterColour))
        << ", \"checker\": false}";
    first = false;
  }
  out << "\n  ]\n}\n";
  std::ofstream file(path);
  file << out.str();
  if (!file) throw Error("viewer: camera report " + path + ": cannot be written");
}

}  // namespace collide::viewer
