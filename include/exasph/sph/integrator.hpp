#pragma once
#include "exasph/util/annotate.hpp"

namespace exasph {

// physics.md §7, one axis of the 2nd-order Press scheme with variable steps:
//   v_{n+1} = (x_n - x_{n-1})/dt_{n-1} + a_n (dt_n + dt_{n-1}/2)
//   x_{n+1} = x_n + dt_n (x_n - x_{n-1})/dt_{n-1} + a_n dt_n (dt_n + dt_{n-1})/2
// Returns the new position and velocity; the caller stores x_n as the new x_{n-1}.
template <class T>
struct PressUpdate {
    T x, v;
};

template <class T>
EXASPH_HD PressUpdate<T> press_update(T x, T x_m1, T a, T dt, T dt_m1) {
    T v_half = (x - x_m1) / dt_m1;
    return {x + dt * v_half + a * dt * (dt + dt_m1) * T(0.5), v_half + a * (dt + T(0.5) * dt_m1)};
}

// physics.md §7, 2nd-order Adams-Bashforth for the internal energy:
//   u_{n+1} = u_n + du_n (dt_n + dt_n^2/(2 dt_{n-1})) - du_{n-1} dt_n^2 / (2 dt_{n-1})
template <class T>
EXASPH_HD T adams_bashforth_energy(T u, T du, T du_m1, T dt, T dt_m1) {
    T k = dt * dt / (T(2) * dt_m1);
    return u + du * (dt + k) - du_m1 * k;
}

} // namespace exasph
