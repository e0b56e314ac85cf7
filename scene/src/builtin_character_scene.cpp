// The character scene: a level for the character mover (collide/character.h) and a player walked
// along a path through it: up a flight of 0.3 m steps, down a 30-degree ramp, through a row of crates
// it pushes aside, over a jump, onto a turning disc it rides. A 50-degree slope, too steep to walk,
// and a platform sliding past stand beside the path for the viewer, where WASD drives the player.
#include "builtin_scene_parts.h"

#include <cmath>

namespace collide::scene::builtin {

Json character() {
  Json doc = demoDocument();
  doc["settings"]["steps"] = 900;
  Json& bodies = doc["bodies"];
  bodies.push_back(groundBox());
  // Stairs up along +x from x = 3: five steps of 0.3 m rise and 0.5 m tread, then a landing 1.5 m
  // high to x = 8.
  for (int step = 0; step < 5; ++step) {
    const double top = 0.3 * (step + 1), from = 3.0 + 0.5 * step;
    bodies.push_back(body("step_" + std::to_string(step), "static", box(0.25, 0.5 * top, 1.0),
                          vec(from + 0.25, 0.5 * top, 0)));
  }
  bodies.push_back(body("landing", "static", box(1.25, 0.75, 1.0), vec(6.75, 0.75, 0)));
  // A ramp from the landing's edge down to the ground at 30 degrees: its top face from (8, 1.5) to
  // (8 + 1.5 / tan 30, 0), 0.2 m thick.
  const double slope = M_PI / 6, length = 1.5 / std::sin(slope);
  const double midX = 8.0 + 0.5 * length * std::cos(slope), midY = 0.75;
  Json ramp = body("ramp", "static", box(0.5 * length, 0.1, 1.0),
                   vec(midX - 0.1 * std::sin(slope), midY - 0.1 * std::cos(slope), 0));
  ramp["rotation"] = turn(-slope, 0, 0, 1);
  bodies.push_back(ramp);
  // A slope too steep to walk (50 degrees), rising towards -z.
  const double steep = 50.0 * M_PI / 180.0;
  Json wedge = body("steep_slope", "static", box(2.0, 0.1, 3.0), vec(0, 1.0, -7.0));
  wedge["rotation"] = turn(steep, 1, 0, 0);
  bodies.push_back(wedge);
  // Crates in the player's way, light enough to push.
  for (int i = 0; i < 3; ++i) {
    Json crate = body("crate_" + std::to_string(i), "dynamic", box(0.4, 0.4, 0.4),
                      vec(11.0 + 0.9 * (i - 1), 0.4, 3.0));
    crate["mass"] = num(15);
    bodies.push_back(crate);
  }
  // A low wall to jump over? A kerb of 0.5 m, higher than a step: the path jumps it.
  bodies.push_back(body("kerb", "static", box(0.2, 0.25, 3.0), vec(5.0, 0.25, 5.0)));
  // A disc turning at 0.5 rad/s, 0.2 m high (a step onto it), and a platform sliding along z.
  Json disc =
      body("turntable", "kinematic", {{"type", "cylinder"}, {"radius", num(2.5)}, {"half_height", num(0.1)}},
           vec(-6.0, 0.1, 0.0));
  disc["angular_velocity"] = vec(0, 0.5, 0);
  bodies.push_back(disc);
  Json platform = body("sliding_platform", "kinematic", box(1.5, 0.15, 1.5), vec(-6.0, 0.15, -12.0));
  platform["velocity"] = vec(0, 0, 0.8);
  bodies.push_back(platform);

  // The player's path: feet positions, walked at 3 m/s.
  const auto waypoint = [](double x, double y, double z, double jump = 0.0) {
    Json w = {{"to", vec(x, y, z)}, {"speed", num(3.0)}};
    if (jump > 0.0) w["jump"] = num(jump);
    return w;
  };
  Json player = {{"name", "player"},
                 {"position", vec(0, 0.02 + 0.3 + 0.6, 0)},
                 {"max_step_height", num(0.35)},
                 {"path",
                  {waypoint(2.5, 0, 0), waypoint(6.5, 1.5, 0), waypoint(11.0, 0, 0), waypoint(11.0, 0, 6.0),
                   waypoint(7.0, 0, 6.0), waypoint(3.0, 0, 5.0, 5.0), waypoint(-6.0, 0.2, 1.5)}}};
  doc["characters"] = Json::array({player});
  return doc;
}

}  // namespace collide::scene::builtin
