// The limited midpoint reconstruction of the artificial viscosity (--av-limiter): the IAD
// velocity gradient (stored as its strain rate) is exact for a linear flow, a linear flow then
// has no approach left to dissipate, and disagreeing slopes (a shock) or close pairs keep the
// full viscosity.
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "exasph/kernel/sinc_kernel.hpp"
#include "exasph/sph/passes.hpp"
#include "kernels.hpp"
#include "neighbour_setup.hpp"
#include "random_particles.hpp"

using namespace exasph;

namespace {
const double kG[9] = {-0.7, 0.2, 0.1, 0.3, -0.4, -0.25, 0.05, 0.15, -0.9};
// Its strain rate (G + G^T) / 2: S_11, S_12, S_13, S_22, S_23, S_33.
const double kS[6] = {kG[0], 0.5 * (kG[1] + kG[3]), 0.5 * (kG[2] + kG[6]),
                      kG[4], 0.5 * (kG[5] + kG[7]), kG[8]};

// The largest |S - S_exact| away from the periodic seam of a linear flow on a perturbed lattice,
// the strain rate stored in single (default) or double precision; `checked` particles.
double worst_strain_error(bool single, std::size_t& checked) {
    const int side = 14;
    Box<double> box;
    auto ps = testref::periodic_lattice(side, 100, box);
    ps.set_narrow_single(single);
    std::mt19937_64 rng(11);
    testref::perturb_positions(ps, box, 0.3, rng);
    const double c = 0.5 * side;
    for (std::size_t i = 0; i < ps.size(); ++i) {
        double d[3] = {ps[Field::x][i] - c, ps[Field::y][i] - c, ps[Field::z][i] - c};
        double* v[3] = {&ps[Field::vx][i], &ps[Field::vy][i], &ps[Field::vz][i]};
        for (int r = 0; r < 3; ++r)
            *v[r] = kG[3 * r] * d[0] + kG[3 * r + 1] * d[1] + kG[3 * r + 2] * d[2];
    }
    NeighbourLists<double> nl;
    testref::sort_and_find_neighbours(ps, box, NeighbourCriterion::symmetric, nl);
    const auto& k = testref::sinc6();
    compute_density(ps, nl, box, k.view());
    compute_iad(ps, nl, box, k.view(), true);
    // Away from the periodic seam, where the linear field jumps, every particle sees it exactly.
    double worst = 0;
    checked = 0;
    for (std::size_t i = 0; i < ps.size(); ++i) {
        bool inside = true;
        for (Field f : {Field::x, Field::y, Field::z})
            inside = inside && ps[f][i] > 4 && ps[f][i] < side - 4;
        if (!inside) continue;
        ++checked;
        for (int e = 0; e < 6; ++e) {
            const double s = single ? double(ps.narrow_as<float>(strain_rate_field(e))[i])
                                    : ps.narrow_as<double>(strain_rate_field(e))[i];
            worst = std::max(worst, std::abs(s - kS[e]));
        }
    }
    return worst;
}
} // namespace

TEST(AvLimiter, IadVelocityGradientIsExactForALinearFlow) {
    std::size_t checked = 0;
    const double exact = worst_strain_error(false, checked); // --double-precision storage
    std::printf("%zu particles: max |S - S_exact| %.3e (stored in double)\n", checked, exact);
    EXPECT_GT(checked, 100u);
    EXPECT_LT(exact, 1e-12);
    // Stored in float (the default), only the storage's rounding is added: |S| < 1.
    const double stored = worst_strain_error(true, checked);
    std::printf("%zu particles: max |S - S_exact| %.3e (stored in float)\n", checked, stored);
    EXPECT_LT(stored, 1e-7);
}

TEST(AvLimiter, LinearFlowLeavesNoApproach) {
    // v_ab = v_a - v_b = -G d for d = x_b - x_a: the pair approaches, but its reconstructed
    // midpoint velocities agree.
    const double d[3] = {0.3, -0.2, 0.5};
    double vab[3];
    for (int r = 0; r < 3; ++r)
        vab[r] = -(kG[3 * r] * d[0] + kG[3 * r + 1] * d[1] + kG[3 * r + 2] * d[2]);
    const double raw = -(vab[0] * d[0] + vab[1] * d[1] + vab[2] * d[2]);
    ASSERT_LT(raw, 0);
    double rec = reconstructed_approach(raw, d[0], d[1], d[2], kS, kS, 1.0, 0.7);
    EXPECT_LT(std::abs(rec), 1e-15);
}

TEST(AvLimiter, DisagreeingSlopesOrClosePairsKeepTheFullApproach) {
    const double d[3] = {0.3, -0.2, 0.5};
    const double vab[3] = {-1.0, 0.4, -0.8};
    const double raw = -(vab[0] * d[0] + vab[1] * d[1] + vab[2] * d[2]);
    double expanding[6];
    for (int e = 0; e < 6; ++e) expanding[e] = -kS[e]; // d.S.d of opposite sign: a shock
    EXPECT_EQ(reconstructed_approach(raw, d[0], d[1], d[2], kS, expanding, 1.0, 0.7), raw);
    // Same slopes, but the pair is far closer than the mean spacing: the reconstruction fades.
    double close = reconstructed_approach(raw, d[0], d[1], d[2], kS, kS, 0.0, 0.7);
    EXPECT_NEAR(close, raw, 1e-4 * std::abs(raw));
}

namespace {
// Runs one momentum-energy instantiation over every particle and returns a and du/dt per
// particle (ax, ay, az, du interleaved).
template <PairTerms kTerms>
std::vector<double> momentum_energy_with(ParticleSet<double>& ps, const NeighbourLists<double>& nl,
                                         const Box<double>& box, const Dissipation<double>& diss) {
    const auto& k = testref::sinc6();
    with_view(ps, [&](auto p) {
        using N = typename decltype(p)::narrow_type;
        OmpLauncher::for_each_neighbourhood(
            nl, MomentumEnergyKernel<double, kTerms, true, true, N>{p, box, k.view(), diss, 0.2});
    });
    std::vector<double> out;
    for (std::size_t i = 0; i < ps.size(); ++i)
        for (Field f : {Field::ax, Field::ay, Field::az, Field::du}) out.push_back(ps[f][i]);
    return out;
}
} // namespace

// The ve, pe and sh schemes run the branch-free `limited` loop (every pair computes the
// reconstruction and the conductivity, which vanish where they do not apply; exp_nonpositive
// for the fade), which vectorises; the general `any` loop takes branches. Both must give the
// same forces to round-off, with and without the conductivity, on a flow with approaching,
// receding, shocked and close pairs.
TEST(AvLimiter, TheVectorisedLoopEqualsTheGeneralOne) {
    Box<double> box;
    auto ps = testref::periodic_lattice(12, 100, box);
    std::mt19937_64 rng(5);
    testref::perturb_positions(ps, box, 0.35, rng);
    std::uniform_real_distribution<double> vel(-1, 1), u(0.5, 1.5), alpha(0.2, 1.5);
    ps.enable(Field::xm);
    ps.enable(Field::kx);
    ps.enable(Field::alpha);
    ps.enable(Field::divv);
    for (std::size_t i = 0; i < ps.size(); ++i) {
        for (Field f : {Field::vx, Field::vy, Field::vz}) ps[f][i] = vel(rng);
        ps[Field::u][i] = u(rng);
        ps[Field::alpha][i] = alpha(rng);
        ps[Field::xm][i] = std::pow(ps[Field::m][i], 0.7);
    }
    NeighbourLists<double> nl;
    testref::sort_and_find_neighbours(ps, box, NeighbourCriterion::symmetric, nl);
    const auto& k = testref::sinc6();
    compute_density(ps, nl, box, k.view());
    compute_iad(ps, nl, box, k.view(), true);
    for (double alpha_u : {1.0, 0.0}) {
        auto diss = Dissipation<double>::of(1.0, alpha_u, true, 100);
        ASSERT_EQ(diss.terms(), PairTerms::limited);
        const auto limited = momentum_energy_with<PairTerms::limited>(ps, nl, box, diss);
        const auto general = momentum_energy_with<PairTerms::any>(ps, nl, box, diss);
        double scale = 0, worst = 0;
        for (double g : general) scale = std::max(scale, std::abs(g));
        for (std::size_t i = 0; i < general.size(); ++i)
            worst = std::max(worst, std::abs(limited[i] - general[i]));
        std::printf("conductivity %.0f: max |limited - general| %.3e of %.3e\n", alpha_u, worst,
                    scale);
        EXPECT_GT(scale, 1.0);
        EXPECT_LT(worst, 1e-12 * scale);
    }
}
