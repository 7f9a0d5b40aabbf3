#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "exasph/particles/particle_set.hpp"
#include "exasph/sim/diagnostics.hpp"
#include "exasph/util/box.hpp"
#include "exasph/util/checksum.hpp"
#include "exasph/util/error.hpp"

namespace exasph {

// Silent-data-corruption defences for particle state at rest between steps (issue 8).

// --inject-fault STEP:FIELD:ID:BIT: flip bit BIT (0 = least significant) of FIELD of the
// particle with id ID at the start of step STEP (before the state is verified), once.
struct FaultSpec {
    std::int64_t step = -1; // < 0: none
    Field field = Field::x;
    std::uint64_t id = 0;
    int bit = 0;
};

inline FaultSpec parse_fault(const std::string& text) {
    FaultSpec f;
    std::vector<std::string> parts;
    std::size_t start = 0;
    for (std::size_t i = 0; i <= text.size(); ++i)
        if (i == text.size() || text[i] == ':') {
            parts.push_back(text.substr(start, i - start));
            start = i + 1;
        }
    const std::string usage = "--inject-fault " + text + ": expected STEP:FIELD:ID:BIT";
    if (parts.size() != 4) throw input_error(usage, true);
    bool found = false;
    for (const auto& info : kFieldTable)
        if (info.name == parts[1] && (info.roles & kState)) f.field = info.field, found = true;
    // (An optional field the run does not carry is refused when the fault is injected.)
    if (!found) throw input_error(usage + " with FIELD a state field (x, vx, u, h, m, ...)", true);
    try {
        std::size_t used = 0;
        f.step = std::stoll(parts[0], &used);
        if (used != parts[0].size() || f.step < 1) throw std::invalid_argument("step");
        f.id = std::stoull(parts[2], &used);
        if (used != parts[2].size()) throw std::invalid_argument("id");
        f.bit = std::stoi(parts[3], &used);
        if (used != parts[3].size() || f.bit < 0 || f.bit >= 64) throw std::invalid_argument("b");
    } catch (const std::exception&) {
        throw input_error(usage + " (STEP >= 1, BIT in 0..63 for double)", true);
    }
    return f;
}

// Flips the bit in this rank's copy of the particle, if it owns it; returns whether it did.
template <class T>
bool inject_fault(ParticleSet<T>& ps, std::size_t n, const FaultSpec& f) {
    static_assert(sizeof(T) == 8 || sizeof(T) == 4);
    if (!ps.enabled(f.field))
        throw input_error("--inject-fault: this run carries no field " +
                              std::string(field_info(f.field).name),
                          true);
    for (std::size_t i = 0; i < n; ++i) {
        if (ps.id[i] != f.id) continue;
        T& v = ps[f.field][i];
        if constexpr (sizeof(T) == 8) {
            std::uint64_t b;
            std::memcpy(&b, &v, 8);
            b ^= std::uint64_t(1) << f.bit;
            std::memcpy(&v, &b, 8);
        } else {
            std::uint32_t b;
            std::memcpy(&b, &v, 4);
            b ^= std::uint32_t(1) << (f.bit % 32);
            std::memcpy(&v, &b, 4);
        }
        return true;
    }
    return false;
}

// Copy of the owned particles' ids and state fields (what a checkpoint holds): the rollback
// point. Derived fields are not kept; a step recomputes them before use, as after a restart.
template <class T>
struct StateCopy {
    std::vector<std::uint64_t> id;
    std::vector<std::vector<T>> fields; // in the order of ps.fields(kState)

    void save(const ParticleSet<T>& ps, std::size_t n) {
        const auto state = ps.fields(kState);
        id.assign(ps.id.begin(), ps.id.begin() + std::ptrdiff_t(n));
        fields.resize(state.size());
        for (std::size_t k = 0; k < state.size(); ++k)
            fields[k].assign(ps[state[k]].begin(), ps[state[k]].begin() + std::ptrdiff_t(n));
    }
    void restore(ParticleSet<T>& ps) const {
        const auto state = ps.fields(kState); // the same set as at save(): the run's options
        ps.resize(id.size());
        std::copy(id.begin(), id.end(), ps.id.begin());
        for (std::size_t k = 0; k < state.size(); ++k)
            std::copy(fields[k].begin(), fields[k].end(), ps[state[k]].begin());
    }
};

// The rollback point on disk (--sdc-rollback-store disk): the same data as StateCopy in one raw
// file per rank, so that no copy of the state stays in memory (~112 B/particle). Written under a
// temporary name and renamed; a checksum of the particles' state hashes is verified when it is
// read back. The file is removed with the object.
template <class T>
class StateFile {
  public:
    StateFile() = default;
    StateFile(const StateFile&) = delete;
    StateFile& operator=(const StateFile&) = delete;
    ~StateFile() {
        if (written_) std::remove(path_.c_str());
    }

    void set_path(std::string path) { path_ = std::move(path); }

    void save(const ParticleSet<T>& ps, std::size_t n) {
        const auto state = ps.fields(kState);
        const std::string tmp = path_ + ".tmp";
        if (!written_) {
            // The directory may not exist yet (the first point is saved before any output).
            std::error_code ec;
            const auto dir = std::filesystem::path(path_).parent_path();
            if (!dir.empty()) std::filesystem::create_directories(dir, ec);
            if (ec) // exit code 3: output I/O failure, like an unwritable --out
                throw Error("cannot create the directory of the rollback point " + path_ + ": " +
                                ec.message(),
                            3, true);
        }
        std::FILE* f = std::fopen(tmp.c_str(), "wb");
        if (!f) throw Error("cannot write the rollback point " + tmp, 3, true);
        const std::uint64_t head[3] = {n, state.size(), state_sum(ps, n, state)};
        bool ok = std::fwrite(head, sizeof head, 1, f) == 1;
        ok = ok && std::fwrite(ps.id.data(), sizeof(std::uint64_t), n, f) == n;
        for (Field fld : state) ok = ok && std::fwrite(ps.data(fld), sizeof(T), n, f) == n;
        ok = std::fclose(f) == 0 && ok;
        if (!ok || std::rename(tmp.c_str(), path_.c_str()) != 0)
            throw Error("cannot write the rollback point " + path_ + " (disk full?)", 3, true);
        written_ = true;
    }

    void restore(ParticleSet<T>& ps) const {
        const auto state = ps.fields(kState);
        std::FILE* f = std::fopen(path_.c_str(), "rb");
        if (!f) throw Error("cannot read the rollback point " + path_, 1, true);
        std::uint64_t head[3] = {0, 0, 0};
        bool ok = std::fread(head, sizeof head, 1, f) == 1 && head[1] == state.size();
        const std::size_t n = ok ? std::size_t(head[0]) : 0;
        ps.resize(n);
        ok = ok && std::fread(ps.id.data(), sizeof(std::uint64_t), n, f) == n;
        for (Field fld : state) ok = ok && std::fread(ps.data(fld), sizeof(T), n, f) == n;
        std::fclose(f);
        if (!ok || state_sum(ps, n, state) != head[2])
            throw Error("the rollback point " + path_ + " is unreadable or altered", 1, true);
    }

  private:
    static std::uint64_t state_sum(const ParticleSet<T>& ps, std::size_t n,
                                   const std::vector<Field>& state);

    std::string path_;
    bool written_ = false;
};

// The rollback point's particles: in memory (StateCopy), or on disk once given a path.
template <class T>
class StateStore {
  public:
    void keep_on_disk(std::string path) {
        file_.set_path(std::move(path));
        on_disk_ = true;
    }
    void save(const ParticleSet<T>& ps, std::size_t n) {
        on_disk_ ? file_.save(ps, n) : memory_.save(ps, n);
    }
    void restore(ParticleSet<T>& ps) const { on_disk_ ? file_.restore(ps) : memory_.restore(ps); }

  private:
    StateCopy<T> memory_;
    StateFile<T> file_;
    bool on_disk_ = false;
};

// Hash of one particle's id and state fields (bit patterns, in field-list order).
template <class T>
std::uint64_t particle_state_hash(const ParticleSet<T>& ps, std::size_t i,
                                  const std::vector<Field>& fields) {
    HashChain h(ps.id[i]);
    for (Field f : fields) h.add_float(ps[f][i]);
    return h.value();
}

// particle_state_hash of the particles [first, first + count), count <= kHashBlock: the chain
// advances one field at a time over the whole block, so that the mixing vectorises.
inline constexpr std::size_t kHashBlock = 256;
template <class T>
void state_hash_block(const ParticleSet<T>& ps, const std::vector<Field>& fields, std::size_t first,
                      std::size_t count, std::uint64_t* h) {
    const std::uint64_t* id = ps.id.data() + first;
#pragma omp simd
    for (std::size_t k = 0; k < count; ++k) h[k] = mix64(id[k]);
    for (Field f : fields) {
        const T* v = ps.data(f) + first;
#pragma omp simd
        for (std::size_t k = 0; k < count; ++k) h[k] = mix64(h[k] ^ float_bits(v[k]));
    }
}

template <class T>
std::uint64_t StateFile<T>::state_sum(const ParticleSet<T>& ps, std::size_t n,
                                      const std::vector<Field>& state) {
    std::uint64_t sum = 0;
    const auto nn = std::int64_t(n);
#pragma omp parallel for schedule(static) reduction(+ : sum)
    for (std::int64_t i = 0; i < nn; ++i) sum += particle_state_hash(ps, std::size_t(i), state);
    return sum;
}

// Guards the owned particles' state between steps: seal() records a hash per particle at the end
// of a step, check() (start of the next step, same order) finds any bit that changed in between,
// and the physics invariants below catch corruption that happened before the seal.
template <class T>
class StateGuard {
  public:
    void seal(const ParticleSet<T>& ps, std::size_t n) {
        fields_ = ps.fields(kState);
        hashes_.resize(n);
        over_hash_blocks(ps, n, [&](std::size_t first, std::size_t count, const std::uint32_t* h) {
            std::copy_n(h, count, hashes_.begin() + std::ptrdiff_t(first));
            return n;
        });
        sealed_ = true;
    }
    void unseal() { sealed_ = false; }

    // Empty when the state is consistent, else what is wrong (the first particle found).
    // `dt` and the accelerations are those of the last step (press_ok: they are valid);
    // `u_positive`: u >= 0 is an invariant (ideal gas, not the Tait EOS that ignores u).
    std::string check(const ParticleSet<T>& ps, std::size_t n, const Box<T>& box, double dt,
                      bool press_ok, bool u_positive) const {
        const auto nn = std::int64_t(n);
        std::int64_t bad_hash = nn, bad_physics = nn;
        if (sealed_ && hashes_.size() == n)
            bad_hash = std::int64_t(over_hash_blocks(
                ps, n, [&](std::size_t first, std::size_t count, const std::uint32_t* h) {
                    for (std::size_t k = 0; k < count; ++k)
                        if (h[k] != hashes_[first + k]) return first + k;
                    return n;
                }));
        std::string why;
#pragma omp parallel for schedule(static) reduction(min : bad_physics)
        for (std::int64_t i = 0; i < nn; ++i)
            if (!physics_violation(ps, i, box, dt, press_ok, u_positive).empty() && i < bad_physics)
                bad_physics = i;
        if (bad_hash < nn)
            why = "particle id " + std::to_string(ps.id[bad_hash]) +
                  ": state changed between steps (hash mismatch)";
        if (bad_physics < nn)
            why += std::string(why.empty() ? "" : "; ") + "particle id " +
                   std::to_string(ps.id[bad_physics]) + ": " +
                   physics_violation(ps, bad_physics, box, dt, press_ok, u_positive);
        return why;
    }

    // The first invariant particle i breaks (for the report), or "" if none.
    static std::string physics_violation(const ParticleSet<T>& ps, std::size_t i, const Box<T>& box,
                                         double dt, bool press_ok, bool u_positive) {
        for (const auto& info : kFieldTable)
            if ((info.roles & kState) && ps.enabled(info.field) &&
                !std::isfinite(ps[info.field][i]))
                return std::string(info.name) + " is not finite";
        if (!(ps[Field::m][i] > T(0))) return "m is not positive";
        if (!(ps[Field::h][i] > T(0))) return "h is not positive";
        if (u_positive && ps[Field::u][i] < T(0)) return "u is negative";
        const Field pos[3] = {Field::x, Field::y, Field::z};
        for (int d = 0; d < 3; ++d) {
            const T x = ps[pos[d]][i];
            if (x < box.lo[d] || x > box.hi[d]) return "position outside the box";
        }
        if (press_ok && !press_consistent(ps, i, dt)) return "x, x_m1, v, a disagree (Press)";
        return "";
    }

  private:
    // After a Press update (sph/integrator.hpp), x - x_m1 = dt (v - a dt / 2) up to round-off
    // in each axis (a periodic wrap moves x and x_m1 together).
    static bool press_consistent(const ParticleSet<T>& ps, std::size_t i, double dt) {
        constexpr double eps = std::numeric_limits<T>::epsilon();
        const Field pos[3] = {Field::x, Field::y, Field::z};
        const Field prev[3] = {Field::x_m1, Field::y_m1, Field::z_m1};
        const Field vel[3] = {Field::vx, Field::vy, Field::vz};
        const Field acc[3] = {Field::ax, Field::ay, Field::az};
        for (int d = 0; d < 3; ++d) {
            const double x = ps[pos[d]][i], xm = ps[prev[d]][i], v = ps[vel[d]][i],
                         a = ps[acc[d]][i];
            const double residual = std::abs((x - xm) - dt * (v - 0.5 * a * dt));
            const double allowed =
                16 * eps * (std::abs(x) + std::abs(xm) + dt * (std::abs(v) + std::abs(a) * dt));
            if (!(residual <= allowed)) return false;
        }
        return true;
    }

    std::vector<Field> fields_;
    // 32 bits per particle (4 B/particle of memory): a changed state goes unnoticed with
    // probability 2^-32 per corrupted particle. particle_state_hash folded to 32 bits, for
    // particles [first, first + count), count <= kHashBlock.
    void sealed_hashes(const ParticleSet<T>& ps, std::size_t first, std::size_t count,
                       std::uint32_t* out) const {
        std::uint64_t h[kHashBlock];
        state_hash_block(ps, fields_, first, count, h);
        for (std::size_t k = 0; k < count; ++k) out[k] = std::uint32_t(h[k] ^ (h[k] >> 32));
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

// Conservation watchdog (issue 8): compares a step's totals with the previous step and the
// start. Mass never changes (round-off of the sum only); momentum is conserved to round-off by
// the symmetric hydro pairs (not by tree gravity, nor by the periodic minimum image for angular
// momentum, which is therefore not checked); the total energy may change in one step by the
// time-integration error, a small fraction of the energy moved between forms in that step,
// dt * sum m (|v.a| + |du|). Returns "" or what was violated.
inline constexpr double kWatchdogEnergyBudget =
    0.25; // clean runs: <= 0.07 after step 1 // of dt * gross power (see docs/resilience)

inline std::string conservation_violation(const Diagnostics& prev, const Diagnostics& now,
                                          double mass0, bool check_momentum) {
    auto rel = [](double a, double b) { return std::abs(a - b) / std::max(std::abs(b), 1e-300); };
    auto num = [](double v) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.3e", v);
        return std::string(buf);
    };
    if (rel(now.mass, mass0) > 1e-12)
        return "total mass changed by " + num(rel(now.mass, mass0)) + " (relative)";
    // The first step after a start or a rollback has no previous accelerations (power 0) and
    // carries the integrator's start-up error (up to 3/4 of dt * power on clean runs); with
    // gravity the potential energy also moves with the adaptive softening and the tree
    // (~5e-4 of |E_pot| in the first steps of Evrard).
    const double factor = prev.power_abs > 0 ? kWatchdogEnergyBudget : 1.5;
    const double budget = factor * now.dt * std::max(now.power_abs, prev.power_abs) +
                          1e-12 * std::abs(now.etot) + 1e-3 * std::abs(now.epot);
    if (std::abs(now.etot - prev.etot) > budget)
        return "total energy changed by " + num(now.etot - prev.etot) + " in one step (budget " +
               num(budget) + ")";
    if (check_momentum) {
        const double dp =
            std::hypot(now.momentum[0] - prev.momentum[0], now.momentum[1] - prev.momentum[1],
                       now.momentum[2] - prev.momentum[2]);
        // Round-off scale: the momenta and the impulses of the step.
        const double scale = std::max(now.momentum_abs, prev.momentum_abs) + now.dt * now.force_abs;
        if (dp > 1e-10 * scale + 1e-300)
            return "linear momentum changed by " + num(dp) + " in one step (scale " + num(scale) +
                   ")";
    }
    return "";
}

} // namespace exasph
