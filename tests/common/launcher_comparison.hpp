#pragma once
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "exasph/run/setup.hpp"
#include "exasph/sim/simulation.hpp"
#include "one_rank_reference.hpp"

namespace exasph::testref {

// Runs `steps` steps of cfg with launcher L (one rank); the owned state sorted by id.
template <class L>
std::vector<ParticleState> run_with(const Config& cfg, int steps, Diagnostics* diag) {
    Simulation<double, L> sim(cfg, make_case(cfg));
    for (int s = 0; s < steps; ++s) sim.step();
    EXPECT_EQ(sim.safety().recoveries(), 0);
    *diag = sim.diagnostics();
    auto st = owned_state(sim);
    std::sort(st.begin(), st.end(), [](const auto& a, const auto& b) { return a.id < b.id; });
    return st;
}

// The same run on launcher L as on the CPU path: every particle's rho, v, u and a within `tol`
// of the field's scale, and the conservation sums alike (issue 18).
template <class L>
void expect_same_as_cpu(const Config& cfg, int steps, double tol, const char* what) {
    Diagnostics cpu_diag, diag;
    const auto cpu = run_with<OmpLauncher>(cfg, steps, &cpu_diag);
    const auto other = run_with<L>(cfg, steps, &diag);
    ASSERT_EQ(cpu.size(), other.size());
    OneRankReference ref;
    for (const auto& s : cpu) ref.state[s.id] = s;
    const Differences d = compare_to_reference(other, ref);
    std::printf("%s -n %d, %d steps: %s vs CPU: rho %.2e v %.2e u %.2e a %.2e\n", cfg.init.c_str(),
                cfg.side, steps, what, d.rho, d.v, d.u, d.a);
    EXPECT_LT(d.rho, tol);
    EXPECT_LT(d.v, tol);
    EXPECT_LT(d.u, tol);
    EXPECT_LT(d.a, tol);
    EXPECT_NEAR(diag.etot, cpu_diag.etot, tol * std::abs(cpu_diag.etot));
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(diag.momentum[c], cpu_diag.momentum[c], tol * cpu_diag.momentum_abs);
    // L_z can be ~0 (Sedov): its scale is at least sum m |v| (times a unit length)
    EXPECT_NEAR(diag.angular_momentum[2], cpu_diag.angular_momentum[2],
                tol * std::max(std::abs(cpu_diag.angular_momentum[2]), cpu_diag.momentum_abs));
}

} // namespace exasph::testref
