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
#include "exasph/io/unit_scales.hpp"
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

// The snapshot format's version (root attribute format_version): 2 is the GADGET layout;
// version 1 (no attribute) held group Step#N with one 1-D dataset per field.
inline constexpr std::int64_t kSnapshotFormatVersion = 2;

// /Header as GADGET-layout readers (yt, GADGET tools) need it: gas counts, MassTable of zeros
// (masses per particle), Time, BoxSize (one number for a cube, else one per axis), one file;
// and exasph's step and dt. Runs with physical units (cgs, or a file's: io/unit_scales.hpp) also
// state their unit scales, as GADGET does.
template <class T>
void write_gadget_header(const h5::Group& header, std::uint64_t n, const OutputState<T>& run,
                         const std::string& units) {
    const std::vector<std::int64_t> gas_count = {std::int64_t(n), 0, 0, 0, 0, 0};
    h5::write_attribute(header, "NumPart_ThisFile", gas_count);
    h5::write_attribute(header, "NumPart_Total", gas_count);
    h5::write_attribute(header, "NumPart_Total_HighWord", std::vector<std::int64_t>(6, 0));
    h5::write_attribute(header, "MassTable", std::vector<double>(6, 0.0));
    h5::write_attribute(header, "Time", run.restart.time);
    h5::write_attribute(header, "Redshift", 0.0);
    h5::write_attribute(header, "NumFilesPerSnapshot", std::int64_t(1));
    h5::write_attribute(header, "Flag_DoublePrecision", std::int64_t(1));
    std::vector<double> side(3);
    for (int d = 0; d < 3; ++d) side[d] = double(run.box.hi[d]) - double(run.box.lo[d]);
    const bool cube = side[0] == side[1] && side[1] == side[2];
    h5::write_attribute(header, "BoxSize", cube ? std::vector<double>{side[0]} : side);
    h5::write_attribute(header, "step", std::int64_t(run.restart.step));
    h5::write_attribute(header, "dt", run.dt);
    if (const auto s = unit_scales(units)) {
        h5::write_attribute(header, "UnitLength_in_cm", s->length_cm);
        h5::write_attribute(header, "UnitMass_in_g", s->mass_g);
        h5::write_attribute(header, "UnitVelocity_in_cm_per_s", s->velocity_cm_per_s);
        h5::write_attribute(header, "UnitTime_in_s", s->length_cm / s->velocity_cm_per_s);
    }
}

// Snapshot in the GADGET layout (docs/file-format.md): /Header, and the gas datasets of the
// chosen fields in /PartType0 (all ranks write their owned particles collectively, no gather)
// with unit:NAME attributes; run attributes on the root; an XDMF sidecar on the same datasets.
// Written under a temporary name, renamed when complete.
template <class T>
std::string write_snapshot(const OutputState<T>& run, const Config& cfg, const std::string& units,
                           const std::vector<Field>& fields, MPI_Comm comm) {
    const std::int64_t step = run.restart.step;
    const std::string path = numbered_path(cfg.out_dir, "snapshot", step, ".h5");
    const std::string group = "/PartType0";
    const std::vector<GadgetDataset> sets = gadget_datasets(fields);
    std::uint64_t n = 0;
    try {
        h5::File file = h5::File::create(temporary_name(path), comm);
        h5::Group root(file, "/", false);
        write_run_attributes(root, cfg, run.box, run.eos, units);
        h5::write_attribute(root, "dt0", run.dt > 0 ? run.dt : run.dt0);
        h5::write_attribute(root, "format_version", kSnapshotFormatVersion);
        h5::Group gas(file, group, true);
        n = write_gadget_datasets(gas, run.particles, run.n_owned, sets, comm);
        for (const GadgetDataset& d : sets)
            h5::write_attribute(gas, "unit:" + d.name, std::string(field_info(d.first).unit));
        write_gadget_header(h5::Group(file, "/Header", true), n, run, units);
    } catch (...) {
        discard_output(path, comm);
        throw;
    }
    commit_output(path, comm);
    int rank = 0;
    MPI_Comm_rank(comm, &rank);
    if (rank == 0) {
        std::vector<XdmfField> xfields;
        for (const GadgetDataset& d : sets)
            xfields.push_back({d.name, std::string(field_info(d.first).unit), d.width});
        const XdmfInformation info = {{"scheme", std::string(choice_name(cfg.scheme))},
                                      {"units", units}};
        const std::string xdmf = numbered_path(cfg.out_dir, "snapshot", step, ".xdmf");
        write_text_file_atomically(
            xdmf, xdmf_document(xdmf_grid(std::filesystem::path(path).filename().string(), group, n,
                                          run.restart.time, gadget_column(Field::x).dataset.name,
                                          xfields, info)));
        write_xdmf_time_series(cfg.out_dir, step);
    }
    return path;
}

} // namespace exasph
