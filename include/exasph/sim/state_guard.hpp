#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "exasph/particles/particle_set.hpp"
#include "exasph/sim/state_hash.hpp"
#include "exasph/util/box.hpp"

namespace exasph {

// Guards the owned particles' state between steps: seal() records a hash per particle at the end
// of a step, check() (start of the next step, same order) finds any bit that changed in between,
// and the physics invariants below catch corruption that happened before the seal.
template <class T>
class StateGuard {
  public:
    // Returns the sum of the hashes (state_hash_sum of the sealed state).
    std::uint64_t seal(const ParticleSet<T>& ps, std::size_t n) {
        fields_ = ps.fields(kState);
        hashes_.resize(n);
        over_hash_blocks(ps, n, [&](std::size_t first, std::size_t count, const std::uint32_t* h) {
            std::copy_n(h, count, hashes_.begin() + std::ptrdiff_t(first));
            return n;
        });
        sealed_ = true;
        std::uint64_t sum = 0;
        for (std::uint32_t h : hashes_) sum += h;
        return sum;
    }

    // Empty when the state is consistent, else what is wrong (the first particle found).
    // `dt` and the accelerations are those of the last step (press_ok: they are valid);
    // `u_positive`: u >= 0 is an invariant (ideal gas, not the Tait EOS that ignores u).
    std::string check(const ParticleSet<T>& ps, std::size_t n, const Box<T>& box, double dt,
                      bool press_ok, bool u_positive) const {
        const auto nn = std::int64_t(n);
        std::int64_t bad_hash = nn;
        if (sealed_ && hashes_.size() == n)
            bad_hash = std::int64_t(over_hash_blocks(
                ps, n, [&](std::size_t first, std::size_t count, const std::uint32_t* h) {
                    for (std::size_t k = 0; k < count; ++k)
                        if (h[k] != hashes_[first + k]) return first + k;
                    return n;
                }));
        std::string why;
        std::vector<const T*> state; // the enabled state fields, looked up once
        for (Field f : ps.fields(kState)) state.push_back(ps.data(f));
        const auto bad_physics =
            std::int64_t(first_violation(ps, state, n, box, dt, press_ok, u_positive));
        if (bad_hash < nn)
            why = "particle id " + std::to_string(ps.id[bad_hash]) +
                  ": state changed between steps (hash mismatch)";
        if (bad_physics < nn)
            why += std::string(why.empty() ? "" : "; ") + "particle id " +
                   std::to_string(ps.id[bad_physics]) + ": " +
                   physics_violation(ps, state, bad_physics, box, dt, press_ok, u_positive);
        return why;
    }

    // The first invariant particle i breaks (for the report), or "" if none.
    // `state` holds the data of ps.fields(kState), in that order.
    static std::string physics_violation(const ParticleSet<T>& ps,
                                         const std::vector<const T*>& state, std::size_t i,
                                         const Box<T>& box, double dt, bool press_ok,
                                         bool u_positive) {
        for (std::size_t k = 0; k < state.size(); ++k)
            if (!std::isfinite(state[k][i]))
                return std::string(field_info(ps.fields(kState)[k]).name) + " is not finite";
        if (!(ps[Field::m][i] > T(0))) return "m is not positive";
        if (!(ps[Field::h][i] > T(0))) return "h is not positive";
        if (u_positive && ps[Field::u][i] < T(0)) return "u is negative";
        for (int d = 0; d < 3; ++d) {
            const T x = ps[pos[d]][i];
            if (x < box.lo[d] || x > box.hi[d]) return "position outside the box";
        }
        if (press_ok && !press_consistent(ps, i, box, dt)) return "x, x_m1, v, a disagree (Press)";
        return "";
    }

  private:
    // After a Press update (sph/integrator.hpp), x - x_m1 = dt (v - a dt / 2) up to round-off
    // in each axis. A periodic wrap moves x and x_m1 together by the period, rounding both at the
    // period's magnitude (which |x| does not show in a box [0, L)).
    static bool press_consistent(const ParticleSet<T>& ps, std::size_t i, const Box<T>& box,
                                 double dt) {
        for (int d = 0; d < 3; ++d) {
            const double period = box.periodic[d] ? double(box.hi[d] - box.lo[d]) : 0.0;
            if (!press_axis_ok(ps[pos[d]][i], ps[prev[d]][i], ps[vel[d]][i], ps[acc[d]][i], period,
                               dt))
                return false;
        }
        return true;
    }
    static bool press_axis_ok(double x, double xm, double v, double a, double period, double dt) {
        constexpr double eps = std::numeric_limits<T>::epsilon();
        const double residual = std::abs((x - xm) - dt * (v - 0.5 * a * dt));
        const double allowed =
            16 * eps *
            (std::abs(x) + std::abs(xm) + 2 * period + dt * (std::abs(v) + std::abs(a) * dt));
        return residual <= allowed;
    }

    // The least index of a particle that breaks an invariant of physics_violation (n if none),
    // tested field by field over blocks of particles: loops over one or a few arrays that
    // vectorise (the test per particle over all its fields took ~1 % of a step).
    static std::size_t first_violation(const ParticleSet<T>& ps, const std::vector<const T*>& state,
                                       std::size_t n, const Box<T>& box, double dt, bool press_ok,
                                       bool u_positive) {
        const auto blocks = std::int64_t((n + kHashBlock - 1) / kHashBlock);
        std::size_t least = n;
#pragma omp parallel for schedule(static) reduction(min : least)
        for (std::int64_t b = 0; b < blocks; ++b) {
            const std::size_t first = std::size_t(b) * kHashBlock;
            const std::size_t count = std::min(kHashBlock, n - first);
            unsigned char bad[kHashBlock] = {};
            auto mark = [&](const T* f, auto broken) {
#pragma omp simd
                for (std::size_t k = 0; k < count; ++k) bad[k] |= broken(f[first + k]);
            };
            for (const T* f : state) mark(f, [](T v) { return !(std::abs(v) <= kFiniteMax); });
            mark(ps[Field::m].data(), [](T v) { return !(v > T(0)); });
            mark(ps[Field::h].data(), [](T v) { return !(v > T(0)); });
            if (u_positive) mark(ps[Field::u].data(), [](T v) { return v < T(0); });
            for (int d = 0; d < 3; ++d) {
                const T lo = box.lo[d], hi = box.hi[d];
                mark(ps[pos[d]].data(), [=](T x) { return x < lo || x > hi; });
            }
            if (press_ok) mark_press(ps, box, dt, first, count, bad);
            for (std::size_t k = 0; k < count; ++k)
                if (bad[k]) {
                    least = std::min(least, first + k);
                    break;
                }
        }
        return least;
    }
    static void mark_press(const ParticleSet<T>& ps, const Box<T>& box, double dt,
                           std::size_t first, std::size_t count, unsigned char* bad) {
        for (int d = 0; d < 3; ++d) {
            const T *x = ps[pos[d]].data() + first, *xm = ps[prev[d]].data() + first;
            const T *v = ps[vel[d]].data() + first, *a = ps[acc[d]].data() + first;
            const double period = box.periodic[d] ? double(box.hi[d] - box.lo[d]) : 0.0;
#pragma omp simd
            for (std::size_t k = 0; k < count; ++k)
                bad[k] |= !press_axis_ok(x[k], xm[k], v[k], a[k], period, dt);
        }
    }
    static constexpr T kFiniteMax = std::numeric_limits<T>::max();
    static constexpr Field pos[3] = {Field::x, Field::y, Field::z};
    static constexpr Field prev[3] = {Field::x_m1, Field::y_m1, Field::z_m1};
    static constexpr Field vel[3] = {Field::vx, Field::vy, Field::vz};
    static constexpr Field acc[3] = {Field::ax, Field::ay, Field::az};

    std::vector<Field> fields_;
    // 32 bits per particle (4 B/particle of memory): a changed state goes unnoticed with
    // probability 2^-32 per corrupted particle. particle_state_hash folded to 32 bits, for
    // particles [first, first + count), count <= kHashBlock.
    void sealed_hashes(const ParticleSet<T>& ps, std::size_t first, std::size_t count,
                       std::uint32_t* out) const {
        std::uint64_t h[kHashBlock];
        state_hash_block(ps, fields_, first, count, h);
        for (std::size_t k = 0; k < count; ++k) out[k] = fold_hash(h[k]);
    }
    // Runs body(first, count, hashes) on the sealed hashes of each block of the first n
    // particles, in parallel; returns the least value the body returned (n for none).
    template <class Body>
    std::size_t over_hash_blocks(const ParticleSet<T>& ps, std::size_t n, Body body) const {
        const auto blocks = std::int64_t((n + kHashBlock - 1) / kHashBlock);
        std::size_t least = n;
#pragma omp parallel for schedule(static) reduction(min : least)
        for (std::int64_t b = 0; b < blocks; ++b) {
            std::uint32_t h[kHashBlock];
            const std::size_t first = std::size_t(b) * kHashBlock;
            const std::size_t count = std::min(kHashBlock, n - first);
            sealed_hashes(ps, first, count, h);
            least = std::min(least, std::size_t(body(first, count, h)));
        }
        return least;
    }

    std::vector<std::uint32_t> hashes_;
    bool sealed_ = false;
};

} // namespace exasph
