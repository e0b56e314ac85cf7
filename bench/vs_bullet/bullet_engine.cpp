// The Bullet side of collide_vs_bullet: a scene::Scene translated body by body into Bullet 3.24
// (single precision, like collide), with Bullet's default settings everywhere the scene says
// nothing. What the translation has to decide:
//  - Pose: Bullet places a body by its centre of mass, collide by its shape's origin. A hull whose
//    centroid is off its origin is given to Bullet with its points shifted by the centroid, and the
//    body placed at origin + R * centroid, so both engines hold the same solid at the same place.
//  - Inertia: Bullet's own (calculateLocalInertia: exact for boxes and spheres, the bounding box's
//    for a hull), as Bullet users get it by default.
//  - Margins: Bullet's defaults (0.04 m around hulls, inside boxes, none on triangle meshes).
//  - Joints: ball -> btPoint2PointConstraint, hinge -> btHingeConstraint (limits, motor; friction as
//    a motor at rest), cone -> btConeTwistConstraint (swing and twist spans; Bullet's twist is
//    symmetric, so the larger of the two limits), slider -> btSliderConstraint, fixed ->
//    btFixedConstraint; collideConnected false disables the pair's collisions as collide does. A
//    cone or ball joint's friction and a soft joint have no Bullet counterpart here and are left
//    out; a distance joint is refused.
//  - Layers: a scene with layers or masks other than the defaults gives Bullet the same bits as its
//    collision filter group and mask (both engines test them both ways).
//  - Materials: Bullet multiplies the two bodies' friction (and restitution). The scene's pair
//    values (e.g. friction 0.5 per pair, averaged) are reproduced by giving every dynamic body
//    sqrt(pair value) and every static body pairValue(dynamic, static) / sqrt(dynamic pair value);
//    a scene whose dynamic bodies differ in a material value cannot be mapped this way and is
//    refused with an Error instead of being silently approximated.
#include "engines.h"

#include <collide/body.h>
#include <collide/error.h>
#include <collide/shapes.h>

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <tuple>

namespace collide::bench {

namespace {

btVector3 toBt(const Vec3& v) { return {v.x, v.y, v.z}; }
Vec3 fromBt(const btVector3& v) { return {v.x(), v.y(), v.z()}; }
btQuaternion toBt(const Quat& q) { return {q.x, q.y, q.z, q.w}; }
Quat fromBt(const btQuaternion& q) { return {q.w(), q.x(), q.y(), q.z()}; }

// Per-body values whose products are the scene's pair values (see the file comment).
std::vector<float> productValues(const scene::Scene& scene, CombineRule rule, float BodyDef::*field,
                                 const char* what) {
  std::set<float> dynamicValues;
  for (const scene::Body& b : scene.bodies) {
    if (b.def.type == BodyType::Dynamic) dynamicValues.insert(b.def.*field);
  }
  std::vector<float> values(scene.bodies.size(), 0.0f);
  if (dynamicValues.empty()) return values;
  if (dynamicValues.size() > 1) {
    throw Error(scene.source + ": Bullet side: the dynamic bodies have " +
                std::to_string(dynamicValues.size()) + " different " + what +
                " values; Bullet's product rule cannot reproduce their pair values");
  }
  const float d = *dynamicValues.begin();
  const float dynamicValue = std::sqrt(combine(rule, d, d));
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodyDef& def = scene.bodies[i].def;
    if (def.type == BodyType::Dynamic) {
      values[i] = dynamicValue;
    } else {
      const float pair = combine(rule, d, def.*field);
      if (dynamicValue == 0.0f && pair != 0.0f) {
        throw Error(scene.source + ": Bullet side: " + what + " pair value " + std::to_string(pair) +
                    " against a static body cannot be made from a dynamic value of 0");
      }
      values[i] = dynamicValue == 0.0f ? 0.0f : pair / dynamicValue;
    }
  }
  return values;
}

void countTick(btDynamicsWorld* world, btScalar) { ++*static_cast<int*>(world->getWorldUserInfo()); }

// Members in construction order; the world goes first on destruction (it unregisters the bodies'
// broad-phase proxies), the bodies and shapes after it.
struct BulletWorld {
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btTriangleIndexVertexArray>> meshes;
  std::vector<std::vector<btScalar>> meshVertices;
  std::vector<std::vector<int>> meshIndices;
  std::vector<std::unique_ptr<btRigidBody>> bodies;  // per scene body
  std::vector<Vec3> localCenters;                    // per scene body: centre of mass in the shape frame
  std::vector<std::unique_ptr<btTypedConstraint>> constraints;
  btDefaultCollisionConfiguration configuration;
  btCollisionDispatcher dispatcher{&configuration};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &configuration};
  int ticks = 0;
};

// One Bullet shape per distinct sphere or box (as Bullet users share them); hulls and meshes are
// one per body, as in the scene.
class ShapeMaker {
 public:
  explicit ShapeMaker(BulletWorld& w) : w_(w) {}

  btCollisionShape* make(const scene::Scene& scene, std::size_t index, Vec3& localCenter) {
    const BodyDef& def = scene.bodies[index].def;
    if (!def.parts.empty()) {
      throw Error("bullet: body \"" + def.name +
                  "\" is made of parts, which the Bullet reference does not build");
    }
    const Shape& shape = def.shape;
    const float s = def.scale;
    localCenter = Vec3(0.0f);
    switch (shape.type()) {
      case ShapeType::Sphere:
        return shared(std::make_tuple(0, s * shape.sphere().radius, 0.0f, 0.0f),
                      [&] { return new btSphereShape(s * shape.sphere().radius); });
      case ShapeType::Box: {
        const Vec3 h = s * shape.box().halfExtents;
        return shared(std::make_tuple(1, h.x, h.y, h.z), [&] { return new btBoxShape(toBt(h)); });
      }
      case ShapeType::Capsule:
        return own(new btCapsuleShape(s * shape.capsule().radius, 2.0f * s * shape.capsule().halfHeight));
      case ShapeType::Cylinder:
        return own(new btCylinderShape(btVector3(s * shape.cylinder().radius, s * shape.cylinder().halfHeight,
                                                 s * shape.cylinder().radius)));
      case ShapeType::Plane:
        return own(new btStaticPlaneShape(toBt(shape.plane().normal), shape.plane().distance * s));
      case ShapeType::ConvexHull: {
        const ConvexHull& hull = shape.convexHull();
        if (def.type == BodyType::Dynamic) localCenter = s * hull.centroid();
        auto* bt = new btConvexHullShape();
        for (const Vec3& v : hull.vertices()) bt->addPoint(toBt(s * v - localCenter), false);
        bt->recalcLocalAabb();
        return own(bt);
      }
      case ShapeType::Mesh: {
        if (def.type == BodyType::Dynamic) {
          throw Error(scene.source + ": Bullet side: body '" + def.name +
                      "': a dynamic triangle mesh is not supported");
        }
        const TriangleMesh& mesh = shape.mesh();
        std::vector<btScalar>& vertices = w_.meshVertices.emplace_back();
        std::vector<int>& indices = w_.meshIndices.emplace_back();
        for (const Vec3& v : mesh.vertices()) {
          vertices.insert(vertices.end(), {s * v.x, s * v.y, s * v.z});
        }
        for (const MeshTriangle& t : mesh.triangles()) {
          indices.insert(indices.end(), {int(t.v[0]), int(t.v[1]), int(t.v[2])});
        }
        auto& array = w_.meshes.emplace_back(std::make_unique<btTriangleIndexVertexArray>(
            int(mesh.triangles().size()), indices.data(), int(3 * sizeof(int)), int(mesh.vertices().size()),
            vertices.data(), int(3 * sizeof(btScalar))));
        return own(new btBvhTriangleMeshShape(array.get(), true));
      }
      default:
        throw Error(scene.source + ": Bullet side: body '" + def.name + "': shape type " +
                    std::string(toString(shape.type())) + " is not translated");
    }
  }

 private:
  btCollisionShape* own(btCollisionShape* shape) {
    w_.shapes.emplace_back(shape);
    return shape;
  }
  template <class Make>
  btCollisionShape* shared(const std::tuple<int, float, float, float>& key, Make make) {
    auto it = cache_.find(key);
    if (it != cache_.end()) return it->second;
    return cache_[key] = own(make());
  }

  BulletWorld& w_;
  std::map<std::tuple<int, float, float, float>, btCollisionShape*> cache_;
};

}  // namespace

namespace {

// A joint frame at `anchor` whose x axis is `axis` (world), in a body's centre-of-mass frame.
btTransform frameIn(const btRigidBody& body, const Vec3& anchor, const Vec3& axis) {
  const Vec3 x = glm::normalize(axis);
  const Vec3 helper = std::abs(x.x) < 0.9f ? Vec3(1.0f, 0.0f, 0.0f) : Vec3(0.0f, 1.0f, 0.0f);
  const Vec3 y = glm::normalize(glm::cross(helper, x));
  const Vec3 z = glm::cross(x, y);
  const btMatrix3x3 basis(x.x, y.x, z.x, x.y, y.y, z.y, x.z, y.z, z.z);
  return body.getWorldTransform().inverse() * btTransform(basis, toBt(anchor));
}

void addConstraints(const scene::Scene& scene, BulletWorld& w) {
  std::map<std::string, std::size_t, std::less<>> index;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) index[scene.bodies[i].def.name] = i;
  const btScalar substep = scene.dt;  // Bullet's one internal step per frame
  for (std::size_t k = 0; k < scene.constraints.size(); ++k) {
    const scene::Constraint& c = scene.constraints[k];
    btRigidBody& a = *w.bodies[index.at(c.a)];
    btRigidBody& b = *w.bodies[index.at(c.b)];
    const std::string who = scene.source + ": Bullet side: constraints[" + std::to_string(k) + "]: ";
    if (c.softness.hertz > 0.0f) throw Error(who + "soft joints are not translated");
    const Vec3 anchor = c.anchor ? *c.anchor : fromBt(b.getCenterOfMassPosition());
    std::unique_ptr<btTypedConstraint> joint;
    switch (c.type) {
      case JointType::Distance:
        throw Error(who + "distance joints are not translated");
      case JointType::Ball:
        joint =
            std::make_unique<btPoint2PointConstraint>(a, b, a.getWorldTransform().inverse() * toBt(anchor),
                                                      b.getWorldTransform().inverse() * toBt(anchor));
        break;
      case JointType::Hinge: {
        const btTransform fa = frameIn(a, anchor, c.axis), fb = frameIn(b, anchor, c.axis);
        auto hinge = std::make_unique<btHingeConstraint>(
            a, b, fa.getOrigin(), fb.getOrigin(), fa.getBasis().getColumn(0), fb.getBasis().getColumn(0));
        if (c.limits.enabled) hinge->setLimit(c.limits.lower, c.limits.upper);
        if (c.motor.enabled) {
          hinge->enableAngularMotor(true, c.motor.speed, c.motor.maxForce * substep);
        } else if (c.friction > 0.0f) {
          hinge->enableAngularMotor(true, 0.0f, c.friction * substep);
        }
        joint = std::move(hinge);
        break;
      }
      case JointType::Cone: {
        auto cone = std::make_unique<btConeTwistConstraint>(a, b, frameIn(a, anchor, c.axis),
                                                            frameIn(b, anchor, c.axis));
        const float twist =
            c.limits.enabled ? std::max(std::abs(c.limits.lower), std::abs(c.limits.upper)) : kPi;
        cone->setLimit(c.swing, c.swing, twist);
        joint = std::move(cone);
        break;
      }
      case JointType::Slider: {
        auto slider = std::make_unique<btSliderConstraint>(a, b, frameIn(a, anchor, c.axis),
                                                           frameIn(b, anchor, c.axis), true);
        slider->setLowerLinLimit(c.limits.enabled ? c.limits.lower : 1.0f);
        slider->setUpperLinLimit(c.limits.enabled ? c.limits.upper : -1.0f);  // lower > upper: free
        slider->setLowerAngLimit(0.0f);
        slider->setUpperAngLimit(0.0f);
        if (c.motor.enabled) {
          slider->setPoweredLinMotor(true);
          slider->setTargetLinMotorVelocity(c.motor.speed);
          slider->setMaxLinMotorForce(c.motor.maxForce);
        }
        joint = std::move(slider);
        break;
      }
      case JointType::Fixed:
        joint = std::make_unique<btFixedConstraint>(a, b, frameIn(a, anchor, Vec3(1, 0, 0)),
                                                    frameIn(b, anchor, Vec3(1, 0, 0)));
        break;
    }
    w.world.addConstraint(joint.get(), !c.collideConnected);
    w.constraints.push_back(std::move(joint));
  }
}

// The scene in Bullet: every body with its shape, mass, friction and restitution.
std::unique_ptr<BulletWorld> buildBullet(const scene::Scene& scene) {
  auto w = std::make_unique<BulletWorld>();
  w->world.setGravity(toBt(scene.world.gravity));
  w->world.setInternalTickCallback(countTick, &w->ticks);
  const std::vector<float> friction =
      productValues(scene, scene.world.frictionCombine, &BodyDef::friction, "friction");
  const std::vector<float> restitution =
      productValues(scene, scene.world.bouncinessCombine, &BodyDef::bounciness, "bounciness");
  ShapeMaker maker(*w);
  w->localCenters.resize(scene.bodies.size());
  bool filtered = false;
  for (const scene::Body& b : scene.bodies)
    filtered = filtered || b.def.layer != 1 || b.def.mask != kAllLayers;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodyDef& def = scene.bodies[i].def;
    if (def.type == BodyType::Kinematic)
      throw Error(scene.source + ": Bullet side: kinematic bodies are not translated");
    btCollisionShape* shape = maker.make(scene, i, w->localCenters[i]);
    const bool dynamic = def.type == BodyType::Dynamic;
    btScalar mass = 0.0f;
    if (dynamic) mass = def.mass ? *def.mass : massProperties(def.shape, def.density, def.scale).mass;
    btVector3 inertia(0.0f, 0.0f, 0.0f);
    if (dynamic) shape->calculateLocalInertia(mass, inertia);
    btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, shape, inertia);
    info.m_startWorldTransform =
        btTransform(toBt(def.rotation), toBt(def.position + def.rotation * w->localCenters[i]));
    info.m_friction = friction[i];
    info.m_restitution = restitution[i];
    auto& body = w->bodies.emplace_back(std::make_unique<btRigidBody>(info));
    if (dynamic) {
      body->setActivationState(DISABLE_DEACTIVATION);
      body->setLinearVelocity(toBt(def.linearVelocity));
      body->setAngularVelocity(toBt(def.angularVelocity));
    }
    if (filtered) {
      if (def.group != 0)
        throw Error(scene.source + ": Bullet side: body '" + def.name +
                    "': collision groups are not translated");
      w->world.addRigidBody(body.get(), static_cast<int>(def.layer), static_cast<int>(def.mask));
    } else {
      w->world.addRigidBody(body.get());
    }
  }
  addConstraints(scene, *w);
  return w;
}

}  // namespace

EngineRun runBullet(const scene::Scene& scene, int steps) {
  using Clock = std::chrono::steady_clock;
  if (scene.world.sleeping)
    throw Error(scene.source + ": Bullet side: only scenes without sleeping are compared");
  EngineRun run;
  const auto buildStart = Clock::now();
  std::unique_ptr<BulletWorld> w = buildBullet(scene);
  run.buildMs = std::chrono::duration<double, std::milli>(Clock::now() - buildStart).count();

  const btScalar dt = scene.dt;
  const double cpuStart = processCpuSeconds();
  const auto start = Clock::now();
  for (int i = 0; i < steps; ++i) w->world.stepSimulation(dt, 1, dt);
  const double wallMs = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
  const double cpuMs = 1e3 * (processCpuSeconds() - cpuStart);
  run.internalSteps = w->ticks;
  run.wallMsPerStep = steps > 0 ? wallMs / steps : 0.0;
  run.cpuMsPerStep = steps > 0 ? cpuMs / steps : 0.0;

  run.poses.resize(scene.bodies.size());
  run.masses.resize(scene.bodies.size(), 0.0);
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const btRigidBody& body = *w->bodies[i];
    const btTransform& t = body.getWorldTransform();
    const Quat rotation = fromBt(t.getRotation());
    run.poses[i] = {fromBt(t.getOrigin()) - rotation * w->localCenters[i], rotation,
                    fromBt(body.getLinearVelocity())};
    run.masses[i] = body.getInvMass() > 0.0f ? 1.0 / body.getInvMass() : 0.0;
  }
  return run;
}

QueryRun queryBullet(const scene::Scene& scene, int steps, const QueryBatch& batch, int repeats) {
  std::unique_ptr<BulletWorld> w = buildBullet(scene);
  for (int i = 0; i < steps; ++i) w->world.stepSimulation(scene.dt, 1, scene.dt);
  w->world.updateAabbs();
  QueryRun run;
  run.rayDistances.assign(batch.rays.size(), kMiss);
  run.sweepFractions.assign(batch.sweeps.size(), kMiss);
  const double rayStart = processCpuSeconds();
  for (int r = 0; r < repeats; ++r) {
    for (std::size_t k = 0; k < batch.rays.size(); ++k) {
      const Ray& ray = batch.rays[k];
      const btVector3 from = toBt(ray.origin), to = toBt(ray.origin + ray.maxDistance * ray.direction);
      btCollisionWorld::ClosestRayResultCallback hit(from, to);
      w->world.rayTest(from, to, hit);
      if (hit.hasHit()) run.rayDistances[k] = hit.m_closestHitFraction * ray.maxDistance;
    }
  }
  run.rayCpuSeconds = processCpuSeconds() - rayStart;
  btSphereShape sphere(batch.sweepRadius);
  const double sweepStart = processCpuSeconds();
  for (int r = 0; r < repeats; ++r) {
    for (std::size_t k = 0; k < batch.sweeps.size(); ++k) {
      const SweepQuery& q = batch.sweeps[k];
      const btTransform from(btQuaternion::getIdentity(), toBt(q.from));
      const btTransform to(btQuaternion::getIdentity(), toBt(q.from + q.translation));
      btCollisionWorld::ClosestConvexResultCallback hit(from.getOrigin(), to.getOrigin());
      w->world.convexSweepTest(&sphere, from, to, hit, 0.0f);
      if (hit.hasHit()) run.sweepFractions[k] = hit.m_closestHitFraction;
    }
  }
  run.sweepCpuSeconds = processCpuSeconds() - sweepStart;
  return run;
}

}  // namespace collide::bench
