// Float lanes for the contact solver (Box2D v3's b2FloatW, in 3D). FloatW is four lanes: SSE2 on
// x86-64, where it is always available, and a plain array elsewhere; simd_avx2.h adds FloatW8, eight
// AVX2 lanes, for a kernel built separately and chosen at run time. Every operation is the IEEE
// operation of each lane (no fused multiply-add), and min/max follow SSE's rule (a > b ? a : b) in
// every build, so the lanes give bit for bit what one lane would: the solver's result does not depend
// on the build, on the lane width, or on how many constraints share a batch.
//
// The kernels are written once over a lane type F: splatT<F>, zeroT<F>, loadT<F>, Vec3T<F> and the
// overloaded operations below, plus gatherRows/scatterRows for the bodies.
#pragma once

#include <collide/math.h>

#include <cmath>
#include <cstddef>

#if defined(__SSE2__) || defined(_M_X64)
#include <emmintrin.h>
#define COLLIDE_SIMD_SSE2 1
#else
#define COLLIDE_SIMD_SSE2 0
#endif

// The solver's small helpers must be inlined into its loops (GCC otherwise keeps gather and scatter
// out of line, a call per batch and body).
#if defined(__GNUC__)
#define COLLIDE_INLINE inline __attribute__((always_inline))
#else
#define COLLIDE_INLINE inline
#endif

namespace collide::detail {

inline constexpr int kLanes = 4;

#if COLLIDE_SIMD_SSE2

struct FloatW {
  __m128 v;
};

inline FloatW splat(float x) { return {_mm_set1_ps(x)}; }
inline FloatW zeroW() { return {_mm_setzero_ps()}; }
inline FloatW loadW(const float* p) { return {_mm_loadu_ps(p)}; }
// Lanes 0 to 3 from four values in registers (no store to memory and load back).
inline FloatW setW(float a, float b, float c, float d) { return {_mm_setr_ps(a, b, c, d)}; }
inline void storeW(float* p, FloatW a) { _mm_storeu_ps(p, a.v); }
inline FloatW operator+(FloatW a, FloatW b) { return {_mm_add_ps(a.v, b.v)}; }
inline FloatW operator-(FloatW a, FloatW b) { return {_mm_sub_ps(a.v, b.v)}; }
inline FloatW operator*(FloatW a, FloatW b) { return {_mm_mul_ps(a.v, b.v)}; }
inline FloatW operator/(FloatW a, FloatW b) { return {_mm_div_ps(a.v, b.v)}; }
inline FloatW operator-(FloatW a) { return {_mm_sub_ps(_mm_setzero_ps(), a.v)}; }
// -a with its sign flipped, as scalar negation does (0 - a above gives +0 for a = +0).
inline FloatW negateW(FloatW a) { return {_mm_xor_ps(a.v, _mm_set1_ps(-0.0f))}; }
inline FloatW maxW(FloatW a, FloatW b) { return {_mm_max_ps(a.v, b.v)}; }
inline FloatW minW(FloatW a, FloatW b) { return {_mm_min_ps(a.v, b.v)}; }
inline FloatW sqrtW(FloatW a) { return {_mm_sqrt_ps(a.v)}; }
// Lane masks: all bits set where the comparison holds.
inline FloatW greaterW(FloatW a, FloatW b) { return {_mm_cmpgt_ps(a.v, b.v)}; }
// Unordered or different: true for NaN lanes.
inline FloatW notEqualW(FloatW a, FloatW b) { return {_mm_cmpneq_ps(a.v, b.v)}; }
// mask ? a : b, per lane.
inline FloatW selectW(FloatW mask, FloatW a, FloatW b) {
  return {_mm_or_ps(_mm_and_ps(mask.v, a.v), _mm_andnot_ps(mask.v, b.v))};
}
inline FloatW orW(FloatW a, FloatW b) { return {_mm_or_ps(a.v, b.v)}; }
inline FloatW andW(FloatW a, FloatW b) { return {_mm_and_ps(a.v, b.v)}; }
inline bool anyW(FloatW mask) { return _mm_movemask_ps(mask.v) != 0; }
inline bool laneSet(FloatW mask, int lane) { return (_mm_movemask_ps(mask.v) >> lane) & 1; }
// Bit i set where lane i of the mask is.
inline unsigned maskBits(FloatW mask) { return static_cast<unsigned>(_mm_movemask_ps(mask.v)); }

// Four rows of four floats to four columns (rows are the lanes' structs, columns the fields).
inline void transpose(FloatW& r0, FloatW& r1, FloatW& r2, FloatW& r3) {
  _MM_TRANSPOSE4_PS(r0.v, r1.v, r2.v, r3.v);
}

#else

struct FloatW {
  float v[kLanes];
};

template <typename F>
inline FloatW lanewise(FloatW a, FloatW b, F f) {
  FloatW r;
  for (int i = 0; i < kLanes; ++i) r.v[i] = f(a.v[i], b.v[i]);
  return r;
}
inline FloatW splat(float x) { return {{x, x, x, x}}; }
inline FloatW zeroW() { return splat(0.0f); }
inline FloatW loadW(const float* p) { return {{p[0], p[1], p[2], p[3]}}; }
inline FloatW setW(float a, float b, float c, float d) { return {{a, b, c, d}}; }
inline void storeW(float* p, FloatW a) {
  for (int i = 0; i < kLanes; ++i) p[i] = a.v[i];
}
inline FloatW operator+(FloatW a, FloatW b) {
  return lanewise(a, b, [](float x, float y) { return x + y; });
}
inline FloatW operator-(FloatW a, FloatW b) {
  return lanewise(a, b, [](float x, float y) { return x - y; });
}
inline FloatW operator*(FloatW a, FloatW b) {
  return lanewise(a, b, [](float x, float y) { return x * y; });
}
inline FloatW operator/(FloatW a, FloatW b) {
  return lanewise(a, b, [](float x, float y) { return x / y; });
}
inline FloatW operator-(FloatW a) { return zeroW() - a; }
inline FloatW negateW(FloatW a) { return {{-a.v[0], -a.v[1], -a.v[2], -a.v[3]}}; }
inline FloatW maxW(FloatW a, FloatW b) {
  return lanewise(a, b, [](float x, float y) { return x > y ? x : y; });
}
inline FloatW minW(FloatW a, FloatW b) {
  return lanewise(a, b, [](float x, float y) { return x < y ? x : y; });
}
inline FloatW sqrtW(FloatW a) {
  FloatW r;
  for (int i = 0; i < kLanes; ++i) r.v[i] = std::sqrt(a.v[i]);
  return r;
}
inline FloatW greaterW(FloatW a, FloatW b) {
  FloatW r;
  for (int i = 0; i < kLanes; ++i) r.v[i] = a.v[i] > b.v[i] ? 1.0f : 0.0f;
  return r;
}
inline FloatW notEqualW(FloatW a, FloatW b) {
  FloatW r;
  for (int i = 0; i < kLanes; ++i) r.v[i] = !(a.v[i] == b.v[i]) ? 1.0f : 0.0f;
  return r;
}
inline FloatW selectW(FloatW mask, FloatW a, FloatW b) {
  FloatW r;
  for (int i = 0; i < kLanes; ++i) r.v[i] = mask.v[i] != 0.0f ? a.v[i] : b.v[i];
  return r;
}
inline FloatW orW(FloatW a, FloatW b) {
  return lanewise(a, b, [](float x, float y) { return x != 0.0f || y != 0.0f ? 1.0f : 0.0f; });
}
inline FloatW andW(FloatW a, FloatW b) {
  return lanewise(a, b, [](float x, float y) { return x != 0.0f && y != 0.0f ? 1.0f : 0.0f; });
}
inline bool anyW(FloatW mask) {
  for (int i = 0; i < kLanes; ++i)
    if (mask.v[i] != 0.0f) return true;
  return false;
}
inline bool laneSet(FloatW mask, int lane) { return mask.v[lane] != 0.0f; }
inline unsigned maskBits(FloatW mask) {
  unsigned bits = 0;
  for (int i = 0; i < kLanes; ++i) bits |= mask.v[i] != 0.0f ? 1u << i : 0u;
  return bits;
}
inline void transpose(FloatW& r0, FloatW& r1, FloatW& r2, FloatW& r3) {
  FloatW* rows[4] = {&r0, &r1, &r2, &r3};
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) {
      const float t = rows[i]->v[j];
      rows[i]->v[j] = rows[j]->v[i];
      rows[j]->v[i] = t;
    }
}

#endif

template <typename F>
inline constexpr int kLaneCount = static_cast<int>(sizeof(F) / sizeof(float));

template <typename F>
F splatT(float x);
template <typename F>
F zeroT();
template <typename F>
F loadT(const float* p);
template <>
inline FloatW splatT<FloatW>(float x) {
  return splat(x);
}
template <>
inline FloatW zeroT<FloatW>() {
  return zeroW();
}
template <>
inline FloatW loadT<FloatW>(const float* p) {
  return loadW(p);
}

// One lane, to fill and read the batches outside the hot loops.
template <typename F>
inline float& laneOf(F& w, int lane) {
  return reinterpret_cast<float*>(&w)[lane];
}
template <typename F>
inline float laneOf(const F& w, int lane) {
  return reinterpret_cast<const float*>(&w)[lane];
}

template <typename F>
struct Vec3T {
  F x, y, z;
};
using Vec3W = Vec3T<FloatW>;

template <typename F>
COLLIDE_INLINE Vec3T<F> operator+(const Vec3T<F>& a, const Vec3T<F>& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <typename F>
COLLIDE_INLINE Vec3T<F> operator-(const Vec3T<F>& a, const Vec3T<F>& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <typename F>
COLLIDE_INLINE Vec3T<F> operator*(F s, const Vec3T<F>& a) {
  return {s * a.x, s * a.y, s * a.z};
}
template <typename F>
COLLIDE_INLINE F dot(const Vec3T<F>& a, const Vec3T<F>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <typename F>
COLLIDE_INLINE Vec3T<F> cross(const Vec3T<F>& a, const Vec3T<F>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <typename F>
inline void setLane(Vec3T<F>& w, int lane, const Vec3& v) {
  laneOf(w.x, lane) = v.x;
  laneOf(w.y, lane) = v.y;
  laneOf(w.z, lane) = v.z;
}
template <typename F>
inline Vec3 laneOf(const Vec3T<F>& w, int lane) {
  return {laneOf(w.x, lane), laneOf(w.y, lane), laneOf(w.z, lane)};
}
// a += s * b, the impulse application.
template <typename F>
COLLIDE_INLINE void addScaled(Vec3T<F>& a, F s, const Vec3T<F>& b) {
  a.x = a.x + s * b.x;
  a.y = a.y + s * b.y;
  a.z = a.z + s * b.z;
}

// Four floats at `offset` of each lane's record, as four columns (x, y, z and the fourth float):
// the solver bodies' rows (solver_body.h) to lanes, and back.
COLLIDE_INLINE void gatherRows(const float* const (&records)[4], std::size_t offset, FloatW& x, FloatW& y,
                               FloatW& z, FloatW& w) {
  x = loadW(records[0] + offset);
  y = loadW(records[1] + offset);
  z = loadW(records[2] + offset);
  w = loadW(records[3] + offset);
  transpose(x, y, z, w);
}
// The rows of the four lanes, to be stored by the caller (only for the bodies it may write).
COLLIDE_INLINE void scatterRows(FloatW x, FloatW y, FloatW z, FloatW w, FloatW (&rows)[4]) {
  transpose(x, y, z, w);
  rows[0] = x;
  rows[1] = y;
  rows[2] = z;
  rows[3] = w;
}

}  // namespace collide::detail
