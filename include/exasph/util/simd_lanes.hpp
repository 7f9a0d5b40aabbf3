#pragma once
// The lanes of the loops written with intrinsics (the pair loops sph/density_simd.hpp,
// iad_simd.hpp, momentum_energy_simd.hpp; the neighbour search's tree/candidate_boxes.hpp and
// tree/leaf_scan.hpp): one source for two instruction sets, chosen by the build's target.
//   Avx2:   a step of 8 pairs, the kernel polynomials on 8 floats (__m256), everything else on
//           two halves of 4 doubles (__m256d); masks are vectors of all-ones lanes.
//   Avx512: a step of 16 pairs, 16 floats (__m512), two halves of 8 doubles (__m512d); masks
//           are mask registers.
// The value types (D: one half's doubles, F: the step's floats, M and FM their masks) are thin
// wrappers whose operators are single intrinsics, so a loop reads like the portable one and
// rounds as it does, operation for operation. Compiled where the target has AVX2 and FMA
// (-march=native on such a host; AVX-512 F where it has that too) and never in device code;
// elsewhere the portable `omp simd` loops run.
#if defined(__AVX2__) && defined(__FMA__) && !defined(__CUDA_ARCH__)
#define EXASPH_SIMD_LANES 1
#include <immintrin.h>

#include <cstdint>

#include "exasph/util/annotate.hpp"

namespace exasph::simd {

// ---- four doubles (AVX2) ----
struct D4 {
    __m256d v;
};
struct M4 {
    __m256d v;
};
EXASPH_INLINE D4 operator+(D4 a, D4 b) {
    return {_mm256_add_pd(a.v, b.v)};
}
EXASPH_INLINE D4 operator-(D4 a, D4 b) {
    return {_mm256_sub_pd(a.v, b.v)};
}
EXASPH_INLINE D4 operator*(D4 a, D4 b) {
    return {_mm256_mul_pd(a.v, b.v)};
}
EXASPH_INLINE D4 operator/(D4 a, D4 b) {
    return {_mm256_div_pd(a.v, b.v)};
}
EXASPH_INLINE D4 fma(D4 a, D4 b, D4 c) {
    return {_mm256_fmadd_pd(a.v, b.v, c.v)};
}
EXASPH_INLINE D4 sqrt(D4 a) {
    return {_mm256_sqrt_pd(a.v)};
}
EXASPH_INLINE D4 min(D4 a, D4 b) {
    return {_mm256_min_pd(a.v, b.v)};
}
EXASPH_INLINE D4 max(D4 a, D4 b) {
    return {_mm256_max_pd(a.v, b.v)};
}
EXASPH_INLINE D4 abs(D4 a) {
    return {_mm256_andnot_pd(_mm256_set1_pd(-0.0), a.v)};
}
EXASPH_INLINE M4 operator<(D4 a, D4 b) {
    return {_mm256_cmp_pd(a.v, b.v, _CMP_LT_OQ)};
}
EXASPH_INLINE M4 operator>(D4 a, D4 b) {
    return {_mm256_cmp_pd(a.v, b.v, _CMP_GT_OQ)};
}
EXASPH_INLINE M4 operator&(M4 a, M4 b) {
    return {_mm256_and_pd(a.v, b.v)};
}
EXASPH_INLINE bool any(M4 m) {
    return _mm256_movemask_pd(m.v) != 0;
}
// Lane k's flag as bit k.
EXASPH_INLINE std::uint32_t bits(M4 m) {
    return std::uint32_t(_mm256_movemask_pd(m.v));
}
EXASPH_INLINE D4 select(M4 m, D4 a) {
    return {_mm256_and_pd(m.v, a.v)};
} // a where m, else 0
EXASPH_INLINE D4 blend(M4 m, D4 a, D4 b) {
    return {_mm256_blendv_pd(a.v, b.v, m.v)};
} // m ? b : a
EXASPH_INLINE D4 round_nearest(D4 a) {
    return {_mm256_round_pd(a.v, _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC)};
}
// The bits of a shifted left by 52 (the exponent field, for 2^k).
EXASPH_INLINE D4 shift_to_exponent(D4 a) {
    return {_mm256_castsi256_pd(_mm256_slli_epi64(_mm256_castpd_si256(a.v), 52))};
}
EXASPH_INLINE double horizontal_sum(D4 a) {
    const __m128d s = _mm_add_pd(_mm256_castpd256_pd128(a.v), _mm256_extractf128_pd(a.v, 1));
    return _mm_cvtsd_f64(_mm_add_sd(s, _mm_unpackhi_pd(s, s)));
}
EXASPH_INLINE double horizontal_max(D4 a) {
    const __m128d m = _mm_max_pd(_mm256_castpd256_pd128(a.v), _mm256_extractf128_pd(a.v, 1));
    return _mm_cvtsd_f64(_mm_max_sd(m, _mm_unpackhi_pd(m, m)));
}

// ---- eight doubles (AVX-512) ----
#ifdef __AVX512F__
// All lanes: the intrinsics below are the zero-masking forms with every lane set, which compile
// to the unmasked instructions; the unmasked forms pass GCC 12 an undefined vector, which it
// reports as maybe uninitialized (GCC bug 105593) wherever they are inlined.
inline constexpr __mmask8 kAll8 = 0xff;
inline constexpr __mmask8 kAll4 = 0x0f;
inline constexpr __mmask16 kAll16 = 0xffff;
struct D8 {
    __m512d v;
};
struct M8 {
    __mmask8 v;
};
EXASPH_INLINE D8 operator+(D8 a, D8 b) {
    return {_mm512_add_pd(a.v, b.v)};
}
EXASPH_INLINE D8 operator-(D8 a, D8 b) {
    return {_mm512_sub_pd(a.v, b.v)};
}
EXASPH_INLINE D8 operator*(D8 a, D8 b) {
    return {_mm512_mul_pd(a.v, b.v)};
}
EXASPH_INLINE D8 operator/(D8 a, D8 b) {
    return {_mm512_div_pd(a.v, b.v)};
}
EXASPH_INLINE D8 fma(D8 a, D8 b, D8 c) {
    return {_mm512_fmadd_pd(a.v, b.v, c.v)};
}
EXASPH_INLINE D8 sqrt(D8 a) {
    return {_mm512_maskz_sqrt_pd(kAll8, a.v)};
}
EXASPH_INLINE D8 min(D8 a, D8 b) {
    return {_mm512_maskz_min_pd(kAll8, a.v, b.v)};
}
EXASPH_INLINE D8 max(D8 a, D8 b) {
    return {_mm512_maskz_max_pd(kAll8, a.v, b.v)};
}
EXASPH_INLINE D8 abs(D8 a) {
    return {_mm512_abs_pd(a.v)};
}
EXASPH_INLINE M8 operator<(D8 a, D8 b) {
    return {_mm512_cmp_pd_mask(a.v, b.v, _CMP_LT_OQ)};
}
EXASPH_INLINE M8 operator>(D8 a, D8 b) {
    return {_mm512_cmp_pd_mask(a.v, b.v, _CMP_GT_OQ)};
}
EXASPH_INLINE M8 operator&(M8 a, M8 b) {
    return {__mmask8(a.v & b.v)};
}
EXASPH_INLINE bool any(M8 m) {
    return m.v != 0;
}
EXASPH_INLINE std::uint32_t bits(M8 m) {
    return m.v;
}
EXASPH_INLINE D8 select(M8 m, D8 a) {
    return {_mm512_maskz_mov_pd(m.v, a.v)};
}
EXASPH_INLINE D8 blend(M8 m, D8 a, D8 b) {
    return {_mm512_mask_blend_pd(m.v, a.v, b.v)};
}
EXASPH_INLINE D8 round_nearest(D8 a) {
    return {_mm512_maskz_roundscale_pd(kAll8, a.v, _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC)};
}
EXASPH_INLINE D8 shift_to_exponent(D8 a) {
    return {_mm512_castsi512_pd(_mm512_maskz_slli_epi64(kAll8, _mm512_castpd_si512(a.v), 52))};
}
EXASPH_INLINE D4 low_half(D8 a) {
    return {_mm512_maskz_extractf64x4_pd(kAll4, a.v, 0)};
}
EXASPH_INLINE D4 high_half(D8 a) {
    return {_mm512_maskz_extractf64x4_pd(kAll4, a.v, 1)};
}
EXASPH_INLINE double horizontal_sum(D8 a) {
    return horizontal_sum(low_half(a) + high_half(a));
}
EXASPH_INLINE double horizontal_max(D8 a) {
    return horizontal_max(max(low_half(a), high_half(a)));
}
#endif

// ---- the floats of a step, the kernel polynomials' precision ----
struct F8 {
    __m256 v;
};
struct FM8 {
    __m256 v;
};
EXASPH_INLINE F8 operator*(F8 a, F8 b) {
    return {_mm256_mul_ps(a.v, b.v)};
}
EXASPH_INLINE F8 fma(F8 a, F8 b, F8 c) {
    return {_mm256_fmadd_ps(a.v, b.v, c.v)};
}
EXASPH_INLINE F8 min(F8 a, F8 b) {
    return {_mm256_min_ps(a.v, b.v)};
}
EXASPH_INLINE FM8 operator<(F8 a, F8 b) {
    return {_mm256_cmp_ps(a.v, b.v, _CMP_LT_OQ)};
}
EXASPH_INLINE FM8 operator&(FM8 a, FM8 b) {
    return {_mm256_and_ps(a.v, b.v)};
}
EXASPH_INLINE F8 select(FM8 m, F8 a) {
    return {_mm256_and_ps(m.v, a.v)};
}
EXASPH_INLINE int count(FM8 m) {
    return __builtin_popcount(unsigned(_mm256_movemask_ps(m.v)));
}
#ifdef __AVX512F__
struct F16 {
    __m512 v;
};
struct FM16 {
    __mmask16 v;
};
EXASPH_INLINE F16 operator*(F16 a, F16 b) {
    return {_mm512_mul_ps(a.v, b.v)};
}
EXASPH_INLINE F16 fma(F16 a, F16 b, F16 c) {
    return {_mm512_fmadd_ps(a.v, b.v, c.v)};
}
EXASPH_INLINE F16 min(F16 a, F16 b) {
    return {_mm512_maskz_min_ps(kAll16, a.v, b.v)};
}
EXASPH_INLINE FM16 operator<(F16 a, F16 b) {
    return {_mm512_cmp_ps_mask(a.v, b.v, _CMP_LT_OQ)};
}
EXASPH_INLINE FM16 operator&(FM16 a, FM16 b) {
    return {__mmask16(a.v & b.v)};
}
EXASPH_INLINE F16 select(FM16 m, F16 a) {
    return {_mm512_maskz_mov_ps(m.v, a.v)};
}
EXASPH_INLINE int count(FM16 m) {
    return __builtin_popcount(unsigned(m.v));
}
#endif

} // namespace exasph::simd
#endif
