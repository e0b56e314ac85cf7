// Eight float lanes (AVX2) for the contact solver's wide kernel (contact_solver_avx2.cpp, the only
// file that includes this; it is compiled with AVX2 and without FMA). The same operations as the
// four-lane FloatW of simd.h, lane for lane the same IEEE results (max/min as SSE: a > b ? a : b).
#pragma once

#include "simd/simd.h"

#include <immintrin.h>

namespace collide::detail {

struct FloatW8 {
  __m256 v;
};

inline FloatW8 operator+(FloatW8 a, FloatW8 b) { return {_mm256_add_ps(a.v, b.v)}; }
inline FloatW8 operator-(FloatW8 a, FloatW8 b) { return {_mm256_sub_ps(a.v, b.v)}; }
inline FloatW8 operator*(FloatW8 a, FloatW8 b) { return {_mm256_mul_ps(a.v, b.v)}; }
inline FloatW8 operator/(FloatW8 a, FloatW8 b) { return {_mm256_div_ps(a.v, b.v)}; }
inline FloatW8 operator-(FloatW8 a) { return {_mm256_sub_ps(_mm256_setzero_ps(), a.v)}; }
inline FloatW8 maxW(FloatW8 a, FloatW8 b) { return {_mm256_max_ps(a.v, b.v)}; }
inline FloatW8 minW(FloatW8 a, FloatW8 b) { return {_mm256_min_ps(a.v, b.v)}; }
inline FloatW8 sqrtW(FloatW8 a) { return {_mm256_sqrt_ps(a.v)}; }
inline FloatW8 greaterW(FloatW8 a, FloatW8 b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_GT_OQ)}; }
inline FloatW8 notEqualW(FloatW8 a, FloatW8 b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_NEQ_UQ)}; }
inline FloatW8 selectW(FloatW8 mask, FloatW8 a, FloatW8 b) { return {_mm256_blendv_ps(b.v, a.v, mask.v)}; }
inline FloatW8 orW(FloatW8 a, FloatW8 b) { return {_mm256_or_ps(a.v, b.v)}; }
inline FloatW8 andW(FloatW8 a, FloatW8 b) { return {_mm256_and_ps(a.v, b.v)}; }
inline bool anyW(FloatW8 mask) { return _mm256_movemask_ps(mask.v) != 0; }
inline bool laneSet(FloatW8 mask, int lane) { return (_mm256_movemask_ps(mask.v) >> lane) & 1; }

template <>
inline FloatW8 splatT<FloatW8>(float x) {
  return {_mm256_set1_ps(x)};
}
template <>
inline FloatW8 zeroT<FloatW8>() {
  return {_mm256_setzero_ps()};
}
template <>
inline FloatW8 loadT<FloatW8>(const float* p) {
  return {_mm256_loadu_ps(p)};
}

// Eight records' rows of four floats as four columns of eight lanes: two 4x4 transposes, one for
// lanes 0-3 (the low halves) and one for lanes 4-7.
COLLIDE_INLINE void gatherRows(const float* const (&records)[8], std::size_t offset, FloatW8& x, FloatW8& y,
                               FloatW8& z, FloatW8& w) {
  const float* const low[4] = {records[0], records[1], records[2], records[3]};
  const float* const high[4] = {records[4], records[5], records[6], records[7]};
  FloatW x0, y0, z0, w0, x1, y1, z1, w1;
  gatherRows(low, offset, x0, y0, z0, w0);
  gatherRows(high, offset, x1, y1, z1, w1);
  x = {_mm256_set_m128(x1.v, x0.v)};
  y = {_mm256_set_m128(y1.v, y0.v)};
  z = {_mm256_set_m128(z1.v, z0.v)};
  w = {_mm256_set_m128(w1.v, w0.v)};
}

COLLIDE_INLINE void scatterRows(FloatW8 x, FloatW8 y, FloatW8 z, FloatW8 w, FloatW (&rows)[8]) {
  FloatW low[4];
  FloatW high[4];
  scatterRows({_mm256_castps256_ps128(x.v)}, {_mm256_castps256_ps128(y.v)}, {_mm256_castps256_ps128(z.v)},
              {_mm256_castps256_ps128(w.v)}, low);
  scatterRows({_mm256_extractf128_ps(x.v, 1)}, {_mm256_extractf128_ps(y.v, 1)},
              {_mm256_extractf128_ps(z.v, 1)}, {_mm256_extractf128_ps(w.v, 1)}, high);
  for (int i = 0; i < 4; ++i) {
    rows[i] = low[i];
    rows[i + 4] = high[i];
  }
}

}  // namespace collide::detail
