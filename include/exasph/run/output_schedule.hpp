#pragma once
#include <cmath>
#include <cstdint>

#include "exasph/config/config.hpp"
#include "exasph/run/checkpoint_interval.hpp"
#include "exasph/util/timer.hpp"

namespace exasph {

// When snapshots and checkpoints are due (-w, --checkpoint-every N|auto, --checkpoint-minutes).
class OutputSchedule {
  public:
    // `mtbf_seconds`: the run's MTBF, used by --checkpoint-every auto.
    OutputSchedule(const Config& cfg, double t_now, double mtbf_seconds = 0)
        : cfg_(cfg), mtbf_(mtbf_seconds) {
        if (cfg.snapshot_every_time > 0)
            next_snapshot_time_ =
                (std::floor(t_now / cfg.snapshot_every_time) + 1) * cfg.snapshot_every_time;
        if (cfg.checkpoint_minutes > 0) interval_ = 60.0 * cfg.checkpoint_minutes;
    }
    bool checkpointing() const {
        return cfg_.checkpoint_every > 0 || cfg_.checkpoint_minutes > 0 || cfg_.checkpoint_auto;
    }
    // Wall-clock checkpoints; with auto, the first comes after the first step (it measures C).
    bool clock_due(double wall_now) const {
        if (cfg_.checkpoint_auto && interval_ <= 0) return true;
        return interval_ > 0 && wall_now - last_checkpoint_wall_ >= interval_;
    }
    // Records a checkpoint that took `cost` seconds; with auto, returns the new interval (else 0).
    double checkpoint_written(double wall_now, double cost) {
        last_checkpoint_wall_ = wall_now;
        if (!cfg_.checkpoint_auto) return 0;
        interval_ = young_daly_interval(std::max(cost, 1e-6), mtbf_);
        return interval_;
    }
    bool checkpoint_due(std::int64_t step) const {
        return cfg_.checkpoint_every > 0 && step % cfg_.checkpoint_every == 0;
    }
    // Every N steps, or at the first step at or after each multiple of T.
    bool snapshot_due(std::int64_t step, double t) {
        if (cfg_.snapshot_every_steps > 0) return step % cfg_.snapshot_every_steps == 0;
        if (cfg_.snapshot_every_time <= 0 || t < next_snapshot_time_ * (1 - 1e-12)) return false;
        while (next_snapshot_time_ <= t * (1 + 1e-12))
            next_snapshot_time_ += cfg_.snapshot_every_time;
        return true;
    }

  private:
    const Config& cfg_;
    double mtbf_ = 0;
    double interval_ = 0; // wall seconds between clock checkpoints (0: none)
    double next_snapshot_time_ = 0;
    double last_checkpoint_wall_ = wall_seconds();
};

} // namespace exasph
