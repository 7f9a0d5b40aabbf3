#pragma once
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "exasph/sim/diagnostics.hpp"

namespace exasph {

// Conservation watchdog (issue 8): compares a step's totals with the previous step and the
// start. Mass never changes (round-off of the sum only); momentum is conserved to round-off by
// the symmetric hydro pairs (not by tree gravity, nor by the periodic minimum image for angular
// momentum, which is therefore not checked); the total energy may change in one step by the
// time-integration error, a small fraction of the energy moved between forms in that step,
// dt * sum m (|v.a| + |du|). Returns "" or what was violated.
inline constexpr double kWatchdogEnergyBudget =
    0.25; // clean runs: <= 0.07 after step 1 // of dt * gross power (see docs/resilience)

// The part of the total energy that must be conserved: stirring puts energy in (e_stir, its
// work so far).
inline double energy_change(const Diagnostics& prev, const Diagnostics& now) {
    return (now.etot - now.e_stir) - (prev.etot - prev.e_stir);
}

// What one step may change the total energy by on a clean run.
inline double energy_budget(const Diagnostics& prev, const Diagnostics& now) {
    // The first step after a start or a rollback has no previous accelerations (power 0) and
    // carries the integrator's start-up error (up to 3/4 of dt * power on clean runs); with
    // gravity the potential energy also moves with the adaptive softening and the tree
    // (~5e-4 of |E_pot| in the first steps of Evrard).
    // The reported velocities are the Press scheme's predictions at the end of each step, so
    // the change between two rows carries the error of the previous step's prediction too:
    // the budget takes the longer of the two steps (a step shortened to end at t_end can be
    // 1000 times shorter than the one before it, with the error of that one).
    const double factor = prev.power_abs > 0 ? kWatchdogEnergyBudget : 1.5;
    const double dt = std::max(now.dt, prev.dt);
    return factor * dt * std::max(now.power_abs, prev.power_abs) + 1e-12 * std::abs(now.etot) +
           1e-3 * std::abs(now.epot);
}

// energy_scale widens the energy budget (EnergyWatchdog, after the run showed its own error).
inline std::string conservation_violation(const Diagnostics& prev, const Diagnostics& now,
                                          double mass0, bool check_momentum,
                                          double energy_scale = 1) {
    auto rel = [](double a, double b) { return std::abs(a - b) / std::max(std::abs(b), 1e-300); };
    auto num = [](double v) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.3e", v);
        return std::string(buf);
    };
    if (rel(now.mass, mass0) > 1e-12)
        return "total mass changed by " + num(rel(now.mass, mass0)) + " (relative)";
    const double budget = energy_scale * energy_budget(prev, now);
    const double de = energy_change(prev, now);
    if (std::abs(de) > budget)
        return "total energy changed by " + num(de) + " in one step (budget " + num(budget) + ")";
    if (check_momentum) {
        const double dp =
            std::hypot(now.momentum[0] - prev.momentum[0], now.momentum[1] - prev.momentum[1],
                       now.momentum[2] - prev.momentum[2]);
        // Round-off scale: the momenta and the impulses of the step.
        const double scale = std::max(now.momentum_abs, prev.momentum_abs) + now.dt * now.force_abs;
        if (dp > 1e-10 * scale + 1e-300)
            return "linear momentum changed by " + num(dp) + " in one step (scale " + num(scale) +
                   ")";
    }
    return "";
}

} // namespace exasph
