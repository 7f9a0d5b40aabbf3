#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "exasph/io/h5_file.hpp"
#include "exasph/particles/field_list.hpp"
#include "exasph/util/error.hpp"

// The gas datasets of the GADGET HDF5 layout (group /PartType0) that GADGET-2/3/4, SWIFT, AREPO,
// GIZMO and yt share, and the exasph fields each holds: the one name table of the layout, used
// by the initial-conditions reader, the snapshot writer and the snapshot readers.
namespace exasph {

// A dataset of `width` values per particle (1: 1-D; 3: N x 3) holding the fields first,
// first + 1, ..., each stored multiplied by `scale`. SmoothingLength is GADGET's kernel support
// radius, which is 2h for exasph's kernels (support 2h, physics.md §2).
struct GadgetDataset {
    std::string name;
    Field first;
    int width = 1;
    double scale = 1.0;
};

inline const std::array<GadgetDataset, 9>& gadget_named_datasets() {
    static const std::array<GadgetDataset, 9> table = {{{"Coordinates", Field::x, 3, 1.0},
                                                        {"Velocities", Field::vx, 3, 1.0},
                                                        {"Acceleration", Field::ax, 3, 1.0},
                                                        {"Masses", Field::m, 1, 1.0},
                                                        {"InternalEnergy", Field::u, 1, 1.0},
                                                        {"SmoothingLength", Field::h, 1, 2.0},
                                                        {"Density", Field::rho, 1, 1.0},
                                                        {"Pressure", Field::p, 1, 1.0},
                                                        {"Potential", Field::phi, 1, 1.0}}};
    return table;
}

// The persistent particle ids' dataset (unsigned 64-bit integers).
inline constexpr const char* kGadgetIds = "ParticleIDs";

// The dataset holding field f, and f's column in it: a named one above, else a 1-D dataset
// under the field's own exasph name (e.g. "du", "nc", "alpha").
struct GadgetColumn {
    GadgetDataset dataset;
    int column = 0;
};

inline GadgetColumn gadget_column(Field f) {
    for (const auto& d : gadget_named_datasets())
        if (int(f) >= int(d.first) && int(f) < int(d.first) + d.width)
            return {d, int(f) - int(d.first)};
    return {{std::string(field_info(f).name), f, 1, 1.0}, 0};
}

// The datasets that hold `fields`, each once, in the order first asked for (a vector is
// written whole when any of its components is asked for).
inline std::vector<GadgetDataset> gadget_datasets(const std::vector<Field>& fields) {
    std::vector<GadgetDataset> out;
    for (Field f : fields) {
        const GadgetDataset d = gadget_column(f).dataset;
        bool seen = false;
        for (const auto& o : out) seen = seen || o.name == d.name;
        if (!seen) out.push_back(d);
    }
    return out;
}

// Checks that the gas dataset `name` holds n rows of `width` values (width 1: 1-D); the error
// names the dataset and the count /Header states.
inline void expect_gas_rows(const h5::Group& gas, const std::string& name, std::uint64_t width,
                            std::uint64_t n, bool integer = false) {
    const std::uint64_t rows = h5::dataset_rows(gas, name, width, integer);
    if (rows != n)
        throw input_error(gas.file().path() + ": /PartType0/" + name + " has " +
                          std::to_string(rows) + " rows, /Header/NumPart_Total[0] says " +
                          std::to_string(n));
}

// This rank's rows [lo, lo + count) of field f from a /PartType0 group of n rows, in exasph's
// units (divided by the dataset's scale). Throws an input error naming a missing dataset.
inline std::vector<double> read_gadget_field(const h5::Group& gas, Field f, std::uint64_t n,
                                             std::uint64_t lo, std::uint64_t count) {
    const GadgetColumn c = gadget_column(f);
    const std::uint64_t width = std::uint64_t(c.dataset.width);
    expect_gas_rows(gas, c.dataset.name, width, n);
    const auto all = h5::read_double_rows(gas, c.dataset.name, lo, count, width);
    std::vector<double> out(count);
    for (std::uint64_t i = 0; i < count; ++i)
        out[i] = all[i * width + std::uint64_t(c.column)] / c.dataset.scale;
    return out;
}

} // namespace exasph
