// Issue 6, acceptance 4 and 5: the Evrard collapse (physics.md §9.4) from a glass, -n 25 (8.2k
// particles), to t = 1.2 with self-gravity: initial potential energy within 2 % of
// -(2/3) G M^2 / R, total energy conserved within 2 % of |E_pot(0)|, kinetic energy peaking near
// t = 1 and falling after the bounce.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "exasph/cases/evrard.hpp"
#include "exasph/run/setup.hpp"
#include "exasph/sim/simulation.hpp"

using namespace exasph;

TEST(Evrard, N25GlassConservesEnergyAndBounces) {
    Config cfg;
    cfg.init = "evrard";
    cfg.side = 25;
    const double t_end = 1.2;
    Simulation<double> sim(cfg, make_case(cfg));
    const auto d0 = sim.diagnostics();
    const double epot_exact = evrard_potential_energy(EvrardParams{});
    std::printf(
        "Evrard -n 25: %llu particles, E_pot(0) %.5f (exact %.5f, %.2f %%), E_tot(0) %.5f\n",
        (unsigned long long)d0.n, d0.epot, epot_exact,
        100 * std::abs(d0.epot - epot_exact) / std::abs(epot_exact), d0.etot);
    EXPECT_GE(d0.n, 8000u);
    EXPECT_NEAR(d0.epot, epot_exact, 0.02 * std::abs(epot_exact));

    sim.set_end_time(t_end);
    double worst_drift = 0, ekin_max = 0, t_ekin_max = 0, epot_min = 0;
    while (sim.time() < t_end * (1 - 1e-12)) {
        sim.step();
        const auto& d = sim.diagnostics();
        worst_drift = std::max(worst_drift, std::abs(d.etot - d0.etot));
        if (d.ekin > ekin_max) ekin_max = d.ekin, t_ekin_max = d.time;
        epot_min = std::min(epot_min, d.epot);
    }
    const auto& d = sim.diagnostics();
    EXPECT_EQ(sim.safety().recoveries(), 0)
        << sim.safety().summary(); // a clean run raises no alarm
    std::printf("Evrard -n 25 to t = %.2f in %lld steps: worst |E_tot - E_tot(0)| %.2e (%.2f %% of "
                "|E_pot(0)|), E_kin max %.4f at t = %.3f, E_kin(t_end) %.4f, E_pot min %.4f\n",
                d.time, (long long)sim.step_count(), worst_drift,
                100 * worst_drift / std::abs(d0.epot), ekin_max, t_ekin_max, d.ekin, epot_min);
    EXPECT_LT(worst_drift, 0.01 * std::abs(d0.epot)); // issue 16: 1 % (softening correction)
    EXPECT_GT(t_ekin_max, 0.75);
    EXPECT_LT(t_ekin_max, 1.1);
    EXPECT_LT(d.ekin, 0.6 * ekin_max);  // falls after the bounce
    EXPECT_LT(epot_min, 2.5 * d0.epot); // deep collapse (about -2 in the literature)
}
