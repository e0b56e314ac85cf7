// The loaders' limits, all in one place (docs/scene-format.md, "Limits"). Each bounds the memory or
// time that one input can take, so that a broken or hostile file is refused with an Error naming the
// file or field, the value and the limit, instead of exhausting memory or running for ever.
#pragma once

#include <collide/world.h>

#include <cstddef>
#include <cstdint>

namespace collide::scene {

// Files, checked before they are read: a scene file, and an OBJ file (a mesh shape's "file" or
// `collide fit`'s argument).
inline constexpr std::uintmax_t kMaxSceneFileBytes = 64ull << 20;  // 64 MiB
inline constexpr std::uintmax_t kMaxObjFileBytes = 256ull << 20;   // 256 MiB
// A recording (`collide-viewer --replay`): JSON, some 200 bytes per body and frame, read whole.
inline constexpr std::uintmax_t kMaxRecordingBytes = 1ull << 30;  // 1 GiB
// A world snapshot (`collide run --from-snapshot`): large-pile's 100,000 cubes take about 60 MB.
inline constexpr std::uintmax_t kMaxSnapshotBytes = 4ull << 30;  // 4 GiB

// Nesting: arrays and objects inside each other in a scene's JSON, and compounds inside compounds.
// A compound level takes three JSON levels (shape, children, child), so the JSON limit leaves room
// for the deepest compound allowed.
inline constexpr int kMaxJsonDepth = 256;
inline constexpr int kMaxCompoundDepth = 64;

// Settings.
inline constexpr int kMaxSubsteps = collide::kMaxSubsteps;  // the world's own limit
inline constexpr float kMaxDt = 1.0f;                       // s
inline constexpr int kMaxSteps = 10'000'000;

// Sizes.
inline constexpr std::size_t kMaxBodies = 1'000'000;
inline constexpr std::size_t kMaxMeshTriangles = 4'000'000;  // inline or from an OBJ file, triangulated
inline constexpr std::size_t kMaxObjFaceVertices = 256;      // one polygon ("f" line) of an OBJ file

}  // namespace collide::scene
