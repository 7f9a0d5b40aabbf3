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

// The silent-data-corruption defences of issue 8 as one component around the step: the test
// fault injection, the state check at the start of a step, the rollback point, the conservation
// watchdog at its end, and the rollback itself. The step asks it at three places (before,
// cleared, after); everything else about corruption lives here.
template <class T>
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

    // Start of step `step`: injects the test fault (once: a rollback replays the step cleanly),
    // then checks the state at rest (and reports a change that the last step's seals found
    // after the diagnostics). Returns whether this rank found it corrupted.
    bool corrupted_before(ParticleSet<T>& ps, std::size_t n, const Box<T>& box, std::int64_t step,
                          double dt_m1, bool u_positive) {
        watchdog_fired_ = false;
        step_ = step;
        seals_.begin(step);
        if (fault_.phase < 0) inject_due(ps, n, -1);
        if (!on()) return false;
        detail_ = std::exchange(late_change_, std::string());
        if (detail_.empty()) detail_ = guard_.check(ps, n, box, dt_m1, press_ok_, u_positive);
        return !detail_.empty();
    }

    // The end of phase `phase` of the step in progress: the step's seals (sim/step_seals.hpp).
    // Returns whether this rank found a change (the step raises kStateChanged). Then the test
    // fault, if it is due now.
    bool after_phase(std::size_t phase, ParticleSet<T>& ps, std::size_t n) {
        const bool changed = on() && found(seals_.phase_ended(phase, ps, n));
        inject_due(ps, n, int(phase));
        return changed;
    }
    // Just before the update and the h update read what the step made (StepSeals).
    bool changed_before_update(const ParticleSet<T>& ps, std::size_t n) {
        return on() && found(seals_.before_update(ps, n));
    }
    bool changed_before_h_update(const ParticleSet<T>& ps, std::size_t n) {
        return on() && found(seals_.before_h_update(ps, n));
    }

    // Every sdc_rollback_every steps, once every rank has found the state clean, it becomes the
    // rollback point (keep_point), replacing the previous one in place (one copy of the state,
    // not two).
    bool point_due(std::int64_t step) const {
        return policy_ == SdcPolicy::rollback && step % every_ == 0;
    }
    void keep_point(const ParticleSet<T>& ps, std::size_t n, const RunPoint<T>& where) {
        point_state_.save(ps, n);
        point_ = where;
        have_point_ = true;
    }

    // End of a step: the step's seals (changed_mid_step: some rank's seals found a change,
    // seen by all through the diagnostics' flags), the conservation watchdog, then the
    // seal of the new state. Returns "" when the step stands, else the detector that refused
    // it (on every rank alike: both verdicts are global).
    // `before`: the diagnostics of the step before, or null when that step or this one was not
    // summed (--diagnostics-every): the watchdog then has nothing to compare.
    std::string verdict_after(const ParticleSet<T>& ps, std::size_t n, const Diagnostics* before,
                              const Diagnostics& now, double mass0, bool check_momentum,
                              bool changed_mid_step) {
        if (!on()) return "";
        if (changed_mid_step) return "the step's seals";
        // Block time steps conserve energy and momentum only to their truncation error (forces
        // between particles on different rungs act at different times): no watchdog there.
        const std::string why =
            press_scheme_ && before ? watchdog_.check(*before, now, mass0, check_momentum) : "";
        if (!why.empty()) {
            if (rank_ == 0) detail_ = "watchdog: " + why;
            watchdog_fired_ = true; // on every rank: the diagnostics are global
            return "the conservation watchdog";
        }
        // A change after the h update is this rank's own finding: the next step's state
        // check reports it, in that step's first collective.
        if (on()) late_change_ = seals_.at_guard_seal(guard_.seal(ps, n));
        press_ok_ = press_scheme_; // block steps keep no x_{n-1} of the Press scheme
        return "";
    }

    void seal(const ParticleSet<T>& ps, std::size_t n) {
        if (on()) guard_.seal(ps, n);
    }

    // All ranks, after a detection by `where` in or before step `step` of a run now at step
    // `current`: restores the rollback point's particles into ps and returns the rest of it, or
    // throws (abort, or nothing to roll back to).
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
        return point_;
    }

    std::int64_t recoveries() const { return recoveries_; }
    // The watchdog's message when it widened its energy budget, once (EnergyWatchdog).
    std::string take_notice() { return watchdog_.take_notice(); }
    // This rank's description of the last detection ("" if another rank detected it).
    const std::string& detail() const { return detail_; }
    const std::string& summary() const { return summary_; }
    std::int64_t detection_step() const { return detection_step_; }

  private:
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
    StepSeals<T> seals_;
    std::string late_change_; // what the seals found after the diagnostics, reported next step
    StateGuard<T> guard_;
    EnergyWatchdog watchdog_;
    StateStore<T> point_state_; // in memory, or on disk (--sdc-rollback-store disk)
    RunPoint<T> point_;
    bool have_point_ = false;
    FaultSpec fault_;
    bool fault_done_ = false, press_ok_ = false, watchdog_fired_ = false;
    bool press_scheme_ = true;           // global steps: the Press invariant and the watchdog hold
    std::int64_t state_check_step_ = -1; // the step the state check last rolled back
    std::int64_t recoveries_ = 0, detection_step_ = -1;
    std::string detail_, summary_;
};

} // namespace exasph
