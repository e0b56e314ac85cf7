// The collide command's fuzzer: the whole command line in-process, through runCollide() (the code
// of tools/collide, linked as a library). Each input becomes an argument vector and two files in a
// fresh temporary folder, the scene file (scene.json) and an OBJ file (mesh.obj), which the scene
// can name; the folder is removed after the input.
//
// The input: seven control bytes, then the scene file's text, then, after the first line "#obj",
// the OBJ file's text ("#" starts a comment in OBJ, so the marker is harmless in either file).
//   0  the subcommand: run (three in eight), bench, fit, scenes, pairs, none (the proxy table)
//   1  flags: --record, --every, --events, --json, --allow-outside-paths, a bad extra argument,
//      --help or --version
//   2  --steps: 0 to 50 (1 to 10 for bench, 0 to 10 for a built-in scene), or a malformed value
//   3  --every: 0 to 11 (0 is refused), or a malformed value
//   4  the scene (or mesh) argument: the scene file, the OBJ file, a built-in scene, a missing
//      file, the folder itself
//   5  which built-in scene (run, bench, scenes --export); bench's --runs (1 or 2)
//   6  where --record, --events and --json write, two bits each: a file of its own, one file
//      shared by all three, the scene file (refused when it is the scene being run), a file in a
//      missing folder
// run and bench always get --steps, so that a scene's settings.steps (up to 10 million) never
// decides the cost; every output path is inside the temporary folder.
//
// Allowed: any exit code (0, 1 with "collide: message", CLI11's codes for a bad command line, 2 for
// faults). A finding: a crash, a sanitizer report or leak, an exception out of runCollide(), an
// input slower than the timeout, or a changed input file (the scene being run, the OBJ file).
// COLLIDE_FUZZ_TRACE=1 prints the argument vector of each input.
#include "command_line.h"

#include <unistd.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

namespace {

namespace fs = std::filesystem;

constexpr std::size_t kControlBytes = 7;
constexpr std::size_t kMaxInputBytes = 16 * 1024;  // a scene and a mesh that run in milliseconds
constexpr int kMaxSteps = 50;
constexpr std::string_view kObjMarker = "#obj\n";

// Built-in scenes that a few steps of run or bench can afford under the sanitizers (not pile, rain
// or terrain, with thousands of bodies), and one name that is not a built-in.
constexpr std::array<const char*, 6> kCheapBuiltins = {"billiards", "proxies",   "revert",
                                                       "chain",     "tunneling", "no-such-scene"};
// `scenes --export` only writes JSON, so it can take any built-in.
constexpr std::array<const char*, 8> kExportNames = {"billiards", "pile",  "rain", "terrain",
                                                     "breakable", "chain", "",     "no-such-scene"};
// Numbers as a user might mistype them: the validators must refuse each with a message.
constexpr std::array<const char*, 8> kMalformedNumbers = {"-1",          "abc",  "",   "1e3",
                                                          "99999999999", "0x10", " 5", "5 "};

std::string readFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void writeFile(const fs::path& path, std::string_view text) {
  std::ofstream out(path, std::ios::binary);
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  if (!out) std::abort();  // the fuzzer's own setup failed, not the command
}

// A number from the control byte: `low + byte % (high - low + 1)` for most values, a malformed
// string for the top 32.
std::string number(std::uint8_t byte, int low, int high) {
  if (byte >= 224) return kMalformedNumbers[byte % kMalformedNumbers.size()];
  return std::to_string(low + byte % (high - low + 1));
}

// Where an output goes (two bits of control byte 6).
std::string outputPath(const fs::path& folder, int choice, const char* ownName) {
  switch (choice & 3) {
    case 0:
      return (folder / ownName).string();
    case 1:
      return (folder / "shared.json").string();
    case 2:
      return (folder / "scene.json").string();
    default:
      return (folder / "no-such-folder" / ownName).string();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < kControlBytes || size > kMaxInputBytes) return 0;
  const std::uint8_t* control = data;
  const std::string_view files(reinterpret_cast<const char*>(data) + kControlBytes, size - kControlBytes);
  const std::size_t marker = files.find(kObjMarker);
  const std::string_view sceneText = files.substr(0, marker);
  const std::string_view objText =
      marker == std::string_view::npos ? "" : files.substr(marker + kObjMarker.size());

  // A fresh folder for each input, under $TMPDIR (or /tmp).
  const char* tmp = std::getenv("TMPDIR");
  std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/collide-cli-fuzz-XXXXXX";
  if (mkdtemp(pattern.data()) == nullptr) std::abort();
  const fs::path folder = pattern;
  const fs::path scenePath = folder / "scene.json";
  const fs::path objPath = folder / "mesh.obj";
  writeFile(scenePath, sceneText);
  writeFile(objPath, objText);

  std::vector<std::string> args = {"collide"};
  const int subcommand = control[0] % 8;
  const std::uint8_t flags = control[1];
  const bool builtin = control[4] % 8 == 4;
  auto sceneArgument = [&]() -> std::string {
    switch (control[4] % 8) {
      case 4:
        return kCheapBuiltins[control[5] % kCheapBuiltins.size()];
      case 5:
        return objPath.string();
      case 6:
        return (folder / "missing.json").string();
      case 7:
        return folder.string();
      default:
        return scenePath.string();
    }
  };
  if (subcommand <= 2) {
    args.insert(args.end(),
                {"run", sceneArgument(), "--steps", number(control[2], 0, builtin ? 10 : kMaxSteps)});
    if (flags & 1) args.insert(args.end(), {"--record", outputPath(folder, control[6], "record.json")});
    if (flags & 2) args.insert(args.end(), {"--every", number(control[3], 0, 11)});
    if (flags & 4) args.insert(args.end(), {"--events", outputPath(folder, control[6] >> 2, "events.jsonl")});
    if (flags & 8) args.insert(args.end(), {"--json", outputPath(folder, control[6] >> 4, "summary.json")});
  } else if (subcommand == 3) {
    args.insert(args.end(), {"bench", sceneArgument(), "--steps", number(control[2], 1, 10), "--runs",
                             std::to_string(1 + control[5] % 2)});
  } else if (subcommand == 4) {
    const int mesh = control[4] % 4;
    args.insert(args.end(), {"fit", mesh == 1   ? scenePath.string()
                                    : mesh == 2 ? (folder / "missing.obj").string()
                                    : mesh == 3 ? folder.string()
                                                : objPath.string()});
  } else if (subcommand == 5) {
    args.push_back("scenes");
    if (flags & 1) args.insert(args.end(), {"--export", kExportNames[control[5] % kExportNames.size()]});
  } else if (subcommand == 6) {
    args.push_back("pairs");
  }
  if ((flags & 16) && subcommand <= 3) args.push_back("--allow-outside-paths");
  if (flags & 32) args.push_back(flags & 2 ? "--no-such-flag" : "extra");
  if (flags & 64) args.push_back(flags & 128 ? "--help" : "--version");

  if (std::getenv("COLLIDE_FUZZ_TRACE")) {
    for (const std::string& a : args) std::fprintf(stderr, "%s ", a.c_str());
    std::fprintf(stderr, "\n");
  }
  std::vector<const char*> argv;
  for (const std::string& a : args) argv.push_back(a.c_str());
  argv.push_back(nullptr);
  (void)runCollide(static_cast<int>(args.size()), argv.data());
  std::fflush(stdout);

  // The command never writes its inputs, whatever the outputs' paths: the scene file when it is the
  // one being run (otherwise it is a file like any other, and an output may replace it), and the
  // OBJ file, which no output names.
  const bool sceneIsInput = subcommand <= 3 && sceneArgument() == scenePath.string();
  if ((sceneIsInput && readFile(scenePath) != sceneText) || readFile(objPath) != objText) std::abort();
  std::error_code error;
  fs::remove_all(folder, error);
  if (error) std::abort();
  return 0;
}
