// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// W numbers side by side for the wide contact solver (docs/solver.md, "Wide rows"): one lane per
// contact manifold. The width comes from the compiler's predefined macros, never from a flag the
// library forces: AVX → 8 floats / 4 doubles, SSE2 (every x86-64) → 4 / 2, anything else (or
// XENO_NO_SIMD) → one portable lane, plain scalar code (Wide<T, 1> below).
//
// Every operation is one IEEE operation per lane, the same in every width: + − × ÷ and sqrt are
// correctly rounded, and min/max follow the SSE rule (max(a, b) = a > b ? a : b, so the second
// operand wins ties and NaN) in the portable lanes too. No fused multiply-add, no approximate
// reciprocal. A lane therefore gets the same bits whatever W it ran in (tests/dynamics/
// wide_test.cpp), which is what lets the solver give the same bits for every width.
#pragma once

#include <cmath>
#include <cstddef>

#if !defined(XENO_NO_SIMD) && (defined(__SSE2__) || defined(_M_X64) || (defined(_M_IX86_FP) && _M_IX86_FP >= 2))
#define XENO_SIMD_SSE2 1
#include <emmintrin.h>
#if defined(__AVX__)
#define XENO_SIMD_AVX 1
#include <immintrin.h>
#endif
#endif

// The lane helpers are small and called in the solver's innermost loop with several registers
// of arguments: a call would spill them all, so they are always inlined where the compiler allows.
// XENO_WIDE_NOINLINE keeps a rarely taken path out of its caller's code.
#if defined(__GNUC__) || defined(__clang__)
#define XENO_WIDE_INLINE inline __attribute__((always_inline))
#define XENO_WIDE_NOINLINE __attribute__((noinline))
#elif defined(_MSC_VER)
#define XENO_WIDE_INLINE __forceinline
#define XENO_WIDE_NOINLINE __declspec(noinline)
#else
#define XENO_WIDE_INLINE inline
#define XENO_WIDE_NOINLINE
#endif

namespace xeno {
namespace detail {

/// Portable lanes: W numbers, one operation per lane. Also the scalar reference of the SIMD
/// specialisations below.
template <class T, int W>
struct Wide {
    static constexpr int width = W;
    T lane[W];

    static Wide splat(T x) {
        Wide r;
        for (int i = 0; i < W; ++i) r.lane[i] = x;
        return r;
    }
    T get(int i) const { return lane[i]; }
    void set(int i, T x) { lane[i] = x; }
    /// W numbers from p (aligned to the register's size in the SIMD specialisations).
    static Wide load(const T* p) {
        Wide r;
        for (int i = 0; i < W; ++i) r.lane[i] = p[i];
        return r;
    }
    /// W numbers from p, any alignment.
    static Wide loadu(const T* p) { return load(p); }
    void store(T* p) const {
        for (int i = 0; i < W; ++i) p[i] = lane[i];
    }

    template <class F>
    static Wide map(const Wide& a, const Wide& b, F f) {
        Wide r;
        for (int i = 0; i < W; ++i) r.lane[i] = f(a.lane[i], b.lane[i]);
        return r;
    }
    friend Wide operator+(const Wide& a, const Wide& b) {
        return map(a, b, [](T x, T y) { return x + y; });
    }
    friend Wide operator-(const Wide& a, const Wide& b) {
        return map(a, b, [](T x, T y) { return x - y; });
    }
    friend Wide operator*(const Wide& a, const Wide& b) {
        return map(a, b, [](T x, T y) { return x * y; });
    }
    friend Wide operator/(const Wide& a, const Wide& b) {
        return map(a, b, [](T x, T y) { return x / y; });
    }
    friend Wide max(const Wide& a, const Wide& b) {
        return map(a, b, [](T x, T y) { return x > y ? x : y; });
    }
    friend Wide min(const Wide& a, const Wide& b) {
        return map(a, b, [](T x, T y) { return x < y ? x : y; });
    }
    friend Wide sqrt(const Wide& a) {
        Wide r;
        for (int i = 0; i < W; ++i) r.lane[i] = std::sqrt(a.lane[i]);
        return r;
    }
    /// |a|: the sign bit cleared (exact, as in the SIMD lanes).
    friend Wide abs(const Wide& a) {
        Wide r;
        for (int i = 0; i < W; ++i) r.lane[i] = std::fabs(a.lane[i]);
        return r;
    }

    /// A lane mask: true lanes of a comparison.
    struct Mask {
        bool lane[W];
    };
    friend Mask operator>(const Wide& a, const Wide& b) {
        Mask m;
        for (int i = 0; i < W; ++i) m.lane[i] = a.lane[i] > b.lane[i];
        return m;
    }
    friend Mask operator<(const Wide& a, const Wide& b) { return b > a; }
    /// m ? a : b, lane by lane.
    friend Wide select(const Mask& m, const Wide& a, const Wide& b) {
        Wide r;
        for (int i = 0; i < W; ++i) r.lane[i] = m.lane[i] ? a.lane[i] : b.lane[i];
        return r;
    }
    /// Bit i set when lane i is true.
    friend unsigned bits(const Mask& m) {
        unsigned r = 0;
        for (int i = 0; i < W; ++i) r |= m.lane[i] ? 1u << i : 0u;
        return r;
    }
};

#if defined(XENO_SIMD_SSE2)
/// Four floats in an SSE register.
template <>
struct Wide<float, 4> {
    static constexpr int width = 4;
    __m128 x;

    static Wide splat(float v) { return {_mm_set1_ps(v)}; }
    // Lanes through memory: the vector types of <immintrin.h> may alias their element type.
    float get(int i) const { return reinterpret_cast<const float*>(&x)[i]; }
    void set(int i, float v) { reinterpret_cast<float*>(&x)[i] = v; }
    static Wide load(const float* p) { return {_mm_load_ps(p)}; }
    static Wide loadu(const float* p) { return {_mm_loadu_ps(p)}; }
    void store(float* p) const { _mm_store_ps(p, x); }
    friend Wide operator+(Wide a, Wide b) { return {_mm_add_ps(a.x, b.x)}; }
    friend Wide operator-(Wide a, Wide b) { return {_mm_sub_ps(a.x, b.x)}; }
    friend Wide operator*(Wide a, Wide b) { return {_mm_mul_ps(a.x, b.x)}; }
    friend Wide operator/(Wide a, Wide b) { return {_mm_div_ps(a.x, b.x)}; }
    friend Wide max(Wide a, Wide b) { return {_mm_max_ps(a.x, b.x)}; }
    friend Wide min(Wide a, Wide b) { return {_mm_min_ps(a.x, b.x)}; }
    friend Wide sqrt(Wide a) { return {_mm_sqrt_ps(a.x)}; }
    friend Wide abs(Wide a) { return {_mm_andnot_ps(_mm_set1_ps(-0.0f), a.x)}; }
    struct Mask {
        __m128 x;
    };
    friend unsigned bits(Mask m) { return static_cast<unsigned>(_mm_movemask_ps(m.x)); }
    friend Mask operator>(Wide a, Wide b) { return {_mm_cmpgt_ps(a.x, b.x)}; }
    friend Mask operator<(Wide a, Wide b) { return {_mm_cmplt_ps(a.x, b.x)}; }
    friend Wide select(Mask m, Wide a, Wide b) { return {_mm_or_ps(_mm_and_ps(m.x, a.x), _mm_andnot_ps(m.x, b.x))}; }
};

/// Two doubles in an SSE2 register.
template <>
struct Wide<double, 2> {
    static constexpr int width = 2;
    __m128d x;

    static Wide splat(double v) { return {_mm_set1_pd(v)}; }
    // Lanes through memory: the vector types of <immintrin.h> may alias their element type.
    double get(int i) const { return reinterpret_cast<const double*>(&x)[i]; }
    void set(int i, double v) { reinterpret_cast<double*>(&x)[i] = v; }
    static Wide load(const double* p) { return {_mm_load_pd(p)}; }
    static Wide loadu(const double* p) { return {_mm_loadu_pd(p)}; }
    void store(double* p) const { _mm_store_pd(p, x); }
    friend Wide operator+(Wide a, Wide b) { return {_mm_add_pd(a.x, b.x)}; }
    friend Wide operator-(Wide a, Wide b) { return {_mm_sub_pd(a.x, b.x)}; }
    friend Wide operator*(Wide a, Wide b) { return {_mm_mul_pd(a.x, b.x)}; }
    friend Wide operator/(Wide a, Wide b) { return {_mm_div_pd(a.x, b.x)}; }
    friend Wide max(Wide a, Wide b) { return {_mm_max_pd(a.x, b.x)}; }
    friend Wide min(Wide a, Wide b) { return {_mm_min_pd(a.x, b.x)}; }
    friend Wide sqrt(Wide a) { return {_mm_sqrt_pd(a.x)}; }
    friend Wide abs(Wide a) { return {_mm_andnot_pd(_mm_set1_pd(-0.0), a.x)}; }
    struct Mask {
        __m128d x;
    };
    friend unsigned bits(Mask m) { return static_cast<unsigned>(_mm_movemask_pd(m.x)); }
    friend Mask operator>(Wide a, Wide b) { return {_mm_cmpgt_pd(a.x, b.x)}; }
    friend Mask operator<(Wide a, Wide b) { return {_mm_cmplt_pd(a.x, b.x)}; }
    friend Wide select(Mask m, Wide a, Wide b) { return {_mm_or_pd(_mm_and_pd(m.x, a.x), _mm_andnot_pd(m.x, b.x))}; }
};
#endif

#if defined(XENO_SIMD_AVX)
/// Eight floats in an AVX register.
template <>
struct Wide<float, 8> {
    static constexpr int width = 8;
    __m256 x;

    static Wide splat(float v) { return {_mm256_set1_ps(v)}; }
    // Lanes through memory: the vector types of <immintrin.h> may alias their element type.
    float get(int i) const { return reinterpret_cast<const float*>(&x)[i]; }
    void set(int i, float v) { reinterpret_cast<float*>(&x)[i] = v; }
    static Wide load(const float* p) { return {_mm256_load_ps(p)}; }
    static Wide loadu(const float* p) { return {_mm256_loadu_ps(p)}; }
    void store(float* p) const { _mm256_store_ps(p, x); }
    friend Wide operator+(Wide a, Wide b) { return {_mm256_add_ps(a.x, b.x)}; }
    friend Wide operator-(Wide a, Wide b) { return {_mm256_sub_ps(a.x, b.x)}; }
    friend Wide operator*(Wide a, Wide b) { return {_mm256_mul_ps(a.x, b.x)}; }
    friend Wide operator/(Wide a, Wide b) { return {_mm256_div_ps(a.x, b.x)}; }
    friend Wide max(Wide a, Wide b) { return {_mm256_max_ps(a.x, b.x)}; }
    friend Wide min(Wide a, Wide b) { return {_mm256_min_ps(a.x, b.x)}; }
    friend Wide sqrt(Wide a) { return {_mm256_sqrt_ps(a.x)}; }
    friend Wide abs(Wide a) { return {_mm256_andnot_ps(_mm256_set1_ps(-0.0f), a.x)}; }
    struct Mask {
        __m256 x;
    };
    friend unsigned bits(Mask m) { return static_cast<unsigned>(_mm256_movemask_ps(m.x)); }
    friend Mask operator>(Wide a, Wide b) { return {_mm256_cmp_ps(a.x, b.x, _CMP_GT_OQ)}; }
    friend Mask operator<(Wide a, Wide b) { return {_mm256_cmp_ps(a.x, b.x, _CMP_LT_OQ)}; }
    friend Wide select(Mask m, Wide a, Wide b) { return {_mm256_blendv_ps(b.x, a.x, m.x)}; }
};

/// Four doubles in an AVX register.
template <>
struct Wide<double, 4> {
    static constexpr int width = 4;
    __m256d x;

    static Wide splat(double v) { return {_mm256_set1_pd(v)}; }
    // Lanes through memory: the vector types of <immintrin.h> may alias their element type.
    double get(int i) const { return reinterpret_cast<const double*>(&x)[i]; }
    void set(int i, double v) { reinterpret_cast<double*>(&x)[i] = v; }
    static Wide load(const double* p) { return {_mm256_load_pd(p)}; }
    static Wide loadu(const double* p) { return {_mm256_loadu_pd(p)}; }
    void store(double* p) const { _mm256_store_pd(p, x); }
    friend Wide operator+(Wide a, Wide b) { return {_mm256_add_pd(a.x, b.x)}; }
    friend Wide operator-(Wide a, Wide b) { return {_mm256_sub_pd(a.x, b.x)}; }
    friend Wide operator*(Wide a, Wide b) { return {_mm256_mul_pd(a.x, b.x)}; }
    friend Wide operator/(Wide a, Wide b) { return {_mm256_div_pd(a.x, b.x)}; }
    friend Wide max(Wide a, Wide b) { return {_mm256_max_pd(a.x, b.x)}; }
    friend Wide min(Wide a, Wide b) { return {_mm256_min_pd(a.x, b.x)}; }
    friend Wide sqrt(Wide a) { return {_mm256_sqrt_pd(a.x)}; }
    friend Wide abs(Wide a) { return {_mm256_andnot_pd(_mm256_set1_pd(-0.0), a.x)}; }
    struct Mask {
        __m256d x;
    };
    friend unsigned bits(Mask m) { return static_cast<unsigned>(_mm256_movemask_pd(m.x)); }
    friend Mask operator>(Wide a, Wide b) { return {_mm256_cmp_pd(a.x, b.x, _CMP_GT_OQ)}; }
    friend Mask operator<(Wide a, Wide b) { return {_mm256_cmp_pd(a.x, b.x, _CMP_LT_OQ)}; }
    friend Wide select(Mask m, Wide a, Wide b) { return {_mm256_blendv_pd(b.x, a.x, m.x)}; }
};
#endif

/// Transposes W records into lanes: out[r] lane l = src[l][r] for r < rows. Each record is `rows`
/// numbers in a row (the solver's per-body state); portable version, through a buffer.
template <class T, int W>
XENO_WIDE_INLINE void load_transposed(const T* const (&src)[W], int rows, Wide<T, W>* out) {
    for (int r = 0; r < rows; ++r)
        for (int l = 0; l < W; ++l) out[r].set(l, src[l][r]);
}

/// The inverse: dst[l][r] = in[r] lane l for r < rows.
template <class T, int W>
XENO_WIDE_INLINE void store_transposed(const Wide<T, W>* in, int rows, T* const (&dst)[W]) {
    for (int r = 0; r < rows; ++r)
        for (int l = 0; l < W; ++l) dst[l][r] = in[r].get(l);
}

#if defined(XENO_SIMD_SSE2)
// SSE2: four rows at a time by 4 × 4 transposes (two at a time for doubles), the rest lane by lane.
XENO_WIDE_INLINE void load_transposed(const float* const (&src)[4], int rows, Wide<float, 4>* out) {
    int r = 0;
    for (; r + 4 <= rows; r += 4) {
        __m128 a = _mm_loadu_ps(src[0] + r), b = _mm_loadu_ps(src[1] + r), c = _mm_loadu_ps(src[2] + r),
               d = _mm_loadu_ps(src[3] + r);
        _MM_TRANSPOSE4_PS(a, b, c, d);
        out[r].x = a, out[r + 1].x = b, out[r + 2].x = c, out[r + 3].x = d;
    }
    for (; r < rows; ++r) out[r].x = _mm_set_ps(src[3][r], src[2][r], src[1][r], src[0][r]);
}
XENO_WIDE_INLINE void store_transposed(const Wide<float, 4>* in, int rows, float* const (&dst)[4]) {
    int r = 0;
    for (; r + 4 <= rows; r += 4) {
        __m128 a = in[r].x, b = in[r + 1].x, c = in[r + 2].x, d = in[r + 3].x;
        _MM_TRANSPOSE4_PS(a, b, c, d);
        _mm_storeu_ps(dst[0] + r, a), _mm_storeu_ps(dst[1] + r, b), _mm_storeu_ps(dst[2] + r, c), _mm_storeu_ps(dst[3] + r, d);
    }
    for (; r < rows; ++r)
        for (int l = 0; l < 4; ++l) dst[l][r] = in[r].get(l);
}
XENO_WIDE_INLINE void load_transposed(const double* const (&src)[2], int rows, Wide<double, 2>* out) {
    int r = 0;
    for (; r + 2 <= rows; r += 2) {
        const __m128d a = _mm_loadu_pd(src[0] + r), b = _mm_loadu_pd(src[1] + r);
        out[r].x = _mm_unpacklo_pd(a, b), out[r + 1].x = _mm_unpackhi_pd(a, b);
    }
    for (; r < rows; ++r) out[r].x = _mm_set_pd(src[1][r], src[0][r]);
}
XENO_WIDE_INLINE void store_transposed(const Wide<double, 2>* in, int rows, double* const (&dst)[2]) {
    int r = 0;
    for (; r + 2 <= rows; r += 2) {
        _mm_storeu_pd(dst[0] + r, _mm_unpacklo_pd(in[r].x, in[r + 1].x));
        _mm_storeu_pd(dst[1] + r, _mm_unpackhi_pd(in[r].x, in[r + 1].x));
    }
    for (; r < rows; ++r) dst[0][r] = in[r].get(0), dst[1][r] = in[r].get(1);
}
#endif

#if defined(XENO_SIMD_AVX)
// AVX: eight float records as two 4 × 4 transposes joined into one register; four double records
// as 2 × 2 unpacks of their two halves.
XENO_WIDE_INLINE void load_transposed(const float* const (&src)[8], int rows, Wide<float, 8>* out) {
    int r = 0;
    for (; r + 4 <= rows; r += 4) {
        __m128 a = _mm_loadu_ps(src[0] + r), b = _mm_loadu_ps(src[1] + r), c = _mm_loadu_ps(src[2] + r),
               d = _mm_loadu_ps(src[3] + r);
        __m128 e = _mm_loadu_ps(src[4] + r), f = _mm_loadu_ps(src[5] + r), g = _mm_loadu_ps(src[6] + r),
               h = _mm_loadu_ps(src[7] + r);
        _MM_TRANSPOSE4_PS(a, b, c, d);
        _MM_TRANSPOSE4_PS(e, f, g, h);
        out[r].x = _mm256_insertf128_ps(_mm256_castps128_ps256(a), e, 1);
        out[r + 1].x = _mm256_insertf128_ps(_mm256_castps128_ps256(b), f, 1);
        out[r + 2].x = _mm256_insertf128_ps(_mm256_castps128_ps256(c), g, 1);
        out[r + 3].x = _mm256_insertf128_ps(_mm256_castps128_ps256(d), h, 1);
    }
    for (; r < rows; ++r)
        out[r].x = _mm256_set_ps(src[7][r], src[6][r], src[5][r], src[4][r], src[3][r], src[2][r], src[1][r], src[0][r]);
}
XENO_WIDE_INLINE void load_transposed(const double* const (&src)[4], int rows, Wide<double, 4>* out) {
    int r = 0;
    for (; r + 2 <= rows; r += 2) {
        const __m128d a = _mm_loadu_pd(src[0] + r), b = _mm_loadu_pd(src[1] + r), c = _mm_loadu_pd(src[2] + r),
                      d = _mm_loadu_pd(src[3] + r);
        out[r].x = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_unpacklo_pd(a, b)), _mm_unpacklo_pd(c, d), 1);
        out[r + 1].x = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_unpackhi_pd(a, b)), _mm_unpackhi_pd(c, d), 1);
    }
    for (; r < rows; ++r) out[r].x = _mm256_set_pd(src[3][r], src[2][r], src[1][r], src[0][r]);
}
#endif

/// The solver's lane count for T on this target (see the file comment).
template <class T>
constexpr int native_width() {
#if defined(XENO_SIMD_AVX)
    return 32 / static_cast<int>(sizeof(T));
#elif defined(XENO_SIMD_SSE2)
    return 16 / static_cast<int>(sizeof(T));
#else
    return 1;  // plain scalar code: measured faster than 4 portable lanes, which compilers do not vectorise well
#endif
}

/// A lane vector of three components, for normals, velocities and offsets.
template <class V>
struct WideVec3 {
    V x, y, z;
    friend WideVec3 operator+(const WideVec3& a, const WideVec3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
    friend WideVec3 operator-(const WideVec3& a, const WideVec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
    friend WideVec3 operator*(const WideVec3& a, const V& s) { return {a.x * s, a.y * s, a.z * s}; }
    friend V dot(const WideVec3& a, const WideVec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
    friend WideVec3 cross(const WideVec3& a, const WideVec3& b) {
        return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
    }
    friend WideVec3 select(const typename V::Mask& m, const WideVec3& a, const WideVec3& b) {
        return {select(m, a.x, b.x), select(m, a.y, b.y), select(m, a.z, b.z)};
    }
};

/// A lane quaternion (w, x, y, z), the rotation of a body since the step began.
template <class V>
struct WideQuat {
    V w;
    WideVec3<V> v;
};

/// The conjugate, the inverse rotation of a unit quaternion.
template <class V>
XENO_WIDE_INLINE WideQuat<V> conjugate(const WideQuat<V>& q) {
    const V zero = V::splat(0);
    return {q.w, {zero - q.v.x, zero - q.v.y, zero - q.v.z}};
}

/// rotate(q, r) of quat.hpp, lane by lane, in the same operations: r + w t + u × t, t = 2 u × r.
template <class V>
XENO_WIDE_INLINE WideVec3<V> rotate(const WideQuat<V>& q, const WideVec3<V>& r) {
    const WideVec3<V> c = cross(q.v, r);
    const V two = V::splat(2);
    const WideVec3<V> t{two * c.x, two * c.y, two * c.z};
    return r + t * q.w + cross(q.v, t);
}

}  // namespace detail
}  // namespace xeno
