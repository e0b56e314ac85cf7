// Four double lanes in one AVX register (dynamics/joint_tree_lanes_avx2.cpp, the only file that
// includes this; it is compiled with AVX2 and without FMA). The same operations as DoubleW4 of
// simd_double.h, lane for lane the same IEEE results (max as SSE: a > b ? a : b).
#pragma once

#include "simd/simd_double.h"

#include <immintrin.h>

namespace collide::detail {

struct DoubleW4Avx {
  __m256d v;
  static DoubleW4Avx splat(double x) { return {_mm256_set1_pd(x)}; }
  static DoubleW4Avx load(const double* p) { return {_mm256_loadu_pd(p)}; }
};
inline void store(double* p, DoubleW4Avx a) { _mm256_storeu_pd(p, a.v); }
inline DoubleW4Avx operator+(DoubleW4Avx a, DoubleW4Avx b) { return {_mm256_add_pd(a.v, b.v)}; }
inline DoubleW4Avx operator-(DoubleW4Avx a, DoubleW4Avx b) { return {_mm256_sub_pd(a.v, b.v)}; }
inline DoubleW4Avx operator*(DoubleW4Avx a, DoubleW4Avx b) { return {_mm256_mul_pd(a.v, b.v)}; }
inline DoubleW4Avx operator/(DoubleW4Avx a, DoubleW4Avx b) { return {_mm256_div_pd(a.v, b.v)}; }
inline DoubleW4Avx maxD(DoubleW4Avx a, DoubleW4Avx b) { return {_mm256_max_pd(a.v, b.v)}; }
inline DoubleW4Avx absD(DoubleW4Avx a) { return {_mm256_andnot_pd(_mm256_set1_pd(-0.0), a.v)}; }
inline DoubleW4Avx greaterD(DoubleW4Avx a, DoubleW4Avx b) { return {_mm256_cmp_pd(a.v, b.v, _CMP_GT_OQ)}; }
inline DoubleW4Avx lessD(DoubleW4Avx a, DoubleW4Avx b) { return {_mm256_cmp_pd(a.v, b.v, _CMP_LT_OQ)}; }
inline DoubleW4Avx notEqualD(DoubleW4Avx a, DoubleW4Avx b) { return {_mm256_cmp_pd(a.v, b.v, _CMP_NEQ_UQ)}; }
inline DoubleW4Avx andD(DoubleW4Avx a, DoubleW4Avx b) { return {_mm256_and_pd(a.v, b.v)}; }
inline DoubleW4Avx orD(DoubleW4Avx a, DoubleW4Avx b) { return {_mm256_or_pd(a.v, b.v)}; }
inline DoubleW4Avx selectD(DoubleW4Avx mask, DoubleW4Avx a, DoubleW4Avx b) {
  return {_mm256_blendv_pd(b.v, a.v, mask.v)};
}
inline unsigned maskBits(DoubleW4Avx mask) { return static_cast<unsigned>(_mm256_movemask_pd(mask.v)); }

}  // namespace collide::detail
