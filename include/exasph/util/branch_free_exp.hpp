#pragma once
#include <bit>
#include <cmath>
#include <cstdint>

#include "exasph/util/annotate.hpp"

namespace exasph {

// e^x for x <= 0 with neither a call nor a branch, so that a pair loop using it still vectorises
// (GCC vectorises std::exp only under -ffast-math). Within 1 ulp of std::exp over [-40, 0]
// (unit test); arguments below -700 give e^-700.
//   x = k ln2 + r, |r| <= ln2/2 (ln2 split in two parts, so that r is exact to round-off),
//   e^r by its Taylor series to r^13 (truncation < r^14/14! < 1e-17),
//   2^k by writing k + 1023 into the exponent bits (k + 1023 lands in the low mantissa bits of
//   (k + 1023) + 2^52; shifted left by 52 they are the exponent field of 2^k).
template <class T>
EXASPH_HD EXASPH_INLINE T exp_nonpositive(T x_in) {
#if defined(__CUDA_ARCH__)
    return T(exp(double(x_in)));
#else
    double x = double(x_in);
    x = x < -700.0 ? -700.0 : x; // (a NaN stays a NaN)
    // k = round(x / ln2) (std::floor(... + 0.5) would keep GCC from vectorising)
    const double k = std::nearbyint(x * 1.4426950408889634);
    const double r = (x - k * 6.93147180369123816490e-01) - k * 1.90821492927058770002e-10;
    // Horner from 1/13! down to 1/0!
    double series = 1.0 / 6227020800.0;
    series = series * r + 1.0 / 479001600.0;
    series = series * r + 1.0 / 39916800.0;
    series = series * r + 1.0 / 3628800.0;
    series = series * r + 1.0 / 362880.0;
    series = series * r + 1.0 / 40320.0;
    series = series * r + 1.0 / 5040.0;
    series = series * r + 1.0 / 720.0;
    series = series * r + 1.0 / 120.0;
    series = series * r + 1.0 / 24.0;
    series = series * r + 1.0 / 6.0;
    series = series * r + 0.5;
    series = series * r + 1.0;
    series = series * r + 1.0;
    const std::uint64_t exponent = std::bit_cast<std::uint64_t>((k + 1023.0) + 0x1p52) << 52;
    return T(series * std::bit_cast<double>(exponent));
#endif
}

} // namespace exasph
