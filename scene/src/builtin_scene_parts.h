// Pieces the built-in scenes share: the document skeleton, bodies and shapes as scene JSON.
#pragma once

#include "json_output.h"

#include <collide/scene/scene.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <string>

namespace collide::scene::builtin {

using Json = nlohmann::json;

// Numbers computed in double, written with 9 significant digits (the float the loader reads).
inline Json num(double value) { return jsonNumber(static_cast<float>(value)); }
inline Json vec(double x, double y, double z) { return Json::array({num(x), num(y), num(z)}); }

// The settings common to the reference scenes (reference-scenes.md): gravity (0, -9.81, 0), 1/60 s,
// 600 steps, sleeping off, friction 0.5 per contact (every body 0.5, averaged).
inline Json referenceDocument() {
  return {{"format", std::string(kFormat)},
          {"settings",
           {{"gravity", vec(0, -9.81, 0)},
            {"dt", num(1.0 / 60.0)},
            {"steps", 600},
            {"broadphase", "tree"},
            {"sleeping", false},
            {"friction_combine", "average"}}},
          {"bodies", Json::array()}};
}

inline Json sphere(double radius) { return {{"type", "sphere"}, {"radius", num(radius)}}; }
inline Json box(double hx, double hy, double hz) {
  return {{"type", "box"}, {"half_extents", vec(hx, hy, hz)}};
}

inline Json body(const std::string& name, const char* type, Json shape, const Json& position) {
  return {{"name", name}, {"type", type}, {"shape", std::move(shape)}, {"position", position}};
}

// The reference ground: a static box 200 x 200 wide whose top face is y = 0.
inline Json groundBox() {
  Json ground = body("ground", "static", box(100, 0.5, 100), vec(0, -0.5, 0));
  ground["friction"] = num(0.5);
  return ground;
}

// The demonstration scenes' settings: the reference ones, 300 steps.
inline Json demoDocument() {
  Json doc = referenceDocument();
  doc["settings"]["steps"] = 300;
  return doc;
}

inline Json groundPlane() {
  return body("ground", "static", {{"type", "plane"}, {"normal", vec(0, 1, 0)}, {"distance", 0}},
              vec(0, 0, 0));
}

// A quaternion [x, y, z, w] turning `angle` about a unit axis.
inline Json turn(double angle, double ax, double ay, double az) {
  const double s = std::sin(angle / 2);
  return Json::array({num(ax * s), num(ay * s), num(az * s), num(std::cos(angle / 2))});
}

}  // namespace collide::scene::builtin
