// Issue 16, acceptance 4: the Kelvin-Helmholtz instability with the default scheme (sh) and no
// physics option grows: McNally et al. (2012)'s mode amplitude grows >= 10x between t = 0.25 and
// t = 2 at -n 24 (measured 16x; -n 48: 21x by t = 2.75, with billows at t = 3; the std and ve
// schemes: no growth at -n 32, docs/validation.md). Energy and momentum conserved.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "case_config.hpp"
#include "exasph/run/setup.hpp"
#include "exasph/sim/simulation.hpp"

using namespace exasph;

namespace {

// McNally et al. (2012), eqs. 4-7: the sin 4 pi x Fourier amplitude of v_y, weighted by
// exp(-4 pi d) with d the distance from the nearer interface (y = 0.25 or 0.75), per volume.
double mode_amplitude(const Simulation<double>& sim) {
    const auto& ps = sim.particles();
    double s = 0, c = 0, d = 0;
    for (std::size_t i = 0; i < sim.n_owned(); ++i) {
        const double x = ps[Field::x][i], y = ps[Field::y][i];
        const double w = std::exp(-4 * M_PI * std::abs((y < 0.5 ? y : 1 - y) - 0.25));
        const double vol = ps[Field::m][i] / ps.value(Field::rho, i);
        s += vol * ps[Field::vy][i] * std::sin(4 * M_PI * x) * w;
        c += vol * ps[Field::vy][i] * std::cos(4 * M_PI * x) * w;
        d += vol * w;
    }
    return 2 * std::hypot(s / d, c / d);
}

} // namespace

TEST(KelvinHelmholtz, N24DefaultSchemeGrowsTheMode) {
    const Config cfg = testref::case_config("kelvin-helmholtz", 24);
    ASSERT_EQ(cfg.scheme, Scheme::sh);
    Simulation<double> sim(cfg, make_case(cfg));
    const auto d0 = sim.diagnostics();
    double a_start = 0, a = 0;
    for (const double t : {0.25, 0.5, 0.75, 1.0, 1.25, 1.5, 1.75, 2.0}) {
        sim.set_end_time(t);
        while (sim.time() < t * (1 - 1e-12)) sim.step();
        a = mode_amplitude(sim);
        if (t == 0.25) a_start = a;
        std::printf("kelvin-helmholtz -n 24 t = %.2f: mode amplitude %.4f (%.1fx t = 0.25's)\n", t,
                    a, a / a_start);
    }
    const auto d = sim.diagnostics();
    const double dp = std::hypot(d.momentum[0] - d0.momentum[0], d.momentum[1] - d0.momentum[1]);
    std::printf("energy drift %.2e, momentum drift %.2e of sum m (|v| + c)\n",
                std::abs(d.etot - d0.etot) / std::abs(d0.etot), dp / d0.momentum_abs);
    EXPECT_EQ(sim.safety().recoveries(), 0) << sim.safety().summary();
    EXPECT_GE(a / a_start, 10.0);
    EXPECT_LE(std::abs(d.etot - d0.etot), 1e-3 * std::abs(d0.etot));
    EXPECT_LE(dp, 1e-10 * d0.momentum_abs);
}
