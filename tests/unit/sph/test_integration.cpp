// Time integration and smoothing-length update (physics.md §2, 7).
#include <cmath>

#include <limits>

#include <gtest/gtest.h>

#include "exasph/sph/av_switch.hpp"
#include "exasph/sph/integrator.hpp"
#include "exasph/sph/smoothing_length.hpp"
#include "exasph/sph/timestep.hpp"

using namespace exasph;

TEST(Press, ExactForConstantAccelerationWithVariableSteps) {
    // x(t) = x0 + v0 t + a t^2 / 2, sampled at irregular times.
    const double x0 = 1.5, v0 = -2.0, a = 3.0;
    auto exact = [&](double t) { return x0 + v0 * t + 0.5 * a * t * t; };
    double dts[] = {0.1, 0.13, 0.07, 0.2, 0.05};
    double t_prev = -0.08, t = 0.0;
    double x_m1 = exact(t_prev), x = exact(t);
    for (double dt : dts) {
        auto r = press_update(x, x_m1, a, dt, t - t_prev);
        t_prev = t;
        t += dt;
        x_m1 = x;
        x = r.x;
        EXPECT_NEAR(x, exact(t), 1e-13);
        EXPECT_NEAR(r.v, v0 + a * t, 1e-13);
    }
}

TEST(AdamsBashforth, ExactForLinearRate) {
    // du/dt = b + c t  ->  u(t) = u0 + b t + c t^2 / 2
    const double u0 = 1.0, b = 0.5, c = -2.0;
    double t_prev = -0.1, t = 0.0, u = u0;
    for (double dt : {0.1, 0.05, 0.15}) {
        u = adams_bashforth_energy(u, b + c * t, b + c * t_prev, dt, t - t_prev);
        t_prev = t;
        t += dt;
        EXPECT_NEAR(u, u0 + b * t + 0.5 * c * t * t, 1e-14);
    }
}

TEST(SmoothingLength, FixedPointAtTargetAndMonotone) {
    EXPECT_DOUBLE_EQ(update_smoothing_length(2.0, 100.0, 100.0), 2.0);
    EXPECT_LT(update_smoothing_length(2.0, 150.0, 100.0), 2.0);
    EXPECT_GT(update_smoothing_length(2.0, 50.0, 100.0), 2.0);
    EXPECT_TRUE(std::isfinite(update_smoothing_length(2.0, 0.0, 100.0)));
}

TEST(TimeStep, CourantAndGrowthLimit) {
    EXPECT_DOUBLE_EQ(courant_time_step(1.0, 10.0, 5.0, 0.2), 0.02);
    EXPECT_DOUBLE_EQ(courant_time_step(1.0, 0.0, 5.0, 0.2), 0.2);
    EXPECT_DOUBLE_EQ(limit_time_step(1.0, 0.5), 0.55);
    EXPECT_DOUBLE_EQ(limit_time_step(0.3, 0.5), 0.3);
}

// A particle without a limit gives +infinity (the minimum's identity), in float as in double,
// and never decides the step: the growth cap does.
TEST(TimeStep, NoLimitIsInfinityAndNeverDecides) {
    EXPECT_EQ(courant_time_step(1.0, 0.0, 0.0, 0.2), std::numeric_limits<double>::infinity());
    EXPECT_EQ(courant_time_step(1.0f, 0.0f, 0.0f, 0.2f), std::numeric_limits<float>::infinity());
    EXPECT_EQ(acceleration_time_step(1.0, 0.0, 0.0, 0.0, 0.2),
              std::numeric_limits<double>::infinity());
    EXPECT_EQ(energy_time_step(1.0, 0.5, 0.3), std::numeric_limits<double>::infinity());
    EXPECT_DOUBLE_EQ(energy_time_step(1.0, -0.5, 0.3), 0.6);
    EXPECT_DOUBLE_EQ(limit_time_step(courant_time_step(1.0, 0.0, 0.0, 0.2), 0.5), 0.55);
}

TEST(AvSwitch, RisesUnderCompressionAndDecaysWithout) {
    // No compression: alpha relaxes towards alpha_min with e-folding time h / (decay c).
    double a = evolve_alpha(1.0, 0.0, 1.0, 1.0, 5.0, 0.05, 1.0, 0.2);
    EXPECT_NEAR(a, 0.05 + 0.95 * std::exp(-1.0), 1e-12);
    // Expansion does not raise it.
    EXPECT_LE(evolve_alpha(0.1, 5.0, 1.0, 1.0, 0.1, 0.05, 1.0, 0.2), 0.1);
    // Strong compression drives it to alpha_max and no further.
    EXPECT_DOUBLE_EQ(evolve_alpha(0.05, -1e3, 1.0, 1.0, 0.1, 0.05, 1.0, 0.2), 1.0);
    double up = evolve_alpha(0.05, -1.0, 1.0, 1.0, 0.1, 0.05, 1.0, 0.2);
    EXPECT_GT(up, 0.05);
    EXPECT_LT(up, 1.0);
}
