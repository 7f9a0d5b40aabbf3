#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "exasph/util/mpi.hpp"

#include "exasph/cases/initial_conditions.hpp"
#include "exasph/cases/initial_h.hpp"
#include "exasph/io/gadget_layout.hpp"
#include "exasph/io/h5_file.hpp"
#include "exasph/io/particle_io.hpp"
#include "exasph/io/unit_scales.hpp"
#include "exasph/util/error.hpp"

// Initial conditions in the GADGET HDF5 layout, which GADGET-2/3/4, SWIFT, AREPO and GIZMO read
// and write and IC tools produce (docs/file-format.md, "Initial conditions from other codes"):
// attributes of /Header (NumPart_Total[6], NumPart_Total_HighWord[6] if present, MassTable[6],
// BoxSize) and the gas particles' datasets in /PartType0: Coordinates and Velocities (N x 3),
// InternalEnergy, Masses (unless MassTable[0] > 0), SmoothingLength, Density and ParticleIDs
// (optional). Gas only: a file with particles of other types is refused, naming them.
namespace exasph {

// Does the file hold the GADGET layout (a /Header group and gas in /PartType0)?
inline bool is_gadget_layout(const h5::Group& root) {
    return h5::has_link(root, "Header") && h5::has_link(root, "PartType0");
}

namespace gadget {

// An attribute of /Header with exactly six numbers (one per particle type).
inline std::array<double, 6> six(const h5::Group& header, const std::string& name) {
    const auto v = h5::read_attribute_doubles(header, name);
    if (v.size() != 6)
        throw input_error(header.file().path() + ": attribute /Header/" + name +
                          " must have 6 entries (one per particle type), has " +
                          std::to_string(v.size()));
    std::array<double, 6> out{};
    for (std::size_t k = 0; k < 6; ++k) out[k] = v[k];
    return out;
}

// Particles of each type: NumPart_Total + 2^32 NumPart_Total_HighWord.
inline std::array<std::uint64_t, 6> particle_counts(const h5::Group& header) {
    const auto low = six(header, "NumPart_Total");
    std::array<double, 6> high{};
    if (h5::has_attribute(header, "NumPart_Total_HighWord"))
        high = six(header, "NumPart_Total_HighWord");
    std::array<std::uint64_t, 6> n{};
    for (std::size_t k = 0; k < 6; ++k) {
        if (!(low[k] >= 0 && high[k] >= 0))
            throw input_error(header.file().path() + ": /Header/NumPart_Total is negative");
        n[k] = std::uint64_t(low[k]) + (std::uint64_t(high[k]) << 32);
    }
    return n;
}

// exasph runs gas alone: other particle types are refused, each named with its count.
inline void refuse_other_types(const std::array<std::uint64_t, 6>& n, const std::string& path) {
    std::string others;
    for (std::size_t k = 1; k < 6; ++k)
        if (n[k] > 0)
            others += (others.empty() ? "" : ", ") + std::string("PartType") + std::to_string(k) +
                      " (" + std::to_string(n[k]) + ")";
    if (!others.empty())
        throw input_error(path + ": particles of types other than gas (" + others +
                          "): exasph reads gas (PartType0) only");
    if (n[0] == 0) throw input_error(path + ": /Header/NumPart_Total says 0 gas particles");
}

// The periodic box [0, BoxSize) on every axis (BoxSize: one number, or one per axis).
template <class T>
Box<T> periodic_box(const h5::Group& header) {
    if (!h5::has_attribute(header, "BoxSize"))
        throw input_error(header.file().path() + ": no attribute /Header/BoxSize: the periodic "
                                                 "box [0, BoxSize) (or run with --open-box)");
    const auto v = h5::read_attribute_doubles(header, "BoxSize");
    if (v.size() != 1 && v.size() != 3)
        throw input_error(header.file().path() + ": attribute /Header/BoxSize must be one number "
                                                 "or three");
    Box<T> box;
    for (int d = 0; d < 3; ++d) {
        const double side = v[v.size() == 1 ? 0 : std::size_t(d)];
        if (!(side > 0 && std::isfinite(side)))
            throw input_error(header.file().path() + ": /Header/BoxSize must be positive, is " +
                              std::to_string(side));
        box.lo[d] = T(0);
        box.hi[d] = T(side);
        box.periodic[d] = true;
    }
    return box;
}

// The gas datasets of this rank's rows [lo, lo + count), as read from the file.
struct GasRows {
    std::vector<double> pos, vel, u, m, h, rho;
    std::vector<std::uint64_t> id;
};

// This rank's rows [lo, lo + count) of a gas dataset of n rows of `width` values; empty when
// optional and absent.
inline std::vector<double> read_gas(const h5::Group& gas, const std::string& name,
                                    std::uint64_t width, std::uint64_t n, std::uint64_t lo,
                                    std::uint64_t count, bool required) {
    if (!required && !h5::has_link(gas, name)) return {};
    expect_gas_rows(gas, name, width, n);
    return h5::read_double_rows(gas, name, lo, count, width);
}

template <class T>
void refuse_negative_energy(const ParticleSet<T>& ps, const std::string& path) {
    const auto& u = ps[Field::u];
    for (std::size_t i = 0; i < ps.size(); ++i)
        if (!(u[i] >= 0))
            throw input_error(path + ": InternalEnergy of particle id " + std::to_string(ps.id[i]) +
                              " must not be negative, is " + std::to_string(u[i]));
}

// The run attributes of a file from another code: ideal gas with gamma = 5/3 (the layout does
// not store it) in the periodic box of BoxSize (unless `open`: then the box is the particles',
// set when they are read), in the file's units where it states them; the first time step 1e-6.
template <class T>
InitialConditions<T> run_attributes(const h5::Group& header, bool open) {
    InitialConditions<T> ic;
    ic.name = header.file().path();
    if (!open) ic.box = periodic_box<T>(header);
    ic.eos = {EosKind::ideal_gas, 5.0 / 3.0, 0.0};
    if (const auto scales = read_unit_scales(header.file())) ic.units = describe_units(*scales);
    return ic;
}

// The bounding box of every rank's positions (rows of x, y, z), open on every axis (one
// collective). An axis on which all particles share a coordinate gets a width of 1e-6 of the
// largest |coordinate| (or 1), so that lo < hi.
template <class T>
Box<T> open_bounding_box(const std::vector<double>& pos, MPI_Comm comm) {
    double lo_neg_hi[6] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL, -HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (std::size_t i = 0; i + 2 < pos.size(); i += 3)
        for (int d = 0; d < 3; ++d) {
            lo_neg_hi[d] = std::max(lo_neg_hi[d], -pos[i + std::size_t(d)]);
            lo_neg_hi[3 + d] = std::max(lo_neg_hi[3 + d], pos[i + std::size_t(d)]);
        }
    MPI_Allreduce(MPI_IN_PLACE, lo_neg_hi, 6, MPI_DOUBLE, MPI_MAX, comm);
    Box<T> box;
    for (int d = 0; d < 3; ++d) {
        double lo = -lo_neg_hi[d], hi = lo_neg_hi[3 + d];
        if (!(lo < hi)) {
            const double pad = 1e-6 * std::max({std::abs(lo), std::abs(hi), 1.0});
            lo -= pad;
            hi += pad;
        }
        box.lo[d] = T(lo);
        box.hi[d] = T(hi);
        box.periodic[d] = false;
    }
    return box;
}

} // namespace gadget

// The gas of a GADGET-layout file into `ic` (whose box, unless `open_box`, and dt0 are set);
// every rank reads its share of the rows. Masses from MassTable[0] when it is positive, else from
// Masses; h from SmoothingLength (the kernel support radius 2h), else ng0 neighbours at the
// particle's Density, else at the box's mean density (the run's first steps then adjust h).
template <class T>
void read_gadget_gas(const h5::File& file, MPI_Comm comm, double ng0, InitialConditions<T>& ic,
                     bool open_box) {
    const std::string& path = file.path();
    h5::Group header(file, "/Header", false), gas(file, "/PartType0", false);
    const auto files = h5::has_attribute(header, "NumFilesPerSnapshot")
                           ? h5::read_attribute_doubles(header, "NumFilesPerSnapshot")
                           : std::vector<double>{};
    if (!files.empty() && files[0] > 1)
        throw input_error(path + ": one file of a set split over several (NumFilesPerSnapshot > "
                                 "1): join them into one file first");
    const auto counts = gadget::particle_counts(header);
    gadget::refuse_other_types(counts, path);
    const std::uint64_t n = counts[0];
    int rank = 0, nranks = 1;
    MPI_Comm_rank(comm, &rank);
    MPI_Comm_size(comm, &nranks);
    const std::uint64_t lo = n * std::uint64_t(rank) / std::uint64_t(nranks);
    const std::uint64_t count = n * std::uint64_t(rank + 1) / std::uint64_t(nranks) - lo;
    auto name = [](Field f) { return gadget_column(f).dataset.name; };

    gadget::GasRows r;
    r.pos = gadget::read_gas(gas, name(Field::x), 3, n, lo, count, true);
    if (open_box) ic.box = gadget::open_bounding_box<T>(r.pos, comm);
    r.vel = gadget::read_gas(gas, name(Field::vx), 3, n, lo, count, false);
    if (r.vel.empty()) r.vel.assign(3 * count, 0.0); // at rest
    r.u = gadget::read_gas(gas, name(Field::u), 1, n, lo, count, true);
    const double table_mass = gadget::six(header, "MassTable")[0];
    r.m = table_mass > 0 ? std::vector<double>(count, table_mass)
                         : gadget::read_gas(gas, name(Field::m), 1, n, lo, count, true);
    r.h = gadget::read_gas(gas, name(Field::h), 1, n, lo, count, false);
    if (r.h.empty()) r.rho = gadget::read_gas(gas, name(Field::rho), 1, n, lo, count, false);
    if (h5::has_link(gas, kGadgetIds)) {
        expect_gas_rows(gas, kGadgetIds, 1, n, true);
        r.id = h5::read_u64(gas, kGadgetIds, lo, count);
    }
    const double support = gadget_column(Field::h).dataset.scale; // SmoothingLength / h
    double volume = 1;
    for (int d = 0; d < 3; ++d) volume *= double(ic.box.hi[d]) - double(ic.box.lo[d]);
    auto& ps = ic.particles;
    ps.resize(count);
    for (std::size_t s = 0; s < count; ++s) {
        const double spacing =
            !r.rho.empty() ? std::cbrt(r.m[s] / r.rho[s]) : std::cbrt(volume / double(n));
        const double h = r.h.empty() ? initial_smoothing_length(spacing, ng0) : r.h[s] / support;
        const double pos[3] = {r.pos[3 * s], r.pos[3 * s + 1], r.pos[3 * s + 2]};
        const double vel[3] = {r.vel[3 * s], r.vel[3 * s + 1], r.vel[3 * s + 2]};
        set_particle(ps, s, r.id.empty() ? lo + s : r.id[s], pos, vel, ic.dt0, h, r.m[s], r.u[s]);
    }
    collective_check(comm, [&] {
        validate_input_particles(ps, path, ic.box);
        gadget::refuse_negative_energy(ps, path); // an ideal gas (other layouts may hold any EOS)
    });
}

} // namespace exasph
