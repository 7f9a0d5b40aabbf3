#pragma once
#include <bit>
#include <cmath>
#include <cstdint>

#include "exasph/util/annotate.hpp"

namespace exasph {

// e^x for x <= 0 with neither a call nor a branch, so that a pair loop using it still vectorises
// (GCC vectorises std::exp only under -ffast-math); the intrinsic pair loops run it on their
// lanes step for step (simd::exp_nonpositive, sph/simd_isa.hpp). Within 1 ulp of std::exp over
// [-40, 0] (unit test); arguments below -700 give e^-700.
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

} // namespace exasph
