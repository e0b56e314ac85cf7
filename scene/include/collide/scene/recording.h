// Reading back what `collide run --record FILE` writes (docs/scene-format.md, "What collide run
// writes"): the time step and, per recorded frame, the step, the time and each body's name, pose,
// velocities and (with sleeping on) whether it was awake. The viewer replays it (collide-viewer
// --replay). Poses are written with 9 significant digits, which gives every float back exactly: a
// replayed frame shows the bodies where the run had them, bit for bit.
#pragma once

#include <collide/math.h>

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace collide::scene {

struct RecordedBody {
  std::string name;
  Vec3 position{0.0f};  // the body origin, as World::transform gives it
  Quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
  Vec3 velocity{0.0f};
  Vec3 angularVelocity{0.0f};
  std::optional<bool> awake;  // recorded with sleeping on
};

struct RecordedFrame {
  int step = 0;
  double time = 0.0;
  std::vector<RecordedBody> bodies;  // the bodies alive at that step (broken ones are gone)
};

struct Recording {
  float dt = 0.0f;
  std::vector<RecordedFrame> frames;  // in step order
};

// Throws collide::Error naming the field ("rec.json: frames[3].bodies[1].rotation: ...") for a
// document that is not a recording: a missing or mistyped field, a non-finite number, a rotation
// that is not a unit quaternion, frames out of step order.
Recording parseRecording(std::string_view text, std::string_view source = "recording");
Recording loadRecording(const std::filesystem::path& path);

}  // namespace collide::scene
