// Issue 60: the diagnostics are one kernel (sph/diagnostics_kern.hpp) reduced along the
// launchers' fixed tree: their sums equal the per-particle formulas of physics.md §10 summed
// directly, and have the same bits on the CPU launcher, the GPU path's host launcher and one
// thread.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "case_config.hpp"
#include "exasph/run/setup.hpp"
#include "exasph/sim/simulation.hpp"

using namespace exasph;
using namespace exasph::testref;

namespace {
constexpr std::size_t kElements = kDiagWithExtent;

template <class L>
std::vector<SumMax> diagnostics_of(ParticleSet<double>& ps, std::size_t n,
                                   const ExactDensity::AtTime& exact) {
    std::vector<SumMax> e(kElements);
    local_diagnostics<L>(ps, n, 17, exact, 100.0, e.data());
    return e;
}

void expect_same_bits(const std::vector<SumMax>& a, const std::vector<SumMax>& b,
                      const char* what) {
    for (std::size_t k = 0; k < a.size(); ++k) {
        EXPECT_EQ(a[k].sum, b[k].sum) << what << ", element " << k;
        EXPECT_EQ(a[k].max, b[k].max) << what << ", element " << k;
    }
}

// A Sedov blast after a few steps: velocities, accelerations, du and an exact solution.
struct Blast {
    Config cfg = case_config("sedov", 20);
    Simulation<double> sim{cfg, make_case(cfg)};
    InitialConditions<double> ic = make_case(cfg);
    Blast() {
        for (int s = 0; s < 3; ++s) sim.step();
    }
};
} // namespace

TEST(Diagnostics, KernelSumsEqualTheFormulasSummedDirectly) {
    Blast b;
    ParticleSet<double> ps = b.sim.particles();
    const std::size_t n = b.sim.n_owned();
    const double t = b.sim.diagnostics().time - b.sim.diagnostics().dt;
    const auto exact = b.ic.exact.at(t);
    const auto e = diagnostics_of<OmpLauncher>(ps, n, exact);
    long double ekin = 0, eint = 0, px = 0, lz = 0, l1 = 0, mass = 0;
    double nc_lo = 1e300, nc_hi = -1e300, rho_max = -1e300, x_lo = 1e300, z_hi = -1e300;
    for (std::size_t i = 0; i < n; ++i) {
        const double m = ps[Field::m][i], vx = ps[Field::vx][i], vy = ps[Field::vy][i];
        const double vz = ps[Field::vz][i], x = ps[Field::x][i], y = ps[Field::y][i];
        ekin += 0.5 * m * (vx * vx + vy * vy + vz * vz);
        eint += m * ps[Field::u][i];
        px += m * vx;
        lz += m * (x * vy - y * vx);
        mass += m;
        const double r = std::hypot(ps[Field::x_m1][i], ps[Field::y_m1][i], ps[Field::z_m1][i]);
        l1 += std::abs(ps.value(Field::rho, i) - b.ic.exact(r, t));
        nc_lo = std::min(nc_lo, ps.value(Field::nc, i));
        nc_hi = std::max(nc_hi, ps.value(Field::nc, i));
        rho_max = std::max(rho_max, ps.value(Field::rho, i));
        x_lo = std::min(x_lo, x);
        z_hi = std::max(z_hi, double(ps[Field::z][i]));
    }
    EXPECT_GT(ekin, 1e-4); // the blast moves
    EXPECT_NEAR(e[0].sum, double(ekin), 1e-13 * double(ekin));
    EXPECT_NEAR(e[1].sum, double(eint), 1e-13 * double(eint));
    EXPECT_NEAR(e[2].sum, double(px), 1e-13 * double(mass));
    EXPECT_NEAR(e[7].sum, double(lz), 1e-13 * double(mass));
    EXPECT_NEAR(e[11].sum, double(l1), 1e-12 * double(l1));
    EXPECT_NEAR(e[13].sum, double(mass), 1e-13 * double(mass));
    EXPECT_EQ(e[8].max, nc_hi);
    EXPECT_EQ(e[9].min(), nc_lo);
    EXPECT_EQ(e[9].sum, double(n));
    EXPECT_EQ(e[10].sum, 17.0 / double(n)); // halos over owned
    EXPECT_EQ(e[11].max, rho_max);
    EXPECT_EQ(e[kDiagElements + 3].min(), x_lo);
    EXPECT_EQ(e[kDiagElements + 2].max, z_hi);
}

TEST(Diagnostics, SameBitsOnEveryLauncherAndThreadCount) {
    Blast b;
    ParticleSet<double> ps = b.sim.particles();
    const std::size_t n = b.sim.n_owned();
    const auto exact = b.ic.exact.at(b.sim.diagnostics().time);
    const auto cpu = diagnostics_of<OmpLauncher>(ps, n, exact);
    expect_same_bits(cpu, diagnostics_of<GpuHostLauncher>(ps, n, exact), "GPU path's host");
    // The exact solution read from a copy of its table, as the step does.
    const std::vector<double> copy = b.ic.exact.table();
    const auto from_copy = b.ic.exact.at(b.sim.diagnostics().time, copy.data());
    expect_same_bits(cpu, diagnostics_of<OmpLauncher>(ps, n, from_copy), "table copy");
#ifdef _OPENMP
    const int threads = omp_get_max_threads();
    omp_set_num_threads(1);
    expect_same_bits(cpu, diagnostics_of<OmpLauncher>(ps, n, exact), "one thread");
    omp_set_num_threads(threads);
#endif
}
