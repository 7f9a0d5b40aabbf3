#pragma once
#include "exasph/config/config.hpp"
#include "exasph/domain/domain.hpp"
#include "exasph/gravity/gravity_solver.hpp"
#include "exasph/sim/phases.hpp"
#include "exasph/sph/passes.hpp"
#include "exasph/util/timer.hpp"

namespace exasph {

// SPEC 3-6, the SPH passes of a step with their halo exchanges, each timed as its phase:
// density and EOS (Tait: rho0 from the first step; volume weights settled first), with gravity
// the softening's zeta, IAD, momentum and energy (its kernel passed through `wrap`), with
// gravity the softening's force. Returns the Courant limit of the pass (+infinity when `wrap`
// keeps each particle's own).
template <class L, class T, class Lists, class Wrap>
double hydro_forces(ParticleSet<T>& ps, const Lists& nl, const Box<T>& box, const KernelView<T>& k,
                    const EosParams& eos, const Config& cfg, Domain<T>& domain,
                    const GravitySolver<T>* gravity, PhaseTimer<kNumPhases>& timer, bool first,
                    Wrap wrap) {
    if (first && cfg.volume_elements)
        settle_volume_weights<L>(ps, nl, box, k, eos, domain.n_owned(), cfg.energy_weights,
                                 [&] { domain.exchange_halos(ps, kHaloSync); });
    compute_density<L>(ps, nl, box, k, eos, first && eos.kind == EosKind::tait);
    if (gravity) compute_softening_zeta<L>(ps, nl, gravity->softening().view(), gravity->G());
    timer.stop(kDensity);
    domain.exchange_halos(ps, kHaloDensity);
    timer.stop(kDensityHalos);
    const auto diss =
        Dissipation<T>::of(cfg.alpha, cfg.conductivity, cfg.av_limiter, cfg.ng0, cfg.tensile_stress,
                           cfg.torque_free, cfg.tensile_exponent, cfg.tensile_stress_positive);
    compute_iad<L>(ps, nl, box, k, cfg.av_limiter, cfg.torque_free, diss);
    domain.exchange_halos(ps, cfg.av_limiter ? kHaloIad | kHaloGrad : kHaloIad);
    timer.stop(kIad);
    const double courant = compute_momentum_energy<L>(ps, nl, box, k, diss, T(cfg.courant), wrap);
    if (gravity) add_softening_correction<L>(ps, nl, k); // SPEC 8's softening
    return courant;
}

} // namespace exasph
