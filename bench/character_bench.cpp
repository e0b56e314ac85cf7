// Characters walking through R4 (docs/character.md, docs/benchmarks.md): the terrain scene
// (reference-scenes.md R4: the 100 x 100 m sine mesh and its 2,000 hulls, stepped 3 s so that the
// hulls lie on the ground) and 1,000 characters (capsules of radius 0.3 m and half height 0.6 m,
// steps of 0.35 m, slopes of 45 degrees) on a grid over the terrain wherever the capsule is clear of
// the hulls. Each walks at 4 m/s in a direction drawn once a second (std::mt19937 seeded 7), turned
// back towards the centre near the terrain's edge. One benchmark iteration is one 60 Hz frame: every
// character's update, the world not stepped (the hulls lie still; what the characters push only
// gains velocity). The counter us_per_character is the time of one character update.
//
// The peer: Bullet's kinematic character controller (btKinematicCharacterController on a
// btPairCachingGhostObject with the same capsule, step height and slope limit) in a collision world
// holding the same triangles (btBvhTriangleMeshShape) and the same hulls where collide's step left
// them (static there: Bullet's controller does not push), each frame the broad phase's pair update
// (which the controller's ghost caches need) and every controller's updateAction with the same walk.
#include <benchmark/benchmark.h>
#include <collide/character.h>
#include <collide/scene/reference_scenes.h>
#include <collide/scene/scene.h>
#include <collide/world.h>

#include <cmath>
#include <memory>
#include <random>
#include <vector>

#if defined(COLLIDE_BENCH_WITH_BULLET)
#include <BulletCollision/CollisionDispatch/btGhostObject.h>
#include <BulletDynamics/Character/btKinematicCharacterController.h>
#include <btBulletCollisionCommon.h>
#endif

using namespace collide;

namespace {

constexpr int kCharacters = 1000;
constexpr float kDt = 1.0f / 60.0f;
constexpr float kWalkSpeed = 4.0f;
constexpr int kFramesPerDirection = 60;
constexpr int kFrames = 600;    // the benchmark's iterations: 10 s of walking
constexpr float kEdge = 44.0f;  // beyond this |x| or |z| a character heads back to the centre

CharacterDef characterDef(const Vec3& position) {
  CharacterDef def;
  def.position = position;
  def.radius = 0.3f;
  def.halfHeight = 0.6f;
  def.maxStepHeight = 0.35f;
  def.maxSlope = 45.0f * kPi / 180.0f;
  return def;
}

// The R4 world with its hulls settled, and the characters' start positions (capsule centres).
struct TerrainWalk {
  scene::SceneWorld built;
  std::vector<Vec3> starts;
  std::vector<float> headings;  // per character and second: kCharacters * seconds, radians
};

const TerrainWalk& terrainWalk() {
  static const std::unique_ptr<TerrainWalk> walk = [] {
    auto out = std::make_unique<TerrainWalk>(
        TerrainWalk{scene::buildWorld(scene::loadReferenceScene("R4")), {}, {}});
    World& world = out->built.world;
    for (int i = 0; i < 180; ++i) world.step(kDt);
    // A grid of 40 x 40 spots 2.3 m apart, first come first served: the first 1,000 whose capsule
    // (grown by 0.2 m) touches nothing but the terrain.
    const CharacterDef def = characterDef(Vec3(0.0f));
    const Shape probe(Capsule{def.radius + 0.2f, def.halfHeight});
    const BodyId terrain = out->built.bodies.front();
    for (int i = 0; i < 40 && out->starts.size() < kCharacters; ++i) {
      for (int k = 0; k < 40 && out->starts.size() < kCharacters; ++k) {
        const float x = -44.85f + 2.3f * static_cast<float>(i), z = -44.85f + 2.3f * static_cast<float>(k);
        const float ground = static_cast<float>(scene::terrainHeight(x, z));
        const Vec3 centre(x, ground + 0.6f + def.halfHeight + def.radius, z);
        bool clear = true;
        for (const OverlapResult& hit : world.overlapShape(probe, Transform{centre, Quat(1, 0, 0, 0), 1.0f}))
          clear = clear && hit.body == terrain;
        if (clear) out->starts.push_back(centre);
      }
    }
    std::mt19937 random(7);
    std::uniform_real_distribution<float> angle(0.0f, 2.0f * kPi);
    for (int i = 0; i < kCharacters * (kFrames / kFramesPerDirection + 1); ++i)
      out->headings.push_back(angle(random));
    return out;
  }();
  return *walk;
}

// The walk of character `index` at `frame` from where its feet are.
Vec3 walkVelocity(const TerrainWalk& walk, std::size_t index, int frame, const Vec3& at) {
  if (std::abs(at.x) > kEdge || std::abs(at.z) > kEdge) {
    const Vec3 home(-at.x, 0.0f, -at.z);
    return kWalkSpeed * glm::normalize(home);
  }
  const float heading =
      walk.headings[static_cast<std::size_t>(frame / kFramesPerDirection) * kCharacters + index];
  return kWalkSpeed * Vec3(std::cos(heading), 0.0f, std::sin(heading));
}

void BM_CharactersThroughR4_collide(benchmark::State& state) {
  const TerrainWalk& walk = terrainWalk();
  // A copy of the settled world per run, so that each run starts alike.
  scene::Scene scene = scene::loadReferenceScene("R4");
  scene::SceneWorld built = scene::buildWorld(scene);
  for (int i = 0; i < 180; ++i) built.world.step(kDt);
  std::vector<Character> characters;
  for (const Vec3& start : walk.starts) characters.emplace_back(characterDef(start));
  int frame = 0;
  for (auto _ : state) {
    for (std::size_t i = 0; i < characters.size(); ++i)
      characters[i].update(built.world, walkVelocity(walk, i, frame, characters[i].position()), kDt);
    ++frame;
  }
  std::size_t onGround = 0, sliding = 0;
  for (const Character& c : characters) {
    onGround += c.isOnGround() ? 1 : 0;
    sliding += c.groundState() == GroundState::Sliding ? 1 : 0;
  }
  state.counters["characters"] = static_cast<double>(characters.size());
  state.counters["on_ground"] = static_cast<double>(onGround);
  state.counters["sliding"] = static_cast<double>(sliding);
  state.counters["us_per_character"] = benchmark::Counter(
      static_cast<double>(characters.size()) * static_cast<double>(state.iterations()) * 1e-6,
      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_CharactersThroughR4_collide)->Iterations(kFrames)->Unit(benchmark::kMillisecond);

#if defined(COLLIDE_BENCH_WITH_BULLET)
void BM_CharactersThroughR4_Bullet(benchmark::State& state) {
  const TerrainWalk& walk = terrainWalk();
  const World& world = walk.built.world;
  btDefaultCollisionConfiguration configuration;
  btCollisionDispatcher dispatcher(&configuration);
  btDbvtBroadphase broadphase;
  btGhostPairCallback ghostPairs;
  broadphase.getOverlappingPairCache()->setInternalGhostPairCallback(&ghostPairs);
  btCollisionWorld bullet(&dispatcher, &broadphase, &configuration);

  // The terrain's triangles.
  const TriangleMesh& mesh = world.shape(walk.built.bodies.front()).mesh();
  std::vector<btScalar> vertices;
  for (const Vec3& v : mesh.vertices()) vertices.insert(vertices.end(), {v.x, v.y, v.z});
  std::vector<int> indices;
  for (const MeshTriangle& t : mesh.triangles())
    indices.insert(indices.end(), {int(t.v[0]), int(t.v[1]), int(t.v[2])});
  btTriangleIndexVertexArray triangles(int(mesh.triangles().size()), indices.data(), 3 * sizeof(int),
                                       int(mesh.vertices().size()), vertices.data(), 3 * sizeof(btScalar));
  btBvhTriangleMeshShape terrainShape(&triangles, true);
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btCollisionObject>> objects;
  const auto addStatic = [&](btCollisionShape* shape, const Transform& t) {
    auto object = std::make_unique<btCollisionObject>();
    object->setCollisionShape(shape);
    object->setWorldTransform(
        btTransform(btQuaternion(t.rotation.x, t.rotation.y, t.rotation.z, t.rotation.w),
                    btVector3(t.position.x, t.position.y, t.position.z)));
    bullet.addCollisionObject(object.get(), btBroadphaseProxy::StaticFilter,
                              btBroadphaseProxy::AllFilter ^ btBroadphaseProxy::StaticFilter);
    objects.push_back(std::move(object));
  };
  addStatic(&terrainShape, world.transform(walk.built.bodies.front()));
  // The hulls where collide's 3 s left them.
  for (std::size_t i = 1; i < walk.built.bodies.size(); ++i) {
    const BodyId id = walk.built.bodies[i];
    auto hull = std::make_unique<btConvexHullShape>();
    for (const Vec3& v : world.shape(id).convexHull().vertices())
      hull->addPoint(btVector3(v.x, v.y, v.z), false);
    hull->recalcLocalAabb();
    addStatic(hull.get(), world.transform(id));
    shapes.push_back(std::move(hull));
  }

  const CharacterDef def = characterDef(Vec3(0.0f));
  btCapsuleShape capsule(def.radius, 2.0f * def.halfHeight);
  std::vector<std::unique_ptr<btPairCachingGhostObject>> ghosts;
  std::vector<std::unique_ptr<btKinematicCharacterController>> controllers;
  for (const Vec3& start : walk.starts) {
    auto ghost = std::make_unique<btPairCachingGhostObject>();
    ghost->setWorldTransform(btTransform(btQuaternion::getIdentity(), btVector3(start.x, start.y, start.z)));
    ghost->setCollisionShape(&capsule);
    ghost->setCollisionFlags(btCollisionObject::CF_CHARACTER_OBJECT);
    bullet.addCollisionObject(ghost.get(), btBroadphaseProxy::CharacterFilter,
                              btBroadphaseProxy::StaticFilter | btBroadphaseProxy::DefaultFilter);
    auto controller = std::make_unique<btKinematicCharacterController>(ghost.get(), &capsule,
                                                                       def.maxStepHeight, btVector3(0, 1, 0));
    controller->setMaxSlope(def.maxSlope);
    controller->setGravity(btVector3(0.0f, -9.81f, 0.0f));
    ghosts.push_back(std::move(ghost));
    controllers.push_back(std::move(controller));
  }
  bullet.updateAabbs();
  broadphase.calculateOverlappingPairs(&dispatcher);

  int frame = 0;
  for (auto _ : state) {
    broadphase.calculateOverlappingPairs(&dispatcher);
    for (std::size_t i = 0; i < controllers.size(); ++i) {
      const btVector3 at = ghosts[i]->getWorldTransform().getOrigin();
      const Vec3 v = walkVelocity(walk, i, frame, Vec3(at.x(), at.y(), at.z()));
      controllers[i]->setWalkDirection(btVector3(v.x, v.y, v.z) * kDt);
      controllers[i]->updateAction(&bullet, kDt);
    }
    ++frame;
  }
  std::size_t onGround = 0;
  for (const auto& c : controllers) onGround += c->onGround() ? 1 : 0;
  state.counters["characters"] = static_cast<double>(controllers.size());
  state.counters["on_ground"] = static_cast<double>(onGround);
  state.counters["us_per_character"] = benchmark::Counter(
      static_cast<double>(controllers.size()) * static_cast<double>(state.iterations()) * 1e-6,
      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  for (auto& ghost : ghosts) bullet.removeCollisionObject(ghost.get());
  for (auto& object : objects) bullet.removeCollisionObject(object.get());
}
BENCHMARK(BM_CharactersThroughR4_Bullet)->Iterations(kFrames)->Unit(benchmark::kMillisecond);
#endif

}  // namespace
