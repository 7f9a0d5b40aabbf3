// Acceptance 6 (issue 2): rotating square patch, -n 30 to t = 0.02 s (physics.md §9.1); issue 17:
// the paper's validation time t = 0.5 s with the case's default scheme (wc).
#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>
#include <omp.h>

#include "case_config.hpp"
#include "exasph/run/setup.hpp"
#include "exasph/sim/simulation.hpp"

using namespace exasph;

namespace {

struct Outcome {
    double lz, etot, max_vx, max_vz;
    bool finite;
};

Outcome run_square_patch(int threads) {
    omp_set_num_threads(threads);
    Config cfg;
    cfg.side = 30;
    Simulation<double> sim(cfg, make_case(cfg));
    sim.set_end_time(0.02);
    while (sim.time() < 0.02) sim.step();
    EXPECT_EQ(sim.safety().recoveries(), 0)
        << sim.safety().summary(); // a clean run raises no alarm
    const auto& ps = sim.particles();
    Outcome o{sim.diagnostics().angular_momentum[2], sim.diagnostics().etot, 0, 0, true};
    for (std::size_t i = 0; i < ps.size(); ++i) {
        o.max_vx = std::max(o.max_vx, std::abs(ps[Field::vx][i]));
        o.max_vz = std::max(o.max_vz, std::abs(ps[Field::vz][i]));
        for (Field f : {Field::x, Field::vx, Field::rho, Field::u})
            o.finite = o.finite && std::isfinite(ps.value(f, i));
    }
    return o;
}

} // namespace

TEST(SquarePatch, AngularMomentumVerticalVelocityAndThreadIndependence) {
    Outcome two = run_square_patch(2);
    std::printf("L_z %.6e, E_tot %.9e, max|vz|/max|vx| %.3e\n", two.lz, two.etot,
                two.max_vz / two.max_vx);
    EXPECT_TRUE(two.finite);
    // Clockwise rotation (v_x = w y, v_y = -w x): L_z is negative; physics.md §9.1 quotes |L_z|.
    EXPECT_NEAR(std::abs(two.lz), 8.33e9, 0.005 * 8.33e9);
    EXPECT_LT(two.max_vz, 1e-3 * two.max_vx);

    Outcome one = run_square_patch(1);
    EXPECT_NEAR(one.lz, two.lz, 1e-10 * std::abs(two.lz));
    EXPECT_NEAR(one.etot, two.etot, 1e-10 * std::abs(two.etot));
}

namespace {

// The closest pair of the owned particles (periodic in z with period `period`), brute force.
double closest_pair(const ParticleSet<double>& ps, double period) {
    double best = std::numeric_limits<double>::infinity();
    const std::size_t n = ps.size();
#pragma omp parallel for reduction(min : best) schedule(dynamic, 64)
    for (std::size_t a = 0; a < n; ++a)
        for (std::size_t b = a + 1; b < n; ++b) {
            const double dx = ps[Field::x][a] - ps[Field::x][b];
            const double dy = ps[Field::y][a] - ps[Field::y][b];
            double dz = std::abs(ps[Field::z][a] - ps[Field::z][b]);
            dz = std::min(dz, period - dz);
            best = std::min(best, dx * dx + dy * dy + dz * dz);
        }
    return std::sqrt(best);
}

double median(std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
}

} // namespace

// Issue 17: -n 20 to t = 0.5 with no option given (scheme wc), its acceptance criteria: L_z within
// 0.2 % at every step (1), v_z (2), E_tot within 1 % (3), no alarm (4), no clumping (5).
TEST(SquarePatch, HalfSecondStaysSymmetricInZWithoutClumpingOrAlarm) {
    omp_set_num_threads(2);
    Config cfg = testref::case_config("square-patch", 20);
    Simulation<double> sim(cfg, make_case(cfg));
    sim.set_end_time(0.5);
    const double lz0 = sim.diagnostics().angular_momentum[2], e0 = sim.diagnostics().etot;
    double worst_lz = 0, worst_e = 0;
    while (sim.time() < 0.5) {
        sim.step();
        worst_lz = std::max(worst_lz, std::abs(sim.diagnostics().angular_momentum[2] / lz0 - 1));
        worst_e = std::max(worst_e, std::abs(sim.diagnostics().etot / e0 - 1));
    }
    EXPECT_EQ(sim.safety().recoveries(), 0) << sim.safety().summary(); // acceptance 4's "no alarm"
    const auto& ps = sim.particles();
    double vxy_max = 0;
    std::vector<double> vz(ps.size());
    for (std::size_t i = 0; i < ps.size(); ++i) {
        vxy_max = std::max(vxy_max, std::hypot(ps[Field::vx][i], ps[Field::vy][i]));
        vz[i] = std::abs(ps[Field::vz][i]);
    }
    const double vz_median = median(vz) / vxy_max;
    const double vz_max = *std::max_element(vz.begin(), vz.end()) / vxy_max;
    const double spacing = 100.0 / 20, closest = closest_pair(ps, 100.0) / spacing;
    std::printf("t = 0.5: worst |dL_z/L_z| %.3e, worst |dE_tot/E_tot| %.3e, |v_z|/max|v_xy| "
                "median %.3e max %.3e, closest pair %.3f of the spacing\n",
                worst_lz, worst_e, vz_median, vz_max, closest);
    EXPECT_LT(vz_median, 1e-6); // acceptance 2
    EXPECT_LT(vz_max, 1e-4);
    EXPECT_GE(closest, 0.5);    // acceptance 5
    EXPECT_LT(worst_lz, 0.002); // acceptance 1
    EXPECT_LT(worst_e, 0.01);   // acceptance 3
}
