// Snapshot fuzzer: World::loadSnapshot on fuzzed bytes. The first byte picks the form: even, the
// bytes as they are (the header's mark, versions, layout, size and checksum all fuzzed); odd, the
// rest is a payload, given this build's header with the right size and checksum, so that the fuzzer
// reaches the checks of the contents themselves (fields read one by one, then every index in
// range). A world that takes a snapshot steps a few times, saves, and loads what it saved.
//
// Allowed: loadSnapshot works or throws collide::Error starting "snapshot: "; a taken world steps
// without throwing and saves bytes that load again into the same bytes. A finding: a crash, a
// sanitizer report, another exception or message, a step that throws, a save that does not load.
#include <collide/world.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <span>
#include <string_view>
#include <vector>

namespace {

using namespace collide;

constexpr std::size_t kHeaderBytes = 8 + 4 + 4 + 8 + 8 + 8;

// This build's header (mark, format, library version and layout), from a snapshot of an empty world.
const std::vector<std::uint8_t>& buildHeader() {
  static const std::vector<std::uint8_t> header = [] {
    std::vector<std::uint8_t> bytes = World().saveSnapshot();
    bytes.resize(kHeaderBytes);
    return bytes;
  }();
  return header;
}

std::vector<std::uint8_t> signedSnapshot(std::span<const std::uint8_t> payload) {
  std::vector<std::uint8_t> bytes = buildHeader();
  const std::uint64_t size = payload.size();
  std::uint64_t hash = 0xcbf29ce484222325ull;
  for (const std::uint8_t byte : payload) hash = (hash ^ byte) * 0x100000001b3ull;
  std::memcpy(bytes.data() + kHeaderBytes - 16, &size, 8);
  std::memcpy(bytes.data() + kHeaderBytes - 8, &hash, 8);
  bytes.insert(bytes.end(), payload.begin(), payload.end());
  return bytes;
}

[[noreturn]] void finding(const char* what, const char* detail) {
  std::fprintf(stderr, "snapshot_fuzzer: %s: %s\n", what, detail);
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::span<const std::uint8_t> rest(data + 1, size - 1);
  const std::vector<std::uint8_t> bytes =
      data[0] & 1 ? signedSnapshot(rest) : std::vector<std::uint8_t>(rest.begin(), rest.end());
  World world;
  try {
    world.loadSnapshot(bytes);
  } catch (const Error& e) {
    if (!std::string_view(e.what()).starts_with("snapshot: "))
      finding("a refusal without its prefix", e.what());
    return 0;
  }
  try {
    for (int i = 0; i < 3; ++i) world.step(1.0f / 60.0f);
  } catch (const Error& e) {
    finding("a taken snapshot's world threw in a step", e.what());
  }
  const std::vector<std::uint8_t> saved = world.saveSnapshot();
  World again;
  try {
    again.loadSnapshot(saved);
  } catch (const Error& e) {
    finding("a world's own snapshot did not load", e.what());
  }
  if (again.saveSnapshot() != saved) finding("a loaded snapshot saved other bytes", "");
  return 0;
}
