// The JavaScript bindings of collide's WebAssembly build (embind; docs/web.md). One class, World,
// holds a world and its bodies in creation order (a scene's world too: World.fromScene), with the
// step, bodies, joints, queries, events, snapshots and what a renderer needs (every body's pose in
// one Float32Array, each shape's geometry, contact points, bounds). Vectors are arrays [x, y, z];
// rotations are [x, y, z, w], the order of three.js's Quaternion.fromArray. A collide::Error becomes
// a JavaScript Error with the library's message.
#include <collide/character.h>
#include <collide/collide.h>
#include <collide/scene/builtin_scenes.h>
#include <collide/scene/runner.h>
#include <collide/scene/scene.h>
#include <collide/version.h>

#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <chrono>
#include <cstdio>
#include <deque>
#include <string>
#include <vector>

using namespace emscripten;

namespace collide::web {
namespace {

// Runs f, turning a C++ exception into a JavaScript Error with its message.
template <typename F>
auto guarded(F&& f) -> decltype(f()) {
  std::string message;
  try {
    return f();
  } catch (const std::exception& e) {
    message = e.what();
  }
  val::global("Error").new_(message).throw_();
}

// ---- Values in and out ----

val array3(const Vec3& v) {
  val out = val::array();
  out.set(0, v.x);
  out.set(1, v.y);
  out.set(2, v.z);
  return out;
}

// An [x, y, z] array (or an object with x, y, z), a fallback when undefined; refused otherwise.
Vec3 vec3(const val& v, const Vec3& fallback, const char* what) {
  if (v.isUndefined() || v.isNull()) return fallback;
  if (v.hasOwnProperty("x")) return Vec3(v["x"].as<float>(), v["y"].as<float>(), v["z"].as<float>());
  if (!v.isArray() && !v.instanceof (val::global("Float32Array")) && !v.instanceof
      (val::global("Float64Array")))
    throw Error(std::string(what) + ": must be an array [x, y, z]");
  if (v["length"].as<int>() != 3) throw Error(std::string(what) + ": must have 3 numbers");
  return Vec3(v[0].as<float>(), v[1].as<float>(), v[2].as<float>());
}

// [x, y, z, w] (three.js order) or {x, y, z, w}.
Quat quat(const val& v, const char* what) {
  if (v.isUndefined() || v.isNull()) return Quat(1, 0, 0, 0);
  if (v.hasOwnProperty("w"))
    return Quat(v["w"].as<float>(), v["x"].as<float>(), v["y"].as<float>(), v["z"].as<float>());
  if (!v.isArray() || v["length"].as<int>() != 4)
    throw Error(std::string(what) + ": must be an array [x, y, z, w]");
  return Quat(v[3].as<float>(), v[0].as<float>(), v[1].as<float>(), v[2].as<float>());
}

template <typename T>
T field(const val& object, const char* name, T fallback) {
  if (object.isUndefined() || object.isNull()) return fallback;
  const val v = object[name];
  return v.isUndefined() || v.isNull() ? fallback : v.as<T>();
}

std::vector<Vec3> points(const val& flat, const char* what) {
  const std::vector<float> xyz = convertJSArrayToNumberVector<float>(flat);
  if (xyz.size() % 3 != 0)
    throw Error(std::string(what) + ": needs 3 numbers per point, got " + std::to_string(xyz.size()));
  std::vector<Vec3> out;
  for (std::size_t i = 0; i < xyz.size(); i += 3) out.emplace_back(xyz[i], xyz[i + 1], xyz[i + 2]);
  return out;
}

// Body and joint ids as { index, generation } objects, and back (`what` names the id in errors).
template <typename Id>
val idValue(Id id) {
  val out = val::object();
  out.set("index", id.index);
  out.set("generation", id.generation);
  return out;
}
template <typename Id>
Id idOf(const val& v, const char* what) {
  if (v.isUndefined() || v.isNull() || !v.hasOwnProperty("index"))
    throw Error(std::string(what) + ": must be a " + what + " id {index, generation}");
  return Id{v["index"].as<std::uint32_t>(), v["generation"].as<std::uint32_t>()};
}
val bodyIdValue(BodyId id) { return idValue(id); }
BodyId bodyId(const val& v) { return idOf<BodyId>(v, "body"); }

// A copy of `values` as a JavaScript typed array of `type` ("Float32Array", "Uint32Array", ...).
template <typename T>
val typedArray(const char* type, const std::vector<T>& values) {
  return val::global(type).new_(typed_memory_view(values.size(), values.data()));
}

// The hash `collide run` prints, as 16 hex digits (a 64-bit number does not fit a JS number).
std::string hashText(std::uint64_t hash) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash));
  return text;
}

// A scene document (JSON text) or the name of a built-in scene.
scene::Scene sceneOf(const std::string& nameOrJson) {
  return nameOrJson.find('{') != std::string::npos ? scene::parseScene(nameOrJson, "scene")
                                                   : scene::loadBuiltinScene(nameOrJson);
}

// ---- Shapes ----

Shape makeSphere(float radius) {
  return guarded([&] { return Shape(Sphere{radius}); });
}
Shape makeCapsule(float radius, float halfHeight) {
  return guarded([&] { return Shape(Capsule{radius, halfHeight}); });
}
Shape makeBox(val halfExtents) {
  return guarded([&] { return Shape(Box{vec3(halfExtents, Vec3(0.5f), "halfExtents")}); });
}
Shape makePlane(val normal, float distance) {
  return guarded([&] { return Shape(Plane{vec3(normal, Vec3(0, 1, 0), "normal"), distance}); });
}
Shape makeEllipsoid(val radii) {
  return guarded([&] { return Shape(Ellipsoid{vec3(radii, Vec3(0.5f), "radii")}); });
}
Shape makeCylinder(float radius, float halfHeight) {
  return guarded([&] { return Shape(Cylinder{radius, halfHeight}); });
}
Shape makeConvexHull(val flatPoints) {
  return guarded([&] { return Shape(ConvexHull::fromPoints(points(flatPoints, "points"))); });
}
Shape makeMesh(val flatVertices, val indices) {
  return guarded([&] {
    std::vector<Vec3> v = points(flatVertices, "vertices");
    const std::vector<std::uint32_t> index = convertJSArrayToNumberVector<std::uint32_t>(indices);
    if (index.size() % 3 != 0) throw Error("indices: needs 3 per triangle");
    std::vector<MeshTriangle> t(index.size() / 3);
    for (std::size_t i = 0; i < index.size(); ++i) {
      if (index[i] >= v.size())
        throw Error("indices[" + std::to_string(i) + "]: " + std::to_string(index[i]) + " is not a vertex");
      t[i / 3].v[i % 3] = index[i];
    }
    return Shape(TriangleMesh::fromTriangles(std::move(v), std::move(t)));
  });
}
Shape parseShapeJson(const std::string& json) {
  return guarded([&] { return scene::parseShape(json, "shape"); });
}

std::string shapeType(const Shape& s) { return std::string(toString(s.type())); }

// The triangles of a polyhedron's faces (fans), local frame.
void hullTriangles(const ConvexHull& hull, std::vector<float>& vertices,
                   std::vector<std::uint32_t>& indices) {
  for (const Vec3& v : hull.vertices()) vertices.insert(vertices.end(), {v.x, v.y, v.z});
  for (const ConvexHull::Face& face : hull.faces()) {
    std::uint32_t edge = face.firstEdge;
    const std::uint32_t first = hull.halfEdges()[edge].origin;
    edge = hull.halfEdges()[edge].next;
    for (std::uint32_t i = 1; i + 1 < face.edgeCount; ++i) {
      const std::uint32_t b = hull.halfEdges()[edge].origin;
      edge = hull.halfEdges()[edge].next;
      indices.insert(indices.end(), {first, b, hull.halfEdges()[edge].origin});
    }
  }
}

// What a renderer needs to draw a shape: its type and sizes, or vertices and triangle indices for
// polyhedra and meshes, or its children with their poses for a compound.
val shapeGeometry(const Shape& s) {
  val out = val::object();
  out.set("type", shapeType(s));
  std::vector<float> vertices;
  std::vector<std::uint32_t> indices;
  switch (s.type()) {
    case ShapeType::Sphere:
      out.set("radius", s.sphere().radius);
      break;
    case ShapeType::Capsule:
      out.set("radius", s.capsule().radius);
      out.set("halfHeight", s.capsule().halfHeight);
      break;
    case ShapeType::Cylinder:
      out.set("radius", s.cylinder().radius);
      out.set("halfHeight", s.cylinder().halfHeight);
      break;
    case ShapeType::Box:
      out.set("halfExtents", array3(s.box().halfExtents));
      break;
    case ShapeType::Ellipsoid:
      out.set("radii", array3(s.ellipsoid().radii));
      break;
    case ShapeType::Plane:
      out.set("normal", array3(s.plane().normal));
      out.set("distance", s.plane().distance);
      break;
    case ShapeType::ConvexHull:
      hullTriangles(s.convexHull(), vertices, indices);
      out.set("faceCount", static_cast<int>(s.convexHull().faces().size()));
      break;
    case ShapeType::Kdop:
      hullTriangles(s.kdop().polytope(), vertices, indices);
      break;
    case ShapeType::Mesh:
      for (const Vec3& v : s.mesh().vertices()) vertices.insert(vertices.end(), {v.x, v.y, v.z});
      for (const MeshTriangle& t : s.mesh().triangles())
        indices.insert(indices.end(), {t.v[0], t.v[1], t.v[2]});
      break;
    case ShapeType::Compound: {
      val children = val::array();
      int i = 0;
      for (const Compound::Child& child : s.compound().children()) {
        val c = shapeGeometry(child.shape);
        c.set("position", array3(child.transform.position));
        const Quat q = child.transform.rotation;
        val r = val::array();
        r.set(0, q.x);
        r.set(1, q.y);
        r.set(2, q.z);
        r.set(3, q.w);
        c.set("rotation", r);
        c.set("scale", child.transform.scale);
        children.set(i++, c);
      }
      out.set("children", children);
      break;
    }
  }
  if (!vertices.empty()) {
    out.set("vertices", typedArray("Float32Array", vertices));
    out.set("indices", typedArray("Uint32Array", indices));
  }
  return out;
}

// ---- The world ----

BodyType bodyType(const std::string& name) {
  if (name == "static") return BodyType::Static;
  if (name == "kinematic") return BodyType::Kinematic;
  if (name == "dynamic") return BodyType::Dynamic;
  throw Error("type: must be \"static\", \"kinematic\" or \"dynamic\", got \"" + name + "\"");
}

class JsWorld {
 public:
  explicit JsWorld(const val& options) {
    guarded([&] {
      WorldDef def;
      if (!options.isUndefined() && !options.isNull()) {
        def.gravity = vec3(options["gravity"], def.gravity, "gravity");
        def.substeps = field<int>(options, "substeps", def.substeps);
        if (options.hasOwnProperty("impactModel"))
          def.impactModel = parseImpactModel(options["impactModel"].as<std::string>());
        if (options.hasOwnProperty("bouncinessCombine"))
          def.bouncinessCombine = parseCombineRule(options["bouncinessCombine"].as<std::string>());
        if (options.hasOwnProperty("frictionCombine"))
          def.frictionCombine = parseCombineRule(options["frictionCombine"].as<std::string>());
        if (options.hasOwnProperty("frictionModel"))
          def.frictionModel = parseFrictionModel(options["frictionModel"].as<std::string>());
        if (options.hasOwnProperty("penetrationResponse"))
          def.penetrationResponse =
              parsePenetrationResponse(options["penetrationResponse"].as<std::string>());
        def.sleeping = field<bool>(options, "sleeping", def.sleeping);
        def.ccd = field<bool>(options, "ccd", def.ccd);
      }
      scene_.world = World(def);
      return 0;
    });
  }
  explicit JsWorld(scene::Scene scene) : dt_(scene.dt), steps_(scene.steps), source_(scene.source) {
    scene_ = scene::buildWorld(scene);
    for (const scene::SceneCharacter& c : scene.characters) {
      sceneCharacters_.push_back(c);  // a deque: the paths keep pointers to them
      walkers_.push_back({Character(c.def), scene::CharacterPath(sceneCharacters_.back())});
    }
  }

  static JsWorld* fromScene(const std::string& nameOrJson) {
    return guarded([&] { return new JsWorld(sceneOf(nameOrJson)); });
  }

  World& world() { return scene_.world; }

  val createBody(const val& d) {
    return guarded([&] {
      BodyDef def;
      const val shape = d["shape"];
      if (shape.isUndefined() || shape.isNull()) throw Error("shape: missing");
      def.shape = shape.as<Shape>();
      if (d.hasOwnProperty("type")) def.type = bodyType(d["type"].as<std::string>());
      def.position = vec3(d["position"], def.position, "position");
      def.rotation = quat(d["rotation"], "rotation");
      def.scale = field<float>(d, "scale", def.scale);
      def.linearVelocity = vec3(d["velocity"], def.linearVelocity, "velocity");
      def.angularVelocity = vec3(d["angularVelocity"], def.angularVelocity, "angularVelocity");
      if (d.hasOwnProperty("mass")) def.mass = d["mass"].as<float>();
      def.density = field<float>(d, "density", def.density);
      def.bounciness = field<float>(d, "bounciness", def.bounciness);
      def.friction = field<float>(d, "friction", def.friction);
      def.gravityScale = field<float>(d, "gravityScale", def.gravityScale);
      def.linearDamping = field<float>(d, "linearDamping", def.linearDamping);
      def.angularDamping = field<float>(d, "angularDamping", def.angularDamping);
      def.sensor = field<bool>(d, "sensor", def.sensor);
      def.ccd = field<bool>(d, "ccd", def.ccd);
      if (d.hasOwnProperty("name")) def.name = d["name"].as<std::string>();
      const BodyId id = scene_.world.createBody(def);
      scene_.bodies.push_back(id);
      return bodyIdValue(id);
    });
  }
  void destroyBody(const val& id) {
    guarded([&] {
      const BodyId body = bodyId(id);
      scene_.world.destroyBody(body);
      std::erase(scene_.bodies, body);
      return 0;
    });
  }
  bool isValid(const val& id) {
    return guarded([&] { return scene_.world.isValid(bodyId(id)); });
  }
  int bodyCount() const { return static_cast<int>(scene_.bodies.size()); }
  // The bodies in creation order (a scene's in the file's order).
  val bodies() const {
    val out = val::array();
    for (std::size_t i = 0; i < scene_.bodies.size(); ++i) out.set(i, bodyIdValue(scene_.bodies[i]));
    return out;
  }

  // Steps; returns the milliseconds they took.
  double step(float dt, int count) {
    return guarded([&] {
      const auto start = std::chrono::steady_clock::now();
      for (int i = 0; i < count; ++i) scene_.world.step(dt);
      return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    });
  }
  float sceneDt() const { return dt_; }
  int sceneSteps() const { return steps_; }
  std::string source() const { return source_; }

  // One body.
  std::string type(const val& id) {
    return guarded([&] { return std::string(toString(scene_.world.type(bodyId(id)))); });
  }
  std::string name(const val& id) {
    return guarded([&] { return scene_.world.name(bodyId(id)); });
  }
  val position(const val& id) {
    return guarded([&] { return array3(scene_.world.transform(bodyId(id)).position); });
  }
  val rotation(const val& id) {
    return guarded([&] {
      const Quat q = scene_.world.transform(bodyId(id)).rotation;
      val out = val::array();
      out.set(0, q.x);
      out.set(1, q.y);
      out.set(2, q.z);
      out.set(3, q.w);
      return out;
    });
  }
  val velocity(const val& id) {
    return guarded([&] { return array3(scene_.world.linearVelocity(bodyId(id))); });
  }
  val angularVelocity(const val& id) {
    return guarded([&] { return array3(scene_.world.angularVelocity(bodyId(id))); });
  }
  void setPose(const val& id, const val& position, const val& rotation) {
    guarded([&] {
      const BodyId body = bodyId(id);
      scene_.world.setTransform(body, vec3(position, Vec3(0.0f), "position"), quat(rotation, "rotation"));
      return 0;
    });
  }
  void setVelocity(const val& id, const val& v) {
    guarded([&] {
      scene_.world.setLinearVelocity(bodyId(id), vec3(v, Vec3(0.0f), "velocity"));
      return 0;
    });
  }
  void setAngularVelocity(const val& id, const val& v) {
    guarded([&] {
      scene_.world.setAngularVelocity(bodyId(id), vec3(v, Vec3(0.0f), "angularVelocity"));
      return 0;
    });
  }
  void applyImpulse(const val& id, const val& impulse, const val& point) {
    guarded([&] {
      scene_.world.applyImpulse(bodyId(id), vec3(impulse, Vec3(0.0f), "impulse"),
                                vec3(point, Vec3(0.0f), "point"));
      return 0;
    });
  }
  float mass(const val& id) {
    return guarded([&] { return scene_.world.mass(bodyId(id)); });
  }
  Shape shape(const val& id) {
    return guarded([&] { return scene_.world.shape(bodyId(id)); });
  }
  float scale(const val& id) {
    return guarded([&] { return scene_.world.transform(bodyId(id)).scale; });
  }
  bool isAwake(const val& id) {
    return guarded([&] { return scene_.world.isAwake(bodyId(id)); });
  }

  // Every body's pose at once, in bodies() order: positions (x, y, z) and rotations (x, y, z, w).
  val positions() const {
    buffer_.clear();
    for (BodyId id : scene_.bodies) {
      const Vec3 p = scene_.world.transform(id).position;
      buffer_.insert(buffer_.end(), {p.x, p.y, p.z});
    }
    return typedArray("Float32Array", buffer_);
  }
  val rotations() const {
    buffer_.clear();
    for (BodyId id : scene_.bodies) {
      const Quat q = scene_.world.transform(id).rotation;
      buffer_.insert(buffer_.end(), {q.x, q.y, q.z, q.w});
    }
    return typedArray("Float32Array", buffer_);
  }
  val velocities() const {
    buffer_.clear();
    for (BodyId id : scene_.bodies) {
      const Vec3 v = scene_.world.linearVelocity(id);
      buffer_.insert(buffer_.end(), {v.x, v.y, v.z});
    }
    return typedArray("Float32Array", buffer_);
  }
  // Each body's world box: minX, minY, minZ, maxX, maxY, maxZ.
  val bounds() const {
    buffer_.clear();
    for (BodyId id : scene_.bodies) {
      const Aabb box = worldBounds(scene_.world.shape(id), scene_.world.transform(id));
      buffer_.insert(buffer_.end(), {box.min.x, box.min.y, box.min.z, box.max.x, box.max.y, box.max.z});
    }
    return typedArray("Float32Array", buffer_);
  }
  // Every touching contact point: x, y, z, then the normal's x, y, z.
  val contactPoints() const {
    buffer_.clear();
    scene_.world.visitContacts([&](const ContactData& contact) {
      for (int i = 0; i < contact.manifold.count; ++i) {
        const Vec3 p = 0.5f * (contact.manifold.points[i].pointOnA + contact.manifold.points[i].pointOnB);
        const Vec3 n = contact.manifold.normal;
        buffer_.insert(buffer_.end(), {p.x, p.y, p.z, n.x, n.y, n.z});
      }
    });
    return typedArray("Float32Array", buffer_);
  }

  val linearMomentum() const { return array3(scene_.world.linearMomentum()); }
  float kineticEnergy() const { return scene_.world.kineticEnergy(); }
  std::string stateHash() const { return hashText(scene::stateHash(scene_)); }

  // Joints.
  val createDistanceJoint(const val& a, const val& b) {
    return guarded([&] {
      DistanceConstraintDef def;
      def.a = bodyId(a);
      def.b = bodyId(b);
      const JointId id = scene_.world.createDistanceConstraint(def);
      return jointValue(id);
    });
  }
  val createBallJoint(const val& a, const val& b, const val& anchor) {
    return guarded([&] {
      BallJointDef def;
      def.a = bodyId(a);
      def.b = bodyId(b);
      def.anchor = vec3(anchor, Vec3(0.0f), "anchor");
      return jointValue(scene_.world.createBallJoint(def));
    });
  }
  // options: { limits: [lower, upper], motor: [speed, maxForce], collideConnected, breakForce }.
  val createHingeJoint(const val& a, const val& b, const val& anchor, const val& axis, const val& options) {
    return guarded([&] {
      return jointValue(scene_.world.createHingeJoint(
          axisJointDef<HingeJointDef>(a, b, anchor, axis, options, Vec3(0, 0, 1))));
    });
  }
  val createSliderJoint(const val& a, const val& b, const val& anchor, const val& axis, const val& options) {
    return guarded([&] {
      return jointValue(scene_.world.createSliderJoint(
          axisJointDef<SliderJointDef>(a, b, anchor, axis, options, Vec3(1, 0, 0))));
    });
  }
  val createFixedJoint(const val& a, const val& b, const val& options) {
    return guarded(
        [&] { return jointValue(scene_.world.createFixedJoint(jointDef<FixedJointDef>(a, b, options))); });
  }
  // options: { swingLimit (radians), twistLimits: [lower, upper], collideConnected, breakForce }.
  val createConeJoint(const val& a, const val& b, const val& anchor, const val& axis, const val& options) {
    return guarded([&] {
      ConeJointDef def = jointDef<ConeJointDef>(a, b, options);
      def.anchor = vec3(anchor, Vec3(0.0f), "anchor");
      def.axis = vec3(axis, Vec3(1, 0, 0), "axis");
      def.swingLimit = field<float>(options, "swingLimit", kPi);
      def.twistLimits = limitsOf(options, "twistLimits");
      return jointValue(scene_.world.createConeJoint(def));
    });
  }
  float jointPosition(const val& joint) {
    return guarded([&] { return scene_.world.jointPosition(jointId(joint)); });
  }
  float jointSpeed(const val& joint) {
    return guarded([&] { return scene_.world.jointSpeed(jointId(joint)); });
  }
  void destroyJoint(const val& joint) {
    guarded([&] {
      scene_.world.destroyConstraint(jointId(joint));
      return 0;
    });
  }
  val jointBreakEvents() const {
    val out = val::array();
    int i = 0;
    for (const JointBreakEvent& e : scene_.world.jointBreakEvents()) {
      val event = val::object();
      event.set("joint", jointValue(e.joint));
      event.set("a", bodyIdValue(e.a));
      event.set("b", bodyIdValue(e.b));
      event.set("force", e.force);
      event.set("torque", e.torque);
      out.set(i++, event);
    }
    return out;
  }
  int jointCount() const { return static_cast<int>(scene_.world.constraintCount()); }

  // Events of the last step.
  val contactEvents() const {
    val out = val::array();
    int i = 0;
    for (const ContactEvent& e : scene_.world.contactEvents()) {
      val event = val::object();
      event.set("type", std::string(e.type == ContactEvent::Type::Begin     ? "begin"
                                    : e.type == ContactEvent::Type::Persist ? "persist"
                                                                            : "end"));
      event.set("a", bodyIdValue(e.a));
      event.set("b", bodyIdValue(e.b));
      event.set("point", array3(e.point));
      event.set("normal", array3(e.normal));
      event.set("impulse", e.impulse);
      event.set("speed", e.speed);
      out.set(i++, event);
    }
    return out;
  }

  // Queries.
  val castRay(const val& origin, const val& direction, float maxDistance) {
    return guarded([&] {
      const std::optional<RayCastResult> hit = scene_.world.castRay(
          Ray{vec3(origin, Vec3(0.0f), "origin"), vec3(direction, Vec3(0, 0, 1), "direction"), maxDistance});
      if (!hit) return val::null();
      val out = val::object();
      out.set("body", bodyIdValue(hit->body));
      out.set("distance", hit->distance);
      out.set("point", array3(hit->point));
      out.set("normal", array3(hit->normal));
      return out;
    });
  }
  val castShape(const Shape& shape, const val& position, const val& translation) {
    return guarded([&] {
      const std::optional<ShapeCastResult> hit = scene_.world.castShape(
          shape, Transform{vec3(position, Vec3(0.0f), "position"), Quat(1, 0, 0, 0), 1.0f},
          vec3(translation, Vec3(0.0f), "translation"));
      if (!hit) return val::null();
      val out = val::object();
      out.set("body", bodyIdValue(hit->body));
      out.set("fraction", hit->fraction);
      out.set("distance", hit->distance);
      out.set("point", array3(hit->point));
      out.set("normal", array3(hit->normal));
      return out;
    });
  }
  val overlapShape(const Shape& shape, const val& position) {
    return guarded([&] {
      val out = val::array();
      int i = 0;
      for (const OverlapResult& r : scene_.world.overlapShape(
               shape, Transform{vec3(position, Vec3(0.0f), "position"), Quat(1, 0, 0, 0), 1.0f}))
        out.set(i++, bodyIdValue(r.body));
      return out;
    });
  }
  bool hasLineOfSight(const val& from, const val& to) {
    return guarded([&] {
      return scene_.world.hasLineOfSight(vec3(from, Vec3(0.0f), "from"), vec3(to, Vec3(0.0f), "to"));
    });
  }

  // The scene's characters (docs/character.md): after each step, each walks its path, or the first
  // walks at `playerWalk` ([x, y, z] m/s; its part along up a jump) when one is given.
  int characterCount() const { return static_cast<int>(walkers_.size()); }
  void updateCharacters(float dt, const val& playerWalk) {
    guarded([&] {
      for (std::size_t i = 0; i < walkers_.size(); ++i) {
        Walker& w = walkers_[i];
        const bool player = i == 0 && !playerWalk.isUndefined() && !playerWalk.isNull();
        const Vec3 walk =
            player ? vec3(playerWalk, Vec3(0.0f), "playerWalk") : w.path.nextVelocity(w.character, dt);
        w.character.update(scene_.world, walk, dt);
      }
      return 0;
    });
  }
  // Each character's capsule: centre x, y, z, radius, half height, and whether it stands (1) or not.
  val characters() const {
    buffer_.clear();
    for (const Walker& w : walkers_) {
      const Vec3 p = w.character.position();
      buffer_.insert(buffer_.end(), {p.x, p.y, p.z, w.character.radius(), w.character.halfHeight(),
                                     w.character.isOnGround() ? 1.0f : 0.0f});
    }
    return typedArray("Float32Array", buffer_);
  }

  // Snapshots (docs/snapshots.md) as Uint8Arrays.
  val saveSnapshot() const {
    snapshot_ = scene_.world.saveSnapshot();
    return typedArray("Uint8Array", snapshot_);
  }
  void loadSnapshot(const val& bytes) {
    guarded([&] {
      const std::vector<std::uint8_t> data = convertJSArrayToNumberVector<std::uint8_t>(bytes);
      scene_.world.loadSnapshot(data);
      return 0;
    });
  }

 private:
  static JointId jointId(const val& v) { return idOf<JointId>(v, "joint"); }
  static val jointValue(JointId id) { return idValue(id); }

  // What every joint definition with options has: its bodies, collideConnected and breakForce.
  template <typename Def>
  static Def jointDef(const val& a, const val& b, const val& options) {
    Def def;
    def.a = bodyId(a);
    def.b = bodyId(b);
    def.collideConnected = field<bool>(options, "collideConnected", false);
    def.breakForce = field<float>(options, "breakForce", kUnbreakable);
    return def;
  }
  // And a hinge's or a slider's: the anchor, the axis, limits and a motor.
  template <typename Def>
  static Def axisJointDef(const val& a, const val& b, const val& anchor, const val& axis, const val& options,
                          const Vec3& defaultAxis) {
    Def def = jointDef<Def>(a, b, options);
    def.anchor = vec3(anchor, Vec3(0.0f), "anchor");
    def.axis = vec3(axis, defaultAxis, "axis");
    def.limits = limitsOf(options, "limits");
    def.motor = motorOf(options);
    return def;
  }
  static JointLimits limitsOf(const val& options, const char* name) {
    if (options.isUndefined() || options.isNull() || !options.hasOwnProperty(name)) return {};
    const val pair = options[name];
    if (!pair.isArray() || pair["length"].as<int>() != 2)
      throw Error(std::string(name) + ": must be [lower, upper]");
    return JointLimits{true, pair[0].as<float>(), pair[1].as<float>()};
  }
  static JointMotor motorOf(const val& options) {
    if (options.isUndefined() || options.isNull() || !options.hasOwnProperty("motor")) return {};
    const val pair = options["motor"];
    if (!pair.isArray() || pair["length"].as<int>() != 2) throw Error("motor: must be [speed, maxForce]");
    return JointMotor{true, pair[0].as<float>(), pair[1].as<float>()};
  }

  struct Walker {
    Character character;
    scene::CharacterPath path;
  };
  scene::SceneWorld scene_;
  std::deque<scene::SceneCharacter> sceneCharacters_;
  std::vector<Walker> walkers_;
  float dt_ = 1.0f / 60.0f;
  int steps_ = 600;
  std::string source_ = "api";
  mutable std::vector<float> buffer_;  // behind the typed arrays returned (copied by new_)
  mutable std::vector<std::uint8_t> snapshot_;
};

JsWorld* makeWorld(val options) { return new JsWorld(options); }

// A character of the game's own (docs/character.md): options position, radius, halfHeight,
// maxSlope, maxStepHeight, skinWidth, pushForce, mass.
Character* makeCharacter(val options) {
  return guarded([&] {
    CharacterDef def;
    def.position = vec3(options["position"], def.position, "position");
    def.radius = field<float>(options, "radius", def.radius);
    def.halfHeight = field<float>(options, "halfHeight", def.halfHeight);
    def.maxSlope = field<float>(options, "maxSlope", def.maxSlope);
    def.maxStepHeight = field<float>(options, "maxStepHeight", def.maxStepHeight);
    def.skinWidth = field<float>(options, "skinWidth", def.skinWidth);
    def.pushForce = field<float>(options, "pushForce", def.pushForce);
    def.mass = field<float>(options, "mass", def.mass);
    return new Character(def);
  });
}
void updateCharacter(Character& c, JsWorld& world, val walk, float dt) {
  guarded([&] {
    c.update(world.world(), vec3(walk, Vec3(0.0f), "walk"), dt);
    return 0;
  });
}
val characterPosition(const Character& c) { return array3(c.position()); }
val characterFeet(const Character& c) { return array3(c.footPosition()); }
std::string characterGroundState(const Character& c) { return std::string(toString(c.groundState())); }
bool characterSetHalfHeight(Character& c, JsWorld& world, float halfHeight) {
  return guarded([&] { return c.setHalfHeight(world.world(), halfHeight); });
}

val builtinSceneNames() {
  val out = val::array();
  int i = 0;
  for (const scene::BuiltinScene& s : scene::builtinScenes()) out.set(i++, std::string(s.name));
  return out;
}

// `collide run NAME --steps N` in WebAssembly: the scene run by the same runner (breakable bodies,
// characters), its state hash as 16 hex digits and its milliseconds per step.
val runScene(const std::string& nameOrJson, int steps) {
  return guarded([&] {
    scene::RunOptions options;
    options.steps = steps;
    const scene::RunSummary summary = scene::runScene(sceneOf(nameOrJson), options);
    val out = val::object();
    out.set("stateHash", hashText(summary.stateHash));
    out.set("steps", summary.steps);
    out.set("msPerStep", summary.steps > 0 ? 1000.0 * summary.wallSeconds / summary.steps : 0.0);
    return out;
  });
}

std::string builtinSceneJson(const std::string& name) {
  return guarded([&] { return scene::builtinSceneJson(name); });
}

// The hull triangle finder (collide/hooks.h) that asks the page: Module.hullTriangles(Float32Array
// of x, y, z) returns the hull's triangles as vertex indices, or null. collide.js installs one
// made with three.js's ConvexHull.
bool hullTrianglesFromJs(const float* xyz, std::size_t count, std::vector<std::uint32_t>& triangles, void*) {
  const val finder = val::module_property("hullTriangles");
  if (finder.isUndefined() || finder.isNull()) return false;
  const val result = finder(val(typed_memory_view(3 * count, xyz)));
  if (result.isUndefined() || result.isNull()) return false;
  triangles = convertJSArrayToNumberVector<std::uint32_t>(result);
  return true;
}

void installHullFinder() { setHullTriangleFinder(&hullTrianglesFromJs); }

}  // namespace
}  // namespace collide::web

EMSCRIPTEN_BINDINGS(collide) {
  using namespace collide;
  using namespace collide::web;
  function("version", optional_override([] { return std::string(kVersion); }));
  function("installHullFinder", &installHullFinder);
  function("builtinScenes", &builtinSceneNames);
  function("builtinSceneJson", &builtinSceneJson);
  function("runScene", &runScene);

  class_<Shape>("Shape")
      .class_function("sphere", &makeSphere)
      .class_function("capsule", &makeCapsule)
      .class_function("box", &makeBox)
      .class_function("plane", &makePlane)
      .class_function("ellipsoid", &makeEllipsoid)
      .class_function("cylinder", &makeCylinder)
      .class_function("convexHull", &makeConvexHull)
      .class_function("mesh", &makeMesh)
      .class_function("fromJson", &parseShapeJson)
      .function("type", &shapeType)
      .function("geometry", &shapeGeometry);

  class_<Character>("Character")
      .constructor(&makeCharacter, allow_raw_pointers())
      .function("update", &updateCharacter)
      .function("position", &characterPosition)
      .function("footPosition", &characterFeet)
      .function("groundState", &characterGroundState)
      .function("isOnGround", &Character::isOnGround)
      .function("setHalfHeight", &characterSetHalfHeight);

  class_<JsWorld>("World")
      .constructor(&makeWorld, allow_raw_pointers())
      .class_function("fromScene", &JsWorld::fromScene, allow_raw_pointers())
      .function("createBody", &JsWorld::createBody)
      .function("destroyBody", &JsWorld::destroyBody)
      .function("isValid", &JsWorld::isValid)
      .function("bodyCount", &JsWorld::bodyCount)
      .function("bodies", &JsWorld::bodies)
      .function("step", &JsWorld::step)
      .function("sceneDt", &JsWorld::sceneDt)
      .function("sceneSteps", &JsWorld::sceneSteps)
      .function("source", &JsWorld::source)
      .function("type", &JsWorld::type)
      .function("name", &JsWorld::name)
      .function("position", &JsWorld::position)
      .function("rotation", &JsWorld::rotation)
      .function("velocity", &JsWorld::velocity)
      .function("angularVelocity", &JsWorld::angularVelocity)
      .function("setPose", &JsWorld::setPose)
      .function("setVelocity", &JsWorld::setVelocity)
      .function("setAngularVelocity", &JsWorld::setAngularVelocity)
      .function("applyImpulse", &JsWorld::applyImpulse)
      .function("mass", &JsWorld::mass)
      .function("shape", &JsWorld::shape)
      .function("scale", &JsWorld::scale)
      .function("isAwake", &JsWorld::isAwake)
      .function("positions", &JsWorld::positions)
      .function("rotations", &JsWorld::rotations)
      .function("velocities", &JsWorld::velocities)
      .function("bounds", &JsWorld::bounds)
      .function("contactPoints", &JsWorld::contactPoints)
      .function("linearMomentum", &JsWorld::linearMomentum)
      .function("kineticEnergy", &JsWorld::kineticEnergy)
      .function("stateHash", &JsWorld::stateHash)
      .function("createDistanceJoint", &JsWorld::createDistanceJoint)
      .function("createBallJoint", &JsWorld::createBallJoint)
      .function("createHingeJoint", &JsWorld::createHingeJoint)
      .function("createSliderJoint", &JsWorld::createSliderJoint)
      .function("createFixedJoint", &JsWorld::createFixedJoint)
      .function("createConeJoint", &JsWorld::createConeJoint)
      .function("jointPosition", &JsWorld::jointPosition)
      .function("jointSpeed", &JsWorld::jointSpeed)
      .function("destroyJoint", &JsWorld::destroyJoint)
      .function("jointBreakEvents", &JsWorld::jointBreakEvents)
      .function("jointCount", &JsWorld::jointCount)
      .function("contactEvents", &JsWorld::contactEvents)
      .function("castRay", &JsWorld::castRay)
      .function("castShape", &JsWorld::castShape)
      .function("overlapShape", &JsWorld::overlapShape)
      .function("hasLineOfSight", &JsWorld::hasLineOfSight)
      .function("characterCount", &JsWorld::characterCount)
      .function("updateCharacters", &JsWorld::updateCharacters)
      .function("characters", &JsWorld::characters)
      .function("saveSnapshot", &JsWorld::saveSnapshot)
      .function("loadSnapshot", &JsWorld::loadSnapshot);
}
