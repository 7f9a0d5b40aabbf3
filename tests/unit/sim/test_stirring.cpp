// The stirring of driven turbulence (sim/stirring.hpp, sph/stir_kern.hpp): the kernel's
// acceleration equals the Fourier sum evaluated directly; the field is solenoidal; its rms over
// the box is the requested one on average; the OU update forgets its start over t_corr.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "exasph/sim/stirring.hpp"
#include "exasph/sph/launch.hpp"
#include "exasph/sph/passes.hpp"

using namespace exasph;

namespace {
Box<double> unit_box() {
    Box<double> b;
    b.periodic = {true, true, true};
    return b;
}

// a(x) = sum_q 2 Re(c_q exp(i k_q . x)), term by term with cos and sin.
std::array<double, 3> direct(const StirModes& m, const double x[3]) {
    std::array<double, 3> a{0, 0, 0};
    for (std::uint32_t q = 0; q < m.count; ++q) {
        double ph = 0;
        for (int d = 0; d < 3; ++d) ph += m.wave[3 * q + d] * m.k0[d] * x[d];
        for (int d = 0; d < 3; ++d)
            a[d] += 2 * (m.coeff[6 * q + d] * std::cos(ph) - m.coeff[6 * q + 3 + d] * std::sin(ph));
    }
    return a;
}
} // namespace

TEST(Stirring, KernelMatchesTheFourierSumAndIsSolenoidal) {
    const Stirring s = Stirring::for_mach(unit_box(), 0.3, 1.0, 7);
    const StirModes m = s.modes();
    // |n|^2 = 2, 3, 4, 5, 6, 8: 12 + 8 + 6 + 24 + 24 + 12 wave vectors, half of them kept.
    EXPECT_EQ(m.count, 43u);
    ParticleSet<double> ps;
    ps.resize(64);
    ps.enable(Field::stir);
    for (std::size_t i = 0; i < 64; ++i) {
        ps[Field::x][i] = 0.013 * i, ps[Field::y][i] = 0.7 - 0.01 * i, ps[Field::z][i] = 0.031 * i;
        ps[Field::vx][i] = 1, ps[Field::vy][i] = 0, ps[Field::vz][i] = 0;
        ps[Field::ax][i] = ps[Field::ay][i] = ps[Field::az][i] = 0;
    }
    add_stirring(ps, 64, m);
    for (std::size_t i = 0; i < 64; ++i) {
        const double x[3] = {ps[Field::x][i], ps[Field::y][i], ps[Field::z][i]};
        const auto a = direct(m, x);
        EXPECT_NEAR(ps[Field::ax][i], a[0], 1e-12);
        EXPECT_NEAR(ps[Field::ay][i], a[1], 1e-12);
        EXPECT_NEAR(ps[Field::az][i], a[2], 1e-12);
        EXPECT_NEAR(ps[Field::stir][i], a[0], 1e-12); // v = (1, 0, 0)
    }
    for (std::uint32_t q = 0; q < m.count; ++q) // k . c = 0 for both parts
        for (int part = 0; part < 2; ++part) {
            double kc = 0;
            for (int d = 0; d < 3; ++d) kc += m.wave[3 * q + d] * m.coeff[6 * q + 3 * part + d];
            EXPECT_NEAR(kc, 0.0, 1e-14);
        }
}

TEST(Stirring, RmsIsTheRequestedOneAndTheUpdateDecorrelates) {
    Stirring s = Stirring::for_mach(unit_box(), 0.3, 1.0, 11);
    const double target = s.state().accel_rms, t_corr = s.state().t_corr;
    EXPECT_NEAR(target, kStirGain * 0.09, 1e-15);
    EXPECT_NEAR(t_corr, 1.0 / 0.6, 1e-15);
    const std::vector<double> start = s.state().coeff;
    double mean_square = 0, overlap = 0;
    const int steps = 4000;
    const double dt = 0.01 * t_corr;
    for (int n = 0; n < steps; ++n) {
        s.advance(n, dt);
        const auto& c = s.state().coeff;
        double sq = 0; // box mean of |a|^2 = sum over modes of 2 |c_q|^2
        for (double v : c) sq += 2 * v * v;
        mean_square += sq / steps;
        if (n == int(3 * t_corr / dt)) // after 3 t_corr: correlation e^-3 with the start
            for (std::size_t k = 0; k < c.size(); ++k) overlap += c[k] * start[k];
    }
    double norm = 0;
    for (double v : start) norm += v * v;
    EXPECT_NEAR(std::sqrt(mean_square), target, 0.1 * target); // 40 t_corr of samples
    EXPECT_LT(std::abs(overlap) / norm, 0.25);
}
