#pragma once
#include <algorithm>
#include <cstdint>

#include "exasph/particles/particle_view.hpp"
#include "exasph/sph/block_step.hpp"
#include "exasph/sph/reduction.hpp"
#include "exasph/sph/timestep.hpp"
#include "exasph/tree/neighbour_span.hpp"
#include "exasph/util/atomic_max.hpp"
#include "exasph/util/box.hpp"

// Per-particle kernels of block time steps (--timesteps block): the kick-drift-kick leapfrog of
// each particle on its rung (sph/block_step.hpp; docs/design-notes.md "Block time steps"). A
// particle's step from t0 to t0 + dt: at t0 its velocity and energy are kicked by half a step,
// v_{1/2} = v(t0) + a(t0) dt/2, u_{1/2} = u(t0) + du(t0) dt/2 (OpenStepKernel); every sub-step
// drifts all positions with v_{1/2} and predicts v and u to the new time for the neighbours that
// read them (DriftKernel); at t0 + dt, with the forces of that time, the closing half kick
// (CloseStepKernel).
namespace exasph {

// The particle's own step limit (Field::dtc holds this step's Courant limit, physics.md §7): with
// gravity also sqrt(eps h / |a|); the energy criterion (energy_time_step, k_u = 0.3); at most
// `growth` times its last step, and at the start of the run at most the case's first step. Inside a
// block growth is 2 (the rung falls by one at most); at a block's start 4, since the new block's
// rungs are anchored afresh (at the smallest limit) and rounding down to them may take back up to
// half: a step can still double there.
template <class T, class N = float>
struct OwnStepLimitKernel {
    ParticleView<T, N> p;
    double first_dt;     // > 0: the first step of the run
    double last_tick_dt; // the tick length of the particle's last step
    double accel_eps;    // 0: no acceleration limit
    double growth;       // 2, or 4 at a block's start

    EXASPH_HD void operator()(ParticleIndex i) const {
        double dt = double(p[Field::dtc][i]);
        if (accel_eps > 0)
            dt = std::min(dt, acceleration_time_step(
                                  double(p[Field::h][i]), double(p[Field::ax][i]),
                                  double(p[Field::ay][i]), double(p[Field::az][i]), accel_eps));
        dt = std::min(dt, double(energy_time_step(p[Field::u][i], p[Field::du][i], T(0.3))));
        if (first_dt > 0)
            dt = std::min(dt, first_dt);
        else
            dt = std::min(dt, growth * double(rung_ticks(int(p[Field::rung][i]))) * last_tick_dt);
        p[Field::dtc][i] = T(dt);
    }
};

// At the end of an active particle's step: the closing half kick with this step's forces, then
// its next rung from its own limit, moved only to a rung whose synchronisation points include
// this tick. Returns i if even the shortest rung is too long for it (the pass names the first).
template <class T, class N = float>
struct CloseStepKernel {
    ParticleView<T, N> p;
    double half_tick_dt; // half the tick length of the step that ends here
    double block_dt;     // the length of rung 0 from here on
    std::int64_t tick;
    bool first; // no step has begun yet: nothing to close
    using Reduction = FirstIndexWhere;

    EXASPH_HD FoundIndex operator()(ParticleIndex i) const {
        const int old = int(p[Field::rung][i]);
        if (!first) {
            const T hs = T(double(rung_ticks(old)) * half_tick_dt);
            for (int d = 0; d < 3; ++d)
                p[component(Field::vx, d)][i] =
                    p[component(Field::vhx, d)][i] + p[component(Field::ax, d)][i] * hs;
            p[Field::u][i] = p[Field::uh][i] + p[Field::du][i] * hs;
        }
        const int r = rung_for_step(double(p[Field::dtc][i]), block_dt);
        if (r > kMaxRung) return FoundIndex::at(i);
        p[Field::rung][i] = T(first ? r : aligned_rung(tick, r));
        return FoundIndex::none();
    }
};

// The limiter (Saitoh & Makino 2009): an active particle on rung k asks every neighbour to be
// on rung k - 2 at least (a step ratio of 4 at most). need[] covers owned and halo particles;
// the halos' bounds go back to their owners (Domain::return_halo_max).
template <class T, class N = float>
struct RungNeedKernel {
    ParticleView<T, N> p;
    int* need;

    template <class Span>
    EXASPH_HD void operator()(ParticleIndex i, Span nb) const {
        const int bound = int(p[Field::rung][i]) - 2;
        if (bound <= 0) return; // every rung is at least 0
        for (std::uint32_t k = 0; k < nb.count; ++k) atomic_max(need + nb[k], bound);
    }
};

// At a tick where a step begins: the opening half kick of the active particles (with the
// limiter's bound on their rung), and the wake-up of an inactive particle whose bound is above
// its rung: its step ends now, on the first rung at or above the bound that this tick
// synchronises, and a new one begins (v and u were predicted to this tick; Durier & Dalla
// Vecchia 2012 end the step early the same way). Returns the tick at which the particle is
// next active (the pass takes the earliest).
template <class T, class N = float>
struct OpenStepKernel {
    ParticleView<T, N> p;
    const std::uint8_t* active;
    const int* need;     // nullptr: no limiter
    double half_tick_dt; // of the steps that begin here
    std::int64_t tick;
    using Reduction = MinOf<std::int64_t>;

    EXASPH_HD std::int64_t operator()(ParticleIndex i) const {
        int r = int(p[Field::rung][i]);
        const int bound = need ? need[i] : -1;
        if (active[i] || bound > r) {
            if (bound > r) r = aligned_rung(tick, bound);
            const T hs = T(double(rung_ticks(r)) * half_tick_dt);
            for (int d = 0; d < 3; ++d)
                p[component(Field::vhx, d)][i] =
                    p[component(Field::vx, d)][i] + p[component(Field::ax, d)][i] * hs;
            p[Field::uh][i] = p[Field::u][i] + p[Field::du][i] * hs;
            p[Field::rung][i] = T(r);
            p[Field::dtc][i] = T(2) * hs; // the step taken (the AV switch evolves over it)
        }
        const std::int64_t s = rung_ticks(r);
        return (tick / s + 1) * s;
    }
};

// Every particle to tick `next`: positions drift with v_{1/2} (periodic wrap; x_m1 keeps the
// position before, as the Press scheme's update does, for the density error), v and u are
// predicted to the new time from the middle of the particle's step, v = v_{1/2} + a (t - t_mid),
// for the neighbours and the diagnostics that read them (and as the value its closing kick
// replaces).
template <class T, class N = float>
struct DriftKernel {
    ParticleView<T, N> p;
    Box<T> box;
    T dt;
    std::int64_t next;
    double tick_dt;

    EXASPH_HD void operator()(ParticleIndex i) const {
        for (int d = 0; d < 3; ++d) { // x_m1: where this sub-step's densities were computed
            const T x0 = p[component(Field::x, d)][i];
            const T x = x0 + p[component(Field::vhx, d)][i] * dt;
            const T shift = box.wrap_shift(x, d);
            p[component(Field::x, d)][i] = x + shift;
            p[component(Field::x_m1, d)][i] = x0 + shift;
        }
        const int r = int(p[Field::rung][i]);
        const std::int64_t s = rung_ticks(r);
        const double from_mid = double(next - rung_step_start(next, r)) - 0.5 * double(s);
        const T since = T(from_mid * tick_dt);
        for (int d = 0; d < 3; ++d)
            p[component(Field::vx, d)][i] =
                p[component(Field::vhx, d)][i] + p[component(Field::ax, d)][i] * since;
        p[Field::u][i] = p[Field::uh][i] + p[Field::du][i] * since;
    }
};

// v[i] under reduction R (MinOf or MaxOf: the extremes of the blocks' own step limits).
template <class T, class R>
struct ValueKernel {
    const T* v;
    using Reduction = R;

    EXASPH_HD double operator()(ParticleIndex i) const { return double(v[i]); }
};

// Stores a neighbour kernel's result per particle instead of reducing it (block time steps: each
// particle's own Courant limit from the momentum-energy pass).
template <class K, class T>
struct StoreResultKernel {
    K k;
    T* out;
    using Reduction = MinOf<double>;

    // Without `out` (global steps) the result is reduced as usual.
    template <class Span>
    EXASPH_HD double operator()(ParticleIndex i, Span nb) const {
        const double r = double(k(i, nb));
        if (!out) return r;
        out[i] = T(r);
        return Reduction::identity();
    }
};

// The `wrap` of the momentum-energy pass that stores each particle's limit in out (when given).
template <class T>
auto store_results_in(T* out) {
    return [out](auto kern) { return StoreResultKernel<decltype(kern), T>{kern, out}; };
}

} // namespace exasph
