// Parallel HDF5 wrappers: see include/exasph/io/h5_file.hpp.
#include "exasph/io/h5_file.hpp"

#include <hdf5.h>

#include "exasph/util/error.hpp"
#include "h5_errors.hpp"

namespace exasph::h5 {

namespace {

// HDF5 prints its own error stacks by default; exasph reports one line instead.
void silence_hdf5() {
    static bool done = false;
    if (!done) {
        H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
        done = true;
    }
}

hid_t access_plist(MPI_Comm comm) {
    hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
    H5Pset_fapl_mpio(fapl, comm, MPI_INFO_NULL);
    return fapl;
}

hid_t collective_transfer() {
    hid_t dxpl = H5Pcreate(H5P_DATASET_XFER);
    H5Pset_dxpl_mpio(dxpl, H5FD_MPIO_COLLECTIVE);
    return dxpl;
}

bool g_write_failed = false;

// Rows [offset, offset + count) of a dataset of n_global rows of `width` values (1: a 1-D
// dataset), written collectively by every rank.
template <class V>
void write_rows(const Group& g, const std::string& name, hid_t memtype, hid_t filetype,
                const V* data, std::uint64_t count, std::uint64_t offset, std::uint64_t n_global,
                std::uint64_t width = 1) {
    const int rank = width > 1 ? 2 : 1;
    hsize_t dims[2] = {n_global, width};
    hid_t fspace = H5Screate_simple(rank, dims, nullptr);
    hid_t dset =
        H5Dcreate2(g.id(), name.c_str(), filetype, fspace, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (dset < 0) {
        H5Sclose(fspace);
        fail_write(g, "cannot create dataset " + where(g, name));
    }
    hsize_t start[2] = {offset, 0}, cnt[2] = {count, width};
    H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start, nullptr, cnt, nullptr);
    hid_t mspace = H5Screate_simple(rank, cnt, nullptr);
    hid_t dxpl = collective_transfer();
    herr_t st = H5Dwrite(dset, memtype, mspace, fspace, dxpl, data);
    H5Pclose(dxpl);
    H5Sclose(mspace);
    H5Sclose(fspace);
    H5Dclose(dset);
    if (st < 0) fail_write(g, "cannot write dataset " + where(g, name));
}

// Rows [offset, offset + count) of a dataset of rows of `width` values (1: a 1-D dataset), read
// collectively by every rank.
template <class V>
std::vector<V> read_rows(const Group& g, const std::string& name, hid_t memtype,
                         std::uint64_t offset, std::uint64_t count, std::uint64_t width = 1) {
    hid_t dset = H5Dopen2(g.id(), name.c_str(), H5P_DEFAULT);
    if (dset < 0) fail(g.file().path(), "missing dataset " + where(g, name), 2);
    hid_t fspace = H5Dget_space(dset);
    const int rank = width > 1 ? 2 : 1;
    hsize_t start[2] = {offset, 0}, cnt[2] = {count, width};
    H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start, nullptr, cnt, nullptr);
    hid_t mspace = H5Screate_simple(rank, cnt, nullptr);
    std::vector<V> out(count * width);
    hid_t dxpl = collective_transfer();
    herr_t st = H5Dread(dset, memtype, mspace, fspace, dxpl, out.data());
    H5Pclose(dxpl);
    H5Sclose(mspace);
    H5Sclose(fspace);
    H5Dclose(dset);
    if (st < 0)
        fail(g.file().path(),
             "cannot read dataset " + where(g, name) + " (truncated or corrupted file?)", 2);
    return out;
}

} // namespace

// `all_ranks`: every rank of the communicator fails the same way (e.g. a check of the file
// itself that every rank makes), so the error ends the run cleanly instead of aborting it.
[[noreturn]] void fail(const std::string& path, const std::string& what, int code, bool all_ranks) {
    throw Error(path + ": " + what, code, all_ranks);
}

std::string where(const Group& g, const std::string& name) {
    return g.name() == "/" ? "/" + name : g.name() + "/" + name;
}

// A write into g's file failed: the file is not closed again (File::mark_failed).
[[noreturn]] void fail_write(const Group& g, const std::string& what) {
    g.file().mark_failed();
    g_write_failed = true;
    fail(g.file().path(), what, 3);
}

File File::create(const std::string& path, MPI_Comm comm, std::uint64_t user_block) {
    silence_hdf5();
    hid_t fapl = access_plist(comm);
    hid_t fcpl = H5Pcreate(H5P_FILE_CREATE);
    if (user_block > 0) H5Pset_userblock(fcpl, hsize_t(user_block));
    hid_t id = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, fcpl, fapl);
    H5Pclose(fcpl);
    H5Pclose(fapl);
    if (id < 0) fail(path, "cannot create file", 3);
    return File(id, path, comm);
}

File File::open_read(const std::string& path, MPI_Comm comm) {
    silence_hdf5();
    htri_t exists = H5Fis_hdf5(path.c_str());
    if (exists <= 0) {
        FILE* f = std::fopen(path.c_str(), "rb");
        if (!f) fail(path, "no such file or not readable", 2, true);
        std::fclose(f);
        fail(path, "not an HDF5 file (truncated or corrupted?)", 2, true);
    }
    hid_t fapl = access_plist(comm);
    hid_t id = H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl);
    H5Pclose(fapl);
    if (id < 0) fail(path, "cannot open as HDF5 (truncated or corrupted?)", 2);
    return File(id, path, comm);
}

File::File(File&& o) noexcept
    : id_(o.id_), path_(std::move(o.path_)), comm_(o.comm_), failed_(o.failed_) {
    o.id_ = -1;
}
File::~File() {
    close();
}
void File::close() {
    if (id_ >= 0 && !failed_) H5Fclose(id_);
    id_ = -1;
}

Group::Group(const File& f, const std::string& name, bool create) : file_(f), name_(name) {
    if (name == "/")
        id_ = H5Gopen2(f.id(), "/", H5P_DEFAULT);
    else if (create)
        id_ = H5Gcreate2(f.id(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    else
        id_ = H5Gopen2(f.id(), name.c_str(), H5P_DEFAULT);
    if (id_ < 0)
        fail(f.path(), (create ? "cannot create group " : "missing group ") + name, create ? 3 : 2);
}
Group::Group(Group&& o) noexcept : file_(o.file_), id_(o.id_), name_(std::move(o.name_)) {
    o.id_ = -1;
}
Group::~Group() {
    if (id_ >= 0) H5Gclose(id_);
}

bool write_failed() {
    return g_write_failed;
}

bool has_link(const Group& g, const std::string& name) {
    return H5Lexists(g.id(), name.c_str(), H5P_DEFAULT) > 0;
}

std::vector<std::string> member_names(const Group& g) {
    std::vector<std::string> out;
    H5G_info_t info;
    if (H5Gget_info(g.id(), &info) < 0) return out;
    for (hsize_t i = 0; i < info.nlinks; ++i) {
        ssize_t len =
            H5Lget_name_by_idx(g.id(), ".", H5_INDEX_NAME, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT);
        if (len < 0) continue;
        std::string name(std::size_t(len), '\0');
        H5Lget_name_by_idx(g.id(), ".", H5_INDEX_NAME, H5_ITER_INC, i, name.data(),
                           std::size_t(len) + 1, H5P_DEFAULT);
        out.push_back(name);
    }
    return out;
}

void write_doubles(const Group& g, const std::string& name, const double* data, std::uint64_t count,
                   std::uint64_t offset, std::uint64_t n_global) {
    write_rows(g, name, H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, data, count, offset, n_global);
}
void write_double_rows(const Group& g, const std::string& name, const double* data,
                       std::uint64_t count, std::uint64_t width, std::uint64_t offset,
                       std::uint64_t n_global) {
    write_rows(g, name, H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, data, count, offset, n_global, width);
}
void write_u64(const Group& g, const std::string& name, const std::uint64_t* data,
               std::uint64_t count, std::uint64_t offset, std::uint64_t n_global) {
    write_rows(g, name, H5T_NATIVE_UINT64, H5T_STD_U64LE, data, count, offset, n_global);
}

std::uint64_t dataset_rows(const Group& g, const std::string& name, std::uint64_t width,
                           bool integer) {
    if (!has_link(g, name)) fail(g.file().path(), "missing dataset " + where(g, name), 2);
    hid_t dset = H5Dopen2(g.id(), name.c_str(), H5P_DEFAULT);
    if (dset < 0) fail(g.file().path(), "cannot open dataset " + where(g, name), 2);
    hid_t type = H5Dget_type(dset);
    H5T_class_t cls = H5Tget_class(type);
    H5Tclose(type);
    hid_t space = H5Dget_space(dset);
    int rank = H5Sget_simple_extent_ndims(space);
    hsize_t dims[8] = {0};
    if (rank > 0 && rank <= 8) H5Sget_simple_extent_dims(space, dims, nullptr);
    H5Sclose(space);
    H5Dclose(dset);
    const int want = width > 1 ? 2 : 1;
    if (rank != want || (width > 1 && dims[1] != width))
        fail(g.file().path(),
             "dataset " + where(g, name) + " must be " +
                 (width > 1 ? "N x " + std::to_string(width) : std::string("1-D")) + ", has " +
                 std::to_string(rank) + " dimensions" +
                 (rank == 2 ? " (N x " + std::to_string(dims[1]) + ")" : ""),
             2);
    if (integer ? cls != H5T_INTEGER : cls != H5T_FLOAT)
        fail(g.file().path(),
             "dataset " + where(g, name) + " must be of " +
                 (integer ? "integer" : "floating-point") + " type",
             2);
    return dims[0];
}

std::uint64_t dataset_length(const Group& g, const std::string& name, bool integer) {
    return dataset_rows(g, name, 1, integer);
}

std::vector<double> read_doubles(const Group& g, const std::string& name, std::uint64_t offset,
                                 std::uint64_t count) {
    return read_rows<double>(g, name, H5T_NATIVE_DOUBLE, offset, count);
}
std::vector<std::uint64_t> read_u64(const Group& g, const std::string& name, std::uint64_t offset,
                                    std::uint64_t count) {
    return read_rows<std::uint64_t>(g, name, H5T_NATIVE_UINT64, offset, count);
}

std::vector<double> read_double_rows(const Group& g, const std::string& name, std::uint64_t offset,
                                     std::uint64_t count, std::uint64_t width) {
    return read_rows<double>(g, name, H5T_NATIVE_DOUBLE, offset, count, width);
}

} // namespace exasph::h5
