// Acceptance 1 (issue 2): normalisation and lookup-table accuracy of the sinc kernels; the
// density pass's polynomial form of them (issue 19).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "exasph/kernel/sinc_kernel.hpp"

using namespace exasph;

namespace {

// 4 pi \int_0^2 w(v) v^2 dv by composite 5-point Gauss-Legendre on 4000 panels: a quadrature
// independent of the Simpson rule used to normalise the kernel.
double volume_integral(const KernelTable<double>& k) {
    const double xg[5] = {0.0, -0.5384693101056831, 0.5384693101056831, -0.9061798459386640,
                          0.9061798459386640};
    const double wg[5] = {0.5688888888888889, 0.4786286704993665, 0.4786286704993665,
                          0.2369268850561891, 0.2369268850561891};
    const int panels = 4000;
    const double len = 2.0 / panels;
    double sum = 0;
    for (int p = 0; p < panels; ++p) {
        double mid = (p + 0.5) * len;
        for (int g = 0; g < 5; ++g) {
            double v = mid + 0.5 * len * xg[g];
            sum += wg[g] * 0.5 * len * k.exact_value(v) * v * v;
        }
    }
    return 4 * M_PI * sum;
}

} // namespace

class SincKernel : public ::testing::TestWithParam<double> {};

TEST_P(SincKernel, IntegratesToOne) {
    KernelTable<double> k(sinc_kernel(GetParam()));
    EXPECT_NEAR(volume_integral(k), 1.0, 1e-6);
}

TEST_P(SincKernel, QuadratureAgreesWithSphynxFit) {
    double n = GetParam();
    KernelTable<double> k(sinc_kernel(n));
    EXPECT_NEAR(k.normalisation() / sinc_normalisation_fit(n), 1.0, 2e-4);
}

TEST_P(SincKernel, TableMatchesDirectEvaluation) {
    KernelTable<double> k(sinc_kernel(GetParam()));
    auto view = k.view();
    double wmax = 0, dwmax = 0;
    for (int i = 0; i <= 4000; ++i) {
        wmax = std::max(wmax, std::abs(k.exact_value(i * 5e-4)));
        dwmax = std::max(dwmax, std::abs(k.exact_derivative(i * 5e-4)));
    }
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> u(0.0, 2.0);
    double err_w = 0, err_dw = 0;
    for (int i = 0; i < 100000; ++i) {
        double v = u(rng);
        err_w = std::max(err_w, std::abs(view.value(v) - k.exact_value(v)));
        err_dw = std::max(err_dw, std::abs(view.derivative(v) - k.exact_derivative(v)));
    }
    EXPECT_LT(err_w / wmax, 1e-6);
    EXPECT_LT(err_dw / dwmax, 1e-6);
}

TEST_P(SincKernel, DerivativeMatchesFiniteDifference) {
    KernelTable<double> k(sinc_kernel(GetParam()));
    for (double v : {0.1, 0.5, 1.0, 1.5, 1.9}) {
        double fd = (k.exact_value(v + 1e-6) - k.exact_value(v - 1e-6)) / 2e-6;
        EXPECT_NEAR(k.exact_derivative(v), fd, 1e-6 * std::abs(k.exact_value(0)));
    }
}

namespace {
// The density pass's polynomials in v^2 (kernel/kernel_poly.hpp): w and 3 w + v w'.
double polynomial_error(double n) {
    KernelTable<double> k(sinc_kernel(n));
    const auto view = k.view();
    const double w0 = k.exact_value(0);
    double err = 0;
    for (int i = 0; i <= 20000; ++i) {
        const double v = i * 1e-4;
        const double gradh = 3 * k.exact_value(v) + v * k.exact_derivative(v);
        err = std::max(err, std::abs(view.w_sq(v * v) - k.exact_value(v)));
        err = std::max(err, std::abs(view.gradh_sq(v * v) - gradh));
    }
    return err / w0;
}
} // namespace

TEST_P(SincKernel, PolynomialMatchesDirectEvaluation) {
    const double err = polynomial_error(GetParam());
    std::printf("n = %g: polynomial error %.2e of w(0)\n", GetParam(), err);
    EXPECT_LT(err, GetParam() <= 8 ? 1e-12 : 1e-9);
}

// A non-integer n has a (2 - v)^n end, which no polynomial follows as closely: 1.3e-7 for
// n = 3.5 (its grad-h term), still within the bound the table is held to above.
TEST(SincKernelPolynomial, NonIntegerAndLargestExponentsWithinTheTablesBound) {
    for (double n : {3.5, 5.5, 12.0}) {
        const double err = polynomial_error(n);
        std::printf("n = %g: polynomial error %.2e of w(0)\n", n, err);
        EXPECT_LT(err, n == 12.0 ? 1e-8 : 1e-6) << n;
    }
}

// The single-precision copies that the pair loops evaluate with float derived fields (16
// terms), at the float v^2 the passes compute. For n <= 9 float arithmetic itself sets the
// error: t = v^2/2 - 1 rounds by up to 6e-8, which moves the value by |d/dt| times that
// (steeper for the grad-h term than for w), plus the evaluation's roundings: measured 1.0e-6
// (n = 4), 1.3e-6 (6) and 1.6e-6 (8) of w(0), mostly in the grad-h term; w alone 3e-7 (with 21
// terms: 9.6e-7, 1.4e-6, 1.7e-6). Beyond, the degree-15 interpolant's own error takes over:
// 4.0e-6 for n = 10 and 2.6e-5 for n = 12 (21 terms: 2.1e-6, 2.5e-6), still far below the
// kernel's discretisation error.
TEST(SincKernelPolynomial, SinglePrecisionWithinFloatRoundOff) {
    for (double n : {4.0, 6.0, 8.0, 10.0, 12.0}) {
        KernelTable<double> k(sinc_kernel(n));
        const auto view = k.view();
        const double w0 = k.exact_value(0);
        double err = 0;
        for (int i = 0; i <= 20000; ++i) {
            const float s = float(i * 1e-4 * i * 1e-4);
            const double v = std::sqrt(double(s));
            const double gradh = 3 * k.exact_value(v) + v * k.exact_derivative(v);
            err = std::max(err, std::abs(double(view.w_in<float>()(s)) - k.exact_value(v)));
            err = std::max(err, std::abs(double(view.gradh_in<float>()(s)) - gradh));
        }
        std::printf("n = %g: single-precision polynomial error %.2e of w(0)\n", n, err / w0);
        EXPECT_LT(err / w0, n <= 8 ? 2.5e-6 : n <= 10 ? 5e-6 : 3e-5) << n;
        EXPECT_EQ(view.w_in<float>()(4.0f), 0.0f);
        EXPECT_EQ(&view.w_in<double>(), &view.w_sq); // the working precision's own polynomial
    }
}

TEST(SincKernelPolynomial, ZeroOutsideSupport) {
    KernelTable<double> k(sinc_kernel(6));
    const auto view = k.view();
    EXPECT_GT(view.w_sq(3.6), 0.0);
    for (double s : {4.0, 5.0, 1e30, std::numeric_limits<double>::infinity(),
                     std::numeric_limits<double>::quiet_NaN()}) {
        EXPECT_EQ(view.w_sq(s), 0.0) << s;
        EXPECT_EQ(view.gradh_sq(s), 0.0) << s;
    }
}

INSTANTIATE_TEST_SUITE_P(Exponents, SincKernel, ::testing::Values(3.0, 4.0, 6.0, 8.0, 10.0));

TEST(SincKernelTable, ZeroOutsideSupport) {
    KernelTable<double> k(sinc_kernel(6));
    auto view = k.view();
    EXPECT_EQ(view.value(2.0), 0.0);
    EXPECT_EQ(view.value(3.5), 0.0);
    EXPECT_GT(view.value(1.99), 0.0);
    // Far outside (a corrupted h makes v huge; the integer index would overflow): zero, and no
    // read outside the table.
    EXPECT_EQ(view.value(1e30), 0.0);
    EXPECT_EQ(view.derivative(1e12), 0.0);
    EXPECT_TRUE(std::isnan(view.value(std::numeric_limits<double>::quiet_NaN())) ||
                view.value(std::numeric_limits<double>::quiet_NaN()) == 0.0);
}
