// Reading a recording (collide/scene/recording.h).
#include <collide/scene/limits.h>
#include <collide/scene/recording.h>

#include "file_text.h"
#include "json_node.h"

#include <cmath>

namespace collide::scene {

namespace {

// A quaternion as written, [x, y, z, w], not normalised again: the recorded floats are the run's.
Quat exactQuaternion(const JsonNode& node) {
  const std::vector<JsonNode> parts = node.elements();
  if (parts.size() != 4) node.fail("must be [x, y, z, w], got " + node.shown());
  const Quat q(parts[3].number(), parts[0].number(), parts[1].number(), parts[2].number());
  if (!(std::abs(glm::dot(q, q) - 1.0f) < 1e-3f)) node.fail("must be a unit quaternion, got " + node.shown());
  return q;
}

}  // namespace

Recording parseRecording(std::string_view text, std::string_view sourceName) {
  const std::string source(sourceName);
  const Json document = parseDocument(text, source);
  const JsonNode root(document, source);
  if (!document.is_object()) throw Error(source + ": a recording must be a JSON object, got " + root.shown());
  root.expectObject({"dt", "frames"});
  Recording recording;
  recording.dt = root.at("dt").positive();
  int lastStep = -1;
  for (const JsonNode& frameNode : root.at("frames").elements()) {
    frameNode.expectObject({"step", "time", "bodies"});
    RecordedFrame& frame = recording.frames.emplace_back();
    frame.step = frameNode.at("step").integer(0, kMaxSteps);
    if (frame.step <= lastStep)
      frameNode.at("step").fail("must come after the last frame's step " + std::to_string(lastStep) +
                                ", got " + std::to_string(frame.step));
    lastStep = frame.step;
    frame.time = frameNode.at("time").number();
    for (const JsonNode& bodyNode : frameNode.at("bodies").elements()) {
      bodyNode.expectObject({"name", "position", "rotation", "velocity", "angular_velocity", "awake"});
      RecordedBody& body = frame.bodies.emplace_back();
      body.name = bodyNode.at("name").string();
      body.position = bodyNode.at("position").vec3();
      body.rotation = exactQuaternion(bodyNode.at("rotation"));
      body.velocity = bodyNode.at("velocity").vec3();
      body.angularVelocity = bodyNode.at("angular_velocity").vec3();
      if (const auto awake = bodyNode.find("awake")) body.awake = awake->boolean();
    }
  }
  return recording;
}

Recording loadRecording(const std::filesystem::path& path) {
  const std::string who = "recording file \"" + path.string() + "\"";
  return parseRecording(readFileText(path, kMaxRecordingBytes, who), path.string());
}

}  // namespace collide::scene
