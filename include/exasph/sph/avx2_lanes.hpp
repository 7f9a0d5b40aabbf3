#pragma once
// Building blocks of the pair loops written for AVX2 (sph/density_avx2.hpp): four doubles read
// through 32-bit indices, the periodic minimum image and KernelPoly on eight floats. Compiled
// where the target has AVX2 and FMA (-march=native on such a host) and never in device code;
// elsewhere the portable `omp simd` loops run.
#if defined(__AVX2__) && defined(__FMA__) && !defined(__CUDA_ARCH__)
#define EXASPH_AVX2_PAIRS 1
#include <immintrin.h>

#include <cstdint>

#include "exasph/kernel/kernel_poly.hpp"
#include "exasph/util/annotate.hpp"
#include "exasph/util/box.hpp"

namespace exasph::avx2 {

// f[i[0..3]]: two scalar loads per 128-bit half. Zen 2 runs these faster than vgatherdpd, and
// GCC emulates its gathers the same way; written out here so that the loop around it is ours.
EXASPH_INLINE __m256d gather4(const double* f, const std::uint32_t* i) {
    const __m128d lo = _mm_loadh_pd(_mm_load_sd(f + i[0]), f + i[1]);
    const __m128d hi = _mm_loadh_pd(_mm_load_sd(f + i[2]), f + i[3]);
    return _mm256_insertf128_pd(_mm256_castpd128_pd256(lo), hi, 1);
}

// Four floats f[i[0..3]] as doubles.
EXASPH_INLINE __m256d gather4_float(const float* f, const std::uint32_t* i) {
    return _mm256_cvtps_pd(_mm_setr_ps(f[i[0]], f[i[1]], f[i[2]], f[i[3]]));
}

// u . v of four lanes of 3-vectors.
EXASPH_INLINE __m256d dot3(const __m256d (&u)[3], const __m256d (&v)[3]) {
    return _mm256_fmadd_pd(u[2], v[2], _mm256_fmadd_pd(u[1], v[1], _mm256_mul_pd(u[0], v[0])));
}

// PeriodicImage on four lanes of one axis: d - L where d > L/2, d + L where d < -L/2 (the same
// comparisons and the same single rounding as the scalar operator; an open axis has L = 0 and
// L/2 = infinity).
struct Image4 {
    __m256d len[3], half[3], neg_half[3];
    explicit Image4(const PeriodicImage<double>& im) {
        for (int d = 0; d < 3; ++d) {
            len[d] = _mm256_set1_pd(im.len[d]);
            half[d] = _mm256_set1_pd(im.half[d]);
            neg_half[d] = _mm256_set1_pd(-im.half[d]);
        }
    }
    EXASPH_INLINE __m256d operator()(__m256d d, int axis) const {
        const __m256d above = _mm256_cmp_pd(d, half[axis], _CMP_GT_OQ);
        d = _mm256_sub_pd(d, _mm256_and_pd(above, len[axis]));
        const __m256d below = _mm256_cmp_pd(d, neg_half[axis], _CMP_LT_OQ);
        return _mm256_add_pd(d, _mm256_and_pd(below, len[axis]));
    }
};

// Eight floats from two halves of four (lanes 0-3, then 4-7).
EXASPH_INLINE __m256 join(__m128 lo, __m128 hi) {
    return _mm256_insertf128_ps(_mm256_castps128_ps256(lo), hi, 1);
}
// Lanes 0-3 / 4-7 of eight floats as doubles.
EXASPH_INLINE __m256d low_pd(__m256 v) {
    return _mm256_cvtps_pd(_mm256_castps256_ps128(v));
}
EXASPH_INLINE __m256d high_pd(__m256 v) {
    return _mm256_cvtps_pd(_mm256_extractf128_ps(v, 1));
}

EXASPH_INLINE double horizontal_sum(__m256d v) {
    const __m128d s = _mm_add_pd(_mm256_castpd256_pd128(v), _mm256_extractf128_pd(v, 1));
    return _mm_cvtsd_f64(_mm_add_sd(s, _mm_unpackhi_pd(s, s)));
}
EXASPH_INLINE std::int32_t horizontal_sum(__m256i v) {
    __m128i s = _mm_add_epi32(_mm256_castsi256_si128(v), _mm256_extracti128_si256(v, 1));
    s = _mm_add_epi32(s, _mm_shuffle_epi32(s, 0x4e));
    s = _mm_add_epi32(s, _mm_shuffle_epi32(s, 0xb1));
    return _mm_cvtsi128_si32(s);
}

// Runs step(indices, valid) over a list eight pairs at a time; `valid` (32-bit lanes: -1 or 0)
// marks the lanes that hold a pair. The last 1-7 pairs form one step whose empty lanes hold
// `self` (a's own index: a valid read, masked off by the loops), instead of a scalar remainder.
template <class Step>
EXASPH_INLINE void for_each_eight(const std::uint32_t* index, std::uint32_t count,
                                  std::uint32_t self, Step&& step) {
    std::uint32_t n = 0;
    for (; n + 8 <= count; n += 8) step(index + n, _mm256_set1_epi32(-1));
    if (n == count) return;
    const std::uint32_t left = count - n;
    std::uint32_t idx[8];
    for (std::uint32_t j = 0; j < 8; ++j) idx[j] = j < left ? index[n + j] : self;
    const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
    step(idx, _mm256_cmpgt_epi32(_mm256_set1_epi32(int(left)), lane));
}

// The powers of t = min(s, 4)/2 - 1 that KernelPoly's Estrin scheme uses, shared by the
// polynomials evaluated at one s.
struct PolyPowers {
    __m256 t, t2, t4, t8;
    EXASPH_INLINE explicit PolyPowers(__m256 s) {
        t = _mm256_fmadd_ps(_mm256_min_ps(s, _mm256_set1_ps(4.0f)), _mm256_set1_ps(0.5f),
                            _mm256_set1_ps(-1.0f)); // min returns 4 for a NaN s, as the scalar
        t2 = _mm256_mul_ps(t, t), t4 = _mm256_mul_ps(t2, t2), t8 = _mm256_mul_ps(t4, t4);
    }
};

// KernelPoly<float>'s coefficients, each broadcast to eight lanes once per particle, so that
// the multiply-adds read them from memory (a broadcast per coefficient and pair step was a fifth
// of the density loop's instructions).
struct PolyLanes {
    static constexpr int kTerms = KernelPoly<float>::kTerms;
    __m256 c[kTerms];
    explicit PolyLanes(const KernelPoly<float>& k) {
        for (int i = 0; i < kTerms; ++i) c[i] = _mm256_set1_ps(k.c[i]);
    }
    // KernelPoly<float>::operator() before its factor (s < 4), in the same order of fused
    // multiply-adds, so every lane rounds as the scalar evaluation does.
    EXASPH_INLINE __m256 operator()(const PolyPowers& w) const {
        static_assert(kTerms == 16, "written out for 16 terms, as KernelPoly<float>");
        auto pair = [&](int i) { return _mm256_fmadd_ps(c[i + 1], w.t, c[i]); };
        const __m256 q0 = _mm256_fmadd_ps(pair(2), w.t2, pair(0));
        const __m256 q1 = _mm256_fmadd_ps(pair(6), w.t2, pair(4));
        const __m256 q2 = _mm256_fmadd_ps(pair(10), w.t2, pair(8));
        const __m256 q3 = _mm256_fmadd_ps(pair(14), w.t2, pair(12));
        const __m256 o0 = _mm256_fmadd_ps(q1, w.t4, q0), o1 = _mm256_fmadd_ps(q3, w.t4, q2);
        return _mm256_fmadd_ps(o1, w.t8, o0);
    }
};

} // namespace exasph::avx2
#endif
