// Issue 8, acceptance 1 and 2: clean runs raise no alarm; single-bit flips injected into x, v, u,
// h, m of Sedov -n 16 (4096 particles, lattice; -n 20 until issue 16 trimmed CI) are detected, and
// with rollback the run ends bitwise equal to the clean run. A flip is "harmful" when, undetected
// (--on-sdc off), it changes some particle's final rho, v or u by more than 1e-3 (v relative to the
// largest speed) or the total mass, energy or momentum by more than 1e-6 relative, or it crashes
// the run. Set EXASPH_SDC_CSV=FILE to keep one row per injection (docs/resilience.md is made from
// it).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <random>

#include "exasph/util/mpi.hpp"
#include <gtest/gtest.h>

#include "exasph/config/scheme.hpp"
#include "exasph/run/setup.hpp"
#include "exasph/sim/simulation.hpp"

using namespace exasph;

namespace {

struct State {
    double rho, vx, vy, vz, u;
};

struct Outcome {
    bool crashed = false;
    std::string error;
    std::map<std::uint64_t, State> particles;
    double mass = 0, etot = 0, p[3] = {0, 0, 0}, pabs = 0;
    std::int64_t recoveries = 0, detected_at = -1;
    std::string summary;
};

// `steps` steps, or to t_end when it is given.
Outcome run(const Config& cfg, int steps, double t_end = -1) {
    Outcome o;
    try {
        Simulation<double> sim(cfg, make_case(cfg, MPI_COMM_SELF), MPI_COMM_SELF);
        if (t_end > 0) sim.set_end_time(t_end);
        while (t_end > 0 ? sim.time() < t_end : sim.step_count() < steps) sim.step();
        const auto& ps = sim.particles();
        for (std::size_t i = 0; i < sim.n_owned(); ++i)
            o.particles[ps.id[i]] = {ps.value(Field::rho, i), ps[Field::vx][i], ps[Field::vy][i],
                                     ps[Field::vz][i], ps[Field::u][i]};
        const auto& d = sim.diagnostics();
        o.mass = d.mass;
        o.etot = d.etot;
        for (int k = 0; k < 3; ++k) o.p[k] = d.momentum[k];
        o.pabs = d.momentum_abs;
        o.recoveries = sim.safety().recoveries();
        o.detected_at = sim.safety().detection_step();
        o.summary = sim.safety().summary();
    } catch (const std::exception& e) {
        o.crashed = true;
        o.error = e.what();
    }
    return o;
}

// Worst change against the clean run (the harm criterion's quantities).
bool harmful(const Outcome& o, const Outcome& clean) {
    if (o.crashed || o.particles.size() != clean.particles.size()) return true;
    double vmax = 0;
    for (const auto& [id, s] : clean.particles)
        vmax = std::max({vmax, std::abs(s.vx), std::abs(s.vy), std::abs(s.vz)});
    for (const auto& [id, c] : clean.particles) {
        auto it = o.particles.find(id);
        if (it == o.particles.end()) return true;
        const State& s = it->second;
        if (!(std::abs(s.rho - c.rho) <= 1e-3 * std::abs(c.rho))) return true;
        if (!(std::abs(s.u - c.u) <= 1e-3 * std::abs(c.u))) return true;
        for (double dv : {s.vx - c.vx, s.vy - c.vy, s.vz - c.vz})
            if (!(std::abs(dv) <= 1e-3 * vmax)) return true;
    }
    auto rel = [](double a, double b, double scale) { return std::abs(a - b) / scale; };
    if (!(rel(o.mass, clean.mass, clean.mass) <= 1e-6)) return true;
    if (!(rel(o.etot, clean.etot, std::abs(clean.etot)) <= 1e-6)) return true;
    for (int k = 0; k < 3; ++k)
        if (!(rel(o.p[k], clean.p[k], clean.pabs) <= 1e-6)) return true;
    return false;
}

bool bitwise_equal(const Outcome& a, const Outcome& b) {
    if (a.crashed || b.crashed || a.particles.size() != b.particles.size()) return false;
    for (const auto& [id, s] : a.particles) {
        const State& t = b.particles.at(id);
        if (s.rho != t.rho || s.vx != t.vx || s.vy != t.vy || s.vz != t.vz || s.u != t.u)
            return false;
    }
    return a.etot == b.etot;
}

constexpr int kSide = 16;

Config sedov_lattice() {
    Config cfg;
    cfg.init = "sedov";
    cfg.side = kSide;
    cfg.lattice = true;
    return cfg;
}

} // namespace

TEST(Sdc, CleanRunsRaiseNoAlarm) {
    for (const char* init : {"square-patch", "sedov", "noh", "evrard"}) {
        Config cfg;
        cfg.init = init;
        cfg.side = 16;
        cfg.lattice = true;
        Outcome o = run(cfg, 40);
        EXPECT_FALSE(o.crashed) << init << ": " << o.error;
        EXPECT_EQ(o.recoveries, 0) << init << ": " << o.summary;
        std::printf("%s -n 16, 40 steps: %lld alarms\n", init, (long long)o.recoveries);
    }
}

// Issue 21: Evrard at ~1,000 particles moves E_tot in its second step by more than the old
// constant budget (7.0e-4 at -n 12, 1.3e-3 at -n 10 on a lattice: E_pot follows h through the
// softening while the gas is at rest) and used to roll back 100 times and die, later once. The
// budget now carries that share (Diagnostics::soft_abs): no alarm to t = 1.
TEST(Sdc, SmallEvrardRunsRaiseNoAlarmToTheEnd) {
    for (int side : {10, 12}) {
        Config cfg;
        cfg.init = "evrard";
        cfg.side = side;
        cfg.lattice = true;
        Outcome o = run(cfg, 0, 1.0);
        EXPECT_FALSE(o.crashed) << "evrard -n " << side << ": " << o.error;
        EXPECT_EQ(o.recoveries, 0) << "evrard -n " << side << ": " << o.summary;
        std::printf("evrard -n %d to t = 1: %lld alarms\n", side, (long long)o.recoveries);
    }
}

// Issue 21: the pe scheme makes u < 0 in Noh at -n 8 (lattice) before step 108. The state check
// used to take that for corruption, roll back 100 times and end with "no verified state"; the
// replay reproduces it, so the run now stops after one rollback and says what happened.
TEST(Sdc, AStateTheRunItselfProducesStopsTheRunAfterOneReplay) {
    Config cfg;
    cfg.init = "noh";
    cfg.side = 8;
    cfg.lattice = true;
    apply_scheme(cfg, Scheme::pe);
    Outcome o = run(cfg, 200);
    ASSERT_TRUE(o.crashed);
    EXPECT_NE(o.error.find("the state check before step 108 found the same problem again"),
              std::string::npos)
        << o.error;
    EXPECT_NE(o.error.find("u is negative): the run itself produced this state"), std::string::npos)
        << o.error;
}

TEST(Sdc, InjectedBitFlipsAreDetectedAndRolledBack) {
    const int steps = 6, injections = 300;
    Config clean_cfg = sedov_lattice();
    const Outcome clean = run(clean_cfg, steps);
    ASSERT_FALSE(clean.crashed) << clean.error;
    ASSERT_EQ(clean.recoveries, 0) << clean.summary;
    const Field fields[] = {Field::x,  Field::y, Field::z, Field::vx, Field::vy,
                            Field::vz, Field::u, Field::h, Field::m};
    std::mt19937_64 rng(2026);
    std::ofstream csv;
    if (const char* path = std::getenv("EXASPH_SDC_CSV")) {
        csv.open(path);
        csv << "step,field,id,bit,harmful,detected,detection_delay,rollback_equal,mechanism\n";
    }
    int n_harmful = 0, n_harmful_detected = 0, n_detected = 0, n_rollback_equal = 0;
    for (int k = 0; k < injections; ++k) {
        const int step = 2 + int(rng() % 3); // 2..4
        const Field f = fields[rng() % 9];
        const std::uint64_t id = rng() % (kSide * kSide * kSide);
        const int bit = int(rng() % 64);
        const std::string spec = std::to_string(step) + ":" + std::string(field_info(f).name) +
                                 ":" + std::to_string(id) + ":" + std::to_string(bit);
        Config off = sedov_lattice();
        off.on_sdc = SdcPolicy::off;
        off.inject_fault = spec;
        const bool harm = harmful(run(off, steps), clean);
        Config on = sedov_lattice();
        on.on_sdc = SdcPolicy::rollback;
        on.sdc_rollback_every = 2;
        on.sdc_rollback_store = RollbackStore::memory; // the disk store is tested by io_sdc_mpi
        on.inject_fault = spec;
        const Outcome guarded = run(on, steps);
        const bool detected = guarded.recoveries > 0 && guarded.detected_at >= step &&
                              guarded.detected_at <= step + 2;
        const bool equal = bitwise_equal(guarded, clean);
        n_harmful += harm;
        n_harmful_detected += harm && detected;
        n_detected += detected;
        n_rollback_equal += equal;
        // Which defences fired: the hash, a physics invariant (reported after it), the watchdog.
        const std::string& sm = guarded.summary;
        const bool by_hash = sm.find("hash mismatch") != std::string::npos;
        const bool by_invariant = guarded.recoveries > 0 &&
                                  sm.find("watchdog") == std::string::npos &&
                                  (!by_hash || sm.find("mismatch); particle") != std::string::npos);
        const std::string mech = std::string(by_hash ? "hash" : "") +
                                 (by_hash && by_invariant ? "+" : "") +
                                 (by_invariant ? "invariant" : "") +
                                 (sm.find("watchdog") != std::string::npos ? "watchdog" : "");
        if (csv)
            csv << step << "," << field_info(f).name << "," << id << "," << bit << "," << harm
                << "," << detected << "," << (detected ? guarded.detected_at - step : -1) << ","
                << equal << "," << mech << "\n";
        if (harm && !detected) std::printf("harmful flip not detected: %s\n", spec.c_str());
        if (!equal)
            std::printf("rollback run differs from the clean run: %s (%s)\n", spec.c_str(),
                        guarded.crashed ? guarded.error.c_str() : guarded.summary.c_str());
    }
    std::printf("%d injections: %d harmful, %d of them detected within 2 steps; %d detected in "
                "all; %d runs with rollback equal to the clean run (bitwise)\n",
                injections, n_harmful, n_harmful_detected, n_detected, n_rollback_equal);
    EXPECT_GE(n_harmful_detected, 0.99 * n_harmful);
    EXPECT_EQ(n_rollback_equal, injections);
}
