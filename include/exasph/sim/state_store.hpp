#pragma once
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "exasph/particles/particle_set.hpp"
#include "exasph/sim/state_hash.hpp"
#include "exasph/util/error.hpp"

namespace exasph {

// The rollback point's particles (issue 8): in memory or in one file per rank.

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
                                   const std::vector<Field>& state) {
        std::uint64_t sum = 0;
        const auto nn = std::int64_t(n);
#pragma omp parallel for schedule(static) reduction(+ : sum)
        for (std::int64_t i = 0; i < nn; ++i) sum += particle_state_hash(ps, std::size_t(i), state);
        return sum;
    }

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

} // namespace exasph
