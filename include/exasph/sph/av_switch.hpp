#pragma once
#include <cmath>

#include "exasph/util/annotate.hpp"

namespace exasph {

// Time-dependent artificial viscosity (Morris & Monaghan 1997, the "later switch" of physics.md
// §6):
//   d alpha/dt = -(alpha - alpha_min) / tau + max(-div v, 0) (alpha_max - alpha),
//   tau = h / (decay c).
// Compression raises alpha towards alpha_max within a few steps; elsewhere it decays to
// alpha_min over a few smoothing lengths' sound-crossing times. The decay term is integrated
// exactly (stable for any dt), the source explicitly; the result is clamped to the range.
template <class T>
EXASPH_HD T evolve_alpha(T alpha, T divv, T h, T c, T dt, T alpha_min, T alpha_max, T decay) {
    T relaxed = c > T(0) ? alpha_min + (alpha - alpha_min) * std::exp(-dt * decay * c / h) : alpha;
    T source = divv < T(0) ? -divv * (alpha_max - alpha) : T(0);
    T next = relaxed + dt * source;
    return next < alpha_min ? alpha_min : (next > alpha_max ? alpha_max : next);
}

} // namespace exasph
