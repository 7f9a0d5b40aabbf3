// Acceptance 1 (issue 5): the Sedov-Taylor and Noh exact solutions.
#include <cmath>

#include <gtest/gtest.h>

#include "exasph/exact/exact_density.hpp"
#include "exasph/exact/noh.hpp"
#include "exasph/exact/sedov.hpp"

using namespace exasph;

TEST(Sedov, Xi0MatchesTheLiterature) {
    EXPECT_NEAR(SedovSolution(5.0 / 3.0).xi0(), 1.1517, 0.001);
    EXPECT_NEAR(SedovSolution(1.4).xi0(), 1.033, 0.001);
}

TEST(Sedov, ShockRadiusAndDensityJumpAtT009) {
    SedovSolution s(5.0 / 3.0);
    const double E = 1, rho = 1, t = 0.09;
    const double rs = s.xi0() * std::pow(E * t * t / rho, 0.2);
    EXPECT_DOUBLE_EQ(s.shock_radius(E, rho, t), rs);
    EXPECT_NEAR(s.at(rs * (1 - 1e-12), t, E, rho).rho, 4.0, 1e-6); // (gamma+1)/(gamma-1)
    EXPECT_EQ(s.at(rs * (1 + 1e-9), t, E, rho).rho, 1.0);
    // Post-shock velocity 2/(gamma+1) of the shock speed 2 R / (5 t).
    EXPECT_NEAR(s.at(rs * (1 - 1e-12), t, E, rho).v, 0.75 * 0.4 * rs / t, 1e-6);
}

TEST(Sedov, ProfileCarriesTheBlastEnergy) {
    SedovSolution s(5.0 / 3.0);
    const double E = 1, t = 0.09, rs = s.shock_radius(E, 1, t);
    const int n = 100000;
    double total = 0;
    for (int i = 0; i < n; ++i) { // midpoint rule in r, independent of the solver's quadrature
        double r = (i + 0.5) / n * rs;
        auto st = s.at(r, t, E, 1);
        total += (0.5 * st.rho * st.v * st.v + st.p / (s.gamma() - 1)) * 4 * M_PI * r * r * rs / n;
    }
    EXPECT_NEAR(total, E, 0.005 * E);
}

TEST(Noh, ShockSpeedAndJumps) {
    NohSolution noh;
    const double t = 0.6;
    EXPECT_NEAR(noh.shock_radius(t), t / 3, 1e-15);
    EXPECT_NEAR(noh.at(0.1, t).rho, 64.0, 1e-12);
    EXPECT_NEAR(noh.at(0.1, t).u, 0.5, 1e-15);
    EXPECT_NEAR(noh.at(0.3, t).rho, std::pow(1 + t / 0.3, 2), 1e-12);
    EXPECT_EQ(noh.at(0.3, t).v, -1.0);
}

TEST(ExactDensity, SedovTableMatchesDirectEvaluation) {
    SedovSolution s(5.0 / 3.0);
    auto table = ExactDensity::sedov(5.0 / 3.0, 1.0, 1.0);
    const double t = 0.05, rs = s.shock_radius(1, 1, t);
    for (double f : {0.2, 0.5, 0.8, 0.95, 0.999})
        EXPECT_NEAR(table(f * rs, t), s.at(f * rs, t, 1, 1).rho, 2e-3) << f;
    EXPECT_EQ(table(1.2 * rs, t), 1.0);
}
