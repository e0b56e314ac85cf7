// The `collide` Python module (docs/python.md): worlds, bodies, shapes, joints, queries, events and
// scene files, with the state of many bodies as NumPy arrays filled in C++ (no per-body Python
// loop). Vectors are any sequence of three numbers in, tuples out; rotations are quaternions
// (w, x, y, z). collide::Error becomes collide.Error (a ValueError) with the library's message.
#include <collide/character.h>
#include <collide/collide.h>
#include <collide/scene/builtin_scenes.h>
#include <collide/scene/runner.h>
#include <collide/scene/scene.h>
#include <collide/version.h>

#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <string>
#include <vector>

namespace py = pybind11;

// ---- Vec3 and Quat: sequences in, tuples out. ----
namespace pybind11::detail {

template <>
struct type_caster<collide::Vec3> {
  PYBIND11_TYPE_CASTER(collide::Vec3, const_name("tuple[float, float, float]"));
  bool load(handle source, bool) {
    if (!PySequence_Check(source.ptr()) || PyUnicode_Check(source.ptr())) return false;
    const auto items = reinterpret_borrow<pybind11::sequence>(source);
    if (items.size() != 3) return false;
    for (int i = 0; i < 3; ++i) value[i] = items[i].cast<float>();
    return true;
  }
  static handle cast(const collide::Vec3& v, return_value_policy, handle) {
    return make_tuple(v.x, v.y, v.z).release();
  }
};

template <>
struct type_caster<collide::Quat> {
  PYBIND11_TYPE_CASTER(collide::Quat, const_name("tuple[float, float, float, float]"));
  bool load(handle source, bool) {
    if (!PySequence_Check(source.ptr()) || PyUnicode_Check(source.ptr())) return false;
    const auto items = reinterpret_borrow<pybind11::sequence>(source);
    if (items.size() != 4) return false;
    value = collide::Quat(items[0].cast<float>(), items[1].cast<float>(), items[2].cast<float>(),
                          items[3].cast<float>());
    return true;
  }
  static handle cast(const collide::Quat& q, return_value_policy, handle) {
    return make_tuple(q.w, q.x, q.y, q.z).release();
  }
};

}  // namespace pybind11::detail

namespace collide {
namespace {

// Names for enums, as the scene files spell them.
BodyType parseBodyType(const std::string& name) {
  if (name == "static") return BodyType::Static;
  if (name == "kinematic") return BodyType::Kinematic;
  if (name == "dynamic") return BodyType::Dynamic;
  throw Error("type: must be \"static\", \"kinematic\" or \"dynamic\", got \"" + name + "\"");
}

std::string bodyTypeName(BodyType type) { return std::string(toString(type)); }

// An (n, 3) float array of n bodies' vectors, filled in C++.
template <typename Get>
py::array_t<float> vectorsOf(const std::vector<BodyId>& ids, Get get) {
  py::array_t<float> out({static_cast<py::ssize_t>(ids.size()), py::ssize_t{3}});
  auto view = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < ids.size(); ++i) {
    const Vec3 v = get(ids[i]);
    for (int k = 0; k < 3; ++k) view(static_cast<py::ssize_t>(i), k) = v[k];
  }
  return out;
}

// The ids a call names, or every live body in creation order.
std::vector<BodyId> idsOr(const World& world, const std::optional<std::vector<BodyId>>& ids) {
  return ids ? *ids : world.bodies();
}

// Reads an (n, 3) array of the same length as `ids`, refusing other shapes and non-finite values.
std::vector<Vec3> readVectors(const py::array_t<float, py::array::c_style | py::array::forcecast>& values,
                              std::size_t count, const char* what) {
  if (values.ndim() != 2 || values.shape(1) != 3 || static_cast<std::size_t>(values.shape(0)) != count)
    throw Error(std::string(what) + ": must be an array of shape (" + std::to_string(count) + ", 3)");
  auto view = values.unchecked<2>();
  std::vector<Vec3> out(count);
  for (std::size_t i = 0; i < count; ++i)
    out[i] = Vec3(view(static_cast<py::ssize_t>(i), 0), view(static_cast<py::ssize_t>(i), 1),
                  view(static_cast<py::ssize_t>(i), 2));
  return out;
}

std::vector<Vec3> pointsFrom(const py::array_t<float, py::array::c_style | py::array::forcecast>& points,
                             const char* what) {
  if (points.ndim() != 2 || points.shape(1) != 3)
    throw Error(std::string(what) + ": must be an array of shape (n, 3)");
  return readVectors(points, static_cast<std::size_t>(points.shape(0)), what);
}

Transform poseOf(const Vec3& position, const Quat& rotation) { return Transform{position, rotation, 1.0f}; }

JointLimits limitsOf(const py::tuple& t) {
  if (t.size() != 2) throw Error("limits: must be (lower, upper)");
  return JointLimits{true, t[0].cast<float>(), t[1].cast<float>()};
}
JointMotor motorOf(const py::tuple& t) {
  if (t.size() != 2) throw Error("motor: must be (speed, max_force)");
  return JointMotor{true, t[0].cast<float>(), t[1].cast<float>()};
}

// A hinge's or a slider's definition: the bodies, the anchor and axis (world frame), limits and a
// motor when given, collide_connected and the break force.
template <typename Def>
Def axisJointDef(BodyId a, BodyId b, const Vec3& anchor, const Vec3& axis,
                 const std::optional<py::tuple>& limits, const std::optional<py::tuple>& motor,
                 bool collideConnected, float breakForce) {
  Def def;
  def.a = a;
  def.b = b;
  def.anchor = anchor;
  def.axis = axis;
  if (limits) def.limits = limitsOf(*limits);
  if (motor) def.motor = motorOf(*motor);
  def.collideConnected = collideConnected;
  def.breakForce = breakForce;
  return def;
}

// The contact events of the last step, as dictionaries a script reads without knowing the types.
py::list contactEventsOf(const World& world) {
  py::list out;
  for (const ContactEvent& e : world.contactEvents()) {
    py::dict d;
    d["type"] = e.type == ContactEvent::Type::Begin     ? "begin"
                : e.type == ContactEvent::Type::Persist ? "persist"
                                                        : "end";
    d["a"] = e.a;
    d["b"] = e.b;
    d["part_a"] = e.partA;
    d["part_b"] = e.partB;
    d["point"] = e.point;
    d["normal"] = e.normal;
    d["impulse"] = e.impulse;
    d["speed"] = e.speed;
    out.append(std::move(d));
  }
  return out;
}

}  // namespace
}  // namespace collide

PYBIND11_MODULE(_collide, m) {
  using namespace collide;
  m.doc() = "collide: collision detection and response for 3D games (docs/python.md)";
  m.attr("__version__") = kVersion;
  py::register_exception<Error>(m, "Error", PyExc_ValueError);
#if defined(COLLIDE_REFERENCE_BUILD)
  m.attr("reference_build") = true;  // the build the scenes' reference state hashes hold for
#else
  m.attr("reference_build") = false;
#endif

  // ---- Ids ----
  py::class_<BodyId>(m, "BodyId", "A body's generation-checked handle.")
      .def_readonly("index", &BodyId::index)
      .def_readonly("generation", &BodyId::generation)
      .def("__eq__", [](const BodyId& a, const BodyId& b) { return a == b; })
      .def("__hash__", [](const BodyId& id) { return (std::uint64_t(id.generation) << 32) | id.index; })
      .def("__repr__", [](const BodyId& id) {
        return "BodyId(" + std::to_string(id.index) + ", generation " + std::to_string(id.generation) + ")";
      });
  py::class_<JointId>(m, "JointId", "A joint's generation-checked handle.")
      .def_readonly("index", &JointId::index)
      .def_readonly("generation", &JointId::generation)
      .def("__eq__", [](const JointId& a, const JointId& b) { return a == b; })
      .def("__hash__", [](const JointId& id) { return (std::uint64_t(id.generation) << 32) | id.index; });

  // ---- Shapes ----
  py::class_<Shape>(m, "Shape", "A geometric proxy. Made by Sphere, Capsule, Box, ... below.")
      .def_property_readonly("type", [](const Shape& s) { return std::string(toString(s.type())); })
      .def(
          "mass_properties",
          [](const Shape& s, float density, float scale) {
            const MassProperties p = massProperties(s, density, scale);
            py::dict d;
            d["mass"] = p.mass;
            d["volume"] = p.volume;
            d["center_of_mass"] = p.centerOfMass;
            py::array_t<float> inertia({3, 3});
            auto view = inertia.mutable_unchecked<2>();
            for (int r = 0; r < 3; ++r)
              for (int c = 0; c < 3; ++c) view(r, c) = p.inertia[c][r];
            d["inertia"] = inertia;
            return d;
          },
          py::arg("density") = 1000.0f, py::arg("scale") = 1.0f,
          "Mass, volume, centre of mass and inertia tensor (about the centre of mass) at a uniform density.")
      .def(
          "bounds",
          [](const Shape& s, const Vec3& position, const Quat& rotation) {
            const Aabb box = worldBounds(s, poseOf(position, rotation));
            return py::make_tuple(box.min, box.max);
          },
          py::arg("position") = Vec3(0.0f), py::arg("rotation") = Quat(1, 0, 0, 0),
          "The (min, max) corners of the box around the shape placed at the pose.")
      .def(
          "contains",
          [](const Shape& s, const Vec3& point, const Vec3& position, const Quat& rotation) {
            return containsPoint(s, poseOf(position, rotation), point);
          },
          py::arg("point"), py::arg("position") = Vec3(0.0f), py::arg("rotation") = Quat(1, 0, 0, 0))
      .def("__repr__",
           [](const Shape& s) { return "<collide.Shape " + std::string(toString(s.type())) + ">"; });

  m.def(
      "Sphere", [](float radius) { return Shape(Sphere{radius}); }, py::arg("radius"));
  m.def(
      "Capsule",
      [](float radius, float halfHeight) {
        return Shape(Capsule{radius, halfHeight});
      },
      py::arg("radius"), py::arg("half_height"),
      "The points within radius of the segment from (0, -half_height, 0) to (0, half_height, 0).");
  m.def(
      "Box", [](const Vec3& halfExtents) { return Shape(Box{halfExtents}); }, py::arg("half_extents"));
  m.def(
      "Plane",
      [](const Vec3& normal, float distance) {
        return Shape(Plane{normal, distance});
      },
      py::arg("normal"), py::arg("distance") = 0.0f,
      "The half-space normal . x <= distance (normal unit): static bodies only.");
  m.def(
      "Ellipsoid", [](const Vec3& radii) { return Shape(Ellipsoid{radii}); }, py::arg("radii"));
  m.def(
      "Cylinder",
      [](float radius, float halfHeight) {
        return Shape(Cylinder{radius, halfHeight});
      },
      py::arg("radius"), py::arg("half_height"));
  m.def(
      "ConvexHull",
      [](const py::array_t<float, py::array::c_style | py::array::forcecast>& points) {
        const std::vector<Vec3> p = pointsFrom(points, "points");
        return Shape(ConvexHull::fromPoints(p));
      },
      py::arg("points"), "The convex hull of an (n, 3) array of points (Qhull).");
  m.def(
      "Kdop",
      [](int k, const py::array_t<float, py::array::c_style | py::array::forcecast>& points) {
        const std::vector<Vec3> p = pointsFrom(points, "points");
        return Shape(Kdop::fromPoints(k, p));
      },
      py::arg("k"), py::arg("points"), "The tightest k-DOP (k = 6, 14, 18 or 26) around the points.");
  m.def(
      "TriangleMesh",
      [](const py::array_t<float, py::array::c_style | py::array::forcecast>& vertices,
         const py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>& triangles) {
        std::vector<Vec3> v = pointsFrom(vertices, "vertices");
        if (triangles.ndim() != 2 || triangles.shape(1) != 3)
          throw Error("triangles: must be an array of shape (m, 3)");
        auto view = triangles.unchecked<2>();
        std::vector<MeshTriangle> t(static_cast<std::size_t>(triangles.shape(0)));
        for (py::ssize_t i = 0; i < triangles.shape(0); ++i) {
          for (int k = 0; k < 3; ++k) {
            const std::int64_t index = view(i, k);
            if (index < 0 || index >= static_cast<std::int64_t>(v.size()))
              throw Error("triangles[" + std::to_string(i) + "]: vertex index " + std::to_string(index) +
                          " out of range [0, " + std::to_string(v.size()) + ")");
            t[static_cast<std::size_t>(i)].v[k] = static_cast<std::uint32_t>(index);
          }
        }
        return Shape(TriangleMesh::fromTriangles(std::move(v), std::move(t)));
      },
      py::arg("vertices"), py::arg("triangles"),
      "A triangle mesh from an (n, 3) array of vertices and an (m, 3) array of vertex indices.");
  m.def(
      "Compound",
      [](const std::vector<py::tuple>& children) {
        std::vector<Compound::Child> out;
        for (std::size_t i = 0; i < children.size(); ++i) {
          const py::tuple& child = children[i];
          const std::string where = "Compound: children[" + std::to_string(i) + "]: ";
          if (child.size() < 2 || child.size() > 3)
            throw Error(where + "must be (shape, position) or (shape, position, rotation)");
          if (!py::isinstance<Shape>(child[0])) throw Error(where + "the first item must be a collide shape");
          Vec3 position(0.0f);
          Quat rotation(1, 0, 0, 0);
          try {
            position = child[1].cast<Vec3>();
            if (child.size() == 3) rotation = child[2].cast<Quat>();
          } catch (const py::cast_error&) {
            throw Error(where + "position must be 3 numbers and rotation 4 (w, x, y, z)");
          }
          out.push_back({child[0].cast<Shape>(), Transform{position, rotation, 1.0f}});
        }
        return Shape(Compound::fromChildren(std::move(out)));
      },
      py::arg("children"), "A compound of (shape, position[, rotation]) children.");
  m.def(
      "load_shape", [](const std::string& json) { return scene::parseShape(json, "shape"); }, py::arg("json"),
      "A shape from its JSON as in scene files, e.g. '{\"type\": \"sphere\", \"radius\": 0.5}'.");

  // ---- The world ----
  py::class_<World>(m, "World", "A collision world: bodies, joints, the step, queries and events.")
      .def(py::init([](const Vec3& gravity, int substeps, const std::string& impactModel,
                       const std::string& bouncinessCombine, const std::string& frictionCombine,
                       const std::string& frictionModel, const std::string& penetrationResponse,
                       bool sleeping, bool ccd, int workers) {
             WorldDef def;
             def.gravity = gravity;
             def.substeps = substeps;
             def.impactModel = parseImpactModel(impactModel);
             def.bouncinessCombine = parseCombineRule(bouncinessCombine);
             def.frictionCombine = parseCombineRule(frictionCombine);
             def.frictionModel = parseFrictionModel(frictionModel);
             def.penetrationResponse = parsePenetrationResponse(penetrationResponse);
             def.sleeping = sleeping;
             def.ccd = ccd;
             def.workerCount = workers;
             return std::make_unique<World>(def);
           }),
           py::kw_only(), py::arg("gravity") = Vec3(0.0f, -9.81f, 0.0f), py::arg("substeps") = 6,
           py::arg("impact_model") = "newton", py::arg("bounciness_combine") = "max",
           py::arg("friction_combine") = "average", py::arg("friction_model") = "coulomb",
           py::arg("penetration_response") = "soft", py::arg("sleeping") = false, py::arg("ccd") = true,
           py::arg("workers") = 1)
      .def(
          "create_body",
          [](World& w, const Shape& shape, const std::string& type, const Vec3& position,
             const Quat& rotation, float scale, const Vec3& velocity, const Vec3& angularVelocity,
             std::optional<float> mass, float density, float bounciness, float friction, float gravityScale,
             float linearDamping, float angularDamping, std::uint32_t layer, std::uint32_t mask, bool sensor,
             bool particle, bool ccd, const std::string& name) {
            BodyDef def;
            def.shape = shape;
            def.type = parseBodyType(type);
            def.position = position;
            def.rotation = rotation;
            def.scale = scale;
            def.linearVelocity = velocity;
            def.angularVelocity = angularVelocity;
            def.mass = mass;
            def.density = density;
            def.bounciness = bounciness;
            def.friction = friction;
            def.gravityScale = gravityScale;
            def.linearDamping = linearDamping;
            def.angularDamping = angularDamping;
            def.layer = layer;
            def.mask = mask;
            def.sensor = sensor;
            def.particle = particle;
            def.ccd = ccd;
            def.name = name;
            return w.createBody(def);
          },
          py::arg("shape"), py::kw_only(), py::arg("type") = "dynamic", py::arg("position") = Vec3(0.0f),
          py::arg("rotation") = Quat(1, 0, 0, 0), py::arg("scale") = 1.0f, py::arg("velocity") = Vec3(0.0f),
          py::arg("angular_velocity") = Vec3(0.0f), py::arg("mass") = std::nullopt,
          py::arg("density") = 1000.0f, py::arg("bounciness") = 0.0f, py::arg("friction") = 0.5f,
          py::arg("gravity_scale") = 1.0f, py::arg("linear_damping") = 0.0f,
          py::arg("angular_damping") = 0.0f, py::arg("layer") = 1u, py::arg("mask") = kAllLayers,
          py::arg("sensor") = false, py::arg("particle") = false, py::arg("ccd") = false,
          py::arg("name") = "")
      .def("destroy_body", &World::destroyBody, py::arg("body"))
      .def("is_valid", py::overload_cast<BodyId>(&World::isValid, py::const_), py::arg("body"))
      .def_property_readonly("body_count", &World::bodyCount)
      .def("bodies", &World::bodies, "The live bodies, in creation order.")
      .def("step", &World::step, py::arg("dt"), py::call_guard<py::gil_scoped_release>())
      .def(
          "steps",
          [](World& w, float dt, int count) {
            for (int i = 0; i < count; ++i) w.step(dt);
          },
          py::arg("dt"), py::arg("count"), py::call_guard<py::gil_scoped_release>(), "count steps of dt.")
      // One body.
      .def(
          "type", [](const World& w, BodyId id) { return bodyTypeName(w.type(id)); }, py::arg("body"))
      .def("name", &World::name, py::arg("body"))
      .def(
          "position", [](const World& w, BodyId id) { return w.transform(id).position; }, py::arg("body"))
      .def(
          "rotation", [](const World& w, BodyId id) { return w.transform(id).rotation; }, py::arg("body"))
      .def(
          "set_pose",
          [](World& w, BodyId id, const Vec3& position, const Quat& rotation) {
            w.setTransform(id, position, rotation);
          },
          py::arg("body"), py::arg("position"), py::arg("rotation") = Quat(1, 0, 0, 0))
      .def("velocity", &World::linearVelocity, py::arg("body"))
      .def("angular_velocity", &World::angularVelocity, py::arg("body"))
      .def("set_velocity", &World::setLinearVelocity, py::arg("body"), py::arg("velocity"))
      .def("set_angular_velocity", &World::setAngularVelocity, py::arg("body"), py::arg("angular_velocity"))
      .def("apply_impulse", &World::applyImpulse, py::arg("body"), py::arg("impulse"), py::arg("point"))
      .def("apply_force", &World::applyForce, py::arg("body"), py::arg("force"), py::arg("point"))
      .def("mass", &World::mass, py::arg("body"))
      .def("center_of_mass", &World::centerOfMass, py::arg("body"))
      .def("shape", &World::shape, py::arg("body"), py::return_value_policy::copy)
      .def("is_awake", &World::isAwake, py::arg("body"))
      // Many bodies at once, as NumPy arrays (every body, in bodies() order, unless ids are given).
      .def(
          "positions",
          [](const World& w, std::optional<std::vector<BodyId>> ids) {
            return vectorsOf(idsOr(w, ids), [&](BodyId id) { return w.transform(id).position; });
          },
          py::arg("bodies") = py::none(), "An (n, 3) array of the bodies' positions.")
      .def(
          "rotations",
          [](const World& w, std::optional<std::vector<BodyId>> ids) {
            const std::vector<BodyId> list = idsOr(w, ids);
            py::array_t<float> out({static_cast<py::ssize_t>(list.size()), py::ssize_t{4}});
            auto view = out.mutable_unchecked<2>();
            for (std::size_t i = 0; i < list.size(); ++i) {
              const Quat q = w.transform(list[i]).rotation;
              const auto row = static_cast<py::ssize_t>(i);
              view(row, 0) = q.w;
              view(row, 1) = q.x;
              view(row, 2) = q.y;
              view(row, 3) = q.z;
            }
            return out;
          },
          py::arg("bodies") = py::none(), "An (n, 4) array of the bodies' rotations (w, x, y, z).")
      .def(
          "velocities",
          [](const World& w, std::optional<std::vector<BodyId>> ids) {
            return vectorsOf(idsOr(w, ids), [&](BodyId id) { return w.linearVelocity(id); });
          },
          py::arg("bodies") = py::none(), "An (n, 3) array of the bodies' linear velocities.")
      .def(
          "angular_velocities",
          [](const World& w, std::optional<std::vector<BodyId>> ids) {
            return vectorsOf(idsOr(w, ids), [&](BodyId id) { return w.angularVelocity(id); });
          },
          py::arg("bodies") = py::none(), "An (n, 3) array of the bodies' angular velocities.")
      .def(
          "set_velocities",
          [](World& w, const std::vector<BodyId>& ids,
             const py::array_t<float, py::array::c_style | py::array::forcecast>& values) {
            const std::vector<Vec3> v = readVectors(values, ids.size(), "velocities");
            for (std::size_t i = 0; i < ids.size(); ++i) w.setLinearVelocity(ids[i], v[i]);
          },
          py::arg("bodies"), py::arg("velocities"),
          "Sets the bodies' linear velocities from an (n, 3) array.")
      .def(
          "set_positions",
          [](World& w, const std::vector<BodyId>& ids,
             const py::array_t<float, py::array::c_style | py::array::forcecast>& values) {
            const std::vector<Vec3> v = readVectors(values, ids.size(), "positions");
            for (std::size_t i = 0; i < ids.size(); ++i)
              w.setTransform(ids[i], v[i], w.transform(ids[i]).rotation);
          },
          py::arg("bodies"), py::arg("positions"), "Moves the bodies to an (n, 3) array of positions.")
      // Totals.
      .def("linear_momentum", &World::linearMomentum)
      .def("kinetic_energy", &World::kineticEnergy)
      // Joints.
      .def(
          "create_distance_joint",
          [](World& w, BodyId a, BodyId b, std::optional<Vec3> anchorA, std::optional<Vec3> anchorB,
             std::optional<float> length) {
            DistanceConstraintDef def;
            def.a = a;
            def.b = b;
            def.localAnchorA = anchorA;
            def.localAnchorB = anchorB;
            def.length = length;
            return w.createDistanceConstraint(def);
          },
          py::arg("a"), py::arg("b"), py::kw_only(), py::arg("local_anchor_a") = std::nullopt,
          py::arg("local_anchor_b") = std::nullopt, py::arg("length") = std::nullopt,
          "A rigid rod between two bodies' anchors (local; their centres unless given).")
      .def(
          "create_ball_joint",
          [](World& w, BodyId a, BodyId b, const Vec3& anchor, bool collideConnected) {
            BallJointDef def;
            def.a = a;
            def.b = b;
            def.anchor = anchor;
            def.collideConnected = collideConnected;
            return w.createBallJoint(def);
          },
          py::arg("a"), py::arg("b"), py::arg("anchor"), py::kw_only(), py::arg("collide_connected") = false)
      .def(
          "create_hinge_joint",
          [](World& w, BodyId a, BodyId b, const Vec3& anchor, const Vec3& axis,
             std::optional<py::tuple> limits, std::optional<py::tuple> motor, bool collideConnected,
             float breakForce) {
            return w.createHingeJoint(
                axisJointDef<HingeJointDef>(a, b, anchor, axis, limits, motor, collideConnected, breakForce));
          },
          py::arg("a"), py::arg("b"), py::arg("anchor"), py::arg("axis"), py::kw_only(),
          py::arg("limits") = std::nullopt, py::arg("motor") = std::nullopt,
          py::arg("collide_connected") = false, py::arg("break_force") = kUnbreakable,
          "A hinge about axis through anchor (world frame); limits = (lower, upper) radians, motor = (speed, "
          "max_torque).")
      .def(
          "create_slider_joint",
          [](World& w, BodyId a, BodyId b, const Vec3& anchor, const Vec3& axis,
             std::optional<py::tuple> limits, std::optional<py::tuple> motor, bool collideConnected,
             float breakForce) {
            return w.createSliderJoint(axisJointDef<SliderJointDef>(a, b, anchor, axis, limits, motor,
                                                                    collideConnected, breakForce));
          },
          py::arg("a"), py::arg("b"), py::arg("anchor"), py::arg("axis"), py::kw_only(),
          py::arg("limits") = std::nullopt, py::arg("motor") = std::nullopt,
          py::arg("collide_connected") = false, py::arg("break_force") = kUnbreakable,
          "A slider along axis (world frame); limits = (lower, upper) metres, motor = (speed, max_force).")
      .def(
          "create_fixed_joint",
          [](World& w, BodyId a, BodyId b, std::optional<Vec3> anchor, bool collideConnected,
             float breakForce) {
            FixedJointDef def;
            def.a = a;
            def.b = b;
            def.anchor = anchor;
            def.collideConnected = collideConnected;
            def.breakForce = breakForce;
            return w.createFixedJoint(def);
          },
          py::arg("a"), py::arg("b"), py::kw_only(), py::arg("anchor") = std::nullopt,
          py::arg("collide_connected") = false, py::arg("break_force") = kUnbreakable,
          "A weld: the bodies keep their relative pose.")
      .def(
          "create_cone_joint",
          [](World& w, BodyId a, BodyId b, const Vec3& anchor, const Vec3& axis, float swingLimit,
             std::optional<py::tuple> twistLimits, bool collideConnected, float breakForce) {
            ConeJointDef def;
            def.a = a;
            def.b = b;
            def.anchor = anchor;
            def.axis = axis;
            def.swingLimit = swingLimit;
            if (twistLimits) def.twistLimits = limitsOf(*twistLimits);
            def.collideConnected = collideConnected;
            def.breakForce = breakForce;
            return w.createConeJoint(def);
          },
          py::arg("a"), py::arg("b"), py::arg("anchor"), py::arg("axis"), py::kw_only(),
          py::arg("swing_limit") = kPi, py::arg("twist_limits") = std::nullopt,
          py::arg("collide_connected") = false, py::arg("break_force") = kUnbreakable,
          "A ball joint whose axis stays within swing_limit radians of axis (ragdoll shoulders, hips).")
      .def(
          "set_joint_motor",
          [](World& w, JointId joint, float speed, float maxForce) {
            w.setJointMotor(joint, JointMotor{true, speed, maxForce});
          },
          py::arg("joint"), py::arg("speed"), py::arg("max_force"))
      .def(
          "set_joint_limits",
          [](World& w, JointId joint, float lower, float upper) {
            w.setJointLimits(joint, JointLimits{true, lower, upper});
          },
          py::arg("joint"), py::arg("lower"), py::arg("upper"))
      .def_property_readonly("joint_count", &World::constraintCount)
      .def(
          "joint_type",
          [](const World& w, JointId joint) { return std::string(toString(w.jointType(joint))); },
          py::arg("joint"))
      .def("destroy_joint", &World::destroyConstraint, py::arg("joint"))
      .def("joint_position", &World::jointPosition, py::arg("joint"))
      .def("joint_speed", &World::jointSpeed, py::arg("joint"))
      // Events of the last step.
      .def("contact_events", &contactEventsOf, "The contact events of the last step: begin, persist, end.")
      .def("sensor_events",
           [](const World& w) {
             py::list out;
             for (const SensorEvent& e : w.sensorEvents()) {
               py::dict d;
               d["type"] = e.type == SensorEvent::Type::Begin ? "begin" : "end";
               d["sensor"] = e.sensor;
               d["visitor"] = e.visitor;
               out.append(std::move(d));
             }
             return out;
           })
      .def("joint_break_events",
           [](const World& w) {
             py::list out;
             for (const JointBreakEvent& e : w.jointBreakEvents()) {
               py::dict d;
               d["joint"] = e.joint;
               d["a"] = e.a;
               d["b"] = e.b;
               d["force"] = e.force;
               d["torque"] = e.torque;
               out.append(std::move(d));
             }
             return out;
           })
      // Queries.
      .def(
          "cast_ray",
          [](const World& w, const Vec3& origin, const Vec3& direction, float maxDistance,
             LayerMask mask) -> py::object {
            const std::optional<RayCastResult> hit = w.castRay(Ray{origin, direction, maxDistance}, mask);
            if (!hit) return py::none();
            py::dict d;
            d["body"] = hit->body;
            d["distance"] = hit->distance;
            d["point"] = hit->point;
            d["normal"] = hit->normal;
            d["part"] = hit->part;
            return d;
          },
          py::arg("origin"), py::arg("direction"), py::arg("max_distance") = 1e30f, py::kw_only(),
          py::arg("mask") = kAllLayers,
          "The closest hit (a dict: body, distance, point, normal, part) or None.")
      .def(
          "cast_shape",
          [](const World& w, const Shape& shape, const Vec3& position, const Vec3& translation,
             const Quat& rotation) -> py::object {
            const std::optional<ShapeCastResult> hit =
                w.castShape(shape, poseOf(position, rotation), translation);
            if (!hit) return py::none();
            py::dict d;
            d["body"] = hit->body;
            d["fraction"] = hit->fraction;
            d["distance"] = hit->distance;
            d["point"] = hit->point;
            d["normal"] = hit->normal;
            return d;
          },
          py::arg("shape"), py::arg("position"), py::arg("translation"),
          py::arg("rotation") = Quat(1, 0, 0, 0),
          "The first body the shape meets moving by translation (a dict: body, fraction, distance, point, "
          "normal) "
          "or None.")
      .def(
          "overlap_shape",
          [](const World& w, const Shape& shape, const Vec3& position, const Quat& rotation) {
            std::vector<BodyId> out;
            for (const OverlapResult& r : w.overlapShape(shape, poseOf(position, rotation)))
              if (out.empty() || !(out.back() == r.body)) out.push_back(r.body);
            return out;
          },
          py::arg("shape"), py::arg("position"), py::arg("rotation") = Quat(1, 0, 0, 0),
          "The bodies the shape overlaps at the pose.")
      .def(
          "overlap_point", [](const World& w, const Vec3& p) { return w.overlapPoint(p); }, py::arg("point"))
      .def(
          "has_line_of_sight",
          [](const World& w, const Vec3& a, const Vec3& b) { return w.hasLineOfSight(a, b); },
          py::arg("from_point"), py::arg("to_point"))
      // Snapshots.
      .def(
          "save_snapshot",
          [](const World& w) {
            const std::vector<std::uint8_t> bytes = w.saveSnapshot();
            return py::bytes(reinterpret_cast<const char*>(bytes.data()), bytes.size());
          },
          "The whole state as bytes (docs/snapshots.md).")
      .def(
          "load_snapshot",
          [](World& w, const py::bytes& data) {
            const std::string bytes = data;
            w.loadSnapshot(std::span(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()));
          },
          py::arg("snapshot"));

  // ---- The character mover (docs/character.md) ----
  py::class_<Character>(m, "Character", "A kinematic capsule walked through a world (docs/character.md).")
      .def(py::init([](const Vec3& position, float radius, float halfHeight, float maxSlope,
                       float maxStepHeight, float skinWidth, float pushForce, float mass, const Vec3& gravity,
                       const Vec3& up) {
             CharacterDef def;
             def.position = position;
             def.radius = radius;
             def.halfHeight = halfHeight;
             def.maxSlope = maxSlope;
             def.maxStepHeight = maxStepHeight;
             def.skinWidth = skinWidth;
             def.pushForce = pushForce;
             def.mass = mass;
             def.gravity = gravity;
             def.up = up;
             return Character(def);
           }),
           py::arg("position"), py::kw_only(), py::arg("radius") = 0.3f, py::arg("half_height") = 0.6f,
           py::arg("max_slope") = 45.0f * kPi / 180.0f, py::arg("max_step_height") = 0.35f,
           py::arg("skin_width") = 0.02f, py::arg("push_force") = 500.0f, py::arg("mass") = 80.0f,
           py::arg("gravity") = Vec3(0.0f, -9.81f, 0.0f), py::arg("up") = Vec3(0.0f, 1.0f, 0.0f))
      .def("update", &Character::update, py::arg("world"), py::arg("walk_velocity"), py::arg("dt"),
           "One update after World.step: walks at walk_velocity across up; its part along up is a jump.")
      .def_property_readonly("position", &Character::position)
      .def_property_readonly("foot_position", &Character::footPosition)
      .def_property_readonly("velocity", &Character::velocity)
      .def_property_readonly("ground_state",
                             [](const Character& c) { return std::string(toString(c.groundState())); })
      .def_property_readonly("is_on_ground", &Character::isOnGround)
      .def_property_readonly("ground_body",
                             [](const Character& c) -> py::object {
                               if (c.groundBody().isNull()) return py::none();
                               return py::cast(c.groundBody());
                             })
      .def_property_readonly("ground_normal", &Character::groundNormal)
      .def_property_readonly("ground_velocity", &Character::groundVelocity)
      .def_property_readonly("half_height", &Character::halfHeight)
      .def_property_readonly("radius", &Character::radius)
      .def("set_position", &Character::setPosition, py::arg("position"), py::arg("stop") = true)
      .def("set_half_height", &Character::setHalfHeight, py::arg("world"), py::arg("half_height"),
           "Crouch or stand, feet kept; False (nothing changes) where the new capsule would overlap.")
      .def(
          "contacts",
          [](const Character& c) {
            py::list out;
            for (const CharacterContact& contact : c.contacts()) {
              py::dict d;
              d["body"] = contact.body;
              d["point"] = contact.point;
              d["normal"] = contact.normal;
              d["pushed"] = contact.pushed;
              out.append(std::move(d));
            }
            return out;
          },
          "What the capsule touched in the last update: dicts of body, point, normal, pushed.");

  // ---- Scenes ----
  py::class_<scene::Scene>(m, "Scene", "A scene file's contents (docs/scene-format.md).")
      .def_readonly("source", &scene::Scene::source)
      .def_readonly("dt", &scene::Scene::dt)
      .def_readonly("steps", &scene::Scene::steps)
      .def_property_readonly("body_count", [](const scene::Scene& s) { return s.bodies.size(); });
  py::class_<scene::SceneWorld>(m, "SceneWorld", "A scene's world and its bodies in scene order.")
      .def_property_readonly(
          "world", [](scene::SceneWorld& sw) -> World& { return sw.world; },
          py::return_value_policy::reference_internal)
      .def_readonly("bodies", &scene::SceneWorld::bodies)
      .def(
          "state_hash", [](const scene::SceneWorld& sw) { return scene::stateHash(sw); },
          "FNV-1a over every body's position, rotation and velocities, as `collide run` prints it.");
  m.def(
      "load_scene", [](const std::string& path) { return scene::loadSceneFile(path); }, py::arg("path"),
      "Reads a scene file (JSON, collide-scene/1; OBJ meshes next to it).");
  m.def(
      "parse_scene", [](const std::string& text) { return scene::parseScene(text, "scene"); },
      py::arg("text"), "A scene from its JSON text.");
  m.def(
      "builtin_scene", [](const std::string& name) { return scene::loadBuiltinScene(name); }, py::arg("name"),
      "One of the built-in scenes (builtin_scenes() lists them).");
  m.def("builtin_scenes", [] {
    std::vector<std::string> names;
    for (const scene::BuiltinScene& s : scene::builtinScenes()) names.emplace_back(s.name);
    return names;
  });
  m.def("build_world", &scene::buildWorld, py::arg("scene"), "The scene's world, ready to step.");
}
