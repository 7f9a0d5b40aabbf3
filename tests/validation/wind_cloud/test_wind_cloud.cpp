// Issue 16, acceptance 6: the wind-cloud test with the default scheme (sh) and no physics option
// destroys the cloud: the surviving fraction (Agertz et al. 2007: cloud particles with
// rho >= 0.64 rho_cloud and u <= 0.9 u_wind) falls below 0.5 before 4 tau_KH, and below 0.1 by
// 4 tau_KH. The CTest's size: -n 12 with the cloud's radius doubled to 0.05 (5.2 cloud spacings
// across it, ~600 particles; the default 0.025 has 2.6 at -n 12). Measured: below 0.5 from
// 0.75 tau_KH, 0 from 3.25 tau_KH; std at the same size 0 from 3 tau_KH, and at -n 20 0.10 at
// 4 tau_KH against sh's 0.018 (docs/validation.md).
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "case_config.hpp"
#include "exasph/cases/wind_cloud.hpp"
#include "exasph/run/setup.hpp"
#include "exasph/sim/simulation.hpp"

using namespace exasph;

namespace {

// Cloud particles (ids from 4 side^3 on, make_wind_cloud) that are still dense and cold.
double surviving_fraction(const Simulation<double>& sim, const WindCloudParams& wp,
                          std::uint64_t first_cloud_id) {
    const auto& ps = sim.particles();
    double cloud = 0, alive = 0;
    for (std::size_t i = 0; i < sim.n_owned(); ++i) {
        if (ps.id[i] < first_cloud_id) continue;
        cloud += 1;
        alive +=
            ps.value(Field::rho, i) >= 0.64 * wp.contrast && ps[Field::u][i] <= 0.9 * wp.u_wind;
    }
    return alive / cloud;
}

} // namespace

TEST(WindCloud, N12DefaultSchemeDestroysTheCloud) {
    Config cfg = testref::case_config("wind-cloud", 12);
    ASSERT_EQ(cfg.scheme, Scheme::sh);
    cfg.case_params = {"radius=0.05"};
    Simulation<double> sim(cfg, make_case(cfg));
    WindCloudParams wp;
    wp.radius = 0.05;
    const double tau = wind_cloud_tau_kh(wp);
    const std::uint64_t first_cloud_id = 4 * 12 * 12 * 12;
    const auto d0 = sim.diagnostics();
    sim.step(); // the densities of t = 0: an intact cloud
    const double fraction0 = surviving_fraction(sim, wp, first_cloud_id);
    std::printf("wind-cloud -n 12, R = 0.05: t = 0, surviving fraction %.3f\n", fraction0);
    EXPECT_GE(fraction0, 0.8);
    double below_half_at = -1, fraction = 1;
    for (int k = 1; k <= 8; ++k) {
        const double t = 0.5 * k * tau;
        sim.set_end_time(t);
        while (sim.time() < t * (1 - 1e-12)) sim.step();
        fraction = surviving_fraction(sim, wp, first_cloud_id);
        if (fraction < 0.5 && below_half_at < 0) below_half_at = 0.5 * k;
        std::printf("wind-cloud -n 12, R = 0.05: t = %.1f tau_KH, surviving fraction %.3f\n",
                    0.5 * k, fraction);
    }
    const auto d = sim.diagnostics();
    std::printf("energy drift %.2e\n", std::abs(d.etot - d0.etot) / std::abs(d0.etot));
    EXPECT_EQ(sim.safety().recoveries(), 0) << sim.safety().summary();
    EXPECT_GT(below_half_at, 0.0);
    EXPECT_LT(below_half_at, 4.0);
    EXPECT_LE(fraction, 0.1);
    EXPECT_LE(std::abs(d.etot - d0.etot), 1e-3 * std::abs(d0.etot));
}
