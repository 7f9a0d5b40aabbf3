#pragma once
#include <cmath>

#include "exasph/util/annotate.hpp"

namespace exasph {

// SPEC 7: per-particle Courant limit K h_a / max_b v^sig_ab, falling back to h_a / c_a (and to
// "no limit" when both speeds vanish).
template <class T>
EXASPH_HD T courant_time_step(T h, T vsig_max, T c, T courant) {
    if (vsig_max > T(0)) return courant * h / vsig_max;
    if (c > T(0)) return h / c;
    return T(1e300);
}

// SPEC 7 with gravity: sqrt(eps h_a / |a_a|) ("no limit" without acceleration).
template <class T>
EXASPH_HD T acceleration_time_step(T h, T ax, T ay, T az, T eps) {
    const T a = std::sqrt(ax * ax + ay * ay + az * az);
    return a > T(0) ? std::sqrt(eps * h / a) : T(1e300);
}

// The global step: the smallest particle limit, never more than `growth` times the previous step.
inline double limit_time_step(double dt_courant, double dt_prev, double growth = 1.1) {
    double cap = growth * dt_prev;
    return dt_courant < cap ? dt_courant : cap;
}

} // namespace exasph
