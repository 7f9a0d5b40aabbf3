#pragma once
#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "exasph/config/config.hpp"
#include "exasph/domain/domain.hpp"
#include "exasph/io/restart_state.hpp"
#include "exasph/particles/particle_set.hpp"
#include "exasph/sim/diagnostics.hpp"
#include "exasph/sph/block_passes.hpp"
#include "exasph/sph/passes.hpp"
#include "exasph/util/error.hpp"

namespace exasph {

// BlockClock::work_bound(): summed over the blocks so far.
struct BlockWorkBound {
    double global_steps = 0, own_limit_updates = 0; // per particle
};

// What BlockClock::choose needs to know of the run.
struct BlockStepInputs {
    bool first;         // the run's first step (nothing to close; steps at most dt0)
    double dt0;         // the case's first step
    double accel_eps;   // > 0 with gravity: the acceleration limit
    double time, t_end; // t_end < 0: none
};

// Block time steps (--timesteps block): the hierarchy's clock and the sub-step's active set.
// A block runs from t0 to end in 2^kMaxRung ticks; at its first tick every particle is active
// and the block's length is chosen (the smallest own step limit times the power of two that
// reaches the largest, at most 2^kMaxRung, and no further than t_end). A sub-step computes forces
// for the particles active at this tick, closes and reopens their steps (with the limiter's
// wake-ups), then drifts everyone to the next tick at which any particle is active. Rollback points
// are taken at block boundaries (at_boundary()), where every particle's state is synchronised; a
// checkpoint inside a block holds the clock (where()) and the derived fields.
template <class T, class L>
class BlockClock {
  public:
    static constexpr double kTicks = double(std::int64_t(1) << kMaxRung);
    // An inactive particle's work in a sub-step relative to an active one's (drift, sort, trees,
    // halos): Evrard -n 40 after t = 0.8 on 4 ranks of ~8,400 particles, a sub-step took 0.097 s
    // plus 70 us per active particle of the rank (fit over 128 sub-steps): 12 us per particle,
    // 0.17 of an active one (docs/scaling.md).
    static constexpr float kInactiveCost = 0.15f;

    // Refuses what block steps do not handle yet; allocates the rung and half-step fields and
    // makes the derived fields move with the particles (inactive ones keep theirs).
    BlockClock(ParticleSet<T>& ps, const Config& cfg, bool stir)
        : limiter_(!cfg.no_timestep_limiter) {
        if (stir)
            throw input_error("--timesteps block: not yet with driven turbulence (--stir-mach)",
                              true);
        for (Field f : {Field::rung, Field::vhx, Field::vhy, Field::vhz, Field::uh, Field::dtc})
            ps.enable(f);
        ps.carry(kState | kDerived);
    }

    // A restart or rollback: `last_block` is the length of the block that ended last (its steps
    // are closed by the next sub-step when `at` is a block's end); `at` inside a block: the
    // sub-step reached there (a checkpoint's, whose derived fields were restored with it).
    void resume(double last_block, const BlockPoint& at) {
        last_tick_dt_ = last_block / kTicks;
        tick_ = at.tick;
        if (tick_ == 0) return;
        t0_ = at.start;
        end_ = at.end;
        tick_dt_ = (end_ - t0_) / kTicks; // as start_block computed it
    }
    // What the limits at the blocks' starts imply (each held for its block): the steps global
    // time steps at the smallest limit would have taken, and the updates per particle had each
    // particle stepped with all of its own limit. Their ratio bounds the work saved.
    const BlockWorkBound& work_bound() const { return bound_; }
    // Where the clock stands (tick 0: a block's end).
    BlockPoint where() const { return tick_ == 0 ? BlockPoint{} : BlockPoint{tick_, t0_, end_}; }
    bool at_boundary() const { return tick_ == 0; }
    double last_block() const { return last_tick_dt_ * kTicks; }
    std::int64_t tick() const { return tick_; }

    // The owned particles active at this tick: flags and their list; the shortest rung and the
    // active particles of each rung go to `work`.
    void select(const ParticleSet<T>& ps, std::size_t n, StepWork& work) {
        active_.assign(n, 0);
        list_.clear();
        work.by_rung.fill(0);
        work.rung_max = 0;
        const T* rung = ps.data(Field::rung);
        for (std::uint32_t i = 0; i < n; ++i) {
            const int r = int(rung[i]);
            work.rung_max = std::max(work.rung_max, double(r));
            if (tick_ != 0 && !on_rung_boundary(tick_, r)) continue;
            active_[i] = 1;
            list_.push_back(i);
            work.by_rung[std::size_t(r)] += 1;
        }
    }
    // --balance cost: each owned particle's expected work in this tick's sub-step, in units of
    // an active particle's: an inactive one still drifts and is sorted, treed and exchanged
    // (kInactiveCost). Known before the sync; depends on the state only (restarts exactly).
    const float* costs(const ParticleSet<T>& ps, std::size_t n) {
        const T* rung = ps.data(Field::rung);
        cost_.resize(n);
        for (std::size_t i = 0; i < n; ++i)
            cost_[i] = tick_ == 0 || on_rung_boundary(tick_, int(rung[i])) ? 1.0f : kInactiveCost;
        return cost_.data();
    }
    const std::uint8_t* active() const { return active_.data(); }
    ParticleRange active_range() const { return {list_.data(), list_.size()}; }
    std::size_t active_count() const { return list_.size(); }

    // After the forces (Field::dtc holds each active particle's Courant limit): closes the
    // active particles' steps, chooses their rungs, applies the limiter (its bounds on halos go
    // back to their owners) and opens the new steps. One collective (the next tick; one more
    // at a block's start). Returns the length of the sub-step to the next tick.
    template <class Lists>
    double choose(ParticleSet<T>& ps, std::size_t n, const Lists& nl, Domain<T>& dom,
                  const BlockStepInputs& in) {
        const double last = tick_ == 0 ? last_tick_dt_ : tick_dt_; // of the steps ending here
        limit_own_steps<L>(ps, active_range(), in.first ? in.dt0 : 0.0, last, in.accel_eps,
                           tick_ == 0 ? 4.0 : 2.0);
        if (tick_ == 0) start_block(ps, n, dom, in);
        close_steps<L>(ps, active_range(), 0.5 * last, tick_dt_ * kTicks, tick_, in.first);
        int* need = nullptr;
        if (limiter_) {
            need_.assign(ps.size(), -1);
            add_rung_needs<L>(ps, nl, need_.data());
            dom.return_halo_max(need_);
            need = need_.data();
        }
        const double next =
            double(open_steps<L>(ps, n, active_.data(), need, 0.5 * tick_dt_, tick_));
        next_ = std::int64_t(dom.collectives().allreduce_min(std::min(next, kTicks)));
        return double(next_ - tick_) * tick_dt_;
    }

    // Drifts the owned particles to the next tick; returns the time there.
    double drift_to_next(ParticleSet<T>& ps, std::size_t n, const Box<T>& box) {
        drift<L>(ps, n, box, double(next_ - tick_) * tick_dt_, next_, tick_dt_);
        if (next_ < std::int64_t(kTicks)) {
            tick_ = next_;
            return t0_ + double(tick_) * tick_dt_;
        }
        last_tick_dt_ = tick_dt_;
        tick_ = 0;
        return end_;
    }

  private:
    void start_block(ParticleSet<T>& ps, std::size_t n, Domain<T>& dom, const BlockStepInputs& in) {
        const auto [least, most] = own_step_extremes<L>(ps, n);
        std::vector<SumMax> e(2);
        e[0].max = most;
        e[1].set_min(least);
        e[0].sum = inverse_limit_sum(ps, n);
        e[1].sum = double(n);
        dom.collectives().allreduce_sum_max(e);
        // The smallest limit times the power of two that reaches the largest (at most 2^24):
        // the particle with the smallest limit steps with all of it (the shortest step, which
        // sets the number of sub-steps), each other one with the longest power-of-two multiple
        // of it within its own. (Anchored at the largest limit instead, the shortest step lies
        // between half the smallest limit and all of it: more sub-steps, and particles with
        // nearly equal limits split between two rungs.)
        double len = e[1].min();
        for (int k = 0; k < kMaxRung && len < e[0].max; ++k) len *= 2;
        t0_ = in.time;
        end_ = t0_ + len;
        if (in.t_end > 0 && end_ >= in.t_end) end_ = in.t_end;
        tick_dt_ = (end_ - t0_) / kTicks;
        bound_.global_steps += (end_ - t0_) / -e[1].max;
        bound_.own_limit_updates += (end_ - t0_) * e[0].sum / e[1].sum;
    }

    // Sum over the owned particles of 1 / own step limit (the limits are in Field::dtc).
    static double inverse_limit_sum(const ParticleSet<T>& ps, std::size_t n) {
        const T* dt = ps.data(Field::dtc);
        double s = 0;
#pragma omp parallel for reduction(+ : s)
        for (std::size_t i = 0; i < n; ++i) s += 1.0 / double(dt[i]);
        return s;
    }

    bool limiter_;
    BlockWorkBound bound_;
    std::int64_t tick_ = 0, next_ = 0;
    double t0_ = 0, end_ = 0, tick_dt_ = 0, last_tick_dt_ = 0;
    // Read by the kernels: FieldArrays, which the CUDA backend's device reads too.
    FieldArray<std::uint8_t> active_;
    FieldArray<std::uint32_t> list_;
    FieldArray<int> need_;
    std::vector<float> cost_; // --balance cost
};

} // namespace exasph
