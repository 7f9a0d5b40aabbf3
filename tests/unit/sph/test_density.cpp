// Acceptance 4 (issue 2): density and Omega on a regular lattice.
#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "exasph/domain/sfc_order.hpp"
#include "exasph/kernel/sinc_kernel.hpp"
#include "exasph/sph/passes.hpp"
#include "kernels.hpp"
#include "random_particles.hpp"

using namespace exasph;

namespace {

struct Prepared {
    ParticleSet<double> ps;
    Box<double> box;
    Octree<double> tree;
    NeighbourLists<double> nl;
};

void prepare(Prepared& s) {
    auto keys = sort_along_curve(s.ps, s.box, CurveKind::hilbert);
    s.tree.build(keys.data(), std::uint32_t(s.ps.size()), 64);
    SearchView<double> sv{s.ps.data(Field::x), s.ps.data(Field::y), s.ps.data(Field::z),
                          s.ps.data(Field::h)};
    s.tree.update_bounds(sv.x, sv.y, sv.z, sv.h);
    s.nl.build(s.tree, sv, s.box, NeighbourCriterion::symmetric, std::uint32_t(s.ps.size()));
}

// Decodes every particle's list: on_list(a, list) once per particle, then on_prefix(a, part) for
// the whole list and, for one particle in 50, every prefix of it (every remainder of the vector
// loops). Stops at the first fatal failure; returns the prefixes checked.
template <class OnList, class OnPrefix>
std::size_t for_each_list_prefix(const NeighbourLists<double>& nl, OnList&& on_list,
                                 OnPrefix&& on_prefix) {
    NeighbourLists<double>::Decoder dec(nl);
    std::size_t checked = 0;
    for (std::size_t g = 0; g < nl.num_groups(); ++g) {
        dec.start(g);
        for (std::uint32_t slot = nl.group_begin(g); slot < nl.group_end(g); ++slot) {
            const std::uint32_t a = nl.member(slot);
            const ContiguousSpan nb = dec.next();
            on_list(a, nb);
            const std::uint32_t first = a % 50 == 0 ? 0 : nb.count;
            for (std::uint32_t len = first; len <= nb.count; ++len, ++checked) {
                on_prefix(a, ContiguousSpan{nb.index, len, nb.wraps});
                if (::testing::Test::HasFatalFailure()) return checked;
            }
        }
    }
    return checked;
}

} // namespace

class LatticeDensity : public ::testing::TestWithParam<double> {};

TEST_P(LatticeDensity, MatchesTrueDensityOmegaIsOneAndEosIsApplied) {
    Prepared s;
    s.ps = testref::periodic_lattice(16, GetParam(), s.box);
    prepare(s);
    for (std::size_t i = 0; i < s.ps.size(); ++i) s.ps[Field::u][i] = 1.0 + 1e-3 * double(i % 17);
    const auto& k = testref::sinc6();
    compute_density(s.ps, s.nl, s.box, k.view());
    double max_rho_err = 0, max_omega_err = 0, max_pgrad_err = 0;
    auto view = make_view(s.ps);
    for (std::size_t i = 0; i < s.ps.size(); ++i) {
        const double rho = s.ps.narrow(Field::rho)[i];
        max_rho_err = std::max(max_rho_err, std::abs(rho - 1.0));
        // Omega is not stored: the kernel's value, and the stored P / (Omega rho^2) (ideal gas)
        const auto list = s.nl.list(std::uint32_t(i));
        const auto r =
            density_kern(std::uint32_t(i), NeighbourSpan{list.data(), std::uint32_t(list.size())},
                         view, s.box, k.view());
        max_omega_err = std::max(max_omega_err, std::abs(r.omega - 1.0));
        const double p = (5.0 / 3.0 - 1.0) * rho * s.ps[Field::u][i];
        EXPECT_FLOAT_EQ(s.ps.narrow(Field::p)[i], float(p));
        max_pgrad_err =
            std::max(max_pgrad_err,
                     std::abs(s.ps.narrow(Field::pgrad)[i] / (p / (r.omega * rho * rho)) - 1.0));
    }
    EXPECT_LT(max_pgrad_err, 1e-6); // single precision
    RecordProperty("max_rho_error", std::to_string(max_rho_err));
    EXPECT_LT(max_rho_err, 5e-3);
    EXPECT_LT(max_omega_err, 1e-2);
    // The neighbour count of the lattice is near the target.
    EXPECT_NEAR(s.ps.narrow(Field::nc)[0], GetParam(), 0.15 * GetParam());
}

INSTANTIATE_TEST_SUITE_P(NeighbourCounts, LatticeDensity, ::testing::Values(100.0, 250.0));

// --energy-weights (pressure-energy SPH): with X = m u the pressure is the smoothed energy
// density, P_a = (gamma - 1) sum_b m_b u_b W_ab(h_a), whatever u does between particles: a jump
// in u by 8 across the box here (the isobaric cube's contrast) enters P only through the sum.
TEST(EnergyWeights, PressureIsTheSmoothedEnergyDensity) {
    Prepared s;
    s.ps = testref::periodic_lattice(16, 100, s.box);
    prepare(s);
    const std::size_t n = s.ps.size();
    for (std::size_t i = 0; i < n; ++i)
        s.ps[Field::u][i] = (s.ps[Field::x][i] < 8 ? 1.0 : 8.0) * (1 + 0.1 * double(i % 7) / 7);
    s.ps.enable(Field::xm), s.ps.enable(Field::kx);
    update_volume_weights(s.ps, n, true);
    EXPECT_DOUBLE_EQ(s.ps[Field::xm][5], s.ps[Field::m][5] * s.ps[Field::u][5]);
    const auto& k = testref::sinc6();
    compute_density(s.ps, s.nl, s.box, k.view());
    double worst = 0, p_min = 1e30, p_max = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const double h = s.ps[Field::h][i];
        double sum = s.ps[Field::m][i] * s.ps[Field::u][i] * k.view().value(0.0);
        for (const std::uint32_t b : s.nl.list(std::uint32_t(i))) {
            double r2 = 0;
            for (const Field f : {Field::x, Field::y, Field::z}) {
                double d = s.ps[f][b] - s.ps[f][i];
                d -= 16 * std::round(d / 16); // the periodic image
                r2 += d * d;
            }
            if (r2 < 4 * h * h)
                sum += s.ps[Field::m][b] * s.ps[Field::u][b] * k.view().value(std::sqrt(r2) / h);
        }
        const double p_direct = (5.0 / 3.0 - 1.0) * sum / (h * h * h);
        const double p = s.ps.narrow(Field::p)[i];
        worst = std::max(worst, std::abs(p / p_direct - 1));
        p_min = std::min(p_min, p), p_max = std::max(p_max, p);
    }
    EXPECT_LT(worst, 1e-5); // single-precision storage of P
    // The smoothed pressure spans the jump: between the two sides' (2/3) u_min and (2/3) u_max.
    EXPECT_GT(p_min, 0.66);
    EXPECT_LT(p_max, 8 * 1.1 * 0.67);
    EXPECT_GT(p_max / p_min, 4.0);
}

// --double-precision: the derived fields move to double storage with their values, the passes
// then store the kernels' double results unrounded, and the single-precision accessor refuses.
TEST(DerivedFieldPrecision, DoubleStorageKeepsTheKernelsResultsUnrounded) {
    Prepared s;
    s.ps = testref::periodic_lattice(10, 100, s.box);
    prepare(s);
    for (std::size_t i = 0; i < s.ps.size(); ++i) s.ps[Field::u][i] = 1.0 + 1e-3 * double(i % 17);
    const auto& k = testref::sinc6();
    compute_density(s.ps, s.nl, s.box, k.view());
    const double rho_single = s.ps.value(Field::rho, 5);
    s.ps.set_narrow_single(false);
    ASSERT_FALSE(s.ps.narrow_single());
    EXPECT_EQ(s.ps.value(Field::rho, 5), rho_single); // moved with its value
    EXPECT_THROW(s.ps.narrow(Field::rho), Error);
    compute_density(s.ps, s.nl, s.box, k.view());
    compute_iad(s.ps, s.nl, s.box, k.view());
    auto view = make_view<double>(s.ps);
    double max_rho_diff = 0, max_c_diff = 0;
    for (std::size_t i = 0; i < s.ps.size(); ++i) {
        const auto list = s.nl.list(std::uint32_t(i));
        const NeighbourSpan nb{list.data(), std::uint32_t(list.size())};
        const auto d = density_kern(std::uint32_t(i), nb, view, s.box, k.view());
        const auto c = iad_kern(std::uint32_t(i), nb, view, s.box, k.view());
        max_rho_diff = std::max(max_rho_diff, std::abs(s.ps[Field::rho][i] - d.rho));
        max_c_diff = std::max(max_c_diff, std::abs(s.ps[Field::c11][i] / c.c11 - 1.0));
    }
    // Double storage: the pass's value is the kernel's to round-off (the driver's inlined copy
    // may round the sum differently in the last bits), far below float's 6e-8.
    EXPECT_LT(max_rho_diff, 1e-13);
    EXPECT_LT(max_c_diff, 1e-13);
    EXPECT_NE(s.ps.value(Field::rho, 5), rho_single);
    s.ps.set_narrow_single(true);
    EXPECT_EQ(s.ps.value(Field::rho, 5), double(float(s.ps.value(Field::rho, 5))));
}

TEST(Eos, IdealGasAndTait) {
    auto g = ideal_gas_eos(2.0, 3.0, 5.0 / 3.0);
    EXPECT_DOUBLE_EQ(g.p, 4.0);
    EXPECT_DOUBLE_EQ(g.c, std::sqrt(5.0 / 3.0 * 2.0));
    auto t = tait_eos(1.0, 1.0, -5.0, 3500.0);
    EXPECT_DOUBLE_EQ(t.p, -5.0);
    auto t2 = tait_eos(2.0, 1.0, 0.0, 10.0);
    EXPECT_DOUBLE_EQ(t2.p, 100.0 / 7.0 * 127.0);
}

TEST(Iad, InverseOfTauOnALatticeIsIsotropic) {
    Prepared s;
    s.ps = testref::periodic_lattice(12, 100, s.box);
    prepare(s);
    const auto& k = testref::sinc6();
    compute_density(s.ps, s.nl, s.box, k.view());
    compute_iad(s.ps, s.nl, s.box, k.view());
    // tau = (1/3) I * sum V r^2 W: C is diagonal with equal entries, off-diagonals vanish. The
    // kernel's result (working precision) is checked; the particle set stores it in single
    // precision (is_narrow).
    auto view = make_view(s.ps);
    for (std::size_t i = 0; i < s.ps.size(); i += 97) {
        const auto list = s.nl.list(std::uint32_t(i));
        auto r = iad_kern(std::uint32_t(i), NeighbourSpan{list.data(), std::uint32_t(list.size())},
                          view, s.box, k.view());
        EXPECT_NEAR(r.c11, r.c22, 1e-9 * r.c11);
        EXPECT_NEAR(r.c33, r.c22, 1e-9 * r.c11);
        EXPECT_NEAR(r.c12, 0.0, 1e-9 * r.c11);
        // (The driver's inlined copy of the kernel may round differently in the last bits.)
        EXPECT_NEAR(s.ps.narrow(Field::c11)[i], r.c11, 1e-7 * r.c11);
        EXPECT_NEAR(s.ps.narrow(Field::c23)[i], r.c23, 1e-7 * r.c11);
    }
}

TEST(Iad, SingularTauIsReported) {
    auto r = invert_symmetric3(1.0, 0.0, 0.0, 1.0, 0.0, 0.0); // coplanar neighbours
    EXPECT_TRUE(r.singular);
    auto ok = invert_symmetric3(2.0, 0.5, 0.0, 1.0, 0.0, 3.0);
    EXPECT_FALSE(ok.singular);
    // C tau = I for the first row.
    EXPECT_NEAR(ok.c11 * 2.0 + ok.c12 * 0.5, 1.0, 1e-14);
    EXPECT_NEAR(ok.c11 * 0.5 + ok.c12 * 1.0, 0.0, 1e-14);
}

// The pair sums through density_pairs (the AVX2 or AVX-512 loop where the build targets it, with
// the image skipped for groups the search found not to wrap, and the last pairs in a masked step;
// on AVX-512 hosts the AVX2 loop too) against the portable loop, on random particles with h
// varying by 2x, in a periodic box and an open one, for every length of list prefix (every
// remainder) of some particles.
TEST(DensityPairs, DispatchedLoopMatchesThePortableOne) {
    for (const bool periodic : {true, false}) {
        Prepared s;
        s.box = testref::unit_box(periodic);
        s.ps = testref::random_cube(6000, 11, 0.04, 0.08);
        for (std::size_t i = 0; i < s.ps.size(); ++i)
            s.ps[Field::m][i] = 1.0 + 0.01 * double(i % 5);
        prepare(s);
        const auto& k = testref::sinc6();
        const auto view = make_view(s.ps);
        std::size_t skipped = 0;
        const std::size_t checked = for_each_list_prefix(
            s.nl, [&](std::uint32_t, ContiguousSpan nb) { skipped += !nb.wraps; },
            [&](std::uint32_t a, ContiguousSpan part) {
                const auto fast = density_pairs(a, part, view, s.box, k.view(), 1.0, 3.0);
                const auto ref = density_pairs_portable(a, part, view, s.box, k.view(), 1.0, 3.0);
                ASSERT_NEAR(fast.k, ref.k, 1e-13 * std::abs(ref.k)) << a << " " << part.count;
                ASSERT_NEAR(fast.dh, ref.dh, 1e-12 * std::abs(ref.k)) << a << " " << part.count;
                ASSERT_EQ(fast.nc, ref.nc) << a << " " << part.count;
#if defined(EXASPH_SIMD_PAIRS) && defined(__AVX512F__)
                // The AVX2 lanes as well, which hosts without AVX-512 run.
                const auto narrow =
                    simd::DensityPairs<simd::Avx2>(a, view, s.box, k.view()).sum(part);
                ASSERT_NEAR(1.0 + narrow.k, ref.k, 1e-13 * std::abs(ref.k)) << a;
                ASSERT_NEAR(3.0 + narrow.dh, ref.dh, 1e-12 * std::abs(ref.k)) << a;
                ASSERT_EQ(double(narrow.nc), ref.nc) << a;
#endif
            });
        EXPECT_GT(checked, s.ps.size());
        // An open box never needs the image; a periodic one does near its faces only.
        if (periodic) {
            EXPECT_GT(skipped, 0u);
            EXPECT_LT(skipped, s.ps.size());
        } else {
            EXPECT_EQ(skipped, s.ps.size());
        }
    }
}

// The IAD pass's sums through iad_sums (the AVX2 or AVX-512 loop where the build targets it; on
// AVX-512 hosts the AVX2 loop too) against the portable loop: tau's moments and D's, with k read
// as float (rho, standard SPH) and as double (volume elements), on random particles and
// velocities in a periodic and an open box, for every list prefix of some particles.
TEST(IadPairs, DispatchedLoopMatchesThePortableOne) {
    for (const bool periodic : {true, false}) {
        Prepared s;
        s.box = testref::unit_box(periodic);
        s.ps = testref::random_cube(5000, 12, 0.05, 0.09);
        std::mt19937_64 rng(5);
        std::uniform_real_distribution<double> u(-1.0, 1.0);
        for (std::size_t i = 0; i < s.ps.size(); ++i) {
            s.ps[Field::m][i] = 1.0 + 0.01 * double(i % 5);
            for (Field f : {Field::vx, Field::vy, Field::vz}) s.ps[f][i] = u(rng);
        }
        prepare(s);
        for (std::size_t i = 0; i < s.ps.size(); ++i)
            s.ps.narrow(Field::rho)[i] = float(5000.0 * (1.0 + 0.3 * u(rng)));
        const auto& k = testref::sinc6();
        const auto view = make_view(s.ps);
        const float* rho = s.ps.narrow(Field::rho);
        const double* kd = s.ps.data(Field::m); // any positive doubles serve as k here
        auto same = [](const IadSums<double>& f, const IadSums<double>& r, int n) {
            double scale = 0;
            for (int c = 0; c < 6; ++c) scale = std::max(scale, std::abs(r.t[c]));
            for (int c = 0; c < 6; ++c)
                if (!(std::abs(f.t[c] - r.t[c]) <= 1e-13 * scale)) return false;
            for (int c = 0; c < n; ++c)
                if (!(std::abs(f.d[c] - r.d[c]) <= 1e-12 * scale)) return false;
            return true;
        };
        const auto kb = k.view();
        const std::size_t checked = for_each_list_prefix(
            s.nl, [](std::uint32_t, ContiguousSpan) {},
            [&](std::uint32_t a, ContiguousSpan part) {
                ASSERT_TRUE(same(iad_sums<false, false>(a, part, view, s.box, kb, rho),
                                 iad_sums_portable<false, false>(a, part, view, s.box, kb, rho), 0))
                    << a << " " << part.count;
                ASSERT_TRUE(same(iad_sums<true, false>(a, part, view, s.box, kb, kd),
                                 iad_sums_portable<true, false>(a, part, view, s.box, kb, kd), 9))
                    << a << " " << part.count;
#if defined(EXASPH_SIMD_PAIRS) && defined(__AVX512F__)
                // The AVX2 lanes as well, which hosts without AVX-512 run.
                using Avx2Rho = simd::IadPairs<simd::Avx2, false, float>;
                using Avx2K = simd::IadPairs<simd::Avx2, true, double>;
                ASSERT_TRUE(same(Avx2Rho(a, view, s.box, kb, rho).sum(part),
                                 iad_sums_portable<false, false>(a, part, view, s.box, kb, rho), 0))
                    << a;
                ASSERT_TRUE(same(Avx2K(a, view, s.box, kb, kd).sum(part),
                                 iad_sums_portable<true, false>(a, part, view, s.box, kb, kd), 9))
                    << a;
#endif
            });
        EXPECT_GT(checked, s.ps.size());
    }
}

// The momentum-energy sums of one form (kTerms, kVolumeElements; constant alpha) through
// momentum_energy_kern (the AVX2 or AVX-512 loop where the build targets it; on AVX-512 hosts
// the AVX2 loop too) against the portable loop, on random particles, velocities and internal
// energies after real density and IAD passes, in a periodic and an open box, for every list
// prefix of some particles.
template <PairTerms kTerms, bool kVolumeElements>
void dispatched_momentum_energy_matches_portable(const Dissipation<double>& diss) {
    for (const bool periodic : {true, false}) {
        Prepared s;
        s.box = testref::unit_box(periodic);
        s.ps = testref::random_cube(5000, 13, 0.05, 0.09);
        std::mt19937_64 rng(9);
        std::uniform_real_distribution<double> u(-1.0, 1.0);
        if (kVolumeElements) s.ps.enable(Field::xm), s.ps.enable(Field::kx);
        for (std::size_t i = 0; i < s.ps.size(); ++i) {
            s.ps[Field::m][i] = 2e-4 * (1.0 + 0.01 * double(i % 5));
            s.ps[Field::u][i] = 1.0 + 0.5 * u(rng);
            for (Field f : {Field::vx, Field::vy, Field::vz}) s.ps[f][i] = u(rng);
            if (kVolumeElements) s.ps[Field::xm][i] = 3e-4 * (1.0 + 0.3 * u(rng));
        }
        prepare(s);
        const auto& k = testref::sinc6();
        compute_density(s.ps, s.nl, s.box, k.view());
        compute_iad(s.ps, s.nl, s.box, k.view(), diss.reconstruct, kVolumeElements);
        const auto view = make_view(s.ps);
        // The sums' round-off scale: the pair terms' magnitudes (they cancel in the sums).
        double a_scale = 0, du_scale = 0;
        auto scale = [&](std::uint32_t a, ContiguousSpan nb) {
            a_scale = du_scale = 1e-300;
            for (std::uint32_t j = 0; j < nb.count; ++j) {
                const auto t = momentum_energy_portable<double, kTerms, false, kVolumeElements>(
                    a, ContiguousSpan{nb.index + j, 1, nb.wraps}, view, s.box, k.view(), diss);
                a_scale += std::abs(t.ax) + std::abs(t.ay) + std::abs(t.az);
                du_scale += std::abs(t.du);
            }
        };
        const std::size_t checked =
            for_each_list_prefix(s.nl, scale, [&](std::uint32_t a, ContiguousSpan part) {
                const auto f = momentum_energy_kern<double, kTerms, false, kVolumeElements>(
                    a, part, view, s.box, k.view(), diss);
                const auto r = momentum_energy_portable<double, kTerms, false, kVolumeElements>(
                    a, part, view, s.box, k.view(), diss);
                ASSERT_NEAR(f.ax, r.ax, 1e-14 * a_scale) << a << " " << part.count;
                ASSERT_NEAR(f.ay, r.ay, 1e-14 * a_scale) << a << " " << part.count;
                ASSERT_NEAR(f.az, r.az, 1e-14 * a_scale) << a << " " << part.count;
                ASSERT_NEAR(f.du, r.du, 1e-14 * du_scale) << a << " " << part.count;
                ASSERT_NEAR(f.vsig_max, r.vsig_max, 1e-13 * r.vsig_max) << a << " " << part.count;
#if defined(EXASPH_SIMD_PAIRS) && defined(__AVX512F__)
                // The AVX2 lanes as well, which hosts without AVX-512 run.
                constexpr bool kLimited = kTerms == PairTerms::limited;
                const auto n =
                    simd::MomentumEnergyPairs<simd::Avx2, kLimited>(a, view, s.box, k.view(), diss)
                        .sum(part);
                ASSERT_NEAR(n.ax, r.ax, 1e-14 * a_scale) << a;
                ASSERT_NEAR(n.ay, r.ay, 1e-14 * a_scale) << a;
                ASSERT_NEAR(n.az, r.az, 1e-14 * a_scale) << a;
                ASSERT_NEAR(n.du, r.du, 1e-14 * du_scale) << a;
                ASSERT_NEAR(n.vsig_max, r.vsig_max, 1e-13 * r.vsig_max) << a;
#endif
            });
        EXPECT_GT(checked, s.ps.size());
    }
}

// The std scheme's form: standard SPH, no options.
TEST(MomentumEnergyPairs, DispatchedLoopMatchesThePortableOne) {
    Dissipation<double> diss;
    diss.alpha = 0.8;
    dispatched_momentum_energy_matches_portable<PairTerms::plain, false>(diss);
}

// The ve scheme's form (volume elements, the slope-limited viscosity, conductivity 1) and the
// pe scheme's (the same without conductivity). The random velocities give both signs of the
// slopes, and close pairs fade the reconstruction.
TEST(MomentumEnergyPairs, LimitedFormMatchesThePortableOne) {
    for (const double alpha_u : {1.0, 0.0}) {
        const auto diss = Dissipation<double>::of(1.0, alpha_u, true, 100);
        ASSERT_EQ(diss.terms(), PairTerms::limited);
        dispatched_momentum_energy_matches_portable<PairTerms::limited, true>(diss);
    }
}
