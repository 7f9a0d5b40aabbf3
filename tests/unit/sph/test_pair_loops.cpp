// The dispatched pair loops (AVX2 or AVX-512 where the build targets them) against the portable
// loops: density, IAD and momentum-energy, for every remainder of the vector steps.
#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "exasph/kernel/sinc_kernel.hpp"
#include "exasph/sph/passes.hpp"
#include "kernels.hpp"
#include "prepared_lists.hpp"
#include "random_particles.hpp"

using namespace exasph;
using testref::for_each_list_prefix;
using testref::prepare;
using testref::Prepared;

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
#if defined(EXASPH_SIMD_LANES) && defined(__AVX512F__)
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
#if defined(EXASPH_SIMD_LANES) && defined(__AVX512F__)
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
#if defined(EXASPH_SIMD_LANES) && defined(__AVX512F__)
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
