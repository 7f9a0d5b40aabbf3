#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include "exasph/domain/collectives.hpp"
#include "exasph/exact/exact_density.hpp"
#include "exasph/particles/particle_set.hpp"
#include "exasph/particles/particle_view.hpp"
#include "exasph/sph/block_step.hpp"
#include "exasph/sph/diagnostics_kern.hpp"

namespace exasph {

// The work of a step: the particles with forces (all with global steps, the active ones with
// block time steps) and the pair terms of one neighbour pass over them; with block steps also
// the shortest rung in use and the active particles of each rung; the compute seconds of the
// step (wall time outside MPI waits: sum and maximum over ranks). Reduced with the diagnostics.
struct StepWork {
    static constexpr std::size_t kElements = 3 + kMaxRung + 1;
    double active = 0, pairs = 0, rung_max = 0, compute_sum = 0, compute_max = 0;
    std::array<double, kMaxRung + 1> by_rung{};

    void pack(SumMax* e) const {
        e[0] = {active, rung_max};
        e[1].sum = pairs;
        e[2] = {compute_sum, compute_max};
        for (int k = 0; k <= kMaxRung; ++k) e[3 + k].sum = by_rung[std::size_t(k)];
    }
    void unpack(const SumMax* e) {
        active = e[0].sum, rung_max = e[0].max, pairs = e[1].sum;
        compute_sum = e[2].sum, compute_max = e[2].max;
        for (int k = 0; k <= kMaxRung; ++k) by_rung[std::size_t(k)] = e[3 + k].sum;
    }
    // The most loaded rank's compute seconds over the mean (1 when nothing was timed).
    double compute_imbalance(int nranks) const {
        return compute_sum > 0 ? compute_max * nranks / compute_sum : 1.0;
    }
};

// Global conserved quantities, neighbour and decomposition statistics of one step (physics.md §10).
struct Diagnostics {
    std::int64_t step = 0;
    double time = 0, dt = 0;
    std::uint64_t n = 0;
    int nranks = 1;
    double ekin = 0, eint = 0, epot = 0, etot = 0;
    std::array<double, 3> momentum{};
    std::array<double, 3> angular_momentum{}; // about the origin
    double nc_min = 0, nc_mean = 0, nc_max = 0;
    double halo_ratio_mean = 0, halo_ratio_max = 0; // halos / owned over ranks
    double rho_max = 0;                             // largest particle density
    double l1_rho = -1; // mean |rho - rho_exact| (when the case has an exact solution, else -1)
    // Scales for the conservation watchdog: total mass, sum_a m_a (|v_a . a_a| + |du_a|) (the
    // gross rate at which energy moves between forms), sum_a m_a (|v_a| + c_a) (momentum and the
    // scale of the pressure forces' impulses) and sum_a m_a |a_a|.
    double mass = 0, power_abs = 0, momentum_abs = 0, force_abs = 0;
    // With gravity: sum_a m_a |zeta_a dh_a|, the potential energy that this step's change of h
    // (and with it of the softening) moves; the next step's E_pot shows it (energy_budget()).
    double soft_abs = 0;
    // Driven turbulence: sum_a m_a v_a . a_stir,a (the stirring's power) and the energy it has
    // put in since the start of the run (etot - e_stir is conserved).
    double stir_power = 0, e_stir = 0;
    StepWork work;
};

// Layout of the diagnostics reduction: SumMax elements 0..18 (local_diagnostics), then six for
// the extent of the positions (which gives next step's box without another collective).
inline constexpr std::size_t kDiagElements = 19;
inline constexpr std::size_t kDiagWithExtent = kDiagElements + 6;

// This rank's contribution over its owned particles [0, n_owned), reduced by the launcher L
// along its fixed tree (DiagnosticsKernel, sph/diagnostics_kern.hpp): the same bits for every
// launcher and thread count. Writes the kDiagElements elements below and, after them, the six
// of the positions' extent (domain/box_extent.hpp's layout).
// The density error needs rho and the positions it was computed at: after the update those
// are x_{n-1} (= x_n of the step), so `exact` is the solution at t - dt.
template <class L, class T>
void local_diagnostics(ParticleSet<T>& ps, std::size_t n_owned, std::size_t n_halo,
                       const ExactDensity::AtTime& exact, double ng0, SumMax* out) {
    const DiagnosticsRecord r = with_view(ps, [&](auto p) {
        using N = typename decltype(p)::narrow_type;
        return L::reduce_tree(n_owned, DiagnosticsKernel<T, N>{p, exact, ng0});
    });
    constexpr double kNone = -std::numeric_limits<double>::infinity();
    const DiagSum first[8] = {DiagSum::ekin, DiagSum::eint, DiagSum::px, DiagSum::py,
                              DiagSum::pz,   DiagSum::lx,   DiagSum::ly, DiagSum::lz};
    for (int k = 0; k < 8; ++k) out[k] = {r[first[k]], kNone};
    out[8] = {r[DiagSum::nc], r[DiagMax::nc]};
    out[9] = {double(n_owned), r[DiagMax::neg_nc]}; // the max of -nc: the least nc
    const double ratio = n_owned > 0 ? double(n_halo) / double(n_owned) : 0.0;
    out[10] = {ratio, ratio};
    out[11] = {r[DiagSum::l1_rho], r[DiagMax::rho]};
    out[12] = {r[DiagSum::epot], kNone};
    const DiagSum scales[6] = {DiagSum::mass,      DiagSum::power_abs,  DiagSum::momentum_abs,
                               DiagSum::force_abs, DiagSum::stir_power, DiagSum::soft_abs};
    for (int k = 0; k < 6; ++k) out[13 + k] = {r[scales[k]], kNone};
    const DiagMax hi[3] = {DiagMax::x, DiagMax::y, DiagMax::z};
    const DiagMax neg_lo[3] = {DiagMax::neg_x, DiagMax::neg_y, DiagMax::neg_z};
    for (int d = 0; d < 3; ++d) {
        out[kDiagElements + d] = {0.0, r[hi[d]]};
        out[kDiagElements + 3 + d] = {0.0, r[neg_lo[d]]};
    }
}

inline Diagnostics diagnostics_from(const SumMax* e, int nranks) {
    Diagnostics d;
    d.ekin = e[0].sum;
    d.eint = e[1].sum;
    d.epot = e[12].sum;
    d.mass = e[13].sum;
    d.power_abs = e[14].sum;
    d.momentum_abs = e[15].sum;
    d.force_abs = e[16].sum;
    d.stir_power = e[17].sum;
    d.soft_abs = e[18].sum;
    d.etot = d.ekin + d.eint + d.epot;
    d.momentum = {e[2].sum, e[3].sum, e[4].sum};
    d.angular_momentum = {e[5].sum, e[6].sum, e[7].sum};
    d.n = std::uint64_t(e[9].sum);
    d.nc_mean = d.n > 0 ? e[8].sum / double(d.n) : 0.0;
    d.nc_max = e[8].max;
    d.nc_min = e[9].min();
    d.nranks = nranks;
    d.halo_ratio_mean = e[10].sum / nranks;
    d.halo_ratio_max = e[10].max;
    d.rho_max = e[11].max;
    return d;
}

} // namespace exasph
