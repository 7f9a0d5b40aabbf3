#pragma once
#include <cmath>

#include "exasph/util/annotate.hpp"

namespace exasph {

enum class EosKind { ideal_gas, tait };

// Equation-of-state parameters (physics.md §4). Which EOS is configuration, not a class hierarchy.
struct EosParams {
    EosKind kind = EosKind::ideal_gas;
    double gamma = 5.0 / 3.0; // ideal gas
    double c0 = 3500.0;       // Tait: constant sound speed
};

template <class T>
struct EosResult {
    T p;
    T c;
};

// Ideal gas: P = (gamma - 1) rho u, c = sqrt(gamma P / rho).
template <class T>
EXASPH_HD EosResult<T> ideal_gas_eos(T rho, T u, T gamma) {
    T p = (gamma - T(1)) * rho * u;
    return {p, std::sqrt(gamma * p / rho)};
}

// Weakly compressible Tait EOS: P = rho0 c0^2 / 7 ((rho/rho0)^7 - 1) + P0, c = c0.
template <class T>
EXASPH_HD EosResult<T> tait_eos(T rho, T rho0, T p0, T c0) {
    T s = rho / rho0;
    T s2 = s * s;
    T s7 = s2 * s2 * s2 * s;
    return {rho0 * c0 * c0 / T(7) * (s7 - T(1)) + p0, c0};
}

} // namespace exasph
