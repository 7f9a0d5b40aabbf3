#pragma once
// Structure-aware fuzzing of the HDF5 readers: the fuzzer's bytes are a recipe of edits applied
// with HDF5 itself to a copy of a real file (fuzz/bases/H/*.h5): attributes and datasets
// deleted or rewritten with other types, shapes and values (NaN, infinities, huge, negative,
// empty), groups added. The result is always a well-formed HDF5 file, so what the fuzzer
// explores is exasph's reading and checking of the contents, not HDF5's parser (which is not
// robust against damaged bytes: docs/resilience.md).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <hdf5.h>

#include "exasph/util/mpi.hpp"

namespace exasph::fuzz {

// (The HDF5 harnesses, built only with MPI.) One MPI process (singleton, no mpirun), finalised at
// exit as a run would be.
inline void start_mpi_once() {
    int started = 0;
    MPI_Initialized(&started);
    if (started) return;
    MPI_Init(nullptr, nullptr);
    std::atexit([] { MPI_Finalize(); });
}

// The recipe's bytes, read one value at a time (zero once exhausted).
class RecipeReader {
  public:
    RecipeReader(const std::uint8_t* d, std::size_t n) : d_(d), n_(n) {}
    bool done() const { return at_ >= n_; }
    std::uint8_t byte() { return at_ < n_ ? d_[at_++] : 0; }
    // A double: one of the values readers must handle, or eight raw bytes.
    double value() {
        static const double table[] = {0.0, -0.0,  1.0,  -1.0,     0.5,      2.0,
                                       1.4, 1e-10, 1e10, 1e300,    -1e300,   5e-324,
                                       3.0, 100.0, NAN,  INFINITY, -INFINITY};
        const std::uint8_t k = byte();
        constexpr std::uint8_t ntable = sizeof(table) / sizeof(table[0]);
        if (k < 3 * ntable) return table[k % ntable];
        double v = 0;
        std::uint8_t raw[8];
        for (auto& b : raw) b = byte();
        std::memcpy(&v, raw, 8);
        return v;
    }

  private:
    const std::uint8_t* d_;
    std::size_t n_;
    std::size_t at_ = 0;
};

namespace detail {

inline void write_attribute(hid_t g, const std::string& name, hid_t type, hid_t space,
                            const void* data) {
    if (H5Aexists(g, name.c_str()) > 0) H5Adelete(g, name.c_str());
    const hid_t a = H5Acreate2(g, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT);
    if (a >= 0) {
        H5Awrite(a, type, data);
        H5Aclose(a);
    }
}

inline void write_dataset(hid_t g, const std::string& name, hid_t type, hid_t space,
                          const void* data) {
    if (H5Lexists(g, name.c_str(), H5P_DEFAULT) > 0) H5Ldelete(g, name.c_str(), H5P_DEFAULT);
    const hid_t d = H5Dcreate2(g, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (d >= 0) {
        H5Dwrite(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data);
        H5Dclose(d);
    }
}

// A space of `count` values: scalar (count 0), 1-D, or 2-D of count x `width`.
inline hid_t make_space(std::size_t count, std::size_t width) {
    if (count == 0) return H5Screate(H5S_SCALAR);
    const hsize_t dims[2] = {count, width};
    return H5Screate_simple(width > 1 ? 2 : 1, dims, nullptr);
}

// One edit of group g, on the object `name`.
inline void apply_edit(hid_t g, const std::string& name, RecipeReader& r) {
    const std::uint8_t op = r.byte() % 8;
    const std::size_t count = op < 4 ? r.byte() % 5 : r.byte();
    const std::size_t width = op == 6 ? 1 + r.byte() % 4 : 1;
    std::vector<double> values(std::max<std::size_t>(1, count * width));
    for (double& v : values) v = r.value();
    std::vector<std::int64_t> ints(values.size());
    std::vector<float> floats(values.size());
    for (std::size_t i = 0; i < values.size(); ++i) {
        ints[i] =
            values[i] == values[i] && std::abs(values[i]) < 9e18 ? std::int64_t(values[i]) : -1;
        floats[i] = float(values[i]);
    }
    const hid_t space = make_space(count, width);
    switch (op) {
    case 0:
        H5Adelete(g, name.c_str());
        break;
    case 1:
        write_attribute(g, name, H5T_NATIVE_DOUBLE, space, values.data());
        break;
    case 2:
        write_attribute(g, name, H5T_NATIVE_INT64, space, ints.data());
        break;
    case 3: { // a string attribute of the recipe's characters
        std::string text(count * 3, ' ');
        for (char& c : text) c = char(r.byte());
        const hid_t t = H5Tcopy(H5T_C_S1);
        H5Tset_size(t, std::max<std::size_t>(1, text.size()));
        const hid_t s = H5Screate(H5S_SCALAR);
        write_attribute(g, name, t, s, text.c_str());
        H5Sclose(s);
        H5Tclose(t);
        break;
    }
    case 4:
        H5Ldelete(g, name.c_str(), H5P_DEFAULT);
        break;
    case 5:
        write_dataset(g, name, H5T_NATIVE_DOUBLE, space, values.data());
        break;
    case 6:
        write_dataset(g, name, H5T_NATIVE_DOUBLE, space, values.data());
        break;
    default: {
        const bool as_float = r.byte() & 1;
        write_dataset(g, name, as_float ? H5T_NATIVE_FLOAT : H5T_NATIVE_INT64, space,
                      as_float ? static_cast<const void*>(floats.data()) : ints.data());
    }
    }
    H5Sclose(space);
}

} // namespace detail

// Writes base (one of `bases`, the files' bytes, chosen by the recipe's first byte) to `path`
// and applies the recipe's edits to it. Each edit names a group (of `groups`) and an object (of
// `names`, or "Step#N" with N from the recipe, so that a file may gain snapshot groups).
inline void apply_recipe(const std::vector<std::vector<char>>& bases, const std::string& path,
                         const std::vector<std::string>& groups,
                         const std::vector<std::string>& names, RecipeReader& r) {
    const auto& base = bases[r.byte() % bases.size()];
    std::ofstream(path, std::ios::binary | std::ios::trunc)
        .write(base.data(), std::streamsize(base.size()));
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    for (int edits = 0; file >= 0 && !r.done() && edits < 16; ++edits) {
        const std::string group = groups[r.byte() % groups.size()];
        const std::uint8_t k = r.byte();
        if (k == 255) { // a new group "Step#N" (snapshot layout) under the root
            const std::string step = "/Step#" + std::to_string(int(r.byte()) - 8);
            const hid_t g = H5Gcreate2(file, step.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
            if (g >= 0) H5Gclose(g);
            continue;
        }
        const hid_t g = H5Gopen2(file, group.c_str(), H5P_DEFAULT);
        if (g < 0) continue;
        detail::apply_edit(g, names[k % names.size()], r);
        H5Gclose(g);
    }
    if (file >= 0) H5Fclose(file);
}

// The bytes of the .h5 files of a directory, in name order (the recipe's first byte picks one).
inline std::vector<std::vector<char>> base_files(const std::string& dir) {
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(dir))
        if (e.path().extension() == ".h5") names.push_back(e.path().string());
    std::sort(names.begin(), names.end());
    std::vector<std::vector<char>> files;
    for (const auto& n : names) {
        std::ifstream in(n, std::ios::binary);
        files.emplace_back(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    return files;
}

} // namespace exasph::fuzz
