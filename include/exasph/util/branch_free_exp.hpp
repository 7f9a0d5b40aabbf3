#pragma once
#include <bit>
#include <cmath>
#include <cstdint>

#include "exasph/util/annotate.hpp"

#if defined(__AVX2__) && defined(__FMA__) && !defined(__CUDA_ARCH__)
#include <immintrin.h>
#endif

namespace exasph {

// e^x for x <= 0 with neither a call nor a branch, so that a pair loop using it still vectorises
// (GCC vectorises std::exp only under -ffast-math). Within 1 ulp of std::exp over [-40, 0]
// (unit test); arguments below -700 give e^-700.
//   x = k ln2 + r, |r| <= ln2/2 (ln2 split in two parts, so that r is exact to round-off),
//   e^r by its Taylor series to r^13 (truncation < r^14/14! < 1e-17),
//   2^k by writing k + 1023 into the exponent bits (k + 1023 lands in the low mantissa bits of
//   (k + 1023) + 2^52; shifted left by 52 they are the exponent field of 2^k).
inline constexpr int kExpSeriesTerms = 14;
// 1/13!, 1/12!, ..., 1/1!, 1/0!
inline constexpr double kExpSeries[kExpSeriesTerms] = {1.0 / 6227020800.0,
                                                       1.0 / 479001600.0,
                                                       1.0 / 39916800.0,
                                                       1.0 / 3628800.0,
                                                       1.0 / 362880.0,
                                                       1.0 / 40320.0,
                                                       1.0 / 5040.0,
                                                       1.0 / 720.0,
                                                       1.0 / 120.0,
                                                       1.0 / 24.0,
                                                       1.0 / 6.0,
                                                       0.5,
                                                       1.0,
                                                       1.0};
inline constexpr double kLog2e = 1.4426950408889634;
inline constexpr double kLn2Hi = 6.93147180369123816490e-01, kLn2Lo = 1.90821492927058770002e-10;

template <class T>
EXASPH_HD EXASPH_INLINE T exp_nonpositive(T x_in) {
#if defined(__CUDA_ARCH__)
    return T(exp(double(x_in)));
#else
    double x = double(x_in);
    x = x < -700.0 ? -700.0 : x; // (a NaN stays a NaN)
    // k = round(x / ln2) (std::floor(... + 0.5) would keep GCC from vectorising)
    const double k = std::nearbyint(x * kLog2e);
    const double r = (x - k * kLn2Hi) - k * kLn2Lo;
    // Horner from 1/13! down to 1/0! (a loop of fixed trip count, unrolled)
    double series = kExpSeries[0];
    for (int j = 1; j < kExpSeriesTerms; ++j) series = series * r + kExpSeries[j];
    const std::uint64_t exponent = std::bit_cast<std::uint64_t>((k + 1023.0) + 0x1p52) << 52;
    return T(series * std::bit_cast<double>(exponent));
#endif
}

#if defined(__AVX2__) && defined(__FMA__) && !defined(__CUDA_ARCH__)
// exp_nonpositive on four lanes, step for step (the AVX2 pair loops, sph/avx2_lanes.hpp).
EXASPH_INLINE __m256d exp_nonpositive4(__m256d x) {
    const __m256d floor = _mm256_set1_pd(-700.0);
    x = _mm256_blendv_pd(x, floor, _mm256_cmp_pd(x, floor, _CMP_LT_OQ)); // a NaN stays a NaN
    const __m256d k = _mm256_round_pd(_mm256_mul_pd(x, _mm256_set1_pd(kLog2e)),
                                      _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC);
    const __m256d r = _mm256_sub_pd(_mm256_sub_pd(x, _mm256_mul_pd(k, _mm256_set1_pd(kLn2Hi))),
                                    _mm256_mul_pd(k, _mm256_set1_pd(kLn2Lo)));
    __m256d series = _mm256_set1_pd(kExpSeries[0]);
    for (int j = 1; j < kExpSeriesTerms; ++j)
        series = _mm256_fmadd_pd(series, r, _mm256_set1_pd(kExpSeries[j]));
    const __m256d biased =
        _mm256_add_pd(_mm256_add_pd(k, _mm256_set1_pd(1023.0)), _mm256_set1_pd(0x1p52));
    const __m256i exponent = _mm256_slli_epi64(_mm256_castpd_si256(biased), 52);
    return _mm256_mul_pd(series, _mm256_castsi256_pd(exponent));
}
#endif

} // namespace exasph
