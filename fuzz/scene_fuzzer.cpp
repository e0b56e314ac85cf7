// Scene loader fuzzer: parseScene on arbitrary bytes must either return a Scene or throw
// collide::Error with a message; any other exception, a crash or a sanitizer report is a finding.
// A parsed scene is also built into a World and stepped once, since a scene the loader accepts
// must be one the World accepts (or refuses with an Error).
#include <collide/scene/scene.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const collide::scene::Scene scene = collide::scene::parseScene(text, "fuzz", "/nonexistent");
    if (scene.bodies.size() > 64) return 0;  // keep each input cheap
    collide::scene::SceneWorld sw = collide::scene::buildWorld(scene);
    sw.world.step(scene.dt);
  } catch (const collide::Error& e) {
    if (std::string_view(e.what()).empty()) std::abort();  // an error must say what is wrong
  }
  return 0;
}
