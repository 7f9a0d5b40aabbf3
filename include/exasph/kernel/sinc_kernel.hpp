#pragma once
#include <cmath>

#include "exasph/kernel/kernel_table.hpp"

namespace exasph {

// Sinc kernels (physics.md §1): f(v) = S_n(pi v / 2), S_n(x) = (sin x / x)^n, support v < 2.
namespace sinc_detail {
inline double sinc(double x) {
    return x < 1e-4 ? 1.0 - x * x / 6.0 : std::sin(x) / x;
}
// d/dx (sin x / x); the series avoids cancellation near 0.
inline double sinc_derivative(double x) {
    return x < 1e-3 ? -x / 3.0 + x * x * x / 30.0 : (x * std::cos(x) - std::sin(x)) / (x * x);
}
inline double shape(double v, double n) {
    double s = sinc(0.5 * M_PI * v);
    return s > 0 ? std::pow(s, n) : 0.0;
}
inline double shape_derivative(double v, double n) {
    double x = 0.5 * M_PI * v;
    double s = sinc(x);
    if (s <= 0) return 0.0;
    return n * std::pow(s, n - 1) * sinc_derivative(x) * 0.5 * M_PI;
}
} // namespace sinc_detail

inline constexpr double kSincExponentMin = 3.0;
inline constexpr double kSincExponentMax = 12.0;

inline KernelShape sinc_kernel(double n) {
    return {sinc_detail::shape, sinc_detail::shape_derivative, n};
}

// SPHYNX fit of the normalisation (physics.md §1), good to ~1e-5; kept to cross-check the
// quadrature.
inline double sinc_normalisation_fit(double n) {
    return 2.7012593e-2 + 2.0410827e-2 * std::sqrt(n) + 3.7451957e-3 * n +
           4.7013839e-2 * n * std::sqrt(n);
}

} // namespace exasph
