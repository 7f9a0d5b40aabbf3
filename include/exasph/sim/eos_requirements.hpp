#pragma once
#include <algorithm>
#include <cstddef>
#include <limits>

#include "exasph/config/choices.hpp"
#include "exasph/domain/collectives.hpp"
#include "exasph/particles/particle_set.hpp"
#include "exasph/sph/eos.hpp"
#include "exasph/util/error.hpp"

namespace exasph {

// What the equation of state and the volume weights need of the particles (all ranks; input
// errors on every rank): the Tait EOS its reference fields; --energy-weights, X = m u
// (sph/update_kern.hpp), an ideal gas whose every particle has u > 0, since rho = m k / X.
template <class T>
void require_eos_inputs(const ParticleSet<T>& ps, std::size_t n, const EosParams& eos,
                        bool energy_weights, Collectives& coll) {
    if (eos.kind == EosKind::tait && !(ps.enabled(Field::rho0) && ps.enabled(Field::p0)))
        throw input_error("the Tait EOS needs the reference fields rho0 and p0", true);
    if (!energy_weights) return;
    if (eos.kind != EosKind::ideal_gas)
        throw input_error("--energy-weights (X = m u) needs an ideal-gas equation of state", true);
    double u_min = std::numeric_limits<double>::max();
    for (std::size_t i = 0; i < n; ++i) u_min = std::min(u_min, double(ps[Field::u][i]));
    u_min = coll.allreduce_min(u_min);
    if (!(u_min > 0))
        throw input_error("--energy-weights (X = m u) needs u > 0 for every particle; the "
                          "smallest u is " +
                              format_number(u_min),
                          true);
}

} // namespace exasph
