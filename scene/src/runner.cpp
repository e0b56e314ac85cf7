// The loop behind `collide run`: step the World, stream the recording and the contact events, apply
// damage to breakable bodies from contact begin events, and gather the summary.
#include "file_text.h"
#include "json_output.h"

#include <collide/scene/limits.h>
#include <collide/scene/output_file.h>
#include <collide/scene/runner.h>

#include <unistd.h>

#include <bit>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <map>
#if defined(__GLIBC__)  // after a C library header has told which one it is
#include <malloc.h>
#endif

namespace collide::scene {

namespace {

// The scene's text and parsed document are freed by now, in the middle of the C heap, where glibc
// keeps them resident; the world's large arrays are mapped from the system (collide/hooks.h) and
// cannot reuse them. Handed back before the world is built: 35 MB of the 65,536-cube lattice's
// scene file.
void releaseFreedHeap() {
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
}

// Streams the recording: {"dt": ..., "frames": [ ... ]}, one frame at a time.
class Recorder {
 public:
  // With sleeping on, each body also carries "awake" (static bodies: false).
  Recorder(const std::string& path, float dt, bool sleeping) : out_(path, "recording"), sleeping_(sleeping) {
    out_.write("{\"dt\": " + jsonNumber(dt).dump() + ", \"frames\": [\n");
  }
  void frame(int step, double time, const SceneWorld& sw) {
    nlohmann::json bodies = nlohmann::json::array();
    for (BodyId id : sw.bodies) {
      if (!sw.world.isValid(id)) continue;  // broken
      const Transform t = sw.world.transform(id);
      nlohmann::json body = {{"name", sw.world.name(id)},
                             {"position", jsonVec3(t.position)},
                             {"rotation", jsonQuat(t.rotation)},
                             {"velocity", jsonVec3(sw.world.linearVelocity(id))},
                             {"angular_velocity", jsonVec3(sw.world.angularVelocity(id))}};
      if (sleeping_) body["awake"] = sw.world.isAwake(id);
      bodies.push_back(std::move(body));
    }
    const nlohmann::json f = {{"step", step}, {"time", time}, {"bodies", std::move(bodies)}};
    out_.write(first_ ? "" : ",\n");
    out_.write(f.dump());
    first_ = false;
  }
  void close() {
    out_.write("\n]}\n");
    out_.close();
  }
  void commit() { out_.commit(); }

 private:
  OutputFile out_;
  bool sleeping_;
  bool first_ = true;
};

void progressBar(int step, int steps) {
  constexpr int kWidth = 40;
  const int filled = steps == 0 ? kWidth : step * kWidth / steps;
  std::fprintf(stderr, "\r[%s%s] %3d%% step %d/%d", std::string(filled, '#').c_str(),
               std::string(kWidth - filled, ' ').c_str(), steps == 0 ? 100 : step * 100 / steps, step, steps);
  if (step == steps) std::fprintf(stderr, "\n");
  std::fflush(stderr);
}

// Mixes a float's bit pattern into an FNV-1a hash (64 bit), byte by byte. memcpy, not std::bit_cast,
// which emscripten's libc++ 14 lacks.
void mixFloat(std::uint64_t& hash, float value) {
  std::uint32_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  for (int i = 0; i < 4; ++i) {
    hash ^= (bits >> (8 * i)) & 0xFFu;
    hash *= 1099511628211ull;
  }
}

}  // namespace

std::uint64_t stateHash(const SceneWorld& sw) {
  std::uint64_t hash = 14695981039346656037ull;  // FNV-1a, 64 bit
  const auto mix = [&](float value) { mixFloat(hash, value); };
  const auto mixVec = [&](const Vec3& v) {
    mix(v.x);
    mix(v.y);
    mix(v.z);
  };
  for (BodyId id : sw.bodies) {
    if (!sw.world.isValid(id)) continue;
    const Transform t = sw.world.transform(id);
    mixVec(t.position);
    mix(t.rotation.x);
    mix(t.rotation.y);
    mix(t.rotation.z);
    mix(t.rotation.w);
    mixVec(sw.world.linearVelocity(id));
    mixVec(sw.world.angularVelocity(id));
  }
  return hash;
}

// A constraint's name in events: its "name", or its place in the file.
std::string jointName(const Scene& scene, const SceneWorld& sw, JointId joint) {
  for (std::size_t i = 0; i < sw.constraints.size(); ++i) {
    if (sw.constraints[i] != joint) continue;
    return scene.constraints[i].name.empty() ? "constraints[" + std::to_string(i) + "]"
                                             : scene.constraints[i].name;
  }
  return "joint " + std::to_string(joint.index);
}

std::vector<std::string> faultFieldNames(std::uint8_t fields) {
  std::vector<std::string> out;
  if (fields & FaultEvent::kPosition) out.emplace_back("position");
  if (fields & FaultEvent::kRotation) out.emplace_back("rotation");
  if (fields & FaultEvent::kLinearVelocity) out.emplace_back("linear_velocity");
  if (fields & FaultEvent::kAngularVelocity) out.emplace_back("angular_velocity");
  return out;
}

namespace {

// runScene; `owned`, when the caller handed the scene over, is `scene` itself, whose bodies go once
// the run has taken what it reads of them.
RunSummary runOwnedOrNot(const Scene& scene, Scene* owned, const RunOptions& options) {
  const int steps = options.steps.value_or(scene.steps);
  if (steps < 0) throw Error("run: steps must be >= 0, got " + std::to_string(steps));
  if (options.recordEvery < 1)
    throw Error("run: --every must be >= 1, got " + std::to_string(options.recordEvery));
  if (!options.snapshotPath.empty() && (options.snapshotAt < 0 || options.snapshotAt > steps))
    throw Error("run: --snapshot-at must be from 0 to the run's " + std::to_string(steps) + " steps, got " +
                std::to_string(options.snapshotAt));
  checkOutputPaths(scene,
                   {{"recording", options.recordPath},
                    {"events", options.eventsPath},
                    {"summary", options.summaryPath},
                    {"snapshot", options.snapshotPath}},
                   {{"snapshot", options.fromSnapshotPath}});

  releaseFreedHeap();
  SceneWorld sw = buildWorld(scene);
  if (!options.fromSnapshotPath.empty()) {
    const std::string who = "snapshot file \"" + options.fromSnapshotPath + "\"";
    const std::string bytes = readFileText(options.fromSnapshotPath, kMaxSnapshotBytes, who);
    try {
      sw.world.loadSnapshot({reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()});
    } catch (const Error& e) {
      throw Error(who + ": " + e.what());
    }
    // Saved from this scene: its bodies are the snapshot's, with their names (a body broken before
    // the snapshot is gone from it, and only that).
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
      const std::string& name = scene.bodies[i].def.name;
      const BodyId id = sw.bodies[i];
      if (sw.world.isValid(id) ? sw.world.name(id) != name : !scene.bodies[i].breakImpulse) {
        throw Error(who + ": not saved from this scene (" + scene.source + "): its body " +
                    std::to_string(id.index) + " is not the scene's body " + std::to_string(i) +
                    (name.empty() ? "" : " (" + name + ")"));
      }
    }
  }
  std::optional<OutputFile> snapshotFile;
  if (!options.snapshotPath.empty()) snapshotFile.emplace(options.snapshotPath, "snapshot");
  const auto saveSnapshot = [&] {
    const std::vector<std::uint8_t> bytes = sw.world.saveSnapshot();
    snapshotFile->write({reinterpret_cast<const char*>(bytes.data()), bytes.size()});
  };
  if (snapshotFile && options.snapshotAt == 0) saveSnapshot();
  RunSummary summary;
  summary.scene = scene.source;
  summary.steps = steps;
  summary.dt = scene.dt;
  for (const Body& b : scene.bodies) {
    (b.def.type == BodyType::Static      ? summary.staticBodies
     : b.def.type == BodyType::Kinematic ? summary.kinematicBodies
                                         : summary.dynamicBodies)++;
  }

  std::optional<Recorder> recorder;
  if (!options.recordPath.empty()) recorder.emplace(options.recordPath, scene.dt, scene.world.sleeping);
  std::optional<OutputFile> events;
  if (!options.eventsPath.empty()) events.emplace(options.eventsPath, "events");
  std::optional<OutputFile> summaryFile;
  if (!options.summaryPath.empty()) summaryFile.emplace(options.summaryPath, "summary");

  // Breakable bodies by slot index: their threshold and the damage so far.
  struct Breakable {
    std::size_t body;
    float threshold;
    float damage = 0.0f;
  };
  std::map<std::uint32_t, Breakable> breakable;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    if (scene.bodies[i].breakImpulse) breakable[sw.bodies[i].index] = {i, *scene.bodies[i].breakImpulse};
  }
  // Names by slot index, for events that name a body broken in the same step.
  std::vector<std::string> names(scene.bodies.size());
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    if (sw.bodies[i].index >= names.size()) names.resize(sw.bodies[i].index + 1);
    names[sw.bodies[i].index] = scene.bodies[i].def.name;
  }
  if (owned) std::vector<Body>().swap(owned->bodies);  // freed: nothing below reads them

  // The scene's characters (our extension): after each step, each walks towards its next waypoint.
  struct Walker {
    Character character;
    const SceneCharacter* scene;
    CharacterPath path;
  };
  std::vector<Walker> walkers;
  for (std::size_t i = 0; i < scene.characters.size(); ++i) {
    try {
      walkers.push_back(
          {Character(scene.characters[i].def), &scene.characters[i], CharacterPath(scene.characters[i])});
    } catch (const Error& e) {
      throw Error(scene.source + ": characters[" + std::to_string(i) + "]: " + e.what());
    }
  }
  const auto walk = [&](Walker& w) {
    w.character.update(sw.world, w.path.nextVelocity(w.character, scene.dt), scene.dt);
  };

  if (recorder) recorder->frame(0, 0.0, sw);
  const int progressEvery = std::max(1, steps / 100);
  const auto start = std::chrono::steady_clock::now();
  for (int step = 1; step <= steps; ++step) {
    sw.world.step(scene.dt);
    summary.total += sw.world.lastStats();
    std::vector<std::size_t> broken;
    for (const ContactEvent& e : sw.world.contactEvents()) {
      ++summary.contactEvents;
      if (events) {
        const nlohmann::json line = {{"step", step},
                                     {"type", e.type == ContactEvent::Type::Begin     ? "begin"
                                              : e.type == ContactEvent::Type::Persist ? "persist"
                                                                                      : "end"},
                                     {"a", names[e.a.index]},
                                     {"b", names[e.b.index]},
                                     {"point", jsonVec3(e.point)},
                                     {"normal", jsonVec3(e.normal)},
                                     {"impulse", jsonNumber(e.impulse)},
                                     {"speed", jsonNumber(e.speed)}};
        events->write(line.dump() + '\n');
      }
      if (e.type != ContactEvent::Type::Begin) continue;
      for (BodyId id : {e.a, e.b}) {
        auto it = breakable.find(id.index);
        if (it == breakable.end()) continue;
        it->second.damage += e.impulse;
        if (it->second.damage > it->second.threshold) {
          broken.push_back(it->second.body);
          breakable.erase(it);
        }
      }
    }
    if (events) {
      for (const SensorEvent& e : sw.world.sensorEvents()) {
        const nlohmann::json line = {{"step", step},
                                     {"type", e.type == SensorEvent::Type::Begin ? "begin" : "end"},
                                     {"a", names[e.sensor.index]},
                                     {"b", names[e.visitor.index]},
                                     {"sensor", true}};
        events->write(line.dump() + '\n');
      }
    }
    for (const FaultEvent& e : sw.world.faultEvents()) {
      summary.faults.push_back({names[e.body.index], step, e.fields});
      if (events) {
        const nlohmann::json line = {{"step", step},
                                     {"type", "fault"},
                                     {"a", names[e.body.index]},
                                     {"fields", faultFieldNames(e.fields)}};
        events->write(line.dump() + '\n');
      }
    }
    for (const JointBreakEvent& e : sw.world.jointBreakEvents()) {
      ++summary.brokenJoints;
      if (!events) continue;
      const nlohmann::json line = {{"step", step},
                                   {"type", "joint_break"},
                                   {"joint", jointName(scene, sw, e.joint)},
                                   {"a", names[e.a.index]},
                                   {"b", names[e.b.index]},
                                   {"force", jsonNumber(e.force)},
                                   {"torque", jsonNumber(e.torque)}};
      events->write(line.dump() + '\n');
    }
    for (std::size_t body : broken) {
      sw.world.destroyBody(sw.bodies[body]);
      ++summary.brokenBodies;
    }
    for (Walker& w : walkers) walk(w);
    if (snapshotFile && step == options.snapshotAt) saveSnapshot();
    if (recorder && (step % options.recordEvery == 0 || step == steps))
      recorder->frame(step, step * double(scene.dt), sw);
    if (options.progress && (step % progressEvery == 0 || step == steps)) progressBar(step, steps);
  }
  summary.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (steps > 0) summary.lastStep = sw.world.lastStats();
  summary.total.proxies = summary.lastStep.proxies;
  summary.momentum = sw.world.linearMomentum();
  summary.kineticEnergy = sw.world.kineticEnergy();
  summary.stateHash = stateHash(sw);
  for (const Walker& w : walkers) {
    // The characters' feet join the hash (FNV-1a on, as stateHash mixes).
    const Vec3 feet = w.character.footPosition();
    for (const float value : {feet.x, feet.y, feet.z}) mixFloat(summary.stateHash, value);
    summary.characters.push_back(
        {w.scene->name, feet, w.character.groundState(), w.path.reached(), w.scene->path.size()});
  }
  summary.worldMemory = sw.world.memoryUse();
  summary.sceneMemory = sceneMemoryBytes(scene, sw);
  summary.sleeping = scene.world.sleeping;
  for (BodyId id : sw.bodies) {
    if (!sw.world.isValid(id) || sw.world.type(id) != BodyType::Dynamic) continue;
    ++(sw.world.isAwake(id) ? summary.awakeBodies : summary.asleepBodies);
  }
  // Every output complete and closed before any replaces its target.
  if (recorder) recorder->close();
  if (events) events->close();
  if (snapshotFile) snapshotFile->close();
  if (summaryFile) {
    summaryFile->write(summaryJson(summary));
    summaryFile->close();
  }
  if (recorder) recorder->commit();
  if (events) events->commit();
  if (snapshotFile) snapshotFile->commit();
  if (summaryFile) summaryFile->commit();
  return summary;
}

}  // namespace

RunSummary runScene(const Scene& scene, const RunOptions& options) {
  return runOwnedOrNot(scene, nullptr, options);
}

RunSummary runScene(Scene&& scene, const RunOptions& options) {
  return runOwnedOrNot(scene, &scene, options);
}

}  // namespace collide::scene
