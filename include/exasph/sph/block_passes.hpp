#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "exasph/particles/particle_set.hpp"
#include "exasph/particles/particle_view.hpp"
#include "exasph/sph/block_kern.hpp"
#include "exasph/sph/launch.hpp"
#include "exasph/sph/passes.hpp"
#include "exasph/util/error.hpp"

// The passes of block time steps (sph/block_kern.hpp) over the active particles `idx` or over
// all owned particles [0, n), on any launcher.
namespace exasph {

template <class L = DefaultLauncher, class T>
void limit_own_steps(ParticleSet<T>& ps, const ParticleRange& idx, double first_dt,
                     double last_tick_dt, double accel_eps, double growth) {
    with_view(ps, [&](auto p) {
        using N = typename decltype(p)::narrow_type;
        L::for_each_of(idx.idx, idx.n,
                       OwnStepLimitKernel<T, N>{p, first_dt, last_tick_dt, accel_eps, growth});
    });
}

// The smallest and largest own step limit of the first n particles.
template <class L = DefaultLauncher, class T>
std::pair<double, double> own_step_extremes(const ParticleSet<T>& ps, std::size_t n) {
    const T* dt = ps.data(Field::dtc);
    const double least = L::reduce(n, ValueKernel<T, MinOf<double>>{dt});
    const double most = L::reduce(n, ValueKernel<T, MaxOf<double>>{dt});
    return {least, most};
}

// Throws Error naming a particle whose limit is below the shortest rung of the block.
template <class L = DefaultLauncher, class T>
void close_steps(ParticleSet<T>& ps, const ParticleRange& idx, double half_tick_dt, double block_dt,
                 std::int64_t tick, bool first) {
    const FoundIndex bad = with_view(ps, [&](auto p) {
        using N = typename decltype(p)::narrow_type;
        return L::reduce_of(idx.idx, idx.n,
                            CloseStepKernel<T, N>{p, half_tick_dt, block_dt, tick, first});
    });
    if (bad.found())
        throw Error("block time steps: particle id " + std::to_string(ps.id[bad.index]) +
                    " needs a step of " + std::to_string(double(ps[Field::dtc][bad.index])) +
                    ", below the shortest rung (dt_max / 2^" + std::to_string(kMaxRung) + ")");
}

template <class L = DefaultLauncher, class T, class Lists>
void add_rung_needs(ParticleSet<T>& ps, const Lists& nl, int* need) {
    with_view(ps, [&](auto p) {
        using N = typename decltype(p)::narrow_type;
        L::for_each_neighbourhood(nl, RungNeedKernel<T, N>{p, need});
    });
}

// Returns the first tick after `tick` at which any of the first n particles is active.
template <class L = DefaultLauncher, class T>
std::int64_t open_steps(ParticleSet<T>& ps, std::size_t n, const std::uint8_t* active,
                        const int* need, double half_tick_dt, std::int64_t tick) {
    return with_view(ps, [&](auto p) {
        using N = typename decltype(p)::narrow_type;
        return L::reduce(n, OpenStepKernel<T, N>{p, active, need, half_tick_dt, tick});
    });
}

template <class L = DefaultLauncher, class T>
void drift(ParticleSet<T>& ps, std::size_t n, const Box<T>& box, double dt, std::int64_t next,
           double tick_dt) {
    with_view(ps, [&](auto p) {
        using N = typename decltype(p)::narrow_type;
        L::for_each(n, DriftKernel<T, N>{p, box, T(dt), next, tick_dt});
    });
}

} // namespace exasph
