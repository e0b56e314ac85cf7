// Graph colouring of the step's constraints (Box2D v3's constraint_graph.c): constraints of one
// colour share no dynamic body, so the solver can take four of them in SIMD lanes and get exactly
// what four sequential solves would give. Static and kinematic bodies are never written by the
// contact solver, so any number of constraints of a colour may share them.
#pragma once

#include <collide/hooks.h>
#include <array>
#include <cstdint>
#include <vector>

namespace collide::detail {

inline constexpr int kGraphColors = 24;
inline constexpr std::uint8_t kOverflowColor = kGraphColors;  // solved one at a time, after the colours

// For each constraint (its two solver bodies; a negative index is a body the solver never writes),
// the first colour where neither dynamic body is used yet, in constraint order, so the colouring is
// deterministic. A constraint touching a static or kinematic body starts at colour 1 (Box2D v3:
// the ground's contacts are then solved after some of the contacts they support, which helps
// stacks). `bits` is scratch, reused across steps.
void colorConstraints(const Array<std::array<std::int32_t, 2>>& writtenBodies, std::size_t bodyCount,
                      Array<std::uint8_t>& outColors, Array<std::uint64_t>& bits);

}  // namespace collide::detail
