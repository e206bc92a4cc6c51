#pragma once
// Four floats processed together: SSE2 (every x86-64) when available, else four plain floats with the same
// semantics. For the few branch-free per-pair loops of the registration (pair features) where Eigen's
// fixed-size arrays fell back to scalar sqrt/division at -O2. IEEE single precision either way (no fused
// multiply-add), so both paths give the same bits.
#include <cmath>
#include <cstdint>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace cosmo::registration {

#if defined(__SSE2__)
struct Float4 {
  __m128 v;
  Float4() = default;
  Float4(__m128 x) : v(x) {}
  explicit Float4(float x) : v(_mm_set1_ps(x)) {}
  Float4(float a, float b, float c, float d) : v(_mm_setr_ps(a, b, c, d)) {}
  static Float4 load(const float* p) { return _mm_load_ps(p); }  ///< 16-byte aligned
  void store(float* p) const { _mm_store_ps(p, v); }
  friend Float4 operator+(Float4 a, Float4 b) { return _mm_add_ps(a.v, b.v); }
  friend Float4 operator-(Float4 a, Float4 b) { return _mm_sub_ps(a.v, b.v); }
  friend Float4 operator*(Float4 a, Float4 b) { return _mm_mul_ps(a.v, b.v); }
  friend Float4 operator/(Float4 a, Float4 b) { return _mm_div_ps(a.v, b.v); }
  friend Float4 operator-(Float4 a) { return _mm_xor_ps(a.v, _mm_set1_ps(-0.f)); }
  friend Float4 sqrt(Float4 a) { return _mm_sqrt_ps(a.v); }
  friend Float4 abs(Float4 a) { return _mm_andnot_ps(_mm_set1_ps(-0.f), a.v); }
  friend Float4 max(Float4 a, Float4 b) { return _mm_max_ps(a.v, b.v); }  ///< b when either is NaN
  friend Float4 min(Float4 a, Float4 b) { return _mm_min_ps(a.v, b.v); }  ///< b when either is NaN
  // Comparisons give lane masks (all bits set where true), used by select() and maskAnd().
  friend Float4 operator<(Float4 a, Float4 b) { return _mm_cmplt_ps(a.v, b.v); }
  friend Float4 operator>(Float4 a, Float4 b) { return _mm_cmpgt_ps(a.v, b.v); }
  friend Float4 operator<=(Float4 a, Float4 b) { return _mm_cmple_ps(a.v, b.v); }
  friend Float4 maskAnd(Float4 a, Float4 b) { return _mm_and_ps(a.v, b.v); }
  /// mask ? a : b per lane.
  friend Float4 select(Float4 mask, Float4 a, Float4 b) {
    return _mm_or_ps(_mm_and_ps(mask.v, a.v), _mm_andnot_ps(mask.v, b.v));
  }
  /// Rows a, b, c, d become columns (a 4 x 4 transpose).
  friend void transpose4(Float4& a, Float4& b, Float4& c, Float4& d) { _MM_TRANSPOSE4_PS(a.v, b.v, c.v, d.v); }
  /// Truncation towards zero to int32 (the value must fit).
  void storeTruncated(std::int32_t* p) const { _mm_store_si128(reinterpret_cast<__m128i*>(p), _mm_cvttps_epi32(v)); }
  /// 1 where the mask is set, else 0.
  void storeMask(std::int32_t* p) const {
    _mm_store_si128(reinterpret_cast<__m128i*>(p), _mm_srli_epi32(_mm_castps_si128(v), 31));
  }
};
#else
struct Float4 {
  float v[4];
  Float4() = default;
  explicit Float4(float x) : v{x, x, x, x} {}
  Float4(float a, float b, float c, float d) : v{a, b, c, d} {}
  static Float4 load(const float* p) {
    return make([&](int k) { return p[k]; });
  }
  void store(float* p) const {
    for (int k = 0; k < 4; ++k) p[k] = v[k];
  }
  template <class F>
  static Float4 make(F f) {
    Float4 r;
    for (int k = 0; k < 4; ++k) r.v[k] = f(k);
    return r;
  }
  static float maskValue(bool b) {
    const std::uint32_t bits = b ? 0xFFFFFFFFu : 0u;
    float f;
    __builtin_memcpy(&f, &bits, 4);
    return f;
  }
  static bool isSet(float f) {
    std::uint32_t bits;
    __builtin_memcpy(&bits, &f, 4);
    return bits != 0u;
  }
  friend Float4 operator+(Float4 a, Float4 b) {
    return make([&](int k) { return a.v[k] + b.v[k]; });
  }
  friend Float4 operator-(Float4 a, Float4 b) {
    return make([&](int k) { return a.v[k] - b.v[k]; });
  }
  friend Float4 operator*(Float4 a, Float4 b) {
    return make([&](int k) { return a.v[k] * b.v[k]; });
  }
  friend Float4 operator/(Float4 a, Float4 b) {
    return make([&](int k) { return a.v[k] / b.v[k]; });
  }
  friend Float4 operator-(Float4 a) {
    return make([&](int k) { return -a.v[k]; });
  }
  friend Float4 sqrt(Float4 a) {
    return make([&](int k) { return std::sqrt(a.v[k]); });
  }
  friend Float4 abs(Float4 a) {
    return make([&](int k) { return std::fabs(a.v[k]); });
  }
  friend Float4 max(Float4 a, Float4 b) {
    return make([&](int k) { return a.v[k] > b.v[k] ? a.v[k] : b.v[k]; });
  }
  friend Float4 min(Float4 a, Float4 b) {
    return make([&](int k) { return a.v[k] < b.v[k] ? a.v[k] : b.v[k]; });
  }
  friend Float4 operator<(Float4 a, Float4 b) {
    return make([&](int k) { return maskValue(a.v[k] < b.v[k]); });
  }
  friend Float4 operator>(Float4 a, Float4 b) {
    return make([&](int k) { return maskValue(a.v[k] > b.v[k]); });
  }
  friend Float4 operator<=(Float4 a, Float4 b) {
    return make([&](int k) { return maskValue(a.v[k] <= b.v[k]); });
  }
  friend Float4 maskAnd(Float4 a, Float4 b) {
    return make([&](int k) { return maskValue(isSet(a.v[k]) && isSet(b.v[k])); });
  }
  friend Float4 select(Float4 mask, Float4 a, Float4 b) {
    return make([&](int k) { return isSet(mask.v[k]) ? a.v[k] : b.v[k]; });
  }
  friend void transpose4(Float4& a, Float4& b, Float4& c, Float4& d) {
    Float4* r[4] = {&a, &b, &c, &d};
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) {
        const float t = r[i]->v[j];
        r[i]->v[j] = r[j]->v[i];
        r[j]->v[i] = t;
      }
  }
  void storeTruncated(std::int32_t* p) const {
    for (int k = 0; k < 4; ++k) p[k] = static_cast<std::int32_t>(v[k]);
  }
  void storeMask(std::int32_t* p) const {
    for (int k = 0; k < 4; ++k) p[k] = isSet(v[k]) ? 1 : 0;
  }
};
#endif

}  // namespace cosmo::registration
