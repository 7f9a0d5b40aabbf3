#pragma once
#include <algorithm>
#include <limits>
#include <type_traits>

#include "exasph/config/config.hpp"
#include "exasph/domain/domain.hpp"
#include "exasph/gravity/gravity_solver.hpp"
#include "exasph/sim/phases.hpp"
#include "exasph/sph/passes.hpp"
#include "exasph/tree/neighbour_groups.hpp"

namespace exasph {

// Whether launcher L runs a pass over some groups of the lists (NeighbourGroups).
template <class L>
constexpr bool splits_groups() {
    if constexpr (requires { L::kSplitsGroups; })
        return L::kSplitsGroups;
    else
        return false;
}

// What the passes of physics.md §3-6 read besides the particles and the lists: the box, the
// kernel, the EOS, the run's configuration, self-gravity (or null: none) and whether this is
// the run's first step. Holds references: lives within the step that made it.
template <class T>
struct HydroInputs {
    const Box<T>& box;
    const KernelView<T>& k;
    const EosParams& eos;
    const Config& cfg;
    const GravitySolver<T>* gravity;
    bool first;

    Dissipation<T> dissipation() const {
        return Dissipation<T>::of(cfg.alpha, cfg.conductivity, cfg.av_limiter, cfg.ng0,
                                  cfg.tensile_stress, cfg.torque_free, cfg.tensile_exponent,
                                  cfg.tensile_stress_positive);
    }
    std::uint8_t iad_halos() const { return cfg.av_limiter ? kHaloIad | kHaloGrad : kHaloIad; }

    // physics.md §3-4 and, with gravity, the softening's zeta, over the lists or a part of them.
    template <class L, class Part>
    void density(ParticleSet<T>& ps, const Part& nl) const {
        compute_density<L>(ps, nl, box, k, eos, first && eos.kind == EosKind::tait);
        if (gravity) compute_softening_zeta<L>(ps, nl, gravity->softening().view(), gravity->G());
    }
    template <class L, class Part>
    void iad(ParticleSet<T>& ps, const Part& nl, const Dissipation<T>& diss) const {
        compute_iad<L>(ps, nl, box, k, cfg.av_limiter, cfg.torque_free, diss);
    }
    template <class L, class Part, class Wrap>
    double momentum_energy(ParticleSet<T>& ps, const Part& nl, const Dissipation<T>& diss,
                           Wrap wrap) const {
        return compute_momentum_energy<L>(ps, nl, box, k, diss, T(cfg.courant), wrap);
    }
};

// One exchange after each pass: density (+ EOS, zeta), its halos, IAD and its halos, momentum and
// energy.
template <class L, class T, class Lists, class EndPhase, class Wrap>
double hydro_passes_in_turn(ParticleSet<T>& ps, const Lists& nl, const HydroInputs<T>& in,
                            Domain<T>& domain, EndPhase end_phase, Wrap wrap) {
    in.template density<L>(ps, nl);
    end_phase(kDensity);
    domain.exchange_halos(ps, kHaloDensity);
    end_phase(kDensityHalos);
    const auto diss = in.dissipation();
    in.template iad<L>(ps, nl, diss);
    domain.exchange_halos(ps, in.iad_halos());
    end_phase(kIad);
    return in.template momentum_energy<L>(ps, nl, diss, wrap);
}

// Runs `pass` over `part` in pieces, letting MPI move the exchange in flight between them.
template <class T, class Pass>
double while_in_flight(const NeighbourGroups<T>& part, Domain<T>& domain, PostedHalos& x,
                       Pass pass) {
    constexpr std::size_t kPieces = 16;
    double least = std::numeric_limits<double>::infinity();
    for (std::size_t c = 0; c < kPieces; ++c) {
        least = std::min(least, double(pass(part.part(c, kPieces))));
        domain.progress_halos(x);
    }
    return least;
}

// The same with each exchange in flight behind work that does not need it (issue 23): the
// density of the particles other ranks receive comes first, its exchange is posted, the other
// densities and the IAD of the groups with only owned neighbours follow; then the IAD of the
// groups that read halos, its exchange posted, the momentum-energy of the owned-only groups.
template <class L, class T, class EndPhase, class Wrap>
double hydro_passes_overlapped(ParticleSet<T>& ps, const NeighbourLists<T>& nl,
                               const HydroInputs<T>& in, Domain<T>& domain, EndPhase end_phase,
                               Wrap wrap) {
    const auto parts = split_for_halo_overlap(nl, domain.sent_flags());
    const auto diss = in.dissipation();
    auto density = [&](const NeighbourGroups<T>& p) { return in.template density<L>(ps, p), 0; };
    auto iad = [&](const NeighbourGroups<T>& p) { return in.template iad<L>(ps, p, diss), 0; };
    auto momentum_energy = [&](const NeighbourGroups<T>& p) {
        return in.template momentum_energy<L>(ps, p, diss, wrap);
    };
    density(parts.sending);
    PostedHalos density_halos = domain.post_halos(ps, kHaloDensity);
    while_in_flight(parts.not_sending, domain, density_halos, density);
    end_phase(kDensity);
    while_in_flight(parts.owned_only, domain, density_halos, iad);
    end_phase(kIad);
    domain.finish_halos(ps, density_halos);
    end_phase(kDensityHalos);
    iad(parts.reading_halos);
    PostedHalos iad_halos = domain.post_halos(ps, in.iad_halos());
    end_phase(kIad);
    const double owned = while_in_flight(parts.owned_only, domain, iad_halos, momentum_energy);
    end_phase(kMomentumEnergy);
    domain.finish_halos(ps, iad_halos);
    end_phase(kIad);
    return std::min(owned, momentum_energy(parts.reading_halos));
}

// physics.md §3-6, the SPH passes of a step with their halo exchanges, each timed as its phase:
// density and EOS (Tait: rho0 from the first step; volume weights settled first), with gravity
// the softening's zeta, IAD, momentum and energy (its kernel passed through `wrap`), with
// gravity the softening's force. Returns the Courant limit of the pass (+infinity when `wrap`
// keeps each particle's own). On several ranks with a launcher that splits passes the halo
// exchanges overlap the work (unless --no-halo-overlap).
template <class L, class T, class Lists, class EndPhase, class Wrap>
double hydro_forces(ParticleSet<T>& ps, const Lists& nl, const HydroInputs<T>& in,
                    Domain<T>& domain, EndPhase end_phase, Wrap wrap) {
    if (in.first && in.cfg.volume_elements)
        settle_volume_weights<L>(ps, nl, in.box, in.k, in.eos, domain.n_owned(),
                                 in.cfg.energy_weights,
                                 [&] { domain.exchange_halos(ps, kHaloSync); });
    double courant = 0;
    if constexpr (splits_groups<L>() && std::is_same_v<Lists, NeighbourLists<T>>) {
        courant = domain.nranks() > 1 && !in.cfg.no_halo_overlap
                      ? hydro_passes_overlapped<L>(ps, nl, in, domain, end_phase, wrap)
                      : hydro_passes_in_turn<L>(ps, nl, in, domain, end_phase, wrap);
    } else {
        courant = hydro_passes_in_turn<L>(ps, nl, in, domain, end_phase, wrap);
    }
    if (in.gravity) add_softening_correction<L>(ps, nl, in.k); // physics.md §8's softening
    return courant;
}

// The step's neighbour lists (of the owned particles, or of the `active` ones) over the domain's
// local and halo trees.
template <class Lists, class D, class T>
auto build_neighbour_lists(Lists& lists, const D& domain, const ParticleSet<T>& ps,
                           const Box<T>& box, const std::uint8_t* active) {
    SearchView<T> sv{ps.data(Field::x), ps.data(Field::y), ps.data(Field::z), ps.data(Field::h)};
    return lists.build(domain.local_tree(), &domain.halo_tree(), sv, box,
                       NeighbourCriterion::symmetric, std::uint32_t(domain.n_owned()), active);
}

} // namespace exasph
