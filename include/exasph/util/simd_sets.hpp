#pragma once
// The two lane sets of the loops written with intrinsics (util/simd_lanes.hpp's types) and what
// every such loop builds from them: reads (contiguous, masked, through 32-bit indices), a step's
// lanes split into halves of doubles, the steps over a list and the periodic minimum image.
// `Native` is the widest set the build's target has: the one test of the instruction set
// (EXASPH_SIMD_LANES: AVX2 and FMA; AVX-512 F beside them for Avx512).
#include "exasph/util/simd_lanes.hpp"

#ifdef EXASPH_SIMD_LANES
#include <cstdint>

#include "exasph/util/box.hpp"

namespace exasph::simd {

// A step of 8 pairs: floats on __m256, doubles in two halves of 4.
struct Avx2 {
    static constexpr const char* kName = "AVX2"; // what --version and the run header print
    using D = D4;
    using M = M4;
    using F = F8;
    using FM = FM8;
    using H = __m128; // the floats of one half
    static constexpr int kHalf = 4, kStep = 8;
    static D splat(double x) { return {_mm256_set1_pd(x)}; }
    static F splat_f(float x) { return {_mm256_set1_ps(x)}; }
    // A half's doubles from f[0..kHalf), or only the lanes `valid` holds (the others 0, unread).
    static EXASPH_INLINE D load(const double* f) { return {_mm256_loadu_pd(f)}; }
    static EXASPH_INLINE D load(const double* f, M valid) {
        return {_mm256_maskload_pd(f, _mm256_castpd_si256(valid.v))};
    }
    // f[i[0..3]]: two scalar loads per 128-bit half. Zen 2 runs these faster than vgatherdpd,
    // and Zen 5 faster than its 8-wide form (docs/performance-log.md).
    static EXASPH_INLINE D gather(const double* f, const std::uint32_t* i) {
        const __m128d lo = _mm_loadh_pd(_mm_load_sd(f + i[0]), f + i[1]);
        const __m128d hi = _mm_loadh_pd(_mm_load_sd(f + i[2]), f + i[3]);
        return {_mm256_insertf128_pd(_mm256_castpd128_pd256(lo), hi, 1)};
    }
    static EXASPH_INLINE D gather(const float* f, const std::uint32_t* i) {
        return {_mm256_cvtps_pd(_mm_setr_ps(f[i[0]], f[i[1]], f[i[2]], f[i[3]]))};
    }
    static EXASPH_INLINE H to_float(D a) { return _mm256_cvtpd_ps(a.v); }
    static EXASPH_INLINE F join(H lo, H hi) {
        return {_mm256_insertf128_ps(_mm256_castps128_ps256(lo), hi, 1)};
    }
    // Lanes of half h (0: 0-3, 1: 4-7) as doubles, and as a mask of doubles.
    static EXASPH_INLINE D half(F a, int h) {
        return {
            _mm256_cvtps_pd(h == 0 ? _mm256_castps256_ps128(a.v) : _mm256_extractf128_ps(a.v, 1))};
    }
    static EXASPH_INLINE M half(FM m, int h) {
        const __m128i bits =
            _mm_castps_si128(h == 0 ? _mm256_castps256_ps128(m.v) : _mm256_extractf128_ps(m.v, 1));
        return {_mm256_castsi256_pd(_mm256_cvtepi32_epi64(bits))};
    }
    static FM all() { return {_mm256_castsi256_ps(_mm256_set1_epi32(-1))}; }
    static EXASPH_INLINE FM first(std::uint32_t n) { // lanes 0..n-1
        const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
        return {_mm256_castsi256_ps(_mm256_cmpgt_epi32(_mm256_set1_epi32(int(n)), lane))};
    }
};

#ifdef __AVX512F__
// A step of 16 pairs: floats on __m512, doubles in two halves of 8.
struct Avx512 {
    static constexpr const char* kName = "AVX-512";
    using D = D8;
    using M = M8;
    using F = F16;
    using FM = FM16;
    using H = __m256;
    static constexpr int kHalf = 8, kStep = 16;
    static D splat(double x) { return {_mm512_set1_pd(x)}; }
    static F splat_f(float x) { return {_mm512_set1_ps(x)}; }
    static EXASPH_INLINE D load(const double* f) { return {_mm512_loadu_pd(f)}; }
    static EXASPH_INLINE D load(const double* f, M valid) {
        return {_mm512_maskz_loadu_pd(valid.v, f)};
    }
    // Eight lanes from two halves of four (as bits).
    static EXASPH_INLINE __m512d concat(__m256d lo, __m256d hi) {
        return _mm512_maskz_insertf64x4(kAll8, _mm512_castpd256_pd512(lo), hi, 1);
    }
    // Avx2's reads twice (vgatherdpd was 65 % slower in the density pass on Zen 5).
    static EXASPH_INLINE D gather(const double* f, const std::uint32_t* i) {
        return {concat(Avx2::gather(f, i).v, Avx2::gather(f, i + 4).v)};
    }
    static EXASPH_INLINE D gather(const float* f, const std::uint32_t* i) {
        return {_mm512_maskz_cvtps_pd(kAll8, _mm256_setr_ps(f[i[0]], f[i[1]], f[i[2]], f[i[3]],
                                                            f[i[4]], f[i[5]], f[i[6]], f[i[7]]))};
    }
    static EXASPH_INLINE H to_float(D a) { return _mm512_maskz_cvtpd_ps(kAll8, a.v); }
    static EXASPH_INLINE F join(H lo, H hi) {
        return {_mm512_castpd_ps(concat(_mm256_castps_pd(lo), _mm256_castps_pd(hi)))};
    }
    static EXASPH_INLINE D half(F a, int h) {
        const __m256d bits = h == 0 ? _mm512_maskz_extractf64x4_pd(kAll4, _mm512_castps_pd(a.v), 0)
                                    : _mm512_maskz_extractf64x4_pd(kAll4, _mm512_castps_pd(a.v), 1);
        return {_mm512_maskz_cvtps_pd(kAll8, _mm256_castpd_ps(bits))};
    }
    static EXASPH_INLINE M half(FM m, int h) { return {__mmask8(h == 0 ? m.v : m.v >> 8)}; }
    static FM all() { return {__mmask16(0xffff)}; }
    static EXASPH_INLINE FM first(std::uint32_t n) { return {__mmask16((1u << n) - 1u)}; }
};
using Native = Avx512;
#else
using Native = Avx2;
#endif

// u . v of a half's lanes of 3-vectors.
template <class D>
EXASPH_INLINE D dot3(const D (&u)[3], const D (&v)[3]) {
    return fma(u[2], v[2], fma(u[1], v[1], u[0] * v[0]));
}

// Runs step(indices, valid) over a list V::kStep pairs at a time; `valid` marks the lanes that
// hold a pair. The last pairs form one step whose empty lanes hold `self` (a's own index: a
// valid read, masked off by the loops), instead of a scalar remainder.
template <class V, class Step>
EXASPH_INLINE void for_each_step(const std::uint32_t* index, std::uint32_t count,
                                 std::uint32_t self, Step&& step) {
    constexpr std::uint32_t kStep = V::kStep;
    std::uint32_t n = 0;
    for (; n + kStep <= count; n += kStep) step(index + n, V::all());
    if (n == count) return;
    const std::uint32_t left = count - n;
    std::uint32_t idx[kStep];
    for (std::uint32_t j = 0; j < kStep; ++j) idx[j] = j < left ? index[n + j] : self;
    step(idx, V::first(left));
}

// PeriodicImage on one half's lanes of one axis: d - L where d > L/2, d + L where d < -L/2 (the
// scalar operator's comparisons and single rounding; an open axis has L = 0, L/2 = infinity).
template <class V>
struct Image {
    using D = typename V::D;
    D len[3], half[3], neg_half[3];
    explicit Image(const PeriodicImage<double>& im) {
        for (int d = 0; d < 3; ++d) {
            len[d] = V::splat(im.len[d]);
            half[d] = V::splat(im.half[d]);
            neg_half[d] = V::splat(-im.half[d]);
        }
    }
    EXASPH_INLINE D operator()(D d, int axis) const {
        d = d - select(d > half[axis], len[axis]);
        return d + select(d < neg_half[axis], len[axis]);
    }
};

} // namespace exasph::simd
#endif
