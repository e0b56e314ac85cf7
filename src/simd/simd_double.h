// Four double lanes for the joint trees' factor and solve, four trees of one shape side by side
// (dynamics/joint_tree_lanes.h). DoubleW4 is two SSE2 halves on x86-64, where SSE2 is always
// available, and a plain array elsewhere; simd_double_avx.h adds DoubleW4Avx, one AVX register,
// for a kernel built separately and chosen at run time. Every operation is the IEEE operation of
// each lane (no fused multiply-add) and max follows SSE's rule (a > b ? a : b), so each lane gives
// bit for bit what the scalar kernel gives its tree.
//
// A lane type D has D::splat(x), D::load(p), store(p, a), + - * /, maxD, absD, greaterD, lessD,
// notEqualD (masks: all bits set where it holds; NaN lanes are not equal), selectD(mask, a, b),
// andD, orD and maskBits (bit i for lane i).
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>

#if defined(__SSE2__) || defined(_M_X64)
#include <emmintrin.h>
#define COLLIDE_SIMD_DOUBLE_SSE2 1
#else
#define COLLIDE_SIMD_DOUBLE_SSE2 0
#endif

namespace collide::detail {

inline constexpr int kDoubleLanes = 4;

#if COLLIDE_SIMD_DOUBLE_SSE2

struct DoubleW4 {
  __m128d lo, hi;  // lanes 0-1, 2-3
  static DoubleW4 splat(double x) { return {_mm_set1_pd(x), _mm_set1_pd(x)}; }
  static DoubleW4 load(const double* p) { return {_mm_loadu_pd(p), _mm_loadu_pd(p + 2)}; }
};
inline void store(double* p, DoubleW4 a) {
  _mm_storeu_pd(p, a.lo);
  _mm_storeu_pd(p + 2, a.hi);
}
inline DoubleW4 operator+(DoubleW4 a, DoubleW4 b) { return {_mm_add_pd(a.lo, b.lo), _mm_add_pd(a.hi, b.hi)}; }
inline DoubleW4 operator-(DoubleW4 a, DoubleW4 b) { return {_mm_sub_pd(a.lo, b.lo), _mm_sub_pd(a.hi, b.hi)}; }
inline DoubleW4 operator*(DoubleW4 a, DoubleW4 b) { return {_mm_mul_pd(a.lo, b.lo), _mm_mul_pd(a.hi, b.hi)}; }
inline DoubleW4 operator/(DoubleW4 a, DoubleW4 b) { return {_mm_div_pd(a.lo, b.lo), _mm_div_pd(a.hi, b.hi)}; }
inline DoubleW4 maxD(DoubleW4 a, DoubleW4 b) { return {_mm_max_pd(a.lo, b.lo), _mm_max_pd(a.hi, b.hi)}; }
inline DoubleW4 absD(DoubleW4 a) {
  const __m128d sign = _mm_set1_pd(-0.0);
  return {_mm_andnot_pd(sign, a.lo), _mm_andnot_pd(sign, a.hi)};
}
inline DoubleW4 greaterD(DoubleW4 a, DoubleW4 b) {
  return {_mm_cmpgt_pd(a.lo, b.lo), _mm_cmpgt_pd(a.hi, b.hi)};
}
inline DoubleW4 lessD(DoubleW4 a, DoubleW4 b) { return {_mm_cmplt_pd(a.lo, b.lo), _mm_cmplt_pd(a.hi, b.hi)}; }
inline DoubleW4 notEqualD(DoubleW4 a, DoubleW4 b) {
  return {_mm_cmpneq_pd(a.lo, b.lo), _mm_cmpneq_pd(a.hi, b.hi)};
}
inline DoubleW4 andD(DoubleW4 a, DoubleW4 b) { return {_mm_and_pd(a.lo, b.lo), _mm_and_pd(a.hi, b.hi)}; }
inline DoubleW4 orD(DoubleW4 a, DoubleW4 b) { return {_mm_or_pd(a.lo, b.lo), _mm_or_pd(a.hi, b.hi)}; }
inline DoubleW4 selectD(DoubleW4 mask, DoubleW4 a, DoubleW4 b) {
  return {_mm_or_pd(_mm_and_pd(mask.lo, a.lo), _mm_andnot_pd(mask.lo, b.lo)),
          _mm_or_pd(_mm_and_pd(mask.hi, a.hi), _mm_andnot_pd(mask.hi, b.hi))};
}
inline unsigned maskBits(DoubleW4 mask) {
  return static_cast<unsigned>(_mm_movemask_pd(mask.lo) | _mm_movemask_pd(mask.hi) << 2);
}

#else

struct DoubleW4 {
  double v[kDoubleLanes];
  static DoubleW4 splat(double x) { return {{x, x, x, x}}; }
  static DoubleW4 load(const double* p) { return {{p[0], p[1], p[2], p[3]}}; }
};
inline void store(double* p, DoubleW4 a) {
  for (int i = 0; i < kDoubleLanes; ++i) p[i] = a.v[i];
}
template <typename F>
inline DoubleW4 lanewise(DoubleW4 a, DoubleW4 b, F f) {
  DoubleW4 r;
  for (int i = 0; i < kDoubleLanes; ++i) r.v[i] = f(a.v[i], b.v[i]);
  return r;
}
// A mask lane: all bits set, or none.
inline double maskLane(bool set) {
  const std::uint64_t bits = set ? ~std::uint64_t{0} : 0;
  double lane;
  std::memcpy(&lane, &bits, sizeof lane);
  return lane;
}
inline bool maskSet(double lane) {
  std::uint64_t bits;
  std::memcpy(&bits, &lane, sizeof bits);
  return bits != 0;
}
inline DoubleW4 operator+(DoubleW4 a, DoubleW4 b) {
  return lanewise(a, b, [](double x, double y) { return x + y; });
}
inline DoubleW4 operator-(DoubleW4 a, DoubleW4 b) {
  return lanewise(a, b, [](double x, double y) { return x - y; });
}
inline DoubleW4 operator*(DoubleW4 a, DoubleW4 b) {
  return lanewise(a, b, [](double x, double y) { return x * y; });
}
inline DoubleW4 operator/(DoubleW4 a, DoubleW4 b) {
  return lanewise(a, b, [](double x, double y) { return x / y; });
}
inline DoubleW4 maxD(DoubleW4 a, DoubleW4 b) {
  return lanewise(a, b, [](double x, double y) { return x > y ? x : y; });
}
inline DoubleW4 absD(DoubleW4 a) {
  return lanewise(a, a, [](double x, double) { return std::fabs(x); });
}
inline DoubleW4 greaterD(DoubleW4 a, DoubleW4 b) {
  return lanewise(a, b, [](double x, double y) { return maskLane(x > y); });
}
inline DoubleW4 lessD(DoubleW4 a, DoubleW4 b) {
  return lanewise(a, b, [](double x, double y) { return maskLane(x < y); });
}
inline DoubleW4 notEqualD(DoubleW4 a, DoubleW4 b) {
  return lanewise(a, b, [](double x, double y) { return maskLane(!(x == y)); });
}
inline DoubleW4 andD(DoubleW4 a, DoubleW4 b) {
  return lanewise(a, b, [](double x, double y) { return maskLane(maskSet(x) && maskSet(y)); });
}
inline DoubleW4 orD(DoubleW4 a, DoubleW4 b) {
  return lanewise(a, b, [](double x, double y) { return maskLane(maskSet(x) || maskSet(y)); });
}
inline DoubleW4 selectD(DoubleW4 mask, DoubleW4 a, DoubleW4 b) {
  DoubleW4 r;
  for (int i = 0; i < kDoubleLanes; ++i) r.v[i] = maskSet(mask.v[i]) ? a.v[i] : b.v[i];
  return r;
}
inline unsigned maskBits(DoubleW4 mask) {
  unsigned bits = 0;
  for (int i = 0; i < kDoubleLanes; ++i) bits |= (maskSet(mask.v[i]) ? 1u : 0u) << i;
  return bits;
}

#endif

}  // namespace collide::detail
