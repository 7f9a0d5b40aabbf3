#pragma once
#include <cmath>
#include <cstdint>
#include <limits>

#include "exasph/particles/particle_index.hpp"
#include "exasph/sph/field_hash_kern.hpp"
#include "exasph/sph/reduction.hpp"
#include "exasph/util/box.hpp"

// The state guard's work between steps (sim/state_guard.hpp) as kernels that a launcher runs
// where the particles live: the seal (each owned particle's state hash, kept, and their sum) and
// the check (the first particle whose hash changed, and the first that breaks an invariant).
namespace exasph {

// After a Press update (sph/integrator.hpp), x - x_m1 = dt (v - a dt / 2) up to round-off in each
// axis, eps the working precision's. A periodic wrap moves x and x_m1 together by the period,
// rounding both at the period's magnitude (which |x| does not show in a box [0, L)).
EXASPH_HD inline bool press_axis_ok(double x, double xm, double v, double a, double period,
                                    double dt, double eps) {
    const double residual = std::abs((x - xm) - dt * (v - 0.5 * a * dt));
    const double allowed =
        16 * eps *
        (std::abs(x) + std::abs(xm) + 2 * period + dt * (std::abs(v) + std::abs(a) * dt));
    return residual <= allowed;
}

// The invariants of a particle's state between steps, the first one broken in this order.
enum class Broken : std::uint8_t { none, not_finite, mass, smoothing_length, energy, box, press };

template <class T>
struct StateInvariants {
    static constexpr int kMost = HashedFields::kMost;
    const T* state[kMost]; // the enabled state fields
    int count = 0;
    const T *m, *h, *u;
    const T *x[3], *x_m1[3], *v[3], *a[3];
    Box<T> box;
    double dt;
    bool press_ok;   // dt and the accelerations are the last step's
    bool u_positive; // u >= 0 is an invariant (ideal gas)

    EXASPH_HD Broken broken(ParticleIndex i) const {
        for (int k = 0; k < count; ++k)
            if (!(std::abs(state[k][i]) <= std::numeric_limits<T>::max()))
                return Broken::not_finite;
        if (!(m[i] > T(0))) return Broken::mass;
        if (!(h[i] > T(0))) return Broken::smoothing_length;
        if (u_positive && u[i] < T(0)) return Broken::energy;
        for (int d = 0; d < 3; ++d)
            if (x[d][i] < box.lo[d] || x[d][i] > box.hi[d]) return Broken::box;
        if (press_ok)
            for (int d = 0; d < 3; ++d) {
                const double period = box.periodic[d] ? double(box.hi[d] - box.lo[d]) : 0.0;
                if (!press_axis_ok(x[d][i], x_m1[d][i], v[d][i], a[d][i], period, dt,
                                   std::numeric_limits<T>::epsilon()))
                    return Broken::press;
            }
        return Broken::none;
    }
};

// The seal: particle i's state hash kept in sealed[i]; their sum (the seal's sum).
struct GuardSealKernel {
    FieldHashKernel hash;
    std::uint32_t* sealed;
    using Reduction = SumOf<std::uint64_t>;

    EXASPH_HD std::uint64_t operator()(ParticleIndex i) const {
        const std::uint64_t h = hash(i);
        sealed[i] = std::uint32_t(h);
        return h;
    }
};

// What the check found: the first particle whose hash differs from its seal, and the first
// that breaks an invariant.
struct GuardFinding {
    FoundIndex changed, broken;
};
struct GuardFindingReduction {
    using value_type = GuardFinding;
    EXASPH_HD static constexpr GuardFinding identity() { return {}; }
    EXASPH_HD static constexpr GuardFinding combine(GuardFinding a, GuardFinding b) {
        return {FirstIndexWhere::combine(a.changed, b.changed),
                FirstIndexWhere::combine(a.broken, b.broken)};
    }
};

// The check; `sealed` null: no seal to compare with.
template <class T>
struct GuardCheckKernel {
    FieldHashKernel hash;
    const std::uint32_t* sealed;
    StateInvariants<T> invariants;
    using Reduction = GuardFindingReduction;

    EXASPH_HD GuardFinding operator()(ParticleIndex i) const {
        GuardFinding f;
        if (sealed && std::uint32_t(hash(i)) != sealed[i]) f.changed = FoundIndex::at(i);
        if (invariants.broken(i) != Broken::none) f.broken = FoundIndex::at(i);
        return f;
    }
};

} // namespace exasph
