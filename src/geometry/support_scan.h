// The support point of a vertex set: the vertex farthest along a direction, by a linear scan over
// the coordinates stored as three blocks (all x, then all y, then all z), four vertices at a time.
//
// GJK and EPA ask a hull for its support point several times per query; at game sizes (tens of
// vertices) a linear scan beats hill climbing over the half-edges (dependent loads, unpredictable
// branches), and over blocked coordinates it runs four dot products per instruction (SSE2, part of
// every x86-64 CPU; a scalar loop elsewhere). The answer is the scalar scan's exactly: the dot
// products are rounded the same way ((x dx + y dy) + z dz) and the first vertex reaching the
// largest one wins.
#pragma once

#include <collide/math.h>

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace collide::detail {

// The number of lanes of each block: the point count rounded up to a multiple of 4.
constexpr std::uint32_t blockedLanes(std::size_t count) {
  return static_cast<std::uint32_t>((count + 3) & ~std::size_t(3));
}

// The points' coordinates blocked for the scan: blockedLanes(n) floats of x, then of y, then of z;
// the padding repeats point 0, which can never win over it.
Array<float> blockCoordinates(std::span<const Vec3> points);
// The same into `out` (3 * blockedLanes(n) floats), for callers that keep their own storage.
void blockCoordinatesInto(std::span<const Vec3> points, float* out);

// The index of the first of `count` points with the largest dot product with `direction` (0 for no
// points or a NaN direction; a NaN product, of coordinates near the float range, counts as
// -infinity), over coordinates made by blockCoordinates.
std::uint32_t farthestAlong(const float* blocked, std::uint32_t count, const Vec3& direction);

}  // namespace collide::detail
