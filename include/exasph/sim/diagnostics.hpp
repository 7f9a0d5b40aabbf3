#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include "exasph/domain/collectives.hpp"
#include "exasph/exact/exact_density.hpp"
#include "exasph/particles/particle_set.hpp"
#include "exasph/sph/block_step.hpp"
#include "exasph/sph/smoothing_length.hpp"
#include "exasph/util/block_sum.hpp"

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

// Layout of the diagnostics reduction: SumMax elements 0..18 below, then six for the extent of
// the positions (which gives next step's box without another collective).
inline constexpr std::size_t kDiagElements = 19;
inline constexpr std::size_t kDiagWithExtent = kDiagElements + 6;

// This rank's contribution over its owned particles [0, n_owned); sums are independent of the
// thread count (block_sum).
// The density error needs rho and the positions it was computed at: after the update those
// are x_{n-1} (= x_n of the step) at time t - dt.
template <class T>
void local_diagnostics(const ParticleSet<T>& ps, std::size_t n_owned, std::size_t n_halo,
                       const ExactDensity& exact, double t_rho, double ng0, SumMax* out) {
    const T *x = ps.data(Field::x), *y = ps.data(Field::y), *z = ps.data(Field::z);
    const T *vx = ps.data(Field::vx), *vy = ps.data(Field::vy), *vz = ps.data(Field::vz);
    const T *m = ps.data(Field::m), *u = ps.data(Field::u);
    // nc, c and rho in either storage (float, or double with --double-precision).
    auto nc = [&](std::size_t i) { return ps.value(Field::nc, i); };
    auto cs = [&](std::size_t i) { return ps.value(Field::c, i); };
    auto rho = [&](std::size_t i) { return ps.value(Field::rho, i); };
    const T* phi = ps.data(Field::phi);
    const T* stir = ps.enabled(Field::stir) ? ps.data(Field::stir) : nullptr;
    const T *ax = ps.data(Field::ax), *ay = ps.data(Field::ay), *az = ps.data(Field::az),
            *du = ps.data(Field::du);
    const T* gsoft = ps.enabled(Field::gsoft) ? ps.data(Field::gsoft) : nullptr;
    const T* kx = ps.enabled(Field::kx) ? ps.data(Field::kx) : nullptr;
    // physics.md §8's softening follows h: E_pot moves by m_a zeta_a dh_a. The density pass left
    // gsoft_a = zeta_a (-h_a / (3 k_a Omega_a)) and physics.md §2 made dh_a / h_a = g(nc_a) - 1
    // from this step's nc, so m_a |zeta_a dh_a| = 3 m_a k_a Omega_a |gsoft_a (g - 1)|, Omega_a ~ 1.
    auto softening_moved = [&](std::size_t i) {
        if (!gsoft) return 0.0;
        const double k = kx ? double(kx[i]) : rho(i);
        const double g = update_smoothing_length(1.0, nc(i), ng0);
        return 3 * double(m[i]) * k * std::abs(double(gsoft[i]) * (g - 1));
    };
    auto s = block_sum<16>(n_owned, [&](std::size_t i) -> std::array<double, 16> {
        const double mi = m[i];
        const double v2 = double(vx[i]) * vx[i] + double(vy[i]) * vy[i] + double(vz[i]) * vz[i];
        const double va = double(vx[i]) * ax[i] + double(vy[i]) * ay[i] + double(vz[i]) * az[i];
        const double a2 = double(ax[i]) * ax[i] + double(ay[i]) * ay[i] + double(az[i]) * az[i];
        return {0.5 * mi * v2,
                mi * u[i],
                mi * vx[i],
                mi * vy[i],
                mi * vz[i],
                mi * (double(y[i]) * vz[i] - double(z[i]) * vy[i]),
                mi * (double(z[i]) * vx[i] - double(x[i]) * vz[i]),
                mi * (double(x[i]) * vy[i] - double(y[i]) * vx[i]),
                nc(i),
                phi ? 0.5 * mi * phi[i] : 0.0, // each pair counted from both sides (physics.md §8)
                mi,
                mi * (std::abs(va) + std::abs(double(du[i]))),
                mi * (std::sqrt(v2) + cs(i)),
                mi * std::sqrt(a2),
                stir ? mi * stir[i] : 0.0,
                softening_moved(i)};
    });
    double nc_lo = std::numeric_limits<double>::infinity(), nc_hi = -nc_lo;
    for (std::size_t i = 0; i < n_owned; ++i) {
        nc_lo = std::min(nc_lo, nc(i));
        nc_hi = std::max(nc_hi, nc(i));
    }
    for (int k = 0; k < 8; ++k) out[k] = {s[k], -std::numeric_limits<double>::infinity()};
    out[8] = {s[8], nc_hi};
    out[9].sum = double(n_owned);
    out[9].set_min(nc_lo);
    double ratio = n_owned > 0 ? double(n_halo) / double(n_owned) : 0.0;
    out[10] = {ratio, ratio};
    const T *xp = ps.data(Field::x_m1), *yp = ps.data(Field::y_m1), *zp = ps.data(Field::z_m1);
    const auto exact_rho = exact.at(t_rho);
    double l1 = 0, rho_max = -std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < n_owned; ++i) {
        rho_max = std::max(rho_max, rho(i));
        if (exact.valid()) {
            double r =
                std::sqrt(double(xp[i]) * xp[i] + double(yp[i]) * yp[i] + double(zp[i]) * zp[i]);
            l1 += std::abs(rho(i) - exact_rho(r));
        }
    }
    out[11] = {l1, rho_max};
    out[12] = {s[9], -std::numeric_limits<double>::infinity()};
    for (int k = 0; k < 6; ++k) out[13 + k] = {s[10 + k], -std::numeric_limits<double>::infinity()};
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
