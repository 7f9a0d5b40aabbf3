#pragma once
#include <algorithm>
#include <string>

#include "exasph/util/mpi.hpp"

#include "exasph/cases/initial_conditions.hpp"
#include "exasph/io/gadget_ic.hpp"
#include "exasph/io/h5_file.hpp"
#include "exasph/io/particle_io.hpp"
#include "exasph/io/root_attributes.hpp"

namespace exasph {

// Does --init name a file (rather than a test case)?
inline bool names_a_file(const std::string& init) {
    auto ends_with = [&](const std::string& s) {
        return init.size() >= s.size() && init.compare(init.size() - s.size(), s.size(), s) == 0;
    };
    return ends_with(".h5") || ends_with(".hdf5") || init.find('/') != std::string::npos;
}

// The group holding the particle datasets: the highest-numbered "Step#N" group (so that a
// snapshot can seed a new run), or the root group.
inline std::string particle_group_name(const h5::Group& root) {
    long best = -1;
    for (const auto& name : h5::member_names(root)) {
        if (name.rfind("Step#", 0) != 0) continue;
        try {
            best = std::max(best, std::stol(name.substr(5)));
        } catch (const std::exception&) {
        }
    }
    return best < 0 ? "/" : "/Step#" + std::to_string(best);
}

// The run attributes exasph writes on a file's root (box, ideal-gas gamma, dt0, t_end, units),
// as the start of initial conditions read from it.
template <class T>
InitialConditions<T> own_run_attributes(const h5::Group& root) {
    const std::string& path = root.file().path();
    InitialConditions<T> ic;
    ic.name = path;
    ic.box = read_box<T>(root);
    if (h5::has_attribute(root, "eos") && h5::read_attribute_string(root, "eos") != "ideal-gas")
        throw input_error(path +
                          ": attribute /eos: only 'ideal-gas' initial conditions can be read");
    ic.eos = {EosKind::ideal_gas, read_finite(root, "gamma", 5.0 / 3.0), 0.0};
    if (!(ic.eos.gamma > 1.0)) throw input_error(path + ": attribute /gamma must be above 1");
    ic.dt0 = read_finite(root, "dt0", 1e-6);
    if (!(ic.dt0 > 0)) throw input_error(path + ": attribute /dt0 must be positive");
    ic.t_end = read_finite(root, "t_end", 0.0);
    if (h5::has_attribute(root, "units")) ic.units = h5::read_attribute_string(root, "units");
    return ic;
}

// Was the file written by exasph (its run attributes on the root)?
inline bool written_by_exasph(const h5::Group& root) {
    return h5::has_attribute(root, "box_lo");
}

// Initial conditions from an HDF5 file in the layout of docs/file-format.md, or in the GADGET
// layout of other codes and of exasph's snapshots (io/gadget_ic.hpp: h from ng0 neighbours where
// the file has none); every rank reads its share. Ideal-gas EOS with the file's gamma.
// `open_box`: a file of another code in the GADGET layout gets open boundaries around its
// particles instead of the periodic box [0, BoxSize) (files exasph wrote state their box).
template <class T>
InitialConditions<T> read_initial_conditions(const std::string& path, MPI_Comm comm,
                                             double ng0 = 100, bool open_box = false) {
    h5::File file = h5::File::open_read(path, comm);
    h5::Group root(file, "/", false);
    const bool own = written_by_exasph(root);
    if (open_box && (own || !is_gadget_layout(root)))
        throw input_error("--open-box: " + path +
                              " is in exasph's layout, which states its box "
                              "(box_lo, box_hi, periodic)",
                          true);
    if (is_gadget_layout(root)) {
        InitialConditions<T> ic =
            own ? own_run_attributes<T>(root)
                : gadget::run_attributes<T>(h5::Group(file, "/Header", false), open_box);
        read_gadget_gas(file, comm, ng0, ic, open_box);
        return ic;
    }
    if (h5::has_link(root, "PartType0"))
        throw input_error(path + ": a GADGET-layout file (it has /PartType0) needs a /Header group",
                          true);
    InitialConditions<T> ic = own_run_attributes<T>(root);
    h5::Group data(file, particle_group_name(root), false);
    auto& ps = ic.particles;
    read_particle_fields(data, ps, {Field::x, Field::y, Field::z, Field::m, Field::h},
                         {Field::vx, Field::vy, Field::vz, Field::u}, false, comm);
    collective_check(comm, [&] { validate_input_particles(ps, path, ic.box); });
    for (std::size_t i = 0; i < ps.size(); ++i) {
        ps[Field::x_m1][i] = ps[Field::x][i] - ps[Field::vx][i] * T(ic.dt0);
        ps[Field::y_m1][i] = ps[Field::y][i] - ps[Field::vy][i] * T(ic.dt0);
        ps[Field::z_m1][i] = ps[Field::z][i] - ps[Field::vz][i] * T(ic.dt0);
    }
    return ic;
}

} // namespace exasph
