// `collide query SCENE`: the world's queries from the command line (docs/queries.md). The scene is
// stepped N times, then one ray, shape cast or overlap is asked and each hit printed as a JSON line,
// nearest first.
#include "commands.h"

#include <collide/error.h>
#include <collide/scene/scene.h>

#include <nlohmann/json.hpp>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

using namespace collide;

namespace {

// "X,Y,Z": three finite numbers.
Vec3 parseVec3(const std::string& text, const std::string& what) {
  Vec3 v(0.0f);
  const char* p = text.data();
  const char* end = text.data() + text.size();
  for (int i = 0; i < 3; ++i) {
    float value = 0.0f;
    const auto [stop, error] = std::from_chars(p, end, value);
    const bool last = i == 2;
    if (error != std::errc() || !std::isfinite(value) || (last ? stop != end : (stop == end || *stop != ',')))
      throw Error(what + ": must be three finite numbers X,Y,Z, got \"" + text + "\"");
    v[i] = value;
    p = last ? stop : stop + 1;
  }
  return v;
}

// A body name as a JSON string (names come from scene files: quotes and control characters escaped).
std::string jsonString(const std::string& text) { return nlohmann::json(text).dump(); }

// The shortest text that reads back as the same float.
std::string jsonNumber(float value) {
  char text[32];
  const auto [end, error] = std::to_chars(text, text + sizeof text, value);
  return error == std::errc() ? std::string(text, end) : std::string("null");
}

std::string jsonVec(const Vec3& v) {
  std::string out = "[";
  out += jsonNumber(v.x);
  out += ", ";
  out += jsonNumber(v.y);
  out += ", ";
  out += jsonNumber(v.z);
  out += "]";
  return out;
}

// The body's name if it has one, else its index in the scene (the scene library keeps that index as
// the body's user data).
std::string bodyLabel(const World& world, BodyId id) {
  const std::string& name = world.name(id);
  return name.empty() ? std::to_string(world.userData(id)) : jsonString(name);
}

std::string hitLine(const World& world, BodyId body, std::uint32_t part, float fraction, float distance,
                    const Vec3& point, const Vec3& normal) {
  return "{\"body\": " + bodyLabel(world, body) + ", \"part\": " + std::to_string(part) +
         ", \"fraction\": " + jsonNumber(fraction) + ", \"distance\": " + jsonNumber(distance) +
         ", \"point\": " + jsonVec(point) + ", \"normal\": " + jsonVec(normal);
}

}  // namespace

int queryCommand(const QueryArguments& arguments) {
  const int asked = (arguments.ray.empty() ? 0 : 1) + (arguments.cast.empty() ? 0 : 1) +
                    (arguments.overlap.empty() ? 0 : 1);
  if (asked != 1) throw Error("query: give exactly one of --ray, --cast and --overlap");
  const scene::LoadOptions options{.allowOutsidePaths = arguments.allowOutsidePaths};
  const scene::Scene loaded = loadSceneArgument(arguments.scene, options);
  scene::SceneWorld built = scene::buildWorld(loaded);
  for (int i = 0; i < arguments.steps; ++i) built.world.step(loaded.dt);
  const World& world = built.world;

  std::vector<std::string> lines;
  if (!arguments.ray.empty()) {
    const Vec3 origin = parseVec3(arguments.ray[0], "--ray origin");
    const Vec3 along = parseVec3(arguments.ray[1], "--ray direction");
    const Ray ray{origin, along, glm::length(along)};
    std::vector<RayCastResult> hits;
    if (arguments.all) {
      hits = world.castRayAll(ray);
    } else if (const auto hit = world.castRay(ray)) {
      hits.push_back(*hit);
    }
    for (const RayCastResult& h : hits)
      lines.push_back(hitLine(world, h.body, h.part, h.fraction, h.distance, h.point, h.normal) + "}");
  } else if (!arguments.cast.empty()) {
    const Shape shape = scene::loadShapeFile(arguments.cast[0], options);
    const Transform pose{parseVec3(arguments.cast[1], "--cast position")};
    const Vec3 translation = parseVec3(arguments.cast[2], "--cast translation");
    std::vector<ShapeCastResult> hits;
    if (arguments.all) {
      hits = world.castShapeAll(shape, pose, translation);
    } else if (const auto hit = world.castShape(shape, pose, translation)) {
      hits.push_back(*hit);
    }
    for (const ShapeCastResult& h : hits) {
      lines.push_back(hitLine(world, h.body, h.part, h.fraction, h.distance, h.point, h.normal) +
                      ", \"initially_overlapping\": " + (h.initiallyOverlapping ? "true" : "false") + "}");
    }
  } else {
    const Shape shape = scene::loadShapeFile(arguments.overlap[0], options);
    const Transform pose{parseVec3(arguments.overlap[1], "--overlap position")};
    for (const OverlapResult& o : world.overlapShape(shape, pose)) {
      lines.push_back("{\"body\": " + bodyLabel(world, o.body) + ", \"part\": " + std::to_string(o.part) +
                      "}");
    }
  }
  for (const std::string& line : lines) std::printf("%s\n", line.c_str());
  return 0;
}
