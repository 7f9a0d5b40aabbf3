// Issue 63, acceptance 2: the Jeans instability in a periodic box (physics.md §9.10) with
// self-gravity through the Ewald sum. A plane wave of density contrast 0.01 along x grows for
// k < k_J at g = sqrt(4 pi G rho - c^2 k^2) and oscillates for k > k_J at
// w = sqrt(c^2 k^2 - 4 pi G rho); both measured within 5 %, from the particles' positions
// (delta(t) = (2/N) sum cos(k x_i), the mode's amplitude), at -n 24 with the default scheme.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "case_config.hpp"
#include "exasph/cases/jeans.hpp"
#include "exasph/run/setup.hpp"
#include "exasph/sim/simulation.hpp"

using namespace exasph;

namespace {

// The mode's amplitude: (2/N) sum_i cos(k x_i) (one rank).
double mode_amplitude(const Simulation<double>& sim, double k) {
    const auto& ps = sim.particles();
    double s = 0;
    for (std::size_t i = 0; i < sim.n_owned(); ++i) s += std::cos(k * ps[Field::x][i]);
    return 2 * s / double(sim.n_owned());
}

Config jeans_config(double ratio) {
    Config cfg = testref::case_config("jeans", 24);
    cfg.case_params = {"ratio=" + std::to_string(ratio)};
    return cfg;
}

} // namespace

// k = k_J / 2: delta = eps cosh(g t), run for three e-foldings (the case's end time).
TEST(Jeans, UnstableModeGrowsAtTheJeansRate) {
    JeansParams p;
    p.ratio = 0.5;
    const JeansTheory th(p);
    const Config cfg = jeans_config(p.ratio);
    Simulation<double> sim(cfg, make_case(cfg));
    const double d0 = mode_amplitude(sim, th.k), t_end = 3 / th.rate;
    sim.set_end_time(t_end);
    while (sim.time() < t_end * (1 - 1e-12)) sim.step();
    const double d1 = mode_amplitude(sim, th.k);
    const double rate = std::acosh(d1 / d0) / sim.time();
    std::printf("jeans ratio 0.5 -n 24: delta %.4e -> %.4e at t = %.4f (%lld steps): growth rate "
                "%.4f, theory %.4f (%+.2f %%)\n",
                d0, d1, sim.time(), (long long)sim.step_count(), rate, th.rate,
                100 * (rate / th.rate - 1));
    EXPECT_NEAR(rate, th.rate, 0.05 * th.rate);
    EXPECT_EQ(sim.safety().recoveries(), 0) << sim.safety().summary();
}

// k = 2 k_J: delta = eps cos(w t); the first zero of delta is at t = pi / (2 w).
TEST(Jeans, StableModeOscillatesAtTheJeansFrequency) {
    JeansParams p;
    p.ratio = 2;
    const JeansTheory th(p);
    const Config cfg = jeans_config(p.ratio);
    Simulation<double> sim(cfg, make_case(cfg));
    double t_prev = 0, d_prev = mode_amplitude(sim, th.k), zero = -1;
    const double d0 = d_prev;
    while (zero < 0 && sim.time() < 2 * M_PI / th.rate) {
        sim.step();
        const double d = mode_amplitude(sim, th.k);
        if (d <= 0) zero = t_prev + (sim.time() - t_prev) * d_prev / (d_prev - d);
        t_prev = sim.time(), d_prev = d;
    }
    ASSERT_GT(zero, 0) << "delta never crossed zero";
    const double w = M_PI / (2 * zero);
    std::printf("jeans ratio 2 -n 24: delta(0) %.4e, first zero at t = %.4f (%lld steps): "
                "frequency %.4f, theory %.4f (%+.2f %%)\n",
                d0, zero, (long long)sim.step_count(), w, th.rate, 100 * (w / th.rate - 1));
    EXPECT_NEAR(w, th.rate, 0.05 * th.rate);
    EXPECT_EQ(sim.safety().recoveries(), 0) << sim.safety().summary();
}
