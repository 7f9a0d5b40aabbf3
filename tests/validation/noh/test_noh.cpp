// Noh -n 40 (33.5k particles, glass) to t = 0.6 with the default scheme and no physics option
// (issue 16, acceptance 1; issue 5, acceptance 3; the ve scheme's limited midpoint-reconstructed
// viscosity, volume elements and artificial conductivity): mean density of the particles in
// 0.05 < r < 0.15 within 20 % of 64, shock radius (where the radially binned density first falls
// below 32) within 10 % of t/3.
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "case_config.hpp"
#include "exasph/run/setup.hpp"
#include "exasph/sim/simulation.hpp"
#include "radial_profile.hpp"

using namespace exasph;

TEST(Noh, N40DefaultSchemeReachesThePostShockState) {
    const Config cfg = testref::case_config("noh", 40);
    const double t_end = 0.6;
    Simulation<double> sim(cfg, make_case(cfg));
    const double e0 = sim.diagnostics().etot;
    sim.set_end_time(t_end);
    while (sim.time() < t_end * (1 - 1e-12)) sim.step();
    EXPECT_EQ(sim.safety().recoveries(), 0) << sim.safety().summary();

    // Density at the positions it was computed at (x_{n-1} after the update), at time t - dt.
    const auto& ps = sim.particles();
    const double t_rho = sim.time() - sim.diagnostics().dt;
    const double width = 0.005;
    const auto prof = testref::radial_density(ps, sim.n_owned(), 0.4, 80);
    double shell_sum = 0, shell_count = 0;
    for (std::size_t i = 0; i < sim.n_owned(); ++i) {
        double x = ps[Field::x_m1][i], y = ps[Field::y_m1][i], z = ps[Field::z_m1][i];
        double r = std::sqrt(x * x + y * y + z * z);
        if (r > 0.05 && r < 0.15) shell_sum += ps.value(Field::rho, i), shell_count += 1;
    }
    ASSERT_GT(shell_count, 1000);
    const double shell = shell_sum / shell_count;
    // Outwards from the shell, the first bin whose mean is below 32, interpolated linearly
    // between bin centres.
    double r_shock = -1;
    for (int b = int(0.05 / width) + 1; b < prof.bins() && r_shock < 0; ++b) {
        ASSERT_GT(prof.count[b], 0);
        double rho_b = prof.mean(b), rho_in = prof.mean(b - 1);
        if (rho_b < 32) r_shock = width * (b - 0.5 + (rho_in - 32) / (rho_in - rho_b));
    }
    const double r_exact = t_rho / 3;
    const double energy_error = std::abs(sim.diagnostics().etot - e0) / std::abs(e0);
    std::printf("Noh -n 40 t = %.4f: shell mean rho %.2f (64), shock radius %.4f (%.4f, %+.1f %%), "
                "energy %.2e\n",
                t_rho, shell, r_shock, r_exact, 100 * (r_shock - r_exact) / r_exact, energy_error);
    EXPECT_GE(shell, 0.8 * 64);
    EXPECT_LE(shell, 1.2 * 64);
    EXPECT_GT(r_shock, 0);
    EXPECT_LE(std::abs(r_shock - r_exact), 0.1 * r_exact);
    EXPECT_LE(energy_error, 0.01); // physics.md §9.3: total energy conserved to ~1 %
}
