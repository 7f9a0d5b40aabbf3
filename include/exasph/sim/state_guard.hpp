#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "exasph/particles/particle_set.hpp"
#include "exasph/sim/state_hash.hpp"
#include "exasph/sph/launch.hpp"
#include "exasph/sph/state_check_kern.hpp"
#include "exasph/util/box.hpp"

namespace exasph {

// Guards the owned particles' state between steps: seal() records a hash per particle at the end
// of a step, check() (start of the next step, same order) finds any bit that changed in between,
// and the physics invariants below catch corruption that happened before the seal. The CPU
// launcher works on blocks of particles a field at a time (vectorised); the GPU path's launchers
// run the kernels of sph/state_check_kern.hpp where the particles are (the same findings).
template <class T, class L = DefaultLauncher>
class StateGuard {
  public:
    // Returns the sum of the hashes (state_hash_sum of the sealed state).
    std::uint64_t seal(const ParticleSet<T>& ps, std::size_t n) {
        fields_ = ps.fields(kState);
        hashes_.resize(n);
        if constexpr (L::kBackend != Backend::openmp) {
            sealed_ = true;
            return L::reduce(n, GuardSealKernel{state_hash(ps), hashes_.data()});
        }
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
        const StateInvariants<T> inv = invariants(ps, box, dt, press_ok, u_positive);
        const auto [bad_hash, bad_physics] = findings(ps, n, inv);
        std::string why;
        if (bad_hash < n)
            why = "particle id " + std::to_string(ps.id[bad_hash]) +
                  ": state changed between steps (hash mismatch)";
        if (bad_physics < n)
            why += std::string(why.empty() ? "" : "; ") + "particle id " +
                   std::to_string(ps.id[bad_physics]) + ": " +
                   physics_violation(ps, inv, bad_physics);
        return why;
    }

    // The invariants of the state fields of ps (sph/state_check_kern.hpp).
    static StateInvariants<T> invariants(const ParticleSet<T>& ps, const Box<T>& box, double dt,
                                         bool press_ok, bool u_positive) {
        StateInvariants<T> inv{};
        const std::vector<Field> state = ps.fields(kState);
        if (state.size() > std::size_t(StateInvariants<T>::kMost))
            throw Error("the state guard checks at most " +
                        std::to_string(StateInvariants<T>::kMost) + " state fields");
        for (Field f : state) inv.state[inv.count++] = ps.data(f);
        inv.m = ps.data(Field::m), inv.h = ps.data(Field::h), inv.u = ps.data(Field::u);
        for (int d = 0; d < 3; ++d) {
            inv.x[d] = ps.data(pos[d]), inv.x_m1[d] = ps.data(prev[d]);
            inv.v[d] = ps.data(vel[d]), inv.a[d] = ps.data(acc[d]);
        }
        inv.box = box, inv.dt = dt, inv.press_ok = press_ok, inv.u_positive = u_positive;
        return inv;
    }

    // The first invariant particle i breaks (for the report), or "" if none.
    static std::string physics_violation(const ParticleSet<T>& ps, const StateInvariants<T>& inv,
                                         std::size_t i) {
        switch (inv.broken(ParticleIndex(i))) {
        case Broken::not_finite:
            for (Field f : ps.fields(kState))
                if (!std::isfinite(ps[f][i]))
                    return std::string(field_info(f).name) + " is not finite";
            return "a state field is not finite";
        case Broken::mass:
            return "m is not positive";
        case Broken::smoothing_length:
            return "h is not positive";
        case Broken::energy:
            return "u is negative";
        case Broken::box:
            return "position outside the box";
        case Broken::press:
            return "x, x_m1, v, a disagree (Press)";
        case Broken::none:
            break;
        }
        return "";
    }

  private:
    // The first particle (n: none) whose hash changed since the seal, and the first that
    // breaks an invariant.
    std::pair<std::size_t, std::size_t> findings(const ParticleSet<T>& ps, std::size_t n,
                                                 const StateInvariants<T>& inv) const {
        const bool compare = sealed_ && hashes_.size() == n;
        if constexpr (L::kBackend != Backend::openmp) {
            const GuardFinding f = L::reduce(
                n, GuardCheckKernel<T>{state_hash(ps), compare ? hashes_.data() : nullptr, inv});
            return {f.changed.found() ? f.changed.index : n, f.broken.found() ? f.broken.index : n};
        }
        std::size_t bad_hash = n;
        if (compare)
            bad_hash = over_hash_blocks(
                ps, n, [&](std::size_t first, std::size_t count, const std::uint32_t* h) {
                    for (std::size_t k = 0; k < count; ++k)
                        if (h[k] != hashes_[first + k]) return first + k;
                    return n;
                });
        return {bad_hash, first_violation(ps, inv, n)};
    }
    FieldHashKernel state_hash(const ParticleSet<T>& ps) const {
        return {ps.id.data(), hashed_fields(ps, fields_)};
    }

    // The least index of a particle that breaks an invariant of physics_violation (n if none),
    // tested field by field over blocks of particles: loops over one or a few arrays that
    // vectorise (the test per particle over all its fields took ~1 % of a step).
    static std::size_t first_violation(const ParticleSet<T>& ps, const StateInvariants<T>& inv,
                                       std::size_t n) {
        const Box<T>& box = inv.box;
        const std::vector<const T*> state(inv.state, inv.state + inv.count);
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
            if (inv.u_positive) mark(ps[Field::u].data(), [](T v) { return v < T(0); });
            for (int d = 0; d < 3; ++d) {
                const T lo = box.lo[d], hi = box.hi[d];
                mark(ps[pos[d]].data(), [=](T x) { return x < lo || x > hi; });
            }
            if (inv.press_ok) mark_press(ps, box, inv.dt, first, count, bad);
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
                bad[k] |= !press_axis_ok(x[k], xm[k], v[k], a[k], period, dt, kEps);
        }
    }
    static constexpr T kFiniteMax = std::numeric_limits<T>::max();
    static constexpr double kEps = std::numeric_limits<T>::epsilon();
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

    FieldArray<std::uint32_t> hashes_; // where the particles are: the device seals them too
    bool sealed_ = false;
};

} // namespace exasph
