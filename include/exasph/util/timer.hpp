#pragma once
#include <array>
#include <chrono>
#include <cstddef>

namespace exasph {

// Wall-clock seconds since an arbitrary epoch.
inline double wall_seconds() {
    using clock = std::chrono::steady_clock;
    return std::chrono::duration<double>(clock::now().time_since_epoch()).count();
}

// Accumulates wall time per named phase of the step. Phases are an enum so that the hot path
// indexes an array; names come from the caller's table.
template <std::size_t NumPhases>
class PhaseTimer {
  public:
    void start() { t0_ = wall_seconds(); }
    // Charges the time since the last start()/stop() to `phase` and restarts the clock.
    void stop(std::size_t phase) {
        double t = wall_seconds();
        step_[phase] += t - t0_;
        t0_ = t;
    }
    // A new step: its phase times start at zero, and so does the clock.
    void begin_step() {
        step_.fill(0.0);
        start();
    }
    void end_step() {
        for (std::size_t i = 0; i < NumPhases; ++i) total_[i] += step_[i];
    }
    const std::array<double, NumPhases>& step_times() const { return step_; }
    double step_total() const {
        double sum = 0;
        for (double t : step_) sum += t;
        return sum;
    }
    const std::array<double, NumPhases>& total_times() const { return total_; }

  private:
    double t0_ = 0.0;
    std::array<double, NumPhases> step_{};
    std::array<double, NumPhases> total_{};
};

} // namespace exasph
