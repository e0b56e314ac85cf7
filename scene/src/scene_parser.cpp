// JSON text -> Scene. Every field of docs/scene-format.md is read here, checked for type and range,
// and unknown fields are refused, so that a typo is an error rather than a silent default.
#include "file_text.h"
#include "json_node.h"
#include "scene_document.h"

#include <collide/scene/limits.h>
#include <collide/scene/obj_file.h>
#include <collide/scene/scene.h>
#include <collide/shapes.h>

#include <set>
#include <sstream>

namespace collide::scene {

namespace {

std::string shortNumber(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

// Runs `parse` and re-throws a library Error (an enum name, a hull that Qhull refuses) with the
// field's path in front.
template <class F>
auto withPath(const JsonNode& node, F&& parse) -> decltype(parse()) {
  try {
    return parse();
  } catch (const Error& e) {
    node.fail(e.what());
  }
}

std::vector<Vec3> readPoints(const JsonNode& node) {
  std::vector<Vec3> points;
  for (const JsonNode& p : node.elements()) points.push_back(p.vec3());
  return points;
}

Transform readPlacement(const JsonNode& node) {
  Transform t;
  if (auto p = node.find("position")) t.position = p->vec3();
  if (auto r = node.find("rotation")) t.rotation = r->quaternion();
  return t;
}

// What reading a shape needs beyond its JSON: where its OBJ files may be.
struct LoadContext {
  std::filesystem::path baseDir;
  LoadOptions options;
  std::vector<std::filesystem::path>* objFiles;  // every OBJ file read, in the order read
};

// The path an OBJ file name of the scene leads to: relative to the scene's folder, and unless the
// options allow it, inside that folder once normalised and once symbolic links are followed.
std::filesystem::path objPath(const JsonNode& file, const LoadContext& context) {
  namespace fs = std::filesystem;
  const std::string name = file.string();
  if (name.empty()) file.fail("must name an OBJ file, got \"\"");
  const fs::path given(name);
  if (context.options.allowOutsidePaths) return context.baseDir / given;  // an absolute name replaces baseDir
  const std::string allow =
      " (OBJ paths are relative to the scene file's folder and stay inside it, unless allowed: "
      "collide run --allow-outside-paths, LoadOptions::allowOutsidePaths)";
  if (given.has_root_name() || given.has_root_directory()) {
    file.fail("must be a relative path, got the absolute path " + file.shown() + allow);
  }
  const fs::path normal = given.lexically_normal();
  if (!normal.empty() && *normal.begin() == "..")
    file.fail("leads outside the scene's folder, got " + file.shown() + allow);
  const fs::path path = context.baseDir / normal;
  std::error_code baseError, pathError;
  const fs::path realBase = fs::weakly_canonical(context.baseDir, baseError);
  const fs::path realPath = fs::weakly_canonical(path, pathError);
  // Fail closed: a path whose links cannot be followed (a loop, a folder that cannot be searched) is
  // not known to stay inside.
  if (baseError || pathError) {
    file.fail("cannot be resolved, got " + file.shown() + ": " +
              (baseError ? baseError : pathError).message());
  }
  const fs::path inside = realPath.lexically_relative(realBase);
  if (inside.empty() || *inside.begin() == "..") {
    file.fail("leads outside the scene's folder through a symbolic link, got " + file.shown() + " (it is " +
              realPath.string() + ")" + allow);
  }
  return path;
}

Shape readShape(const JsonNode& node, const LoadContext& context, int compoundDepth);

Shape readMesh(const JsonNode& node, const LoadContext& context) {
  node.expectObject({"type", "vertices", "triangles", "file"});
  const bool inlineMesh = node.has("vertices") || node.has("triangles");
  if (inlineMesh == node.has("file")) node.fail("a mesh needs either vertices and triangles, or file");
  std::vector<Vec3> vertices;
  std::vector<MeshTriangle> triangles;
  if (auto file = node.find("file")) {
    const std::filesystem::path path = objPath(*file, context);
    ObjMesh mesh = withPath(*file, [&] { return readObjFile(path); });
    context.objFiles->push_back(path);
    vertices = std::move(mesh.vertices);
    triangles = std::move(mesh.triangles);
  } else {
    vertices = readPoints(node.at("vertices"));
    const JsonNode trianglesNode = node.at("triangles");
    if (trianglesNode.value().is_array() && trianglesNode.value().size() > kMaxMeshTriangles) {
      trianglesNode.fail("holds " + std::to_string(trianglesNode.value().size()) +
                         " triangles, more than the limit of " + std::to_string(kMaxMeshTriangles));
    }
    for (const JsonNode& t : trianglesNode.elements()) {
      const auto corners = t.elements();
      if (corners.size() != 3) t.fail("must be a triangle [i, j, k], got " + t.shown());
      MeshTriangle triangle;
      for (int k = 0; k < 3; ++k) {
        const int index = corners[k].integer(0);
        if (static_cast<std::size_t>(index) >= vertices.size()) {
          corners[k].fail("vertex index out of range (" + std::to_string(vertices.size()) +
                          " vertices), got " + corners[k].shown());
        }
        triangle.v[k] = static_cast<std::uint32_t>(index);
      }
      triangles.push_back(triangle);
    }
  }
  return withPath(
      node, [&] { return Shape(TriangleMesh::fromTriangles(std::move(vertices), std::move(triangles))); });
}

// `compoundDepth`: how many compounds hold this shape.
Shape readShape(const JsonNode& node, const LoadContext& context, int compoundDepth) {
  if (!node.value().is_object()) node.fail("must be a shape object, got " + node.shown());
  const std::string type = node.at("type").string();
  if (type == "sphere") {
    node.expectObject({"type", "radius"});
    return Sphere{node.at("radius").positive()};
  }
  if (type == "capsule") {
    node.expectObject({"type", "radius", "half_height"});
    return Capsule{node.at("radius").positive(), node.at("half_height").positive()};
  }
  if (type == "cylinder") {
    node.expectObject({"type", "radius", "half_height"});
    return Cylinder{node.at("radius").positive(), node.at("half_height").positive()};
  }
  if (type == "plane") {
    node.expectObject({"type", "normal", "distance"});
    const JsonNode normalNode = node.at("normal");
    const Vec3 normal = normalNode.vec3();
    if (std::abs(glm::length(normal) - 1.0f) > 1e-3f) {
      normalNode.fail("must be a unit vector, got " + normalNode.shown());
    }
    return Plane{glm::normalize(normal), node.at("distance").number()};
  }
  if (type == "box") {
    node.expectObject({"type", "half_extents"});
    return Box{node.at("half_extents").positiveVec3()};
  }
  if (type == "ellipsoid") {
    node.expectObject({"type", "radii"});
    return Ellipsoid{node.at("radii").positiveVec3()};
  }
  if (type == "convex_hull") {
    node.expectObject({"type", "points"});
    const JsonNode pointsNode = node.at("points");
    const auto points = readPoints(pointsNode);
    return withPath(pointsNode, [&] { return Shape(ConvexHull::fromPoints(points)); });
  }
  if (type == "kdop") {
    node.expectObject({"type", "k", "points"});
    const JsonNode kNode = node.at("k");
    const int k = kNode.integer(0);
    if (k != 6 && k != 14 && k != 18 && k != 26) kNode.fail("must be 6, 14, 18 or 26, got " + kNode.shown());
    const JsonNode pointsNode = node.at("points");
    const auto points = readPoints(pointsNode);
    return withPath(pointsNode, [&] { return Shape(Kdop::fromPoints(k, points)); });
  }
  if (type == "mesh") return readMesh(node, context);
  if (type == "compound") {
    node.expectObject({"type", "children"});
    if (compoundDepth >= kMaxCompoundDepth) {
      node.fail("compounds nest more than " + std::to_string(kMaxCompoundDepth) + " levels deep (the limit)");
    }
    const JsonNode childrenNode = node.at("children");
    std::vector<Compound::Child> children;
    for (const JsonNode& child : childrenNode.elements()) {
      child.expectObject({"shape", "position", "rotation"});
      const JsonNode shapeNode = child.at("shape");
      Shape shape = readShape(shapeNode, context, compoundDepth + 1);
      if (shape.type() == ShapeType::Plane) shapeNode.fail("a compound child cannot be a plane");
      children.push_back({std::move(shape), readPlacement(child)});
    }
    if (children.empty()) childrenNode.fail("a compound needs at least one child");
    return withPath(node, [&] { return Shape(Compound::fromChildren(std::move(children))); });
  }
  node.at("type").fail(
      "unknown shape type " + node.at("type").shown() +
      " (expected sphere, capsule, plane, box, cylinder, ellipsoid, convex_hull, kdop, mesh or compound)");
}

void readSettings(const JsonNode& node, Scene& scene) {
  node.expectObject({"gravity", "dt", "steps", "substeps", "broadphase", "ccd", "sleeping",
                     "bounciness_combine", "friction_combine", "impact_model", "friction_model",
                     "penetration_response", "persist_events", "restitution_threshold", "workers"});
  WorldDef& w = scene.world;
  if (auto n = node.find("gravity")) w.gravity = n->vec3();
  if (auto n = node.find("dt")) {
    scene.dt = n->positive();
    if (scene.dt > kMaxDt) n->fail("must be at most " + shortNumber(kMaxDt) + " s, got " + n->shown());
  }
  if (auto n = node.find("steps")) scene.steps = n->integer(0, kMaxSteps);
  if (auto n = node.find("substeps")) w.substeps = n->integer(1, kMaxSubsteps);
  if (auto n = node.find("workers")) w.workerCount = n->integer(1, kMaxWorkers);
  if (auto n = node.find("broadphase")) {
    w.broadPhase.type = withPath(*n, [&] { return parseBroadPhaseType(n->string()); });
  }
  if (auto n = node.find("ccd")) scene.world.ccd = n->boolean();
  if (auto n = node.find("sleeping")) w.sleeping = n->boolean();
  if (auto n = node.find("persist_events")) w.persistEvents = n->boolean();
  if (auto n = node.find("restitution_threshold")) w.contact.restitutionThreshold = n->nonNegative();
  if (auto n = node.find("bounciness_combine")) {
    w.bouncinessCombine = withPath(*n, [&] { return parseCombineRule(n->string()); });
  }
  if (auto n = node.find("friction_combine")) {
    w.frictionCombine = withPath(*n, [&] { return parseCombineRule(n->string()); });
  }
  if (auto n = node.find("impact_model"))
    w.impactModel = withPath(*n, [&] { return parseImpactModel(n->string()); });
  if (auto n = node.find("friction_model")) {
    w.frictionModel = withPath(*n, [&] { return parseFrictionModel(n->string()); });
  }
  if (auto n = node.find("penetration_response")) {
    w.penetrationResponse = withPath(*n, [&] { return parsePenetrationResponse(n->string()); });
  }
}

Material readMaterial(const JsonNode& node) {
  node.expectObject({"bounciness", "friction", "rolling_resistance", "density"});
  Material m;
  if (auto n = node.find("bounciness")) m.bounciness = n->unitInterval();
  if (auto n = node.find("friction")) m.friction = n->nonNegative();
  if (auto n = node.find("rolling_resistance")) m.rollingResistance = n->nonNegative();
  if (auto n = node.find("density")) m.density = n->positive();
  return m;
}

BodyType readBodyType(const JsonNode& node) {
  const std::string name = node.string();
  if (name == "static") return BodyType::Static;
  if (name == "kinematic") return BodyType::Kinematic;
  if (name == "dynamic") return BodyType::Dynamic;
  node.fail("unknown body type " + node.shown() + " (expected static, kinematic or dynamic)");
}

const Material& namedMaterial(const JsonNode& n, const Scene& scene) {
  const auto it = scene.materials.find(n.string());
  if (it == scene.materials.end()) n.fail("unknown material " + n.shown());
  return it->second;
}

// A part of a body (docs/scene-format.md, "Parts"): its defaults are the body's own values (its
// material, friction, bounciness, rolling resistance, density, sensor flag, layer, mask and group),
// then the part's material, then the part's own fields.
PartDef readPart(const JsonNode& node, const BodyDef& body, const Scene& scene, const LoadContext& context) {
  node.expectObject({"shape", "position", "rotation", "material", "bounciness", "friction",
                     "rolling_resistance", "density", "sensor", "layer", "mask", "group"});
  PartDef part;
  const JsonNode shapeNode = node.at("shape");
  part.shape = readShape(shapeNode, context, 0);
  if (part.shape.type() == ShapeType::Plane)
    shapeNode.fail("a plane cannot be a part; make it a body of its own");
  if (part.shape.type() == ShapeType::Mesh && body.type == BodyType::Dynamic) {
    shapeNode.fail("a mesh part can only be on a static or kinematic body, got a dynamic body");
  }
  if (auto n = node.find("position")) part.position = n->vec3();
  if (auto n = node.find("rotation")) part.rotation = n->quaternion();
  part.material = {body.friction, body.bounciness, body.rollingResistance};
  part.density = body.density;
  part.sensor = body.sensor;
  part.layer = body.layer;
  part.mask = body.mask;
  part.group = body.group;
  if (auto n = node.find("material")) {
    const Material& m = namedMaterial(*n, scene);
    if (m.bounciness) part.material.bounciness = *m.bounciness;
    if (m.friction) part.material.friction = *m.friction;
    if (m.rollingResistance) part.material.rollingResistance = *m.rollingResistance;
    if (m.density) part.density = *m.density;
  }
  if (auto n = node.find("bounciness")) part.material.bounciness = n->unitInterval();
  if (auto n = node.find("friction")) part.material.friction = n->nonNegative();
  if (auto n = node.find("rolling_resistance")) part.material.rollingResistance = n->nonNegative();
  if (auto n = node.find("density")) part.density = n->nonNegative();
  if (auto n = node.find("sensor")) part.sensor = n->boolean();
  if (auto n = node.find("layer")) part.layer = n->bits();
  if (auto n = node.find("mask")) part.mask = n->bits();
  if (auto n = node.find("group")) part.group = n->integer(std::numeric_limits<int>::min());
  return part;
}

// A character (our extension, docs/scene-format.md): the capsule, its limits and its path.
SceneCharacter readCharacter(const JsonNode& node, const Scene& scene) {
  node.expectObject({"name", "position", "up", "radius", "half_height", "max_slope", "max_step_height",
                     "skin_width", "push_force", "mass", "gravity", "mask", "path"});
  SceneCharacter character;
  character.name = node.at("name").string();
  if (character.name.empty()) node.at("name").fail("must not be empty");
  CharacterDef& d = character.def;
  d.position = node.at("position").vec3();
  d.gravity = scene.world.gravity;
  if (auto n = node.find("up")) {
    d.up = n->vec3();
    if (!(glm::length(d.up) > 1e-6f)) n->fail("must be a non-zero direction, got " + n->shown());
    d.up = glm::normalize(d.up);
  }
  if (auto n = node.find("radius")) d.radius = n->positive();
  if (auto n = node.find("half_height")) d.halfHeight = n->nonNegative();
  if (auto n = node.find("max_slope")) {
    d.maxSlope = n->positive();
    if (!(d.maxSlope < 0.5f * kPi)) n->fail("must be in (0, pi/2) radians, got " + n->shown());
  }
  if (auto n = node.find("max_step_height")) d.maxStepHeight = n->nonNegative();
  if (auto n = node.find("skin_width")) d.skinWidth = n->positive();
  if (auto n = node.find("push_force")) d.pushForce = n->nonNegative();
  if (auto n = node.find("mass")) d.mass = n->positive();
  if (auto n = node.find("gravity")) d.gravity = n->vec3();
  if (auto n = node.find("mask")) d.filter.mask = n->bits();
  if (auto n = node.find("path")) {
    for (const JsonNode& w : n->elements()) {
      w.expectObject({"to", "speed", "jump"});
      SceneCharacter::Waypoint& waypoint = character.path.emplace_back();
      waypoint.to = w.at("to").vec3();
      if (auto speed = w.find("speed")) waypoint.speed = speed->positive();
      if (auto jump = w.find("jump")) waypoint.jump = jump->nonNegative();
    }
  }
  return character;
}

Body readBody(const JsonNode& node, const Scene& scene, const LoadContext& context) {
  node.expectObject({"name",
                     "type",
                     "shape",
                     "parts",
                     "position",
                     "rotation",
                     "scale",
                     "velocity",
                     "angular_velocity",
                     "mass",
                     "density",
                     "material",
                     "bounciness",
                     "friction",
                     "rolling_resistance",
                     "ccd",
                     "sensor",
                     "break_impulse",
                     "particle",
                     "layer",
                     "mask",
                     "group",
                     "gravity_scale",
                     "linear_damping",
                     "angular_damping"});
  Body body;
  BodyDef& d = body.def;
  d.name = node.at("name").string();
  if (d.name.empty()) node.at("name").fail("must not be empty");
  d.type = readBodyType(node.at("type"));
  if (node.has("shape") && node.has("parts")) node.at("parts").fail("give shape or parts, not both");
  if (!node.has("parts")) {
    const JsonNode shapeNode = node.at("shape");
    d.shape = readShape(shapeNode, context, 0);
    if (d.shape.type() == ShapeType::Plane && d.type != BodyType::Static) {
      shapeNode.fail("a plane can only be on a static body, got a " + std::string(toString(d.type)) +
                     " body");
    }
    if (d.shape.type() == ShapeType::Mesh && d.type == BodyType::Dynamic) {
      shapeNode.fail("a mesh can only be on a static or kinematic body, got a dynamic body");
    }
  }
  if (auto n = node.find("position")) d.position = n->vec3();
  if (auto n = node.find("rotation")) d.rotation = n->quaternion();
  if (auto n = node.find("scale")) d.scale = n->positive();
  if (auto n = node.find("velocity")) d.linearVelocity = n->vec3();
  if (auto n = node.find("angular_velocity")) d.angularVelocity = n->vec3();

  // Material values first, then the body's own.
  if (auto n = node.find("material")) {
    body.material = n->string();
    const Material& m = namedMaterial(*n, scene);
    if (m.bounciness) d.bounciness = *m.bounciness;
    if (m.friction) d.friction = *m.friction;
    if (m.rollingResistance) d.rollingResistance = *m.rollingResistance;
    if (m.density) d.density = *m.density;
  }
  if (node.has("mass") && node.has("density")) node.at("density").fail("give mass or density, not both");
  if (auto n = node.find("mass")) d.mass = n->positive();
  if (auto n = node.find("density")) d.density = n->positive();
  if (auto n = node.find("bounciness")) d.bounciness = n->unitInterval();
  if (auto n = node.find("friction")) d.friction = n->nonNegative();
  if (auto n = node.find("rolling_resistance")) d.rollingResistance = n->nonNegative();
  if (auto n = node.find("gravity_scale")) d.gravityScale = n->number();
  if (auto n = node.find("linear_damping")) d.linearDamping = n->nonNegative();
  if (auto n = node.find("angular_damping")) d.angularDamping = n->nonNegative();
  if (auto n = node.find("ccd")) body.def.ccd = n->boolean();
  if (auto n = node.find("sensor")) d.sensor = n->boolean();
  if (auto n = node.find("layer")) d.layer = n->bits();
  if (auto n = node.find("mask")) d.mask = n->bits();
  if (auto n = node.find("group")) d.group = n->integer(std::numeric_limits<int>::min());
  if (auto n = node.find("break_impulse")) body.breakImpulse = n->positive();
  // Our extension: a point mass (BodyDef::particle), the links of chains and nets.
  if (auto n = node.find("particle")) d.particle = n->boolean();
  if (auto partsNode = node.find("parts")) {
    if (d.particle) node.at("particle").fail("a particle is a point mass of one sphere and has no parts");
    const std::vector<JsonNode> elements = partsNode->elements();
    if (elements.empty()) partsNode->fail("must hold at least one part");
    bool anyMass = false;
    for (const JsonNode& partNode : elements) {
      d.parts.push_back(readPart(partNode, d, scene, context));
      anyMass = anyMass || d.parts.back().density > 0.0f;
    }
    if (d.type == BodyType::Dynamic && !anyMass)
      partsNode->fail("a dynamic body needs a part with density > 0");
  }
  if (d.particle) {
    const JsonNode n = node.at("particle");
    if (d.type != BodyType::Dynamic)
      n.fail("a particle must be a dynamic body, got a " + std::string(toString(d.type)) + " body");
    if (d.shape.type() != ShapeType::Sphere)
      n.fail("a particle's shape must be a sphere, got " + std::string(toString(d.shape.type())));
    if (d.angularVelocity != Vec3(0.0f))
      node.at("angular_velocity")
          .fail("a particle has no angular velocity, got " + node.at("angular_velocity").shown());
  }
  return body;
}

// A [lower, upper] pair of finite numbers, lower <= upper.
JointLimits readLimits(const JsonNode& n) {
  const std::vector<JsonNode> pair = n.elements();
  if (pair.size() != 2) n.fail("must be [lower, upper], got " + n.shown());
  const JointLimits limits{true, pair[0].number(), pair[1].number()};
  if (!(limits.lower <= limits.upper)) n.fail("lower must be <= upper, got " + n.shown());
  return limits;
}

Constraint readConstraint(const JsonNode& node, const std::map<std::string, std::size_t>& names,
                          const std::vector<Body>& bodies) {
  if (!node.value().is_object()) node.fail("must be a constraint object, got " + node.shown());
  const JsonNode typeNode = node.at("type");
  const std::string type = typeNode.string();
  static const std::map<std::string, JointType, std::less<>> kTypes = {
      {"distance", JointType::Distance}, {"ball", JointType::Ball},   {"hinge", JointType::Hinge},
      {"slider", JointType::Slider},     {"fixed", JointType::Fixed}, {"cone", JointType::Cone}};
  const auto known = kTypes.find(type);
  if (known == kTypes.end()) {
    typeNode.fail("unknown constraint type " + typeNode.shown() +
                  " (expected distance, ball, hinge, slider, fixed or cone)");
  }
  Constraint c;
  c.type = known->second;
  c.collideConnected = c.type == JointType::Distance;
  switch (c.type) {
    case JointType::Distance:
      node.expectObject({"type", "name", "a", "b", "anchor_a", "anchor_b", "length", "compliance", "limits",
                         "collide_connected", "break_force", "stiffness", "damping"});
      break;
    case JointType::Ball:
      node.expectObject({"type", "name", "a", "b", "anchor", "collide_connected", "break_force", "stiffness",
                         "damping", "friction"});
      break;
    case JointType::Hinge:
    case JointType::Slider:
      node.expectObject({"type", "name", "a", "b", "anchor", "axis", "limits", "motor", "collide_connected",
                         "break_force", "break_torque", "stiffness", "damping", "friction"});
      break;
    case JointType::Fixed:
      node.expectObject({"type", "name", "a", "b", "anchor", "collide_connected", "break_force",
                         "break_torque", "stiffness", "damping"});
      break;
    case JointType::Cone:
      node.expectObject({"type", "name", "a", "b", "anchor", "axis", "swing", "twist", "collide_connected",
                         "break_force", "break_torque", "stiffness", "damping", "friction"});
      break;
  }
  if (auto n = node.find("name")) c.name = n->string();
  for (const char* key : {"a", "b"}) {
    const JsonNode n = node.at(key);
    const std::string name = n.string();
    if (!names.contains(name)) n.fail("unknown body " + n.shown());
    (key[0] == 'a' ? c.a : c.b) = name;
  }
  if (c.a == c.b) node.at("b").fail("must differ from a, got " + node.at("b").shown());
  if (auto n = node.find("collide_connected")) c.collideConnected = n->boolean();
  if (auto n = node.find("break_force")) c.breakForce = n->positive();
  if (auto n = node.find("break_torque")) c.breakTorque = n->positive();
  if (auto n = node.find("stiffness")) c.softness.hertz = n->nonNegative();
  if (auto n = node.find("damping")) c.softness.dampingRatio = n->nonNegative();
  if (auto n = node.find("friction")) c.friction = n->nonNegative();
  if (c.type == JointType::Fixed) {
    if (auto n = node.find("anchor")) c.anchor = n->vec3();
    return c;
  }
  if (c.type != JointType::Distance) c.anchor = node.at("anchor").vec3();
  if (c.type == JointType::Hinge || c.type == JointType::Slider || c.type == JointType::Cone) {
    const JsonNode n = node.at("axis");
    c.axis = n.vec3();
    if (!(glm::length(c.axis) > 1e-6f)) n.fail("must be a non-zero direction, got " + n.shown());
  }
  if (auto n = node.find("limits")) c.limits = readLimits(*n);
  if (c.type == JointType::Hinge || c.type == JointType::Slider) {
    if (auto n = node.find("motor")) {
      const char* force = c.type == JointType::Hinge ? "max_torque" : "max_force";
      n->expectObject({"speed", force});
      c.motor = {true, n->at("speed").number(), n->at(force).nonNegative()};
    }
  }
  if (c.type == JointType::Cone) {
    if (auto n = node.find("swing")) {
      c.swing = n->nonNegative();
      if (c.swing > kPi) n->fail("must be within [0, pi], got " + n->shown());
    }
    if (auto n = node.find("twist")) c.limits = readLimits(*n);
  }
  if (c.type != JointType::Distance) return c;
  // A particle cannot turn, so an anchor off its centre would have no lever (the World refuses it).
  const auto readAnchor = [&](const char* key, const std::string& bodyName) -> std::optional<Vec3> {
    const auto n = node.find(key);
    if (!n) return std::nullopt;
    const Vec3 anchor = n->vec3();
    if (bodies[names.at(bodyName)].def.particle && anchor != Vec3(0.0f))
      n->fail("a particle's anchor must be its centre [0, 0, 0], got " + n->shown());
    return anchor;
  };
  c.anchorA = readAnchor("anchor_a", c.a);
  c.anchorB = readAnchor("anchor_b", c.b);
  if (auto n = node.find("length")) c.length = n->nonNegative();
  if (auto n = node.find("compliance")) c.compliance = n->nonNegative();
  if (c.compliance > 0.0f && c.softness.hertz > 0.0f)
    node.at("stiffness").fail("a distance constraint has one spring: stiffness or compliance, got both");
  if (c.limits.enabled && c.limits.lower < 0.0f)
    node.at("limits").fail("lengths must be >= 0, got " + node.at("limits").shown());
  return c;
}

// Line and column (1-based) of a byte offset, for messages about malformed JSON.
std::pair<std::size_t, std::size_t> lineColumn(std::string_view text, std::size_t offset) {
  std::size_t line = 1, column = 1;
  for (std::size_t i = 0; i < offset && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return {line, column};
}

// nlohmann's DOM builder behind a SAX handler that remembers where in the document it is, so that
// a parse error (a syntax error, or a number such as 1e999 that overflows a double) can name its
// line, column and, for a number, the field path. It also refuses what nlohmann's parser accepts
// silently: a key given twice in one object (nlohmann keeps the last), and nesting deeper than
// kMaxJsonDepth (nlohmann parses any depth, but copying, printing and freeing a value recurse).
class PathTrackingSax {
 public:
  using DomParser = nlohmann::detail::json_sax_dom_parser<Json>;
  explicit PathTrackingSax(Json& result) : dom_(result, false) {}

  bool null() { return value(), dom_.null(); }
  bool boolean(bool v) { return value(), dom_.boolean(v); }
  bool number_integer(Json::number_integer_t v) { return value(), dom_.number_integer(v); }
  bool number_unsigned(Json::number_unsigned_t v) { return value(), dom_.number_unsigned(v); }
  bool number_float(Json::number_float_t v, const std::string& s) { return value(), dom_.number_float(v, s); }
  bool string(std::string& v) { return value(), dom_.string(v); }
  bool binary(Json::binary_t& v) { return value(), dom_.binary(v); }
  bool start_object(std::size_t n) {
    value();
    if (!enter()) return false;
    frames_.push_back({false, 0, "", {}});
    return dom_.start_object(n);
  }
  bool key(std::string& k) {
    Frame& frame = frames_.back();
    frame.key = k;
    if (!frame.keys.insert(k).second) {
      refusal_ = "duplicate key: an object holds each key once";
      return false;
    }
    return dom_.key(k);
  }
  bool end_object() {
    frames_.pop_back();
    return dom_.end_object();
  }
  bool start_array(std::size_t n) {
    value();
    if (!enter()) return false;
    frames_.push_back({true, 0, "", {}});
    return dom_.start_array(n);
  }
  bool end_array() {
    frames_.pop_back();
    return dom_.end_array();
  }
  bool parse_error(std::size_t position, const std::string& token, const Json::exception& e) {
    position_ = position;
    token_ = token;
    what_ = e.what();
    numberOverflow_ = e.id == 406;
    return false;
  }

  // Where the pending value would go: the key just read, or the next array slot.
  std::string path() const {
    std::string out;
    for (std::size_t i = 0; i < frames_.size(); ++i) {
      const Frame& f = frames_[i];
      if (f.array) {
        out += "[" + std::to_string(i + 1 == frames_.size() ? f.count : f.count - 1) + "]";
      } else {
        out += (out.empty() ? "" : ".") + f.key;
      }
    }
    return out;
  }
  std::size_t position() const { return position_; }
  const std::string& token() const { return token_; }
  const std::string& what() const { return what_; }
  bool numberOverflow() const { return numberOverflow_; }
  // Why the handler stopped the parse (a duplicate key, too deep); empty after a parse error.
  const std::string& refusal() const { return refusal_; }

 private:
  struct Frame {
    bool array;
    std::size_t count;           // array elements started
    std::string key;             // object: the last key
    std::set<std::string> keys;  // object: every key so far
  };
  void value() {
    if (!frames_.empty() && frames_.back().array) ++frames_.back().count;
  }
  bool enter() {
    if (frames_.size() < static_cast<std::size_t>(kMaxJsonDepth)) return true;
    refusal_ =
        "arrays and objects nest more than " + std::to_string(kMaxJsonDepth) + " levels deep (the limit)";
    return false;
  }
  DomParser dom_;
  std::vector<Frame> frames_;
  std::size_t position_ = 0;
  std::string token_, what_, refusal_;
  bool numberOverflow_ = false;
};

// The parser's explanation without its prefix ("[json.exception.parse_error.101] parse error at
// line 1, column 2: "), the line and column being given separately, and with bytes that are not
// printable ASCII (the input's, quoted in "last read: ...") written as \xNN.
std::string parseExplanation(const std::string& what) {
  const std::size_t colon = what.find(": ");
  const std::string text = colon == std::string::npos ? what : what.substr(colon + 2);
  std::string out;
  for (const char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    if (c >= 0x20 && c < 0x7f) {
      out += ch;
    } else {
      static const char* const hex = "0123456789abcdef";
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  return out;
}

}  // namespace

Json parseDocument(std::string_view text, const std::string& source) {
  // nlohmann's parser takes a NUL byte for the end of the input and would ignore what follows it.
  if (const std::size_t nul = text.find('\0'); nul != std::string_view::npos) {
    const auto [line, column] = lineColumn(text, nul);
    throw Error(source + ": malformed JSON at line " + std::to_string(line) + ", column " +
                std::to_string(column) + ": a NUL byte (JSON text has none)");
  }
  Json document;
  PathTrackingSax sax(document);
  if (Json::sax_parse(text, &sax)) return document;
  if (!sax.refusal().empty()) {
    const std::string path = sax.path();
    throw Error(source + ": " + (path.empty() ? "" : path + ": ") + sax.refusal());
  }
  // nlohmann's position is one past the offending character.
  const auto [line, column] = lineColumn(text, sax.position() == 0 ? 0 : sax.position() - 1);
  const std::string where = "line " + std::to_string(line) + ", column " + std::to_string(column);
  if (sax.numberOverflow()) {
    throw Error(source + ": " + sax.path() + ": must be a finite number within float range, got " +
                sax.token() + " (" + where + ")");
  }
  throw Error(source + ": malformed JSON at " + where + ": " + parseExplanation(sax.what()));
}

Scene parseScene(std::string_view text, std::string_view sourceName, const std::filesystem::path& baseDir,
                 const LoadOptions& options) {
  Json document = parseDocument(text, std::string(sourceName));
  return readSceneDocument(document, sourceName, baseDir, options);
}

Scene readSceneDocument(Json& document, std::string_view sourceName, const std::filesystem::path& baseDir,
                        const LoadOptions& options) {
  Scene scene;
  scene.source = sourceName;
  const JsonNode root(document, scene.source);
  const LoadContext context{baseDir, options, &scene.objFiles};
  if (!document.is_object()) root.fail("a scene must be a JSON object, got " + root.shown());
  root.expectObject({"format", "settings", "materials", "bodies", "constraints", "characters"});
  const JsonNode format = root.at("format");
  if (format.string() != kFormat)
    format.fail("must be \"" + std::string(kFormat) + "\", got " + format.shown());

  if (auto n = root.find("settings")) readSettings(*n, scene);
  if (auto n = root.find("materials")) {
    if (!n->value().is_object()) n->fail("must be an object mapping names to materials, got " + n->shown());
    for (const auto& [name, unused] : n->value().items())
      scene.materials[name] = readMaterial(*n->find(name));
  }
  std::map<std::string, std::size_t> names;
  if (auto n = root.find("bodies")) {
    if (n->value().is_array() && n->value().size() > kMaxBodies) {
      n->fail("holds " + std::to_string(n->value().size()) + " bodies, more than the limit of " +
              std::to_string(kMaxBodies));
    }
    const std::vector<JsonNode> bodies = n->elements();
    Json& bodiesJson = document.at("bodies");  // the same array, to free each body's JSON once read
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      const JsonNode& b = bodies[i];
      Body body = readBody(b, scene, context);
      const auto [it, inserted] = names.emplace(body.def.name, scene.bodies.size());
      if (!inserted) {
        b.at("name").fail("duplicate name " + b.at("name").shown() + " (also bodies[" +
                          std::to_string(it->second) + "])");
      }
      // The body holds what its JSON said (a hull's points are a hull now): the JSON goes, so that
      // the bodies built next reuse its memory instead of the scene being held twice.
      bodiesJson[i] = nullptr;
      body.def.userData = scene.bodies.size();
      scene.bodies.push_back(std::move(body));
    }
  }
  if (auto n = root.find("constraints")) {
    for (const JsonNode& c : n->elements())
      scene.constraints.push_back(readConstraint(c, names, scene.bodies));
  }
  if (auto n = root.find("characters")) {
    std::map<std::string, std::size_t> characterNames;
    for (const JsonNode& c : n->elements()) {
      SceneCharacter character = readCharacter(c, scene);
      const auto [it, inserted] = characterNames.emplace(character.name, scene.characters.size());
      if (!inserted)
        c.at("name").fail("duplicate name " + c.at("name").shown() + " (also characters[" +
                          std::to_string(it->second) + "])");
      scene.characters.push_back(std::move(character));
    }
  }
  return scene;
}

void normalizeIntegers(Json& document) {
  if (document.is_number_integer() && !document.is_number_unsigned()) {
    const auto value = document.get<std::int64_t>();
    if (value >= 0) document = static_cast<std::uint64_t>(value);
  } else if (document.is_structured()) {
    for (Json& element : document) normalizeIntegers(element);
  }
}

Scene loadSceneFile(const std::filesystem::path& path, const LoadOptions& options) {
  const std::string text = readFileText(path, kMaxSceneFileBytes, "scene file " + path.string());
  Scene scene =
      parseScene(text, path.string(), path.parent_path().empty() ? "." : path.parent_path(), options);
  scene.file = path;
  return scene;
}

Shape parseShape(std::string_view text, std::string_view sourceName, const std::filesystem::path& baseDir,
                 const LoadOptions& options) {
  const std::string source(sourceName);
  const Json document = parseDocument(text, source);
  const JsonNode root(document, source);
  std::vector<std::filesystem::path> objFiles;
  const LoadContext context{baseDir, options, &objFiles};
  return readShape(root, context, 0);
}

Shape loadShapeFile(const std::filesystem::path& path, const LoadOptions& options) {
  const std::string text = readFileText(path, kMaxSceneFileBytes, "shape file " + path.string());
  return parseShape(text, path.string(), path.parent_path().empty() ? "." : path.parent_path(), options);
}

}  // namespace collide::scene
