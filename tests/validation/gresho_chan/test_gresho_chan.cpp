// Issue 16, acceptance 3: the Gresho-Chan vortex with the default scheme and no physics option
// keeps its azimuthal velocity profile: L1(v_phi) / v0 <= 0.05 at t = 1; energy and linear
// momentum conserved.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "case_config.hpp"
#include "exasph/cases/gresho_chan.hpp"
#include "exasph/run/setup.hpp"
#include "exasph/sim/simulation.hpp"

using namespace exasph;

namespace {

// Mean |v_phi - v_phi,exact(r)| / v0 over the particles within r < 0.5 of the vortex centre.
double l1_vphi(const Simulation<double>& sim, const GreshoChanParams& gp) {
    const auto& ps = sim.particles();
    double sum = 0, count = 0;
    for (std::size_t i = 0; i < sim.n_owned(); ++i) {
        const double x = ps[Field::x][i], y = ps[Field::y][i];
        const double r = std::sqrt(x * x + y * y);
        if (r >= 0.5 || r == 0) continue;
        const double vphi = (x * ps[Field::vy][i] - y * ps[Field::vx][i]) / r;
        sum += std::abs(vphi - gresho_vphi(gp, r));
        count += 1;
    }
    return sum / count / gp.speed;
}

} // namespace

TEST(GreshoChan, N40DefaultSchemeKeepsTheVortex) {
    const Config cfg = testref::case_config("gresho-chan", 40);
    Simulation<double> sim(cfg, make_case(cfg));
    const GreshoChanParams gp;
    const auto d0 = sim.diagnostics();
    for (const double t : {0.25, 0.5, 1.0}) {
        sim.set_end_time(t);
        while (sim.time() < t * (1 - 1e-12)) sim.step();
        const auto& d = sim.diagnostics();
        std::printf("Gresho-Chan -n 40 t = %.2f: L1(v_phi)/v0 %.4f, E_tot %.3e rel, L_z %.3e rel\n",
                    t, l1_vphi(sim, gp), std::abs(d.etot - d0.etot) / std::abs(d0.etot),
                    std::abs(d.angular_momentum[2] - d0.angular_momentum[2]) /
                        std::abs(d0.angular_momentum[2]));
    }
    EXPECT_EQ(sim.safety().recoveries(), 0) << sim.safety().summary();
    const auto& d = sim.diagnostics();
    EXPECT_LE(l1_vphi(sim, gp), 0.05);
    EXPECT_LE(std::abs(d.etot - d0.etot), 1e-3 * std::abs(d0.etot));
}
