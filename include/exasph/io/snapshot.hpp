#pragma once
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "exasph/util/mpi.hpp"

#include "exasph/config/config.hpp"
#include "exasph/io/atomic_output.hpp"
#include "exasph/io/output_state.hpp"
#include "exasph/io/particle_io.hpp"
#include "exasph/io/run_attributes.hpp"
#include "exasph/io/xdmf.hpp"

namespace exasph {

// Resolves -f names to fields (x, y, z are always written: ParaView needs the geometry). The
// strain rate (strain_xx ..) exists only in runs with --av-limiter (`with_gradient`).
inline std::vector<Field> snapshot_field_list(const std::vector<std::string>& names,
                                              bool with_gradient = false) {
    std::vector<Field> out{Field::x, Field::y, Field::z};
    if (names.empty()) {
        for (const auto& info : kFieldTable)
            if ((info.roles & kSnapshot) &&
                std::find(out.begin(), out.end(), info.field) == out.end())
                out.push_back(info.field);
        return out;
    }
    for (const auto& n : names) {
        auto it = std::find_if(kFieldTable.begin(), kFieldTable.end(),
                               [&](const FieldInfo& f) { return f.name == n; });
        if (it == kFieldTable.end()) {
            std::string known;
            for (const auto& f : kFieldTable) {
                if (!known.empty()) known += ',';
                known += f.name;
            }
            throw input_error("-f: unknown field '" + n + "' (known: " + known + ")", true);
        }
        if ((it->roles & kHaloGrad) && !with_gradient)
            throw input_error("-f: field '" + n + "' is computed only with --av-limiter", true);
        if (std::find(out.begin(), out.end(), it->field) == out.end()) out.push_back(it->field);
    }
    return out;
}

// What makes a run carry an optional field (for error messages).
inline std::string optional_field_needs(Field f) {
    switch (f) {
    case Field::alpha:
    case Field::divv:
        return "per-particle alpha needs --av-switch; otherwise alpha is --alpha";
    case Field::xm:
    case Field::kx:
        return "only with --volume-elements";
    case Field::phi:
        return "only with self-gravity";
    case Field::stir:
        return "only with stirring (--stir-mach)";
    case Field::rho0:
    case Field::p0:
        return "only with the Tait EOS";
    default:
        return "only with --av-limiter";
    }
}

inline std::string numbered_path(const std::string& dir, const char* stem, std::int64_t step,
                                 const char* ext) {
    char name[64];
    std::snprintf(name, sizeof name, "%s_%06lld%s", stem, (long long)step, ext);
    return (std::filesystem::path(dir) / name).string();
}

// Snapshot in the H5Part layout: group Step#N holding one 1-D dataset per field (all ranks write
// their owned particles collectively, no gather), with time/step/dt attributes, run attributes
// on the root, and an XDMF sidecar. Written under a temporary name, renamed when complete.
template <class T>
std::string write_snapshot(const OutputState<T>& run, const Config& cfg, const std::string& units,
                           const std::vector<Field>& fields, MPI_Comm comm) {
    const std::int64_t step = run.restart.step;
    const std::string path = numbered_path(cfg.out_dir, "snapshot", step, ".h5");
    const std::string group = "/Step#" + std::to_string(step);
    std::uint64_t n = 0;
    try {
        h5::File file = h5::File::create(temporary_name(path), comm);
        h5::Group root(file, "/", false);
        write_run_attributes(root, cfg, run.box, run.eos, units);
        h5::write_attribute(root, "dt0", run.dt > 0 ? run.dt : run.dt0);
        h5::Group g(file, group, true);
        h5::write_attribute(g, "time", run.restart.time);
        h5::write_attribute(g, "step", std::int64_t(step));
        h5::write_attribute(g, "dt", run.dt);
        n = write_particle_fields(g, run.particles, run.n_owned, fields, true, comm);
        write_position_rows(g, run.particles, run.n_owned, comm);
        h5::write_attribute(g, "unit:xyz", std::string("length"));
        h5::write_attribute(g, "numParticles", std::int64_t(n));
        for (Field f : fields)
            h5::write_attribute(g, "unit:" + std::string(field_info(f).name),
                                std::string(field_info(f).unit));
    } catch (...) {
        discard_output(path, comm);
        throw;
    }
    commit_output(path, comm);
    int rank = 0;
    MPI_Comm_rank(comm, &rank);
    if (rank == 0) {
        std::vector<XdmfField> xfields;
        for (Field f : fields)
            xfields.push_back({std::string(field_info(f).name), std::string(field_info(f).unit)});
        const XdmfInformation info = {{"scheme", std::string(choice_name(cfg.scheme))},
                                      {"units", units}};
        const std::string xdmf = numbered_path(cfg.out_dir, "snapshot", step, ".xdmf");
        write_text_file_atomically(
            xdmf, xdmf_document(xdmf_grid(std::filesystem::path(path).filename().string(), group, n,
                                          run.restart.time, xfields, info)));
        write_xdmf_time_series(cfg.out_dir, step);
    }
    return path;
}

} // namespace exasph
