#pragma once
#include <algorithm>
#include <limits>

#include "exasph/domain/collectives.hpp"
#include "exasph/sph/passes.hpp"
#include "exasph/sph/timestep.hpp"

namespace exasph {

// SPEC 7, one global step: the smallest Courant limit (from the momentum-energy pass) and, with
// gravity (accel_eps > 0), acceleration limit over all ranks (one collective), at most 1.1 x the
// previous step; the first step is the case's dt0 (or less); none goes past t_end (if > 0).
template <class L, class T>
double global_time_step(ParticleSet<T>& ps, std::size_t n, double courant, double accel_eps,
                        Collectives& coll, bool first, double dt0, double dt_m1, double time,
                        double t_end) {
    double dt_min = std::min(courant, std::numeric_limits<double>::max());
    if (accel_eps > 0) dt_min = std::min(dt_min, acceleration_time_step_min<L>(ps, n, accel_eps));
    dt_min = coll.allreduce_min(dt_min);
    double dt = first ? std::min(dt0, dt_min) : limit_time_step(dt_min, dt_m1);
    if (t_end > 0 && time + dt > t_end) dt = std::max(t_end - time, 0.0);
    return dt;
}

} // namespace exasph
