#pragma once
#include <algorithm>
#include <cstdint>
#include <limits>

#include "exasph/domain/collectives.hpp"
#include "exasph/sph/passes.hpp"
#include "exasph/sph/timestep.hpp"

namespace exasph {

// physics.md §7: this rank's smallest limit: the Courant limit (from the momentum-energy pass) and,
// with gravity (accel_eps > 0), the acceleration limit.
template <class L, class T>
double local_time_step_limit(ParticleSet<T>& ps, std::size_t n, double courant, double accel_eps) {
    double dt_min = std::min(courant, std::numeric_limits<double>::max());
    if (accel_eps > 0) dt_min = std::min(dt_min, acceleration_time_step_min<L>(ps, n, accel_eps));
    return dt_min;
}

// The step from the smallest limit over all ranks: at most 1.1 x the previous step; the first
// step is the case's dt0 (or less); none goes past t_end (if > 0). Never decreases as dt_min
// grows, so this rank's own limit gives a bound of the step the ranks choose together.
inline double step_from_limit(double dt_min, bool first, double dt0, double dt_m1, double time,
                              double t_end) {
    double dt = first ? std::min(dt0, dt_min) : limit_time_step(dt_min, dt_m1);
    if (t_end > 0 && time + dt > t_end) dt = std::max(t_end - time, 0.0);
    return dt;
}

// What every rank knows of the run's time: the step count, the time, the last step and the
// case's first one, and the end time (<= 0: none).
struct StepClock {
    double dt_m1 = 0, dt0 = 0, time = 0, t_end = -1;
    std::int64_t step = 0;

    double step_from(double dt_min) const {
        return step_from_limit(dt_min, step == 0, dt0, dt_m1, time, t_end);
    }
    // Whether the run ends here: after step `steps` (< 0: none) or at the end time.
    bool ends(std::int64_t steps) const {
        return (steps >= 0 && step >= steps) || (t_end > 0 && time >= t_end * (1 - 1e-12));
    }
    void stepped(double dt, double t_next) { time = t_next, dt_m1 = dt, ++step; }
};

// physics.md §7, one global step: the smallest limit over all ranks (one collective).
template <class L, class T>
double global_time_step(ParticleSet<T>& ps, std::size_t n, double courant, double accel_eps,
                        Collectives& coll, const StepClock& clock) {
    return clock.step_from(coll.allreduce_min(local_time_step_limit<L>(ps, n, courant, accel_eps)));
}

} // namespace exasph
