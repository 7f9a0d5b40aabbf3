// Issue 16, acceptance 2: the correction for softening that follows h
// (gravity/softening_correction.hpp). Its zeta is E_pot's derivative by h, and its force does
// the work that E_pot's change through h takes, with no net force.
#include <cmath>
#include <cstdio>
#include <random>

#include <gtest/gtest.h>

#include "exasph/gravity/gravity_kern.hpp"
#include "exasph/sph/passes.hpp"
#include "kernels.hpp"
#include "neighbour_setup.hpp"
#include "random_particles.hpp"

using namespace exasph;

namespace {

struct Patch {
    Box<double> box;
    ParticleSet<double> ps;
    NeighbourLists<double> nl;
    std::vector<double> dh_dk; // -h / (3 k Omega), as the density pass leaves it
};

// A disordered cube with free surfaces (gravity needs an open box), varied h, m and v.
Patch make_patch() {
    Patch s;
    s.ps = testref::periodic_lattice(12, 100, s.box);
    std::mt19937_64 rng(11);
    testref::perturb_positions(s.ps, s.box, 0.3, rng);
    s.box.periodic = {false, false, false};
    std::uniform_real_distribution<double> vel(-1, 1), hf(0.95, 1.25), mf(0.9, 1.1);
    for (std::size_t i = 0; i < s.ps.size(); ++i) {
        for (Field f : {Field::vx, Field::vy, Field::vz}) s.ps[f][i] = vel(rng);
        s.ps[Field::u][i] = 1;
        s.ps[Field::h][i] *= hf(rng);
        s.ps[Field::m][i] *= mf(rng);
    }
    s.ps.enable(Field::gsoft);
    testref::sort_and_find_neighbours(s.ps, s.box, NeighbourCriterion::symmetric, s.nl);
    compute_density(s.ps, s.nl, s.box, testref::sinc6().view());
    s.dh_dk.assign(s.ps[Field::gsoft].begin(), s.ps[Field::gsoft].end());
    return s;
}

// E_pot's pairs with particle c, with c's smoothing length hc (G = 1): the tree's own pair law.
double pair_energy(const ParticleSet<double>& ps, std::size_t c, double hc,
                   const SofteningView<double>& soft) {
    double e = 0;
    for (std::size_t b = 0; b < ps.size(); ++b) {
        if (b == c) continue;
        const GravityField g = pair_field(
            ps[Field::x][c] - ps[Field::x][b], ps[Field::y][c] - ps[Field::y][b],
            ps[Field::z][c] - ps[Field::z][b], ps[Field::m][b], 0.5 * (hc + ps[Field::h][b]), soft);
        e += ps[Field::m][c] * g.phi;
    }
    return e;
}

} // namespace

TEST(SofteningCorrection, ZetaIsThePotentialEnergysDerivativeByH) {
    Patch s = make_patch();
    const SofteningTable<double> table(testref::sinc6());
    compute_softening_zeta(s.ps, s.nl, table.view(), 1.0);
    double worst = 0;
    for (std::size_t c = 0; c < s.ps.size(); c += 97) {
        const double hc = s.ps[Field::h][c], d = 1e-4 * hc;
        const double de_dh = (pair_energy(s.ps, c, hc + d, table.view()) -
                              pair_energy(s.ps, c, hc - d, table.view())) /
                             (2 * d);
        const double zeta = s.ps[Field::gsoft][c] / s.dh_dk[c];
        worst = std::max(worst, std::abs(s.ps[Field::m][c] * zeta / de_dh - 1));
    }
    std::printf("m zeta against dE_pot/dh by differences: worst relative difference %.2e\n", worst);
    EXPECT_LT(worst, 1e-3);
}

TEST(SofteningCorrection, ForceDoesTheWorkOfHAndHasNoNetForce) {
    Patch s = make_patch();
    const SofteningTable<double> table(testref::sinc6());
    compute_softening_zeta(s.ps, s.nl, table.view(), 1.0);
    for (Field f : {Field::ax, Field::ay, Field::az}) std::fill(s.ps[f].begin(), s.ps[f].end(), 0);
    const auto k = testref::sinc6().view();
    add_softening_correction(s.ps, s.nl, k);
    const auto& p = s.ps;
    // dE_pot/dt through h: sum_a m_a zeta_a dh_a/dt = sum_ab m_a xi_a X_b v_ab . grad_a W_ab(h_a)
    double power_h = 0, power_f = 0, scale = 0, net[3] = {0, 0, 0}, net_scale = 0;
    for (std::size_t a = 0; a < p.size(); ++a) {
        const double ha = p[Field::h][a];
        for (std::size_t b = 0; b < p.size(); ++b) {
            const double r_ab[3] = {p[Field::x][a] - p[Field::x][b],
                                    p[Field::y][a] - p[Field::y][b],
                                    p[Field::z][a] - p[Field::z][b]};
            const double r = std::hypot(r_ab[0], r_ab[1], r_ab[2]);
            if (b == a || r >= 2 * ha) continue;
            const double g = k.derivative(r / ha) / (ha * ha * ha * ha * r);
            double vdot = 0;
            for (int d = 0; d < 3; ++d)
                vdot +=
                    (p[Field(int(Field::vx) + d)][a] - p[Field(int(Field::vx) + d)][b]) * r_ab[d];
            power_h += p[Field::m][a] * p[Field::gsoft][a] * p[Field::m][b] * vdot * g;
        }
        const double acc[3] = {p[Field::ax][a], p[Field::ay][a], p[Field::az][a]};
        for (int d = 0; d < 3; ++d) {
            power_f += p[Field::m][a] * p[Field(int(Field::vx) + d)][a] * acc[d];
            net[d] += p[Field::m][a] * acc[d];
        }
        scale += std::abs(p[Field::m][a] * (p[Field::vx][a] * acc[0] + p[Field::vy][a] * acc[1] +
                                            p[Field::vz][a] * acc[2]));
        net_scale += p[Field::m][a] * std::hypot(acc[0], acc[1], acc[2]);
    }
    const double net_ratio = std::hypot(net[0], net[1], net[2]) / net_scale;
    std::printf("work of the correction %.6e, E_pot's change through h %.6e (sum |m v.a| %.3e); "
                "net force %.2e of sum m|a|\n",
                power_f, power_h, scale, net_ratio);
    EXPECT_GT(std::abs(power_h), 1e-3 * scale); // the test is not of zeros
    EXPECT_LT(std::abs(power_f + power_h), 1e-10 * scale);
    EXPECT_LT(net_ratio, 1e-12);
}
