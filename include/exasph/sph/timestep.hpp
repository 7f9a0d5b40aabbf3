#pragma once
#include <cmath>

#include "exasph/sph/reduction.hpp"
#include "exasph/util/annotate.hpp"

namespace exasph {

// A particle without a limit of some kind (no speed, no acceleration, u not falling): +infinity,
// the identity of the minimum the step is chosen by, so that it never decides the step.
template <class T>
EXASPH_HD constexpr T no_time_step_limit() {
    return MinOf<T>::identity();
}

// physics.md §7: per-particle Courant limit K h_a / max_b v^sig_ab, falling back to h_a / c_a (and
// to "no limit" when both speeds vanish).
template <class T>
EXASPH_HD T courant_time_step(T h, T vsig_max, T c, T courant) {
    if (vsig_max > T(0)) return courant * h / vsig_max;
    if (c > T(0)) return h / c;
    return no_time_step_limit<T>();
}

// physics.md §7 with gravity: sqrt(eps h_a / |a_a|) ("no limit" without acceleration).
template <class T>
EXASPH_HD T acceleration_time_step(T h, T ax, T ay, T az, T eps) {
    const T a = std::sqrt(ax * ax + ay * ay + az * az);
    return a > T(0) ? std::sqrt(eps * h / a) : no_time_step_limit<T>();
}

// Block time steps' energy criterion: a particle losing internal energy may lose at most the
// fraction k_u of it over a step at its current rate, dt <= k_u u / |du| (no limit while u
// grows). The leapfrog kicks u by du dt/2 twice with the rates at both ends; the Courant limit
// bounds adiabatic cooling (|du| / u = (gamma - 1) |div v| <= (gamma - 1) v_sig / h) but not
// conduction, which can drain a hot particle next to cold ones within one long step.
template <class T>
EXASPH_HD T energy_time_step(T u, T du, T k_u) {
    return du < T(0) ? k_u * u / -du : no_time_step_limit<T>();
}

// The global step: the smallest particle limit, never more than `growth` times the previous step.
inline double limit_time_step(double dt_courant, double dt_prev, double growth = 1.1) {
    double cap = growth * dt_prev;
    return dt_courant < cap ? dt_courant : cap;
}

} // namespace exasph
