#pragma once
// Checked reading of the scalar and vector attributes of a file's root (initial conditions,
// snapshots, checkpoints): every value a run would use is finite and in range, or the file is
// refused with one line naming the attribute (exit 2, on every rank alike).
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "exasph/io/h5_file.hpp"
#include "exasph/util/box.hpp"
#include "exasph/util/error.hpp"

namespace exasph {

inline Error attribute_error(const h5::Group& g, const std::string& name, const std::string& what) {
    return input_error(g.file().path() + ": attribute /" + name + " " + what, true);
}

// A finite number; `dflt` where the attribute is absent (required when there is none).
inline double read_finite(const h5::Group& g, const std::string& name,
                          std::optional<double> dflt = std::nullopt) {
    if (dflt && !h5::has_attribute(g, name)) return *dflt;
    const auto v = h5::read_attribute_doubles(g, name);
    if (v.size() != 1 || !std::isfinite(v[0]))
        throw attribute_error(g, name, "must be one finite number");
    return v[0];
}

// Three finite numbers; `dflt` for each where the attribute is absent (required without one).
inline std::vector<double> read_vec3(const h5::Group& g, const std::string& name,
                                     std::optional<double> dflt = std::nullopt) {
    if (dflt && !h5::has_attribute(g, name)) return std::vector<double>(3, *dflt);
    auto v = h5::read_attribute_doubles(g, name);
    if (v.size() != 3)
        throw attribute_error(g, name, "must have 3 values, has " + std::to_string(v.size()));
    for (double x : v)
        if (!std::isfinite(x)) throw attribute_error(g, name, "must be finite");
    return v;
}

// The box: box_lo < box_hi on each axis, periodic flags (absent: open).
template <class T>
Box<T> read_box(const h5::Group& g) {
    const auto lo = read_vec3(g, "box_lo"), hi = read_vec3(g, "box_hi"),
               per = read_vec3(g, "periodic", 0.0);
    Box<T> box;
    for (int d = 0; d < 3; ++d) {
        if (!(lo[d] < hi[d]) || !std::isfinite(T(hi[d]) - T(lo[d])))
            throw attribute_error(g, "box_lo", "and /box_hi: box_lo < box_hi on each axis, finite");
        box.lo[d] = T(lo[d]);
        box.hi[d] = T(hi[d]);
        box.periodic[d] = per[d] != 0;
    }
    return box;
}

} // namespace exasph
