// Joint scenes (docs/joints.md): pendulums and a long chain, a plank bridge carrying a crate,
// ragdolls tumbling down stairs, and a machine of motors, a weld and a lift.
#include "builtin_scene_parts.h"

#include <cmath>
#include <string>

namespace collide::scene::builtin {

namespace {

Json capsule(double radius, double halfHeight) {
  return {{"type", "capsule"}, {"radius", num(radius)}, {"half_height", num(halfHeight)}};
}

Json joint(const char* type, const std::string& a, const std::string& b, const Json& anchor) {
  return {{"type", type}, {"a", a}, {"b", b}, {"anchor", anchor}};
}

}  // namespace

// A uniform rod of 1 m on a hinge, released at 60 degrees; a 50-link chain of 0.1 kg box links
// (0.1 m) on ball joints hanging from a static bar, released level so that it whips.
Json pendulum() {
  Json doc = demoDocument();
  Json& bodies = doc["bodies"];
  Json& constraints = doc["constraints"] = Json::array();
  bodies.push_back(groundPlane());
  bodies.push_back(body("hinge_post", "static", box(0.05, 0.05, 0.1), vec(-3, 4, 0)));
  constexpr double kRod = 1.0, kStart = M_PI / 3;
  Json rod = body("rod", "dynamic", box(0.02, kRod / 2, 0.02),
                  vec(-3 + 0.5 * kRod * std::sin(kStart), 4 - 0.5 * kRod * std::cos(kStart), 0));
  rod["rotation"] = turn(kStart, 0, 0, 1);
  rod["mass"] = num(1);
  bodies.push_back(rod);
  Json hinge = joint("hinge", "hinge_post", "rod", vec(-3, 4, 0));
  hinge["axis"] = vec(0, 0, 1);
  constraints.push_back(hinge);

  constexpr int kLinks = 50;
  constexpr double kLink = 0.1, kTop = 6;
  bodies.push_back(body("bar", "static", box(0.05, 0.05, 0.05), vec(0, kTop, 0)));
  std::string previous = "bar";
  for (int k = 0; k < kLinks; ++k) {
    const std::string name = "link_" + std::to_string(k);
    Json link = body(name, "dynamic", box(kLink / 2, 0.01, 0.01), vec((k + 0.5) * kLink, kTop, 0));
    link["mass"] = num(0.1);
    bodies.push_back(link);
    constraints.push_back(joint("ball", previous, name, vec(k * kLink, kTop, 0)));
    previous = name;
  }
  return doc;
}

// A bridge of 40 planks (2 kg, 0.25 m) hinged end to end between two static posts 9 m apart,
// hanging as a circular arc from posts 4 m up, with a 50 kg crate set on its middle. Its pins have
// friction (2 N m): without it a hanging bridge swings on for ever, as a frictionless one would.
Json bridge() {
  Json doc = demoDocument();
  doc["settings"]["steps"] = 600;
  Json& bodies = doc["bodies"];
  Json& constraints = doc["constraints"] = Json::array();
  bodies.push_back(groundPlane());
  constexpr int kPlanks = 40;
  constexpr double kSpan = 9.0, kLength = 10.0, kHeight = 4.0, kPinFriction = 2.0;
  // The arc of length kLength over the chord kSpan: sin(t) / t = kSpan / kLength, t = half the
  // arc's angle (Newton's method from 1).
  double t = 1.0;
  for (int i = 0; i < 20; ++i) {
    const double f = std::sin(t) / t - kSpan / kLength;
    const double df = (t * std::cos(t) - std::sin(t)) / (t * t);
    t -= f / df;
  }
  const double radius = kLength / (2 * t);
  const double centreY = kHeight + radius * std::cos(t);
  const auto onArc = [&](double phi) {
    return std::pair(radius * std::sin(phi), centreY - radius * std::cos(phi));
  };
  const auto [leftX, leftY] = onArc(-t);
  bodies.push_back(body("post_left", "static", box(0.1, 0.1, 0.6), vec(leftX - 0.1, leftY, 0)));
  const auto [rightX, rightY] = onArc(t);
  bodies.push_back(body("post_right", "static", box(0.1, 0.1, 0.6), vec(rightX + 0.1, rightY, 0)));
  std::string previous = "post_left";
  for (int i = 0; i < kPlanks; ++i) {
    const double phi0 = -t + 2 * t * i / kPlanks, phi1 = -t + 2 * t * (i + 1) / kPlanks;
    const auto [x0, y0] = onArc(phi0);
    const auto [x1, y1] = onArc(phi1);
    const double chord = std::hypot(x1 - x0, y1 - y0);
    const std::string name = "plank_" + std::to_string(i);
    Json plank = body(name, "dynamic", box(chord / 2, 0.025, 0.5), vec((x0 + x1) / 2, (y0 + y1) / 2, 0));
    plank["rotation"] = turn(std::atan2(y1 - y0, x1 - x0), 0, 0, 1);
    plank["mass"] = num(2);
    bodies.push_back(plank);
    Json hinge = joint("hinge", previous, name, vec(x0, y0, 0));
    hinge["axis"] = vec(0, 0, 1);
    hinge["friction"] = num(kPinFriction);
    constraints.push_back(hinge);
    previous = name;
  }
  Json last = joint("hinge", previous, "post_right", vec(rightX, rightY, 0));
  last["axis"] = vec(0, 0, 1);
  last["friction"] = num(kPinFriction);
  constraints.push_back(last);
  // On the middle planks (the arc's lowest point), just above them.
  Json crate = body("crate", "dynamic", box(0.3, 0.3, 0.3), vec(0, onArc(0).second + 0.025 + 0.3 + 0.01, 0));
  crate["mass"] = num(50);
  bodies.push_back(crate);
  return doc;
}

// One ragdoll of 11 bodies standing at (x, y, z): pelvis, torso and head on cone joints, arms on
// cone shoulders and hinge elbows, legs on cone hips and hinge knees, each joint within a human's
// range (radians), with a little friction (3 N m), as a body's joints have: without it a limb
// resting on a stair edge rocks on for ever. Neighbours do not collide; other limbs do.
void addRagdoll(Json& bodies, Json& constraints, const std::string& tag, double x, double y, double z) {
  constexpr double kJointFriction = 3.0;  // N m
  const auto at = [&](double dx, double dy, double dz) { return vec(x + dx, y + dy, z + dz); };
  const auto limb = [&](const std::string& part, Json shape, const Json& position) {
    bodies.push_back(body(tag + part, "dynamic", std::move(shape), position));
  };
  limb("pelvis", box(0.15, 0.1, 0.1), at(0, 1.0, 0));
  limb("torso", box(0.15, 0.2, 0.1), at(0, 1.35, 0));
  limb("head", sphere(0.1), at(0, 1.7, 0));
  const auto cone = [&](const std::string& a, const std::string& b, const Json& anchor, const Json& axis,
                        double swing, double twist) {
    Json j = joint("cone", tag + a, tag + b, anchor);
    j["axis"] = axis;
    j["swing"] = num(swing);
    j["twist"] = Json::array({num(-twist), num(twist)});
    j["friction"] = num(kJointFriction);
    constraints.push_back(j);
  };
  const auto hinge = [&](const std::string& a, const std::string& b, const Json& anchor, double lo,
                         double hi) {
    Json j = joint("hinge", tag + a, tag + b, anchor);
    j["axis"] = vec(1, 0, 0);
    j["limits"] = Json::array({num(lo), num(hi)});
    j["friction"] = num(kJointFriction);
    constraints.push_back(j);
  };
  cone("pelvis", "torso", at(0, 1.1, 0), vec(0, 1, 0), 0.5, 0.4);
  cone("torso", "head", at(0, 1.57, 0), vec(0, 1, 0), 0.6, 0.8);
  for (const int side : {-1, 1}) {
    const std::string s = side < 0 ? "_right" : "_left";
    const double arm = 0.22 * side, leg = 0.09 * side;
    limb("upper_arm" + s, capsule(0.05, 0.1), at(arm, 1.36, 0));
    limb("lower_arm" + s, capsule(0.045, 0.1), at(arm, 1.08, 0));
    limb("thigh" + s, capsule(0.07, 0.15), at(leg, 0.68, 0));
    limb("shin" + s, capsule(0.06, 0.15), at(leg, 0.24, 0));
    cone("torso", "upper_arm" + s, at(arm, 1.5, 0), vec(0, -1, 0), 1.5, 0.7);
    hinge("upper_arm" + s, "lower_arm" + s, at(arm, 1.22, 0), -2.5, 0.0);  // the elbow bends forward
    cone("pelvis", "thigh" + s, at(leg, 0.88, 0), vec(0, -1, 0), 1.2, 0.5);
    hinge("thigh" + s, "shin" + s, at(leg, 0.46, 0), 0.0, 2.5);  // the knee bends back
  }
}

// Eight ragdolls thrown down a flight of six stairs (0.3 m high, 0.5 m deep).
Json ragdolls() {
  Json doc = demoDocument();
  doc["settings"]["steps"] = 600;
  doc["settings"]["sleeping"] = true;
  Json& bodies = doc["bodies"];
  Json& constraints = doc["constraints"] = Json::array();
  bodies.push_back(groundPlane());
  constexpr int kStairs = 6;
  for (int i = 0; i < kStairs; ++i) {
    const double height = 0.3 * (kStairs - i);
    bodies.push_back(body("stair_" + std::to_string(i), "static", box(3, height / 2, 0.25),
                          vec(0, height / 2, 0.5 * i + 0.25)));
  }
  for (int k = 0; k < 8; ++k) {
    const std::string tag = "doll_" + std::to_string(k) + "_";
    const std::size_t first = bodies.size();
    addRagdoll(bodies, constraints, tag, -2.25 + 1.5 * (k % 4), 0.3 * kStairs + 0.05 + 2.0 * (k / 4), 0.25);
    // Each doll leans forward and walks off the top stair.
    for (std::size_t b = first; b < bodies.size(); ++b)
      bodies[b]["velocity"] = vec(0, 0, 1.5 + 0.25 * (k % 3));
  }
  return doc;
}

// A windmill (a rotor of a hub and four blades, one body of parts, on a motorised hinge) that bats
// falling balls, and a lift (a platform on a motorised slider with limits, a rail welded to it)
// that carries crates up to its stop.
Json machine() {
  Json doc = demoDocument();
  doc["settings"]["steps"] = 600;
  Json& bodies = doc["bodies"];
  Json& constraints = doc["constraints"] = Json::array();
  bodies.push_back(groundPlane());
  bodies.push_back(body("tower", "static", box(0.2, 2, 0.2), vec(0, 2, 0)));
  Json rotor = {{"name", "rotor"}, {"type", "dynamic"}, {"position", vec(0, 4, 0.35)}};
  Json parts = Json::array({{{"shape", box(0.15, 0.15, 0.1)}}});
  for (int k = 0; k < 4; ++k) {
    const double angle = k * M_PI / 2;
    parts.push_back({{"shape", box(0.08, 0.9, 0.02)},
                     {"position", vec(-1.05 * std::sin(angle), 1.05 * std::cos(angle), 0)},
                     {"rotation", turn(angle, 0, 0, 1)}});
  }
  rotor["parts"] = parts;
  bodies.push_back(rotor);
  Json axle = joint("hinge", "tower", "rotor", vec(0, 4, 0.35));
  axle["axis"] = vec(0, 0, 1);
  axle["motor"] = {{"speed", num(1.0)}, {"max_torque", num(2000)}};
  constraints.push_back(axle);
  for (int k = 0; k < 6; ++k)
    bodies.push_back(
        body("ball_" + std::to_string(k), "dynamic", sphere(0.2), vec(-0.8 + 0.3 * k, 7 + 0.6 * k, 0.35)));

  bodies.push_back(body("lift_base", "static", box(0.6, 0.05, 0.6), vec(4, 0.05, 0)));
  Json platform = body("platform", "dynamic", box(0.6, 0.05, 0.6), vec(4, 0.2, 0));
  platform["mass"] = num(20);
  bodies.push_back(platform);
  Json lift = joint("slider", "lift_base", "platform", vec(4, 0.2, 0));
  lift["axis"] = vec(0, 1, 0);
  lift["limits"] = Json::array({num(0), num(2)});
  lift["motor"] = {{"speed", num(0.5)}, {"max_force", num(2000)}};
  constraints.push_back(lift);
  Json rail = body("rail", "dynamic", box(0.6, 0.1, 0.03), vec(4, 0.35, -0.57));
  rail["mass"] = num(5);
  bodies.push_back(rail);
  constraints.push_back(
      {{"type", "fixed"}, {"a", "platform"}, {"b", "rail"}, {"anchor", vec(4, 0.25, -0.57)}});
  for (int k = 0; k < 3; ++k) {
    Json crate = body("crate_" + std::to_string(k), "dynamic", box(0.15, 0.15, 0.15),
                      vec(3.7 + 0.3 * k, 0.41 + 0.31 * k, 0));
    bodies.push_back(crate);
  }
  return doc;
}

// Box2D v3's and Box3D's joint_grid benchmark in 3D: a 100 x 100 grid of 1 kg spheres (0.4 m,
// 1 m apart) in a vertical plane, each joined by ball joints to its neighbours to the left and
// above, hanging from seven static spheres in the middle of its top row. The spheres do not collide
// with each other (layer 2, a mask without it): the grid measures the joints alone.
Json jointGrid() {
  Json doc = demoDocument();
  doc["settings"]["steps"] = 600;
  Json& bodies = doc["bodies"];
  Json& constraints = doc["constraints"] = Json::array();
  constexpr int kSide = 100;
  constexpr double kTop = 100.0;
  const auto name = [](int column, int row) {
    return "s_" + std::to_string(column) + "_" + std::to_string(row);
  };
  for (int column = 0; column < kSide; ++column) {
    for (int row = 0; row < kSide; ++row) {
      const bool pinned = row == 0 && column >= kSide / 2 - 3 && column <= kSide / 2 + 3;
      Json ball = body(name(column, row), pinned ? "static" : "dynamic", sphere(0.4),
                       vec(column - kSide / 2, kTop - row, 0));
      if (!pinned) ball["mass"] = num(1);
      ball["layer"] = 2;
      ball["mask"] = 0xFFFFFFFFu & ~2u;
      bodies.push_back(ball);
      const bool leftPinned = row == 0 && column - 1 >= kSide / 2 - 3 && column - 1 <= kSide / 2 + 3;
      if (column > 0 && !(pinned && leftPinned)) {
        constraints.push_back(joint("ball", name(column - 1, row), name(column, row),
                                    vec(column - 0.5 - kSide / 2, kTop - row, 0)));
      }
      if (row > 0) {
        constraints.push_back(joint("ball", name(column, row - 1), name(column, row),
                                    vec(column - kSide / 2, kTop - row + 0.5, 0)));
      }
    }
  }
  return doc;
}

// 100 ragdolls (1,100 bodies, 1,000 joints) dropped in a 5 x 5 x 4 stack onto the ground, each
// tipped by a sideways push so that they tumble into a pile.
Json ragdollPile() {
  Json doc = demoDocument();
  doc["settings"]["steps"] = 600;
  Json& bodies = doc["bodies"];
  Json& constraints = doc["constraints"] = Json::array();
  bodies.push_back(groundBox());
  for (int k = 0; k < 100; ++k) {
    const int column = k % 5, rank = (k / 5) % 5, level = k / 25;
    const std::string tag = "doll_" + std::to_string(k) + "_";
    const std::size_t first = bodies.size();
    addRagdoll(bodies, constraints, tag, 1.2 * (column - 2), 0.2 + 2.0 * level, 1.2 * (rank - 2));
    const double push = 0.5 + 0.25 * (k % 3);
    for (std::size_t b = first; b < bodies.size(); ++b) {
      bodies[b]["velocity"] = vec(k % 2 == 0 ? push : -push, 0, k % 4 < 2 ? push : -push);
    }
  }
  return doc;
}

}  // namespace collide::scene::builtin
