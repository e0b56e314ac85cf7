// The summary of a run, as the table `collide run` prints and as JSON (--json).
#include "json_output.h"

#include <collide/scene/runner.h>

#include <algorithm>
#include <cstdio>

namespace collide::scene {

namespace {

std::string hex(std::uint64_t value) {
  char text[24];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(value));
  return text;
}

nlohmann::json stageJson(const StageTimes& t) {
  nlohmann::json json;
  for (const StageTimes::Stage& stage : StageTimes::kStages) json[stage.key] = t.*stage.seconds;
  json["total"] = t.total();
  return json;
}

nlohmann::json statsJson(const StepStats& s) {
  return {{"potential_pairs", s.potentialPairs},      {"broad_phase_pairs", s.keptPairs},
          {"narrow_phase_tests", s.narrowPhaseTests}, {"reused_manifolds", s.reusedManifolds},
          {"contact_pairs", s.contactPairs},          {"stage_seconds", stageJson(s.time)}};
}

nlohmann::json memoryJson(const WorldMemory& m, std::size_t scene) {
  nlohmann::json json;
  for (const WorldMemory::Category& category : WorldMemory::kCategories)
    json[category.key] = m.*category.bytes;
  json["world"] = m.total();
  json["scene"] = scene;
  return json;
}

}  // namespace

std::string formatSummary(const RunSummary& s) {
  std::string out;
  char line[256];
  const auto add = [&](const char* format, auto... values) {
    std::snprintf(line, sizeof line, format, values...);
    out += line;
  };
  const double simTime = s.steps * double(s.dt);
  add("scene           %s\n", s.scene.c_str());
  add("steps           %d x %.3f ms = %.3f s simulated\n", s.steps, s.dt * 1e3, simTime);
  add("wall time       %.3f s, %.3f ms/step\n", s.wallSeconds,
      s.steps == 0 ? 0.0 : s.wallSeconds * 1e3 / s.steps);
  add("bodies          %d: %d static, %d kinematic, %d dynamic\n",
      s.staticBodies + s.kinematicBodies + s.dynamicBodies, s.staticBodies, s.kinematicBodies,
      s.dynamicBodies);
  if (s.sleeping)
    add("sleeping        %d awake, %d asleep (dynamic bodies at the end)\n", s.awakeBodies, s.asleepBodies);
  if (s.brokenBodies > 0) add("broken          %d bodies removed\n", s.brokenBodies);
  if (s.brokenJoints > 0) add("broken joints   %d\n", s.brokenJoints);
  add("contact events  %llu\n", static_cast<unsigned long long>(s.contactEvents));
  if (!s.faults.empty()) {
    // The figures below count the frozen bodies as they were left (stopped where the faulted step
    // began), so the summary says first that the run did not simulate them to the end.
    add("faults          %zu %s frozen by the fault guard (state no longer finite; docs/reliability.md)\n",
        s.faults.size(), s.faults.size() == 1 ? "body" : "bodies");
    constexpr std::size_t kListed = 8;
    for (std::size_t i = 0; i < std::min(s.faults.size(), kListed); ++i) {
      const RunSummary::Fault& f = s.faults[i];
      std::string fields;
      for (const std::string& name : faultFieldNames(f.fields)) fields += (fields.empty() ? "" : ", ") + name;
      out += "                " + f.body + " at step " + std::to_string(f.step) + ": " + fields + "\n";
    }
    if (s.faults.size() > kListed) add("                and %zu more\n", s.faults.size() - kListed);
  }
  add("\n%-24s %14s %16s\n", "pairs", "last step", "total");
  const auto row = [&](const char* name, std::uint64_t last, std::uint64_t total) {
    add("%-24s %14llu %16llu\n", name, static_cast<unsigned long long>(last),
        static_cast<unsigned long long>(total));
  };
  row("potential n(n-1)/2", s.lastStep.potentialPairs, s.total.potentialPairs);
  row("kept by broad phase", s.lastStep.keptPairs, s.total.keptPairs);
  row("narrow-phase tests", s.lastStep.narrowPhaseTests, s.total.narrowPhaseTests);
  row("  manifold reused", s.lastStep.reusedManifolds, s.total.reusedManifolds);
  row("in contact", s.lastStep.contactPairs, s.total.contactPairs);
  if (s.total.potentialPairs > 0) {
    add("in contact / potential: %.4f%%\n",
        100.0 * double(s.total.contactPairs) / double(s.total.potentialPairs));
  }
  // Where the step's time went, averaged over the run.
  const StageTimes& t = s.total.time;
  if (s.steps > 0 && t.total() > 0.0) {
    add("\n%-24s %14s %16s\n", "time by stage", "ms/step", "share");
    for (const StageTimes::Stage& stage : StageTimes::kStages) {
      const double seconds = t.*stage.seconds;
      add("%-24s %14.4f %15.1f%%\n", stage.label, seconds * 1e3 / s.steps, 100.0 * seconds / t.total());
    }
  }
  // What the world and the scene hold at the end, by stage.
  const double worldBytes = double(s.worldMemory.total());
  add("\n%-24s %14s %16s\n", "heap at the end", "MB", "share of world");
  for (const WorldMemory::Category& category : WorldMemory::kCategories) {
    const double bytes = double(s.worldMemory.*category.bytes);
    add("%-24s %14.3f %15.1f%%\n", category.label, bytes / 1e6,
        worldBytes > 0.0 ? 100.0 * bytes / worldBytes : 0.0);
  }
  add("%-24s %14.3f\n", "world", worldBytes / 1e6);
  add("%-24s %14.3f\n", "scene", double(s.sceneMemory) / 1e6);
  add("\nmomentum        (%.6g, %.6g, %.6g) kg m/s\n", s.momentum.x, s.momentum.y, s.momentum.z);
  add("kinetic energy  %.6g J\n", s.kineticEnergy);
  for (const RunSummary::CharacterEnd& c : s.characters) {
    add("character       %s: feet at (%.3f, %.3f, %.3f), %s, %zu of %zu waypoints\n", c.name.c_str(),
        c.position.x, c.position.y, c.position.z, std::string(toString(c.ground)).c_str(), c.waypointsReached,
        c.waypoints);
  }
  add("state hash      %s\n", hex(s.stateHash).c_str());
  return out;
}

std::string summaryJson(const RunSummary& s) {
  nlohmann::json characters = nlohmann::json::array();
  for (const RunSummary::CharacterEnd& c : s.characters) {
    characters.push_back({{"name", c.name},
                          {"feet", jsonVec3(c.position)},
                          {"ground", toString(c.ground)},
                          {"waypoints_reached", c.waypointsReached},
                          {"waypoints", c.waypoints}});
  }
  nlohmann::json faults = nlohmann::json::array();
  for (const RunSummary::Fault& f : s.faults)
    faults.push_back({{"body", f.body}, {"step", f.step}, {"fields", faultFieldNames(f.fields)}});
  const nlohmann::json j = {
      {"scene", s.scene},
      {"steps", s.steps},
      {"dt", jsonNumber(s.dt)},
      {"sim_time", s.steps * double(s.dt)},
      {"wall_seconds", s.wallSeconds},
      {"ms_per_step", s.steps == 0 ? 0.0 : s.wallSeconds * 1e3 / s.steps},
      {"bodies",
       {{"static", s.staticBodies}, {"kinematic", s.kinematicBodies}, {"dynamic", s.dynamicBodies}}},
      {"broken_bodies", s.brokenBodies},
      {"broken_joints", s.brokenJoints},
      {"sleeping", {{"enabled", s.sleeping}, {"awake", s.awakeBodies}, {"asleep", s.asleepBodies}}},
      {"contact_events", s.contactEvents},
      {"faults", faults},
      {"last_step", statsJson(s.lastStep)},
      {"total", statsJson(s.total)},
      {"momentum", jsonVec3(s.momentum)},
      {"kinetic_energy", jsonNumber(s.kineticEnergy)},
      {"memory_bytes", memoryJson(s.worldMemory, s.sceneMemory)},
      {"characters", characters},
      {"state_hash", hex(s.stateHash)}};
  return j.dump(2) + "\n";
}

}  // namespace collide::scene
