// collide_vs_bullet: the reference scenes (docs/benchmarks.md, reference-scenes.md) built from one
// scene description in collide and in Bullet 3.24, run in turn in one process, several times.
//
// Every (run, scene, engine) executes in a forked child, so that each engine's memory is measured
// alone and cleanly: the child trims the heap, resets its peak resident set (/proc/self/clear_refs,
// "5"), builds the world, steps it, and reports VmHWM - VmRSS(start) as the memory the engine
// needed, together with its timings and the stability figures, through a pipe. The scene itself is
// loaded (JSON parsed, hulls built) once in the parent, before any fork, and is not counted for
// either engine. Runs alternate engines scene by scene, so a change of machine load during the
// benchmark hits both.
#include "engines.h"
#include "figures.h"

#include <collide/error.h>
#include <collide/scene/builtin_scenes.h>

#include <CLI/CLI.hpp>

#include <malloc.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

using namespace collide;
using namespace collide::bench;

namespace {

struct SceneInfo {
  std::string id;                // R1 ... or the file name
  std::string name;              // the built-in name, or the path
  std::optional<double> target;  // the goal: collide / Bullet below this ratio
};

const std::vector<SceneInfo> kReferenceScenes = {{"R1", "pile", 0.34},
                                                 {"R2", "rain", 0.67},
                                                 {"R3", "pyramid", 0.63},
                                                 {"R4", "terrain", 0.16},
                                                 {"B1", "billiards", {}}};
// The joint benchmarks (issue scenes, not run by default): Box3D's joint grid and a ragdoll pile.
const std::vector<SceneInfo> kJointScenes = {{"J1", "joint-grid", 0.5}, {"J2", "ragdoll-pile", 0.5}};

SceneInfo resolveScene(const std::string& arg) {
  for (const std::vector<SceneInfo>* list : {&kReferenceScenes, &kJointScenes}) {
    for (const SceneInfo& s : *list) {
      if (arg == s.id || arg == s.name) return s;
    }
  }
  if (scene::isBuiltinScene(arg)) return {arg, arg, {}};
  if (std::filesystem::exists(arg)) return {std::filesystem::path(arg).filename().string(), arg, {}};
  throw Error("--scene: '" + arg +
              "' is not a benchmark scene (R1 R2 R3 R4 B1 J1 J2 or their names), a "
              "built-in scene or a file");
}

scene::Scene loadScene(const SceneInfo& info) {
  return scene::isBuiltinScene(info.name) ? scene::loadBuiltinScene(info.name)
                                          : scene::loadSceneFile(info.name);
}

// What a child sends back: plain data, written raw through the pipe (same binary on both ends).
struct Report {
  bool ok = false;
  char error[512] = {};
  double buildMs = 0.0;
  double wallMsPerStep = 0.0;
  double cpuMsPerStep = 0.0;
  int steps = 0;
  int internalSteps = 0;
  long rssStartKb = 0;
  long rssPeakKb = 0;
  Figures figures;
};

long statusKb(const char* field) {
  std::ifstream in("/proc/self/status");
  std::string line;
  const std::size_t n = std::strlen(field);
  while (std::getline(in, line)) {
    if (line.compare(0, n, field) == 0 && line.size() > n && line[n] == ':')
      return std::stol(line.substr(n + 1));
  }
  return -1;
}

Report runChild(const scene::Scene& scene, Engine engine, int steps) {
  Report r;
  r.steps = steps;
  malloc_trim(0);
  {
    // Reset the peak resident set to the current one (Linux >= 4.0), so VmHWM measures this run.
    std::ofstream clear("/proc/self/clear_refs");
    clear << "5";
  }
  r.rssStartKb = statusKb("VmRSS");
  const EngineRun run = engine == Engine::Collide ? runCollide(scene, steps) : runBullet(scene, steps);
  r.rssPeakKb = statusKb("VmHWM");
  r.buildMs = run.buildMs;
  r.wallMsPerStep = run.wallMsPerStep;
  r.cpuMsPerStep = run.cpuMsPerStep;
  r.internalSteps = run.internalSteps;
  r.figures = computeFigures(scene, run.poses, run.masses);
  r.ok = true;
  return r;
}

Report forkRun(const scene::Scene& scene, Engine engine, int steps) {
  std::fflush(stdout);
  std::fflush(stderr);
  int fds[2];
  if (pipe(fds) != 0) throw Error(std::string("pipe: ") + std::strerror(errno));
  const pid_t pid = fork();
  if (pid < 0) throw Error(std::string("fork: ") + std::strerror(errno));
  if (pid == 0) {
    close(fds[0]);
    Report r;
    try {
      r = runChild(scene, engine, steps);
    } catch (const std::exception& e) {
      std::snprintf(r.error, sizeof r.error, "%s", e.what());
    }
    const char* p = reinterpret_cast<const char*>(&r);
    std::size_t left = sizeof r;
    while (left > 0) {
      const ssize_t n = write(fds[1], p, left);
      if (n <= 0) _exit(3);
      p += n;
      left -= static_cast<std::size_t>(n);
    }
    _exit(0);
  }
  close(fds[1]);
  Report r;
  char* p = reinterpret_cast<char*>(&r);
  std::size_t got = 0;
  while (got < sizeof r) {
    const ssize_t n = read(fds[0], p + got, sizeof r - got);
    if (n <= 0) break;
    got += static_cast<std::size_t>(n);
  }
  close(fds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  if (got != sizeof r) {
    r = Report{};
    if (WIFSIGNALED(status)) {
      std::snprintf(r.error, sizeof r.error, "the %s run died of signal %d",
                    std::string(toString(engine)).c_str(), WTERMSIG(status));
    } else {
      std::snprintf(r.error, sizeof r.error, "the %s run exited with status %d and no report",
                    std::string(toString(engine)).c_str(), WEXITSTATUS(status));
    }
  }
  return r;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

struct Summary {
  std::vector<Report> runs;
  double cpuMs() const {
    std::vector<double> v;
    for (const Report& r : runs) v.push_back(r.cpuMsPerStep);
    return median(v);
  }
  double wallMs() const {
    std::vector<double> v;
    for (const Report& r : runs) v.push_back(r.wallMsPerStep);
    return median(v);
  }
  double buildMs() const {
    std::vector<double> v;
    for (const Report& r : runs) v.push_back(r.buildMs);
    return median(v);
  }
  // MB: the largest growth over the runs.
  double memoryMb() const {
    long kb = 0;
    for (const Report& r : runs) kb = std::max(kb, r.rssPeakKb - r.rssStartKb);
    return kb / 1024.0;
  }
  // MB: the largest peak of the whole process over the runs (the child's VmHWM: the libraries, the
  // scene loaded before the fork and the engine), what `/usr/bin/time -f %M` would report of it.
  double processMb() const {
    long kb = 0;
    for (const Report& r : runs) kb = std::max(kb, r.rssPeakKb);
    return kb / 1024.0;
  }
  const Figures& figures() const { return runs.front().figures; }
};

std::string jsonNumber(double v) {
  if (!std::isfinite(v)) return "null";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::string figuresJson(const Figures& f) {
  std::ostringstream o;
  o << "{\"static_bodies\": " << f.staticBodies << ", \"dynamic_bodies\": " << f.dynamicBodies
    << ", \"dynamic_mass\": " << jsonNumber(f.dynamicMass) << ", \"top_body\": " << f.topBody
    << ", \"top_displacement\": [" << jsonNumber(f.topDisplacement.x) << ", "
    << jsonNumber(f.topDisplacement.y) << ", " << jsonNumber(f.topDisplacement.z)
    << "], \"mean_speed\": " << jsonNumber(f.meanSpeed) << ", \"max_speed\": " << jsonNumber(f.maxSpeed)
    << ", \"lowest_point_y\": " << jsonNumber(f.lowestPointY)
    << ", \"finite\": " << (f.finite ? "true" : "false");
  if (f.hasTerrain) {
    o << ", \"below_terrain\": " << f.belowTerrain << ", \"below_terrain_by_1cm\": " << f.belowTerrainBy1cm
      << ", \"deepest_below_terrain\": " << jsonNumber(f.deepestBelowTerrain);
  }
  o << "}";
  return o.str();
}

std::string formatRatio(double r) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3f", r);
  return text;
}

// Each run's own ratio, collide / Bullet: the two engines ran back to back, so a slow spell of a
// shared host weighs on both. Their median is steadier than the ratio of the two medians, which
// may take its numerator and its denominator from different runs.
std::vector<double> runRatios(const Summary& collide, const Summary& bullet) {
  std::vector<double> ratios;
  for (std::size_t r = 0; r < collide.runs.size() && r < bullet.runs.size(); ++r)
    ratios.push_back(collide.runs[r].cpuMsPerStep / bullet.runs[r].cpuMsPerStep);
  return ratios;
}

std::string engineJson(const Summary& s) {
  std::ostringstream o;
  o << "{\"cpu_ms_per_step\": " << jsonNumber(s.cpuMs())
    << ", \"wall_ms_per_step\": " << jsonNumber(s.wallMs()) << ", \"build_ms\": " << jsonNumber(s.buildMs())
    << ", \"memory_mb\": " << jsonNumber(s.memoryMb()) << ", \"process_mb\": " << jsonNumber(s.processMb())
    << ", \"runs_cpu_ms_per_step\": [";
  for (std::size_t i = 0; i < s.runs.size(); ++i) o << (i ? ", " : "") << jsonNumber(s.runs[i].cpuMsPerStep);
  o << "], \"runs_wall_ms_per_step\": [";
  for (std::size_t i = 0; i < s.runs.size(); ++i) o << (i ? ", " : "") << jsonNumber(s.runs[i].wallMsPerStep);
  o << "], \"figures\": " << figuresJson(s.figures()) << "}";
  return o.str();
}

}  // namespace

int main(int argc, char** argv) try {
  CLI::App app{"collide_vs_bullet: the reference scenes in collide and in Bullet, same process, same bodies"};
  int runs = 3;
  std::optional<int> steps;
  std::vector<std::string> sceneArgs;
  std::string jsonPath;
  app.add_option("--runs", runs, "runs of each scene and engine (median reported)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--steps", steps, "steps per run (default: the scene's settings.steps, 600)")
      ->check(CLI::PositiveNumber);
  app.add_option("--scene", sceneArgs,
                 "R1 R2 R3 R4 B1 J1 J2 (or pile rain pyramid terrain billiards joint-grid ragdoll-pile, any "
                 "built-in or a "
                 "scene file); repeatable; default all five");
  app.add_option("--json", jsonPath, "also write the results to this JSON file");
  int workers = 1;
  app.add_option("--workers", workers,
                 "collide's workers (WorldDef::workerCount; Bullet stays single-threaded); with more than "
                 "one, read the wall times: the CPU time counts every thread")
      ->check(CLI::Range(1, kMaxWorkers))
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  std::vector<SceneInfo> infos;
  if (sceneArgs.empty()) infos = kReferenceScenes;
  for (const std::string& a : sceneArgs) infos.push_back(resolveScene(a));
  std::vector<scene::Scene> scenes;
  for (const SceneInfo& info : infos) {
    scenes.push_back(loadScene(info));
    scenes.back().world.workerCount = workers;
  }

  std::vector<std::map<Engine, Summary>> results(infos.size());
  for (int run = 0; run < runs; ++run) {
    for (std::size_t i = 0; i < infos.size(); ++i) {
      const int n = steps.value_or(scenes[i].steps);
      // Alternate which engine goes first, so neither always follows the other's memory traffic.
      const Engine order[2] = {run % 2 ? Engine::Bullet : Engine::Collide,
                               run % 2 ? Engine::Collide : Engine::Bullet};
      for (Engine engine : order) {
        std::fprintf(stderr, "run %d/%d  %-3s %-10s %-8s ...", run + 1, runs, infos[i].id.c_str(),
                     infos[i].name.c_str(), std::string(toString(engine)).c_str());
        Report r = forkRun(scenes[i], engine, n);
        if (!r.ok) throw Error(infos[i].id + ": " + r.error);
        std::fprintf(stderr, " %.3f ms/step (cpu), %.3f (wall)\n", r.cpuMsPerStep, r.wallMsPerStep);
        results[i][engine].runs.push_back(r);
      }
    }
  }

  // Same scene in both engines: equal body counts and masses, and each engine took every step.
  bool consistent = true;
  for (std::size_t i = 0; i < infos.size(); ++i) {
    const Figures& c = results[i][Engine::Collide].figures();
    const Figures& b = results[i][Engine::Bullet].figures();
    const auto problem = [&](const std::string& what) {
      std::fprintf(stderr, "collide_vs_bullet: %s: %s\n", infos[i].id.c_str(), what.c_str());
      consistent = false;
    };
    if (c.staticBodies != b.staticBodies || c.dynamicBodies != b.dynamicBodies) {
      problem("body counts differ: collide " + std::to_string(c.dynamicBodies) + " dynamic + " +
              std::to_string(c.staticBodies) + " static, Bullet " + std::to_string(b.dynamicBodies) + " + " +
              std::to_string(b.staticBodies));
    }
    if (std::abs(c.dynamicMass - b.dynamicMass) > 1e-5 * std::max(1.0, c.dynamicMass)) {
      problem("total dynamic mass differs: collide " + jsonNumber(c.dynamicMass) + " kg, Bullet " +
              jsonNumber(b.dynamicMass) + " kg");
    }
    for (Engine e : {Engine::Collide, Engine::Bullet}) {
      for (const Report& r : results[i][e].runs) {
        if (r.internalSteps != r.steps) {
          problem(std::string(toString(e)) + " took " + std::to_string(r.internalSteps) +
                  " internal steps for " + std::to_string(r.steps) + " calls");
        }
      }
    }
  }

  std::printf(
      "Median over %d run(s); ms per step = CPU time of the stepping loop / steps (wall time in the "
      "JSON).\n\n",
      runs);
  std::printf(
      "| scene | bodies | steps | collide ms/step | Bullet ms/step | collide/Bullet | goal "
      "| per-run ratios (median) | wall ratio | collide MB | Bullet MB |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (std::size_t i = 0; i < infos.size(); ++i) {
    const Summary& c = results[i][Engine::Collide];
    const Summary& b = results[i][Engine::Bullet];
    const double ratio = c.cpuMs() / b.cpuMs();
    const std::string target =
        infos[i].target ? (ratio < *infos[i].target ? "< " : "! < ") + jsonNumber(*infos[i].target) : "-";
    const std::vector<double> ratios = runRatios(c, b);
    std::string perRun;
    for (const double r : ratios) perRun += (perRun.empty() ? "" : " ") + formatRatio(r);
    std::printf("| %s %s | %d | %d | %.3f | %.3f | %.3f | %s | %s (%.3f) | %.2f | %.1f | %.1f |\n",
                infos[i].id.c_str(), infos[i].name.c_str(), c.figures().dynamicBodies, c.runs.front().steps,
                c.cpuMs(), b.cpuMs(), ratio, target.c_str(), perRun.c_str(), median(ratios),
                c.wallMs() / b.wallMs(), c.memoryMb(), b.memoryMb());
  }
  std::printf("\n(goal: the bound on collide/Bullet the project aims for; \"! <\" marks one not met.)\n\n");
  // Memory: the engine's growth above (VmHWM - VmRSS at the fork), and here the whole process.
  std::printf("| scene | collide process MB | Bullet process MB | collide/Bullet |\n|---|---:|---:|---:|\n");
  for (std::size_t i = 0; i < infos.size(); ++i) {
    const Summary& c = results[i][Engine::Collide];
    const Summary& b = results[i][Engine::Bullet];
    std::printf("| %s %s | %.1f | %.1f | %.3f |\n", infos[i].id.c_str(), infos[i].name.c_str(), c.processMb(),
                b.processMb(), c.processMb() / b.processMb());
  }
  std::printf("\n");
  std::printf(
      "| scene | engine | top body dx, dy, dz (mm) | mean speed | max speed | lowest point y | below terrain "
      "(any / >1 cm, deepest mm) |\n");
  std::printf("|---|---|---:|---:|---:|---:|---:|\n");
  for (std::size_t i = 0; i < infos.size(); ++i) {
    for (Engine e : {Engine::Collide, Engine::Bullet}) {
      const Figures& f = results[i][e].figures();
      char terrain[96] = "-";
      if (f.hasTerrain) {
        std::snprintf(terrain, sizeof terrain, "%d / %d, %.1f", f.belowTerrain, f.belowTerrainBy1cm,
                      1e3 * f.deepestBelowTerrain);
      }
      std::printf("| %s | %s | %.1f, %.1f, %.1f | %.4f | %.4f | %.4f | %s |%s\n", infos[i].id.c_str(),
                  std::string(toString(e)).c_str(), 1e3 * f.topDisplacement.x, 1e3 * f.topDisplacement.y,
                  1e3 * f.topDisplacement.z, f.meanSpeed, f.maxSpeed, f.lowestPointY, terrain,
                  f.finite ? "" : " NON-FINITE");
    }
  }

  if (!jsonPath.empty()) {
    std::ofstream out(jsonPath);
    if (!out) throw Error("--json: " + jsonPath + " cannot be written");
    out << "{\"runs\": " << runs << ", \"scenes\": [\n";
    for (std::size_t i = 0; i < infos.size(); ++i) {
      const Summary& c = results[i][Engine::Collide];
      const Summary& b = results[i][Engine::Bullet];
      out << "  {\"id\": \"" << infos[i].id << "\", \"name\": \"" << infos[i].name
          << "\", \"steps\": " << c.runs.front().steps
          << ", \"target\": " << (infos[i].target ? jsonNumber(*infos[i].target) : "null")
          << ", \"ratio\": " << jsonNumber(c.cpuMs() / b.cpuMs())
          << ", \"wall_ratio\": " << jsonNumber(c.wallMs() / b.wallMs()) << ", \"run_ratios\": [";
      const std::vector<double> ratios = runRatios(c, b);
      for (std::size_t r = 0; r < ratios.size(); ++r) out << (r ? ", " : "") << jsonNumber(ratios[r]);
      out << "], \"median_run_ratio\": " << jsonNumber(median(ratios))
          << ",\n   \"collide\": " << engineJson(c) << ",\n   \"bullet\": " << engineJson(b) << "}"
          << (i + 1 < infos.size() ? "," : "") << "\n";
    }
    out << "]}\n";
  }
  return consistent ? 0 : 1;
} catch (const std::exception& e) {
  std::fprintf(stderr, "collide_vs_bullet: %s\n", e.what());
  return 1;
}
