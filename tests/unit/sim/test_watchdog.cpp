// The conservation watchdog (sim/watchdog.hpp): a real energy jump is reported, and the last
// step of a run, shortened to end at t_end, is not (its row carries the error of the full step
// before it: Sedov -n 40 --t-end 0.05 used to roll back its last step forever).
#include <gtest/gtest.h>

#include "exasph/sim/watchdog.hpp"

using namespace exasph;

namespace {
Diagnostics row(double dt, double etot) {
    Diagnostics d;
    d.dt = dt;
    d.etot = etot;
    d.mass = 1;
    d.power_abs = 34; // Sedov -n 40 at t = 0.05
    return d;
}
} // namespace

TEST(Watchdog, AShortenedLastStepIsNotCorruption) {
    const Diagnostics prev = row(6.5e-4, 0.99994), last = row(3.5e-6, 0.99994 - 2.5e-4);
    EXPECT_EQ(conservation_violation(prev, last, 1.0, true), "");
}

TEST(Watchdog, AnEnergyJumpIsReported) {
    const Diagnostics prev = row(6.5e-4, 0.99994), now = row(6.5e-4, 0.99994 - 2e-2);
    EXPECT_NE(conservation_violation(prev, now, 1.0, true).find("total energy changed"),
              std::string::npos);
    Diagnostics moved = now;
    moved.etot = prev.etot - 2.5e-4;
    EXPECT_EQ(conservation_violation(prev, moved, 1.0, true), ""); // within 0.25 dt power
}

TEST(Watchdog, StirringWorkIsNotAViolation) {
    Diagnostics prev = row(6.5e-4, 1.0), now = row(6.5e-4, 1.1);
    EXPECT_NE(conservation_violation(prev, now, 1.0, false), "");
    now.e_stir = 0.1; // the stirring did that work
    EXPECT_EQ(conservation_violation(prev, now, 1.0, false), "");
}
