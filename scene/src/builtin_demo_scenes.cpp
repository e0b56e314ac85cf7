// Demonstration scenes: every proxy type in one pile, the two penetration responses, a wall that
// breaks under contact impulses (the lecture's ad-hoc effects driven by collision events), and
// particles joined by distance constraints.
#include "builtin_scene_parts.h"

#include <cmath>

namespace collide::scene::builtin {

namespace {

Json gemPoints() {
  return Json::array({vec(0.35, 0, 0), vec(-0.35, 0, 0), vec(0, 0.45, 0), vec(0, -0.45, 0), vec(0, 0, 0.35),
                      vec(0, 0, -0.35), vec(0.2, 0.2, 0.2), vec(-0.2, -0.2, 0.2)});
}

// One proxy of each droppable type (meshes stay static: scene-format.md).
std::vector<std::pair<std::string, Json>> droppableShapes() {
  return {
      {"sphere", sphere(0.3)},
      {"capsule", {{"type", "capsule"}, {"radius", num(0.2)}, {"half_height", num(0.3)}}},
      {"box", box(0.3, 0.2, 0.25)},
      {"cylinder", {{"type", "cylinder"}, {"radius", num(0.25)}, {"half_height", num(0.25)}}},
      {"ellipsoid", {{"type", "ellipsoid"}, {"radii", vec(0.35, 0.25, 0.2)}}},
      {"hull", {{"type", "convex_hull"}, {"points", gemPoints()}}},
      {"kdop", {{"type", "kdop"}, {"k", 18}, {"points", gemPoints()}}},
      {"compound",
       {{"type", "compound"},
        {"children",
         {{{"shape", sphere(0.2)}, {"position", vec(-0.35, 0, 0)}},
          {{"shape", {{"type", "capsule"}, {"radius", num(0.08)}, {"half_height", num(0.2)}}},
           {"rotation", turn(M_PI / 2, 0, 0, 1)}},
          {{"shape", box(0.15, 0.15, 0.15)}, {"position", vec(0.35, 0, 0)}}}}}},
  };
}

}  // namespace

// Three of every droppable proxy type in columns, falling onto a ground plane, a static mesh ramp
// and each other.
Json proxies() {
  Json doc = demoDocument();
  Json& bodies = doc["bodies"];
  bodies.push_back(groundPlane());
  // A static mesh: a ramp of two triangles rising towards -x, and its back.
  Json ramp = body(
      "ramp", "static",
      {{"type", "mesh"},
       {"vertices",
        {vec(-6, 0, -3), vec(-6, 0, 3), vec(-3, 0, -3), vec(-3, 0, 3), vec(-6, 1.5, -3), vec(-6, 1.5, 3)}},
       {"triangles", {{2, 4, 3}, {3, 4, 5}}}},
      vec(0, 0, 0));
  bodies.push_back(ramp);
  const auto shapes = droppableShapes();
  for (int layer = 0; layer < 3; ++layer) {
    for (std::size_t s = 0; s < shapes.size(); ++s) {
      const double x = -4.5 + 1.2 * double(s) + 0.15 * layer, z = 0.1 * layer;
      Json b = body(shapes[s].first + "_" + std::to_string(layer), "dynamic", shapes[s].second,
                    vec(x, 1.0 + 1.1 * layer, z));
      b["rotation"] = turn(0.4 + 0.7 * layer + 0.3 * double(s), 0.6, 0.0, 0.8);
      b["density"] = 500;
      // Round shapes roll and rock on a point contact, which passes no friction torque: the
      // resistance brings them to rest, as real ones do.
      b["rolling_resistance"] = 0.02;
      bodies.push_back(b);
    }
  }
  return doc;
}

// The same drop with one penetration response: boxes and spheres falling fast into a heap, so that
// bodies penetrate and the response shows (run `revert`, `revert-project` and `revert-soft` and
// compare).
Json penetrationDrop(const char* response) {
  Json doc = demoDocument();
  doc["settings"]["penetration_response"] = response;
  Json& bodies = doc["bodies"];
  bodies.push_back(groundBox());
  for (int i = 0; i < 12; ++i) {
    const double x = 0.3 * (i % 3) - 0.3, z = 0.3 * ((i / 3) % 2), y = 1.0 + 0.7 * i;
    Json b = i % 2 == 0 ? body("box_" + std::to_string(i), "dynamic", box(0.3, 0.3, 0.3), vec(x, y, z))
                        : body("ball_" + std::to_string(i), "dynamic", sphere(0.3), vec(x, y, z));
    b["velocity"] = vec(0, -8, 0);
    b["rotation"] = turn(0.5 * i, 0, 0.6, 0.8);
    bodies.push_back(b);
  }
  return doc;
}

// A wall of 6 rows of 8 and 7 bricks, each removed once the impulses of its contact begin events add up to
// more than 45 N s; a heavy ball thrown at it breaks a hole. The weight the bottom bricks carry at rest
// (under 10 N s in the first contact step) stays well under the threshold.
Json breakable() {
  Json doc = demoDocument();
  Json& bodies = doc["bodies"];
  bodies.push_back(groundBox());
  constexpr double kHalfX = 0.2, kHalfY = 0.1, kHalfZ = 0.1;
  for (int row = 0; row < 6; ++row) {
    // Running bond: odd rows have 7 bricks over the joints below, so that no brick overhangs.
    const int count = row % 2 == 0 ? 8 : 7;
    for (int i = 0; i < count; ++i) {
      Json b = body("brick_" + std::to_string(row) + "_" + std::to_string(i), "dynamic",
                    box(kHalfX, kHalfY, kHalfZ),
                    vec((i - (count - 1) / 2.0) * 2 * kHalfX, kHalfY + row * 2 * kHalfY, 0));
      b["density"] = 1000;
      b["break_impulse"] = 45;
      bodies.push_back(b);
    }
  }
  Json ball = body("wrecking_ball", "dynamic", sphere(0.25), vec(0, 0.5, -4));
  ball["velocity"] = vec(0, 2, 14);
  ball["mass"] = 60;
  bodies.push_back(ball);
  return doc;
}

// Particles and rigid distance constraints: a rope of 10 particles hanging from a static hook,
// released 30 degrees from vertical, and a 7 x 7 net of particles (links between grid neighbours)
// falling over a static ball. Sleeping is on: the net comes to rest draped over the ball, its rim on
// the ground, and sleeps; the rope keeps swinging (nothing damps it).
Json chain() {
  Json doc = demoDocument();
  doc["settings"]["sleeping"] = true;
  Json& bodies = doc["bodies"];
  Json& constraints = doc["constraints"] = Json::array();
  bodies.push_back(groundPlane());
  const auto particle = [&](const std::string& name, double radius, double mass, const Json& position) {
    Json p = body(name, "dynamic", sphere(radius), position);
    p["particle"] = true;
    p["mass"] = num(mass);
    bodies.push_back(p);
  };
  const auto link = [&](const std::string& a, const std::string& b) {
    constraints.push_back({{"type", "distance"}, {"a", a}, {"b", b}});  // rigid, length as placed
  };

  constexpr double kHookX = -3, kHookY = 5, kLink = 0.35, kAngle = M_PI / 6;
  bodies.push_back(body("hook", "static", box(0.1, 0.1, 0.1), vec(kHookX, kHookY, 0)));
  std::string previous = "hook";
  for (int k = 0; k < 10; ++k) {
    const std::string name = "rope_" + std::to_string(k);
    const double along = (k + 1) * kLink;
    particle(name, 0.05, 0.1, vec(kHookX + along * std::sin(kAngle), kHookY - along * std::cos(kAngle), 0));
    link(previous, name);
    previous = name;
  }

  constexpr double kBallX = 2, kBallRadius = 0.4, kSpacing = 0.25;
  bodies.push_back(body("ball", "static", sphere(kBallRadius), vec(kBallX, kBallRadius, 0)));
  constexpr int kSide = 7;
  const auto knot = [](int i, int j) { return "net_" + std::to_string(i) + "_" + std::to_string(j); };
  for (int i = 0; i < kSide; ++i) {
    for (int j = 0; j < kSide; ++j) {
      const double x = kBallX + (i - (kSide - 1) / 2.0) * kSpacing, z = (j - (kSide - 1) / 2.0) * kSpacing;
      particle(knot(i, j), 0.06, 0.05, vec(x, 3, z));
      if (i > 0) link(knot(i - 1, j), knot(i, j));
      if (j > 0) link(knot(i, j - 1), knot(i, j));
    }
  }
  return doc;
}

// What continuous detection covers, side by side (docs/ccd.md): in each lane a small sphere (radius
// 0.05) at 300 m/s and a spinning box at 200 m/s fly at a thin plate, once flagged `ccd` (lanes at
// z < 0) and once not (z > 0). The plates of lanes 0 and 1 are static: every shot stops, the
// continuous pass covers static geometry for every body. Those of lanes 2 and 3 are kinematic (held
// still): only the flagged shots stop, the flag extends the pass to moving bodies. No gravity, so
// what passes keeps going. Speculative contacts stop a straight, non-spinning shot on their own; the
// spin and the oblique angle are what defeat them, and what the time-of-impact pass catches.
Json tunneling() {
  Json doc = demoDocument();
  doc["settings"]["gravity"] = vec(0, 0, 0);
  doc["settings"]["steps"] = 60;
  doc["settings"]["ccd"] = true;
  Json& bodies = doc["bodies"];
  constexpr int kLanes = 4;
  for (int on = 0; on < 2; ++on) {
    const char* flag = on == 1 ? "ccd" : "no_ccd";
    const double side = on == 1 ? -1.0 : 1.0;
    for (int lane = 0; lane < kLanes; ++lane) {
      const double z = side * (1.0 + 1.5 * lane), y = 1.0 + 0.13 * lane;
      const std::string tag = std::string(flag) + "_" + std::to_string(lane);
      const char* plateType = lane < 2 ? "static" : "kinematic";
      bodies.push_back(body("plate_" + tag, plateType, box(0.01, 0.6, 0.6), vec(0, y, z)));
      Json ball = body("ball_" + tag, "dynamic", sphere(0.05), vec(-3, y - 0.3, z));
      const double angle = 0.03 + 0.02 * lane;  // slightly upwards, so it meets the plate obliquely
      ball["velocity"] = vec(300 * std::cos(angle), 300 * std::sin(angle), 0);
      ball["angular_velocity"] = vec(0, 0, 400 + 50 * lane);
      ball["ccd"] = on == 1;
      bodies.push_back(ball);
      Json brick = body("box_" + tag, "dynamic", box(0.1, 0.05, 0.03), vec(-3, y + 0.3, z));
      brick["velocity"] = vec(200, 0, 0);
      brick["angular_velocity"] = vec(0, 30 + 10 * lane, 60);
      brick["ccd"] = on == 1;
      bodies.push_back(brick);
    }
  }
  return doc;
}

}  // namespace collide::scene::builtin
