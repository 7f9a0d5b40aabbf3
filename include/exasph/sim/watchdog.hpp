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
    0.25; // of dt * gross power; clean runs reach 0.07 (0.18 in the Evrard collapse) after step 1

// The part of the total energy that must be conserved: stirring puts energy in (e_stir, its
// work so far).
inline double energy_change(const Diagnostics& prev, const Diagnostics& now) {
    return (now.etot - now.e_stir) - (prev.etot - prev.e_stir);
}

// What one step may change the total energy by on a clean run.
inline double energy_budget(const Diagnostics& prev, const Diagnostics& now) {
    // The first step after a start or a rollback has no previous accelerations (power 0) and
    // carries the integrator's start-up error (up to 3/4 of dt * power on clean runs).
    // The reported velocities are the Press scheme's predictions at the end of each step, so
    // the change between two rows carries the error of the previous step's prediction too:
    // the budget takes the longer of the two steps (a step shortened to end at t_end can be
    // 1000 times shorter than the one before it, with the error of that one).
    // With gravity, E_pot also moves with the softening when h changes (physics.md §2 relaxes h
    // towards ng0 neighbours, which the softening correction's force does not pay for): the
    // previous step's h change moved it by about sum m |zeta dh| (Diagnostics::soft_abs; Evrard
    // -n 10, step 2: 1.35e-3 estimated, 1.27e-3 seen); and the tree's approximation changes as
    // its nodes open and close (2e-4 |E_pot|). Evrard -n 8 to 16 to t = 1 reach at most 0.64
    // of the budget without that last term (the collapse, where dt grows 10 % a step).
    // A step that the time-step limit cut to 1/r of the one before it shows that the dynamics
    // sped up during that one, which then ran r times longer than its end allowed; its error
    // shows in this row and grows with r (Evrard -n 10 --lattice --scheme std, step 141:
    // r = 4.1, 0.254 dt P). The budget grows with r (at most 10 times).
    const double sped_up = now.dt > 0 ? std::clamp(prev.dt / now.dt, 1.0, 10.0) : 1.0;
    const double factor = (prev.power_abs > 0 ? kWatchdogEnergyBudget : 1.5) * sped_up;
    const double dt = std::max(now.dt, prev.dt);
    return factor * dt * std::max(now.power_abs, prev.power_abs) + 2 * prev.soft_abs +
           2e-4 * std::abs(now.epot) + 1e-12 * std::abs(now.etot);
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
