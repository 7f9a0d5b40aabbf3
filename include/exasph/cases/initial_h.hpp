#pragma once
#include <cmath>

namespace exasph {

// Smoothing length that puts ng0 neighbours within 2h at number density 1/spacing^3.
inline double initial_smoothing_length(double spacing, double ng0) {
    return 0.5 * spacing * std::cbrt(3.0 * ng0 / (4.0 * M_PI));
}

} // namespace exasph
