#pragma once
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <utility>

#include "exasph/sim/watchdog.hpp"

namespace exasph {

// The conservation watchdog with a budget calibrated by the run itself (issue 21). A rollback
// replays a step bit for bit (a rolled-back run ends equal to the clean run: test_sdc), so an
// energy change that comes back identical when its step is replayed is what the integrator does
// at this resolution, not a flipped bit (a flip lives in one state copy and is gone after the
// rollback). (Evrard at ~1,000 particles, whose E_pot moves with h in its first steps, used to
// roll back until it gave up; the budget now estimates that share, sim/watchdog.hpp, and no
// clean run of the false-alarm sweep needs this.) The watchdog then accepts the step and widens
// its energy budget for the rest of the run to twice the change it saw, and says so (notice()). A
// real flip must then move the energy more than that to be caught here; the state check before each
// step does not depend on this budget.
class EnergyWatchdog {
  public:
    // "" when the step conserved what it must, else why it must be rolled back. Every rank
    // decides the same: the diagnostics are global sums.
    std::string check(const Diagnostics& prev, const Diagnostics& now, double mass0,
                      bool check_momentum) {
        std::string why = conservation_violation(prev, now, mass0, check_momentum, scale_);
        if (why.empty() || why.rfind("total energy", 0) != 0) return why;
        const double de = energy_change(prev, now);
        if (now.step != replay_step_ || de != replay_change_) {
            replay_step_ = now.step; // roll back; judged again when this step comes back
            replay_change_ = de;
            return why;
        }
        const double was = scale_;
        scale_ = 2 * std::abs(de) / energy_budget(prev, now);
        replay_step_ = -1;
        char buf[320];
        std::snprintf(buf, sizeof buf,
                      "the energy change of step %lld (%.3e) came back identical when the step "
                      "was replayed: the run's own integration error, not corruption; the "
                      "watchdog's energy budget is now %.3g times its default (was %.3g)",
                      (long long)now.step, de, scale_, was);
        notice_ = buf;
        return conservation_violation(prev, now, mass0, check_momentum, scale_);
    }

    // The budget's factor over the default (1 until the run showed a larger error of its own).
    double scale() const { return scale_; }

    // The last widening's message, once ("" when there is nothing new).
    std::string take_notice() { return std::exchange(notice_, std::string()); }

  private:
    double scale_ = 1;
    std::int64_t replay_step_ = -1; // the step last rolled back for its energy, and its change
    double replay_change_ = 0;
    std::string notice_;
};

} // namespace exasph
