// Four float lanes for the contact solver (Box2D v3's b2FloatW, in 3D): SSE2 on x86-64, where it is
// always available, and a plain array elsewhere. Every operation is the IEEE operation of each lane,
// and min/max follow SSE's rule (a > b ? a : b) in both builds, so the lanes give bit for bit what one
// lane would: the solver's result does not depend on which build or how many constraints share a batch.
#pragma once

#include <collide/math.h>

#include <cmath>

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
inline void storeW(float* p, FloatW a) { _mm_storeu_ps(p, a.v); }
inline FloatW operator+(FloatW a, FloatW b) { return {_mm_add_ps(a.v, b.v)}; }
inline FloatW operator-(FloatW a, FloatW b) { return {_mm_sub_ps(a.v, b.v)}; }
inline FloatW operator*(FloatW a, FloatW b) { return {_mm_mul_ps(a.v, b.v)}; }
inline FloatW operator/(FloatW a, FloatW b) { return {_mm_div_ps(a.v, b.v)}; }
inline FloatW operator-(FloatW a) { return {_mm_sub_ps(_mm_setzero_ps(), a.v)}; }
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

// One lane of a FloatW, to fill and read the batches outside the hot loops.
inline float& laneOf(FloatW& w, int lane) { return reinterpret_cast<float*>(&w)[lane]; }
inline float laneOf(const FloatW& w, int lane) { return reinterpret_cast<const float*>(&w)[lane]; }

struct Vec3W {
  FloatW x, y, z;
};

inline Vec3W operator+(const Vec3W& a, const Vec3W& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3W operator-(const Vec3W& a, const Vec3W& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3W operator*(FloatW s, const Vec3W& a) { return {s * a.x, s * a.y, s * a.z}; }
inline FloatW dot(const Vec3W& a, const Vec3W& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3W cross(const Vec3W& a, const Vec3W& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline void setLane(Vec3W& w, int lane, const Vec3& v) {
  laneOf(w.x, lane) = v.x;
  laneOf(w.y, lane) = v.y;
  laneOf(w.z, lane) = v.z;
}
inline Vec3 laneOf(const Vec3W& w, int lane) {
  return {laneOf(w.x, lane), laneOf(w.y, lane), laneOf(w.z, lane)};
}

// a += s * b, the impulse application.
inline void addScaled(Vec3W& a, FloatW s, const Vec3W& b) {
  a.x = a.x + s * b.x;
  a.y = a.y + s * b.y;
  a.z = a.z + s * b.z;
}

}  // namespace collide::detail
