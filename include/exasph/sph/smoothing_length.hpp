#pragma once
#include <cmath>

#include "exasph/util/annotate.hpp"

namespace exasph {

// physics.md §2: h_new = h * 0.5 * (1 + c0 ng0 / nc)^(1/3), c0 = 7, a fixed point at nc = ng0.
// A particle with no neighbour counts as one so that h grows by a bounded factor.
template <class T>
EXASPH_HD T update_smoothing_length(T h, T nc, T ng0) {
    constexpr T kC0 = 7;
    T n = nc > T(1) ? nc : T(1);
    return h * T(0.5) * std::cbrt(T(1) + kC0 * ng0 / n);
}

} // namespace exasph
