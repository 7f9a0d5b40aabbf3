// Issue 6, acceptance 1-4: tree gravity against direct summation, momentum, potential energies.
#include <cmath>
#include <cstdio>
#include <random>

#include "exasph/util/mpi.hpp"
#include <gtest/gtest.h>

#include "direct_gravity.hpp"
#include "exasph/cases/evrard.hpp"
#include "exasph/domain/domain.hpp"
#include "exasph/gravity/gravity_solver.hpp"
#include "exasph/kernel/sinc_kernel.hpp"
#include "kernels.hpp"

using namespace exasph;

namespace {

const KernelTable<double>& kernel() {
    return testref::sinc6();
}

// N equal-mass particles (total mass 1) at the given positions; h from the local density `rho`
// so that about 100 neighbours fall within 2h, as in an SPH run.
template <class Pos, class Rho>
ParticleSet<double> make_particles(std::size_t n, Pos pos, Rho rho) {
    ParticleSet<double> ps;
    ps.resize(n);
    const double m = 1.0 / double(n);
    for (std::size_t i = 0; i < n; ++i) {
        double p[3];
        pos(p);
        ps.id[i] = i;
        ps[Field::x][i] = p[0];
        ps[Field::y][i] = p[1];
        ps[Field::z][i] = p[2];
        ps[Field::m][i] = m;
        ps[Field::h][i] = 0.5 * std::cbrt(3.0 * 100 * m / (4 * M_PI * rho(p)));
    }
    return ps;
}

ParticleSet<double> uniform_cube(std::size_t n, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    return make_particles(
        n, [&](double* p) { p[0] = u(rng), p[1] = u(rng), p[2] = u(rng); },
        [](const double*) { return 1.0; });
}

ParticleSet<double> uniform_sphere(std::size_t n, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    return make_particles(
        n,
        [&](double* p) {
            do {
                p[0] = u(rng), p[1] = u(rng), p[2] = u(rng);
            } while (p[0] * p[0] + p[1] * p[1] + p[2] * p[2] >= 1.0);
        },
        [](const double*) { return 3.0 / (4 * M_PI); });
}

// Plummer sphere with scale radius 1, truncated at 10 (99.7 % of the mass).
ParticleSet<double> plummer(std::size_t n, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::normal_distribution<double> g(0.0, 1.0);
    return make_particles(
        n,
        [&](double* p) {
            double r;
            do {
                r = 1.0 / std::sqrt(std::pow(u(rng), -2.0 / 3.0) - 1.0);
            } while (r > 10.0);
            double d[3] = {g(rng), g(rng), g(rng)};
            double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            for (int k = 0; k < 3; ++k) p[k] = r * d[k] / len;
        },
        [](const double* p) {
            double r2 = p[0] * p[0] + p[1] * p[1] + p[2] * p[2];
            return 3.0 / (4 * M_PI) * std::pow(1.0 + r2, -2.5);
        });
}

// Tree gravity (G = 1) of the particles on one rank; `ps` comes back in the domain's order.
void tree_gravity(ParticleSet<double>& ps, double theta) {
    Box<double> box;
    box.periodic = {false, false, false};
    Domain<double> dom(MPI_COMM_SELF, 128, 64, CurveKind::hilbert);
    dom.init(ps, box);
    dom.sync(ps, box);
    for (Field f : {Field::ax, Field::ay, Field::az}) std::fill(ps[f].begin(), ps[f].end(), 0.0);
    GravitySolver<double> solver(kernel(), 1.0, theta, 16);
    solver.compute(ps, dom.n_owned(), dom.assignment(), box, dom.curve(), dom.collectives());
}

struct ForceErrors {
    double rms = 0, max = 0, momentum = 0;
};

ForceErrors force_errors(ParticleSet<double> ps, double theta) {
    tree_gravity(ps, theta);
    SofteningTable<double> soft(kernel());
    auto ref = testref::direct_gravity(ps, ps.size(), soft.view());
    ForceErrors e;
    double p[3] = {0, 0, 0}, pabs = 0;
    for (std::size_t i = 0; i < ps.size(); ++i) {
        const double a[3] = {ps[Field::ax][i], ps[Field::ay][i], ps[Field::az][i]};
        const double r[3] = {ref[i].ax, ref[i].ay, ref[i].az};
        const double dn = std::hypot(a[0] - r[0], a[1] - r[1], a[2] - r[2]);
        const double rel = dn / std::hypot(r[0], r[1], r[2]);
        e.rms += rel * rel;
        e.max = std::max(e.max, rel);
        const double m = ps[Field::m][i];
        for (int d = 0; d < 3; ++d) p[d] += m * a[d];
        pabs += m * std::hypot(a[0], a[1], a[2]);
    }
    e.rms = std::sqrt(e.rms / double(ps.size()));
    e.momentum = std::hypot(p[0], p[1], p[2]) / pabs;
    return e;
}

double potential_energy(const ParticleSet<double>& ps) {
    double e = 0;
    for (std::size_t i = 0; i < ps.size(); ++i) e += 0.5 * ps[Field::m][i] * ps[Field::phi][i];
    return e;
}

} // namespace

TEST(Softening, TableIsConsistent) {
    SofteningTable<double> t(kernel());
    EXPECT_NEAR(t.enclosed_mass(), 1.0, 1e-9);
    auto v = t.view();
    double f, psi, f2, psi2;
    // Continuity with the point-mass law at q = 2.
    v.eval(2.0 - 1e-12, f, psi);
    EXPECT_NEAR(f, 0.125, 1e-6);
    EXPECT_NEAR(psi, 0.5, 1e-6);
    // a = -grad phi: d psi / dq = -q F(q).
    for (double q : {0.1, 0.5, 1.0, 1.5, 1.9}) {
        const double dq = 1e-3;
        v.eval(q + dq, f2, psi2);
        v.eval(q - dq, f, psi);
        const double dpsi = (psi2 - psi) / (2 * dq);
        v.eval(q, f, psi);
        EXPECT_NEAR(dpsi, -q * f, 1e-4 * q * f) << "q = " << q;
    }
}

// Moments combined from parts equal the moments of the whole, and the expansion converges like
// (size / distance)^4 (octupole order).
TEST(Multipole, CombineAndConverge) {
    auto ps = uniform_cube(60, 7);
    const double *x = ps.data(Field::x), *y = ps.data(Field::y), *z = ps.data(Field::z),
                 *m = ps.data(Field::m);
    Multipole parts[3] = {particle_multipole(x, y, z, m, 0, 10),
                          particle_multipole(x, y, z, m, 10, 35),
                          particle_multipole(x, y, z, m, 35, 60)};
    Multipole all = particle_multipole(x, y, z, m, 0, 60), comb = combine_multipoles(parts, 3);
    EXPECT_NEAR(comb.mass, all.mass, 1e-14);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(comb.com[k], all.com[k], 1e-14);
    for (int k = 0; k < 6; ++k) EXPECT_NEAR(comb.q[k], all.q[k], 1e-14);
    for (int k = 0; k < 10; ++k) EXPECT_NEAR(comb.s[k], all.s[k], 1e-14);
    EXPECT_NEAR(comb.d2, all.d2, 1e-14);
    double previous = 1;
    for (double dist : {4.0, 8.0, 16.0}) {
        const double p[3] = {all.com[0] + dist * 0.6, all.com[1] - dist * 0.48,
                             all.com[2] + dist * 0.64};
        GravityField f, ref;
        add_multipole_field(all, p[0] - all.com[0], p[1] - all.com[1], p[2] - all.com[2], f);
        for (int k = 0; k < 60; ++k) {
            Multipole point;
            point.mass = m[k];
            point.com[0] = x[k], point.com[1] = y[k], point.com[2] = z[k];
            add_multipole_field(point, p[0] - x[k], p[1] - y[k], p[2] - z[k], ref);
        }
        const double err = std::hypot(f.ax - ref.ax, f.ay - ref.ay, f.az - ref.az) /
                           std::hypot(ref.ax, ref.ay, ref.az);
        const double perr = std::abs(f.phi - ref.phi) / std::abs(ref.phi);
        std::printf("distance %g: relative error a %.2e phi %.2e\n", dist, err, perr);
        EXPECT_LT(err, 0.1 * std::pow(1.0 / dist, 4));
        EXPECT_LT(perr, 0.1 * std::pow(1.0 / dist, 4));
        if (dist > 4) { // 16 at fourth order (8 with quadrupoles only)
            EXPECT_LT(err, previous / 12);
        }
        previous = err;
    }
}

// Acceptance 1 and 2 for one particle distribution.
static void check_force_accuracy(const char* name, const ParticleSet<double>& ps) {
    auto e5 = force_errors(ps, 0.5);
    auto e3 = force_errors(ps, 0.3);
    std::printf("%s: theta 0.5 rms %.3e max %.3e momentum %.3e; theta 0.3 rms %.3e max %.3e "
                "momentum %.3e\n",
                name, e5.rms, e5.max, e5.momentum, e3.rms, e3.max, e3.momentum);
    EXPECT_LT(e5.rms, 1e-3) << name;
    EXPECT_LT(e5.max, 1e-2) << name;
    EXPECT_LT(e3.rms, e5.rms) << name;
    EXPECT_LT(e5.momentum, 1e-3) << name;
}

TEST(TreeGravity, ForceAccuracyUniformCube) {
    check_force_accuracy("uniform cube", uniform_cube(10000, 1));
}

TEST(TreeGravity, ForceAccuracyPlummer) {
    check_force_accuracy("plummer", plummer(10000, 2));
}

TEST(TreeGravity, UniformSpherePotentialEnergy) {
    auto ps = uniform_sphere(10000, 3);
    tree_gravity(ps, 0.5);
    const double e = potential_energy(ps), exact = -3.0 / 5.0;
    std::printf("uniform sphere: E_pot %.6f, exact %.6f, relative error %.3e\n", e, exact,
                std::abs(e - exact) / std::abs(exact));
    EXPECT_NEAR(e, exact, 0.01 * std::abs(exact));
}

TEST(TreeGravity, EvrardInitialPotentialEnergy) {
    EvrardParams ep;
    ep.side = 30;
    auto ic = make_evrard<double>(ep, CaseContext::one_rank(UnitCubePoints::lattice(30)));
    auto& ps = ic.particles;
    tree_gravity(ps, 0.5);
    const double e = potential_energy(ps), exact = evrard_potential_energy(ep);
    std::printf("evrard (%zu particles, lattice): E_pot %.6f, exact %.6f, relative error %.3e\n",
                ps.size(), e, exact, std::abs(e - exact) / std::abs(exact));
    EXPECT_NEAR(e, exact, 0.02 * std::abs(exact));
}
