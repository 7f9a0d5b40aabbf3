#pragma once
#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <string>
#include <unistd.h>
#include <utility>

#include "exasph/config/config.hpp"
#include "exasph/io/restart_state.hpp"
#include "exasph/sim/diagnostics.hpp"
#include "exasph/sim/energy_watchdog.hpp"
#include "exasph/sim/fault.hpp"
#include "exasph/sim/phases.hpp"
#include "exasph/sim/state_guard.hpp"
#include "exasph/sim/state_store.hpp"
#include "exasph/sim/step_seals.hpp"

namespace exasph {

// Where a rollback returns to, besides the particles.
template <class T>
struct RunPoint {
    RestartState rs;
    Box<T> box;
    Diagnostics diag;
};

// What a step brought to the net's verdict (SafetyNet::conclude). `step` is the clock's step
// when the verdict is asked (after the update: the step just made). The votes are what every
// rank has seen in the step's collectives (ControlFlags); `now` is set when the step advanced,
// `before` when it and the step before were both summed (the watchdog compares them).
struct StepOutcome {
    std::int64_t step = 0;
    bool corrupt_before = false; // kCorruptBefore: a rank's check at rest found corruption
    bool state_changed = false;  // kStateChanged: a rank's seals found a change
    const Diagnostics* before = nullptr;
    const Diagnostics* now = nullptr;
    double mass0 = 0;
    bool check_momentum = false; // no external force: momentum is conserved
};

// What the start of a step tells the step: whether this rank found its state corrupted (the
// step votes it), and whether a rollback point is due (kept at the next clean sync).
struct StepStart {
    bool corrupt = false;
    bool point_due = false;
};

// The silent-data-corruption defences of issue 8 as one component around the step: the test
// fault injection, the state check at the start of a step, the seals inside it, the rollback
// point, the conservation watchdog at its end, and the rollback itself. The step meets it at
// four places (docs/architecture.md "Step vs. safety"): begin_step, phase_ended (from the one
// call that ends each phase), keep_point (after a sync whose vote was clean) and conclude (the
// verdict, with the rollback when the step does not stand); everything else about corruption
// lives here. The seals' hashes run on the launcher L.
template <class T, class L = DefaultLauncher>
class SafetyNet {
  public:
    SafetyNet(const Config& cfg, int rank)
        : policy_(cfg.on_sdc), every_(std::max(cfg.sdc_rollback_every, 1)), rank_(rank),
          press_scheme_(cfg.timesteps == TimeStepping::global) {
        if (cfg.sdc_rollback_store == RollbackStore::disk) {
            const std::string dir =
                cfg.sdc_rollback_dir.empty() ? cfg.out_dir : cfg.sdc_rollback_dir;
            // the process id keeps runs that share a scratch directory apart
            const std::string name = ".sdc-rollback-rank" + std::to_string(rank) + "-" +
                                     std::to_string(::getpid()) + ".bin";
            point_state_.keep_on_disk((std::filesystem::path(dir) / name).string());
        }
        if (!cfg.inject_fault.empty()) fault_ = parse_fault(cfg.inject_fault);
    }

    bool on() const { return policy_ != SdcPolicy::off; }

    // Start of step `step` (1 for the run's first), the owned particles [0, n) at rest in `box`:
    // seals the state when the run starts or has rolled back (nothing changes it between
    // steps), injects the test fault when due (once: a rollback replays the step cleanly), then
    // checks the state (or reports a change the last step's seals found after its diagnostics).
    StepStart begin_step(ParticleSet<T>& ps, std::size_t n, const Box<T>& box, std::int64_t step,
                         double dt_m1, bool u_positive) {
        if (!sealed_ && on()) guard_.seal(ps, n);
        sealed_ = true;
        watchdog_fired_ = false;
        step_ = step;
        seals_.begin(step);
        if (fault_.phase < 0) inject_due(ps, n, -1);
        const bool point_due = policy_ == SdcPolicy::rollback && (step - 1) % every_ == 0;
        if (!on()) return {false, point_due};
        detail_ = std::exchange(late_change_, std::string());
        if (detail_.empty()) detail_ = guard_.check(ps, n, box, dt_m1, press_ok_, u_positive);
        return {!detail_.empty(), point_due};
    }

    // The end of phase `phase` of the step in progress: the step's seals (sim/step_seals.hpp),
    // then the test fault if it is due now, then the comparisons that the next phase's reads
    // need (the update reads the state and the accelerations: after the time step, or with
    // block steps, which close and open steps in the time-step phase, after gravity; the h
    // update reads the updated state). Returns whether this rank found a change (the step
    // raises kStateChanged).
    bool phase_ended(Phase phase, ParticleSet<T>& ps, std::size_t n) {
        bool changed = on() && found(seals_.phase_ended(phase, ps, n));
        inject_due(ps, n, int(phase));
        if (phase == (press_scheme_ ? kTimeStep : kGravity))
            changed = (on() && found(seals_.before_update(ps, n))) || changed;
        if (phase == kUpdate) changed = (on() && found(seals_.before_h_update(ps, n))) || changed;
        return changed;
    }

    // When StepStart::point_due, once every rank has found the state clean, it becomes the
    // rollback point, replacing the previous one in place (one copy of the state, not two).
    void keep_point(const ParticleSet<T>& ps, std::size_t n, const RunPoint<T>& where) {
        point_state_.save(ps, n);
        point_ = where;
        have_point_ = true;
    }

    // The verdict on a step: null when it stands (the new state is sealed for the next step's
    // check), else the rollback point, its particles restored into ps, after a detection that
    // every rank has seen alike (all votes are global); throws when there is nothing to roll
    // back to, or with --on-sdc abort.
    const RunPoint<T>* conclude(ParticleSet<T>& ps, std::size_t n, const StepOutcome& o) {
        const std::string next = std::to_string(o.step + 1);
        if (o.corrupt_before)
            return &roll_back(ps, "the state check before step " + next, o.step + 1, o.step);
        if (!o.now && o.state_changed) // voted before the update, in the time step's collective
            return &roll_back(ps, "the step's seals by step " + next, o.step + 1, o.step);
        const std::string by = verdict_after(ps, n, o);
        if (by.empty()) return nullptr;
        return &roll_back(ps, by + " after step " + std::to_string(o.step), o.step, o.step);
    }

    std::int64_t recoveries() const { return recoveries_; }
    // The watchdog's message when it widened its energy budget, once (EnergyWatchdog).
    std::string take_notice() { return watchdog_.take_notice(); }
    // This rank's description of the last detection ("" if another rank detected it).
    const std::string& detail() const { return detail_; }
    const std::string& summary() const { return summary_; }
    std::int64_t detection_step() const { return detection_step_; }

  private:
    // After the diagnostics: the step's seals (a change some rank found mid-step), the
    // conservation watchdog, then the seal of the new state. "" when the step stands, else the
    // detector that refused it.
    std::string verdict_after(const ParticleSet<T>& ps, std::size_t n, const StepOutcome& o) {
        if (!on()) return "";
        if (o.state_changed) return "the step's seals";
        // Block time steps conserve energy and momentum only to their truncation error (forces
        // between particles on different rungs act at different times): no watchdog there.
        const std::string why = press_scheme_ && o.before
                                    ? watchdog_.check(*o.before, *o.now, o.mass0, o.check_momentum)
                                    : "";
        if (!why.empty()) {
            if (rank_ == 0) detail_ = "watchdog: " + why;
            watchdog_fired_ = true; // on every rank: the diagnostics are global
            return "the conservation watchdog";
        }
        // A change after the h update is this rank's own finding: the next step's state
        // check reports it, in that step's first collective.
        late_change_ = seals_.at_guard_seal(guard_.seal(ps, n));
        press_ok_ = press_scheme_; // block steps keep no x_{n-1} of the Press scheme
        return "";
    }

    // All ranks, after a detection by `where` in or before step `step` of a run now at step
    // `current`: restores the rollback point's particles into ps and returns the rest of it, or
    // throws (abort, or nothing to roll back to). The next step's start seals the state again.
    const RunPoint<T>& roll_back(ParticleSet<T>& ps, const std::string& where, std::int64_t step,
                                 std::int64_t current) {
        ++recoveries_;
        detection_step_ = step;
        const bool can = policy_ == SdcPolicy::rollback && have_point_ && recoveries_ <= 100 &&
                         point_.rs.step < current + 1;
        const std::string detail = detail_.empty() ? "found on another rank" : detail_;
        if (!can)
            throw Error("silent data corruption detected by " + where + " (" + detail + "); " +
                            (policy_ == SdcPolicy::abort ? "aborting (--on-sdc abort)"
                                                         : "no verified state to roll back to"),
                        1, true);
        // The state check finding a bad state again at the same step after the rollback: the
        // replay reproduced it, so the run itself made that state (e.g. u < 0 from a scheme
        // that fails at this resolution), not a flip, and more rollbacks cannot mend it.
        const bool by_state_check = !watchdog_fired_;
        if (by_state_check && step == state_check_step_)
            throw Error(where + " found the same problem again after replaying the step (" +
                            detail +
                            "): the run itself produced this state, not corruption; "
                            "stopping (a larger -n, a smaller --courant or another "
                            "--scheme may avoid it)",
                        1, true);
        state_check_step_ = by_state_check ? step : -1;
        summary_ = "corruption detected by " + where + " (" + detail + "): rolled back to step " +
                   std::to_string(point_.rs.step);
        point_state_.restore(ps);
        press_ok_ = false; // accelerations are not part of the rollback point
        sealed_ = false;
        return point_;
    }

    bool found(std::string change) {
        if (change.empty()) return false;
        detail_ = std::move(change);
        return true;
    }
    void inject_due(ParticleSet<T>& ps, std::size_t n, int phase) {
        if (fault_.step != step_ || fault_.phase != phase || fault_done_) return;
        inject_fault(ps, n, fault_); // on the rank that owns the particle
        fault_done_ = true;
    }

    SdcPolicy policy_;
    std::int64_t every_;
    int rank_;
    std::int64_t step_ = 0; // the step in progress
    StepSeals<T, L> seals_;
    std::string late_change_; // what the seals found after the diagnostics, reported next step
    StateGuard<T, L> guard_;
    EnergyWatchdog watchdog_;
    StateStore<T> point_state_; // in memory, or on disk (--sdc-rollback-store disk)
    RunPoint<T> point_;
    bool have_point_ = false;
    FaultSpec fault_;
    bool fault_done_ = false, press_ok_ = false, watchdog_fired_ = false, sealed_ = false;
    bool press_scheme_ = true;           // global steps: the Press invariant and the watchdog hold
    std::int64_t state_check_step_ = -1; // the step the state check last rolled back
    std::int64_t recoveries_ = 0, detection_step_ = -1;
    std::string detail_, summary_;
};

} // namespace exasph
