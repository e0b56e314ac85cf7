// The blocked support scan (see support_scan.h).
#include "geometry/support_scan.h"

#include <bit>
#include <cmath>
#include <limits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace collide::detail {

void blockCoordinatesInto(std::span<const Vec3> points, float* out) {
  const std::size_t lanes = blockedLanes(points.size());
  for (std::size_t i = 0; i < lanes && !points.empty(); ++i) {
    const Vec3& p = points[i < points.size() ? i : 0];
    for (int axis = 0; axis < 3; ++axis) out[axis * lanes + i] = p[axis];
  }
}

Array<float> blockCoordinates(std::span<const Vec3> points) {
  Array<float> blocked(points.empty() ? 0 : 3 * blockedLanes(points.size()));
  blockCoordinatesInto(points, blocked.data());
  return blocked;
}

std::uint32_t farthestAlong(const float* blocked, std::uint32_t count, const Vec3& direction) {
  if (count == 0) return 0;
  const std::uint32_t lanes = blockedLanes(count);
  const float* xs = blocked;
  const float* ys = xs + lanes;
  const float* zs = ys + lanes;
#if defined(__SSE2__)
  // Two passes, both four points per instruction: the largest dot product (a running maximum per
  // lane), then the first block holding it, recomputed with the same rounding. Cheaper than carrying
  // an index per lane through the first pass (the second stops at the winner, half-way on average).
  // A NaN product (coordinates near the float range, whose terms overflow to opposite infinities)
  // counts as -infinity: it never wins, and the maximum is then one number in every lane, which
  // only the padding's copy of point 0 could share after point 0 itself.
  const __m128 dx = _mm_set1_ps(direction.x), dy = _mm_set1_ps(direction.y), dz = _mm_set1_ps(direction.z);
  const __m128 lowest = _mm_set1_ps(-std::numeric_limits<float>::infinity());
  auto dots = [&](std::uint32_t i) {
    const __m128 xy = _mm_add_ps(_mm_mul_ps(_mm_loadu_ps(xs + i), dx), _mm_mul_ps(_mm_loadu_ps(ys + i), dy));
    // max(NaN, b) is b: the NaN lanes become -infinity.
    return _mm_max_ps(_mm_add_ps(xy, _mm_mul_ps(_mm_loadu_ps(zs + i), dz)), lowest);
  };
  __m128 best = dots(0);
  for (std::uint32_t i = 4; i < lanes; i += 4) best = _mm_max_ps(best, dots(i));
  best = _mm_max_ps(best, _mm_shuffle_ps(best, best, _MM_SHUFFLE(2, 3, 0, 1)));
  best = _mm_max_ps(best, _mm_shuffle_ps(best, best, _MM_SHUFFLE(1, 0, 3, 2)));
  for (std::uint32_t i = 0; i < lanes; i += 4) {
    const int equal = _mm_movemask_ps(_mm_cmpeq_ps(dots(i), best));
    if (equal != 0) return i + static_cast<std::uint32_t>(std::countr_zero(static_cast<unsigned>(equal)));
  }
  return 0;  // not reached: some lane holds the maximum
#else
  const auto dot = [&](std::uint32_t i) {
    const float value = xs[i] * direction.x + ys[i] * direction.y + zs[i] * direction.z;
    return std::isnan(value) ? -std::numeric_limits<float>::infinity() : value;
  };
  std::uint32_t bestIndex = 0;
  float best = dot(0);
  for (std::uint32_t i = 1; i < count; ++i) {
    const float value = dot(i);
    if (value > best) best = value, bestIndex = i;
  }
  return bestIndex;
#endif
}

}  // namespace collide::detail
