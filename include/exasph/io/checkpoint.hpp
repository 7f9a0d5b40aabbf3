#pragma once
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "exasph/util/mpi.hpp"

#include "exasph/cases/initial_conditions.hpp"
#include "exasph/config/config.hpp"
#include "exasph/config/validate.hpp"
#include "exasph/io/atomic_output.hpp"
#include "exasph/io/file_seal.hpp"
#include "exasph/io/output_state.hpp"
#include "exasph/io/particle_io.hpp"
#include "exasph/io/restart_state.hpp"
#include "exasph/io/root_attributes.hpp"
#include "exasph/io/run_attributes.hpp"
#include "exasph/io/snapshot.hpp"
#include "exasph/util/checksum.hpp"

namespace exasph {

// Sealed (file_seal.hpp); 4 added the block-time-step clock and /derived inside a block (a
// version-3 file is a version-4 file without them, and is read as one).
inline constexpr const char* kCheckpointFormat = "exasph-checkpoint-4";
inline constexpr const char* kCheckpointFormatPrevious = "exasph-checkpoint-3";

// The particle fields a checkpoint holds: the state, and inside a block of block time steps
// (RestartState::block) the derived fields too, which inactive particles carry between sub-steps.
inline std::uint8_t checkpoint_roles(const RestartState& rs) {
    return rs.block.tick != 0 ? kState | kDerived : kState;
}

// Checksum of everything a restart continues from: per particle a hash chain of its id and the
// bits of every field of checkpoint_roles (in field-list order), summed over particles modulo 2^64
// so that it does not depend on how the particles are distributed or ordered; plus a chain of the
// scalars and the global tree. One collective (a sum); rank-count independent.
template <class T>
std::uint64_t checkpoint_checksum(const ParticleSet<T>& ps, std::size_t n, const RestartState& rs,
                                  double dt0, MPI_Comm comm) {
    const auto fields = ps.fields(checkpoint_roles(rs));
    std::uint64_t sum = 0;
    for (std::size_t i = 0; i < n; ++i) {
        HashChain h(ps.id[i]);
        for (Field f : fields) h.add_float(ps.value(f, i));
        sum += h.value();
    }
    MPI_Allreduce(MPI_IN_PLACE, &sum, 1, MPI_UINT64_T, MPI_SUM, comm);
    HashChain scalars(0x65786173706800ull);
    scalars.add_float(rs.time).add(std::uint64_t(rs.step)).add_float(rs.dt_m1).add_float(dt0);
    for (auto k : rs.leaf_keys) scalars.add(k);
    if (rs.block.tick != 0)
        scalars.add(std::uint64_t(rs.block.tick)).add_float(rs.block.start).add_float(rs.block.end);
    if (!rs.stir.coeff.empty()) { // a run with stirring
        scalars.add_float(rs.stir.accel_rms).add_float(rs.stir.t_corr);
        scalars.add_float(rs.stir.energy_in);
        for (double c : rs.stir.coeff) scalars.add_float(c);
    }
    return sum + scalars.value();
}

// Driven turbulence: the stirring's state (sim/stirring.hpp) as root attributes.
inline void write_stir_state(const h5::Group& root, const StirState& st) {
    h5::write_attribute(root, "stir_accel_rms", st.accel_rms);
    h5::write_attribute(root, "stir_t_corr", st.t_corr);
    h5::write_attribute(root, "stir_energy_in", st.energy_in);
    h5::write_attribute(root, "stir_coeff", st.coeff);
}

inline StirState read_stir_state(const h5::Group& root) {
    auto coeff = h5::read_attribute_doubles(root, "stir_coeff");
    for (double c : coeff)
        if (!std::isfinite(c)) throw attribute_error(root, "stir_coeff", "must be finite");
    return {read_finite(root, "stir_accel_rms"), read_finite(root, "stir_t_corr"),
            read_finite(root, "stir_energy_in"), coeff};
}

// Block time steps inside a block: the clock as root attributes.
inline void write_block_point(const h5::Group& root, const BlockPoint& b) {
    h5::write_attribute(root, "block_tick", b.tick);
    h5::write_attribute(root, "block_start", b.start);
    h5::write_attribute(root, "block_end", b.end);
}

inline BlockPoint read_block_point(const h5::Group& root, const Config& cfg) {
    BlockPoint b;
    const double tick = read_finite(root, "block_tick");
    b.start = read_finite(root, "block_start");
    b.end = read_finite(root, "block_end");
    if (!(tick > 0 && tick < 0x1p24 && b.end > b.start))
        throw attribute_error(root, "block_tick", "out of range (or block_end <= block_start)");
    if (cfg.timesteps != TimeStepping::block)
        throw attribute_error(root, "block_tick", "given, but the run has global time steps");
    b.tick = std::int64_t(tick);
    return b;
}

// Inside a block: the derived fields of /derived (the optional ones the run had; reading one
// enables it), with the ids, which must be those of /state in the same order.
template <class T>
void read_derived_fields(const h5::File& file, ParticleSet<T>& ps, MPI_Comm comm) {
    h5::Group derived(file, "/derived", false);
    std::vector<Field> required, optional;
    for (Field f : fields_with_role(kDerived))
        (field_info(f).roles & kOptional ? optional : required).push_back(f);
    const std::vector<std::uint64_t> ids(ps.id.begin(), ps.id.end());
    read_particle_fields(derived, ps, required, optional, true, comm);
    int same = std::equal(ps.id.begin(), ps.id.end(), ids.begin(), ids.end());
    MPI_Allreduce(MPI_IN_PLACE, &same, 1, MPI_INT, MPI_MIN, comm); // all ranks: 1
    if (!same) throw input_error(file.path() + ": /derived/id differs from /state/id", true);
}

// Test hook for the crash-safety test: with EXASPH_TEST_CHECKPOINT_STALL=STEP set, the checkpoint
// of that step sleeps for a minute after writing half of its data (so a test can SIGKILL the run
// mid-write). Costs one getenv per checkpoint otherwise.
inline void checkpoint_test_stall(std::int64_t step) {
    const char* s = std::getenv("EXASPH_TEST_CHECKPOINT_STALL");
    if (s && std::atoll(s) == step) std::this_thread::sleep_for(std::chrono::seconds(60));
}

// The checkpoints of a directory, newest first (their names carry the step, zero-padded).
inline std::vector<std::string> checkpoints_newest_first(const std::string& dir) {
    std::vector<std::string> found;
    std::error_code ec;
    for (const auto& e : std::filesystem::directory_iterator(dir, ec)) {
        const auto name = e.path().filename().string();
        if (name.rfind("checkpoint_", 0) == 0 && e.path().extension() == ".h5")
            found.push_back(e.path().string());
    }
    std::sort(found.rbegin(), found.rend());
    return found;
}

// Keeps the newest `keep` checkpoints of the directory, deleting older ones (rank 0).
inline void prune_checkpoints(const std::string& dir, std::size_t keep) {
    const auto found = checkpoints_newest_first(dir);
    std::error_code ec;
    for (std::size_t i = keep; i < found.size(); ++i) std::filesystem::remove(found[i], ec);
}

// Everything needed to continue exactly: all state fields and ids of the owned particles, the
// step, time, previous dt, first dt, box, EOS, parameters and the global tree, with their
// checksum (verified on restart), then sealed (io/file_seal.hpp: a hash of the whole file in its
// user block). Atomic (temporary name, then rename); the previous checkpoint is kept.
template <class T>
std::string write_checkpoint(const OutputState<T>& run, const Config& cfg, const std::string& units,
                             MPI_Comm comm) {
    const auto& rs = run.restart;
    const std::string path = numbered_path(cfg.out_dir, "checkpoint", rs.step, ".h5");
    int rank = 0;
    MPI_Comm_rank(comm, &rank);
    const std::uint64_t checksum =
        checkpoint_checksum(run.particles, run.n_owned, rs, run.dt0, comm);
    try {
        h5::File file = h5::File::create(temporary_name(path), comm, kSealBytes);
        h5::Group root(file, "/", false);
        h5::write_attribute(root, "format", std::string(kCheckpointFormat));
        h5::write_attribute(root, "checksum", hex64(checksum));
        write_run_attributes(root, cfg, run.box, run.eos, units);
        h5::write_attribute(root, "time", rs.time);
        h5::write_attribute(root, "step", std::int64_t(rs.step));
        h5::write_attribute(root, "dt_m1", rs.dt_m1);
        h5::write_attribute(root, "dt0", run.dt0);
        if (!rs.stir.coeff.empty()) write_stir_state(root, rs.stir);
        if (rs.block.tick != 0) write_block_point(root, rs.block);
        h5::Group state(file, "/state", true);
        const auto fields = run.particles.fields(kState); // the optional ones the run carries
        const std::vector<Field> first(fields.begin(), fields.begin() + fields.size() / 2);
        const std::vector<Field> second(fields.begin() + fields.size() / 2, fields.end());
        write_particle_fields(state, run.particles, run.n_owned, first, false, comm);
        checkpoint_test_stall(rs.step);
        write_particle_fields(state, run.particles, run.n_owned, second, true, comm);
        if (rs.block.tick != 0) {
            h5::Group derived(file, "/derived", true);
            write_particle_fields(derived, run.particles, run.n_owned,
                                  run.particles.fields(kDerived), true, comm);
        }
        h5::Group domain(file, "/domain", true);
        const auto& keys = rs.leaf_keys;
        h5::write_u64(domain, "leaf_keys", keys.data(), rank == 0 ? keys.size() : 0, 0,
                      keys.size());
    } catch (...) {
        discard_output(path, comm);
        throw;
    }
    try {
        seal_file(temporary_name(path), comm);
    } catch (...) {
        discard_output(path, comm);
        throw;
    }
    commit_output(path, comm);
    if (rank == 0) prune_checkpoints(cfg.out_dir, 2);
    return path;
}

template <class T>
struct Checkpoint {
    InitialConditions<T> ic;
    RestartState rs;
};

// Reads a checkpoint written by any rank count; fills the physics parameters of cfg. Refuses a
// file whose seal or checksum does not match its contents (altered or corrupted on disk): the
// seal is verified before HDF5 reads a byte of it.
template <class T>
Checkpoint<T> read_checkpoint(const std::string& path, Config& cfg, MPI_Comm comm) {
    verify_seal(path, comm, "an exasph checkpoint");
    h5::File file = h5::File::open_read(path, comm);
    h5::Group root(file, "/", false);
    const std::string format =
        h5::has_attribute(root, "format") ? h5::read_attribute_string(root, "format") : "";
    if (format != kCheckpointFormat && format != kCheckpointFormatPrevious)
        throw input_error(path + ": not an exasph checkpoint (attribute /format)", true);
    Checkpoint<T> cp;
    read_run_parameters(root, cfg);
    try { // the parameters together, as for a new run (each was range-checked when read)
        validate_config(cfg);
    } catch (const Error& e) {
        throw input_error(path + ": its parameters: " + e.what(), true);
    }
    cp.ic.box = read_box<T>(root);
    const std::string eos = h5::read_attribute_string(root, "eos");
    if (eos != "tait" && eos != "ideal-gas")
        throw attribute_error(root, "eos", "'" + eos + "' is not tait or ideal-gas");
    cp.ic.eos.kind = eos == "tait" ? EosKind::tait : EosKind::ideal_gas;
    cp.ic.eos.gamma = read_finite(root, "gamma");
    cp.ic.eos.c0 = read_finite(root, "sound_speed");
    cp.ic.units = h5::read_attribute_string(root, "units");
    cp.ic.dt0 = read_finite(root, "dt0");
    cp.ic.name = cfg.init;
    cp.rs.time = read_finite(root, "time");
    const double step = read_finite(root, "step");
    cp.rs.dt_m1 = read_finite(root, "dt_m1");
    if (!(cp.ic.dt0 > 0 && cp.rs.dt_m1 >= 0 && step >= 0 && step < 9e15 && cp.ic.eos.gamma > 0))
        throw input_error(path + ": dt0, dt_m1, step or gamma out of range", true);
    cp.rs.step = std::int64_t(step);
    if (h5::has_attribute(root, "stir_coeff")) cp.rs.stir = read_stir_state(root);
    if (h5::has_attribute(root, "block_tick")) cp.rs.block = read_block_point(root, cfg);
    cp.ic.particles.set_narrow_single(!cfg.double_precision); // derived fields: as written
    h5::Group state(file, "/state", false);
    // Optional state fields (Tait reference state, alpha, X) are in the file when the run
    // carried them; reading one enables it.
    std::vector<Field> required, optional;
    for (Field f : fields_with_role(kState))
        (field_info(f).roles & kOptional ? optional : required).push_back(f);
    read_particle_fields(state, cp.ic.particles, required, optional, true, comm);
    if (cp.rs.block.tick != 0) read_derived_fields(file, cp.ic.particles, comm);
    h5::Group domain(file, "/domain", false);
    const std::uint64_t nkeys = h5::dataset_length(domain, "leaf_keys", true);
    cp.rs.leaf_keys = h5::read_u64(domain, "leaf_keys", 0, nkeys);
    const std::string stored = h5::read_attribute_string(root, "checksum");
    const std::string found =
        hex64(checkpoint_checksum(cp.ic.particles, cp.ic.particles.size(), cp.rs, cp.ic.dt0, comm));
    if (stored != found)
        throw input_error(path + ": checksum mismatch (stored " + stored + ", contents " + found +
                              "): the file was altered or corrupted; not restarting",
                          true);
    collective_check(comm, [&] { validate_input_particles(cp.ic.particles, path, cp.ic.box); });
    return cp;
}

} // namespace exasph
