// The HDF5 wrappers of io/h5_file.hpp in a build without HDF5 (CMake EXASPH_HDF5=OFF): opening
// or creating a file is an error naming the file and the cure; nothing else can be reached,
// since every other call needs an open file. The command line refuses the options that need
// files before a run starts (config/validate.hpp).
#include "exasph/io/h5_file.hpp"
#include "exasph/util/error.hpp"

namespace exasph::h5 {
namespace {

[[noreturn]] void no_hdf5(const std::string& path, int code) {
    throw Error(path +
                    ": this build has no HDF5 (snapshots, checkpoints, `exasph glass` "
                    "files and HDF5 initial conditions need it: configure with -DEXASPH_HDF5=ON)",
                code, true);
}

} // namespace

File File::create(const std::string& path, MPI_Comm, std::uint64_t) {
    no_hdf5(path, 3);
}
File File::open_read(const std::string& path, MPI_Comm) {
    no_hdf5(path, 2);
}
File::File(File&& o) noexcept : id_(o.id_), path_(std::move(o.path_)), comm_(o.comm_) {}
File::~File() = default;
void File::close() {}
Group::Group(const File& f, const std::string& name, bool) : file_(f), id_(-1), name_(name) {
    no_hdf5(f.path(), 2);
}
Group::Group(Group&& o) noexcept : file_(o.file_), id_(o.id_), name_(std::move(o.name_)) {}
Group::~Group() = default;
bool write_failed() {
    return false;
}

bool has_link(const Group& g, const std::string&) {
    no_hdf5(g.file().path(), 2);
}
bool has_attribute(const Group& g, const std::string&) {
    no_hdf5(g.file().path(), 2);
}
std::vector<std::string> member_names(const Group& g) {
    no_hdf5(g.file().path(), 2);
}
void write_doubles(const Group& g, const std::string&, const double*, std::uint64_t, std::uint64_t,
                   std::uint64_t) {
    no_hdf5(g.file().path(), 3);
}
void write_u64(const Group& g, const std::string&, const std::uint64_t*, std::uint64_t,
               std::uint64_t, std::uint64_t) {
    no_hdf5(g.file().path(), 3);
}
void write_double_rows(const Group& g, const std::string&, const double*, std::uint64_t,
                       std::uint64_t, std::uint64_t, std::uint64_t) {
    no_hdf5(g.file().path(), 3);
}
std::uint64_t dataset_rows(const Group& g, const std::string&, std::uint64_t, bool) {
    no_hdf5(g.file().path(), 2);
}
std::vector<double> read_double_rows(const Group& g, const std::string&, std::uint64_t,
                                     std::uint64_t, std::uint64_t) {
    no_hdf5(g.file().path(), 2);
}
std::uint64_t dataset_length(const Group& g, const std::string&, bool) {
    no_hdf5(g.file().path(), 2);
}
std::vector<double> read_doubles(const Group& g, const std::string&, std::uint64_t, std::uint64_t) {
    no_hdf5(g.file().path(), 2);
}
std::vector<std::uint64_t> read_u64(const Group& g, const std::string&, std::uint64_t,
                                    std::uint64_t) {
    no_hdf5(g.file().path(), 2);
}
void write_attribute(const Group& g, const std::string&, double) {
    no_hdf5(g.file().path(), 3);
}
void write_attribute(const Group& g, const std::string&, std::int64_t) {
    no_hdf5(g.file().path(), 3);
}
void write_attribute(const Group& g, const std::string&, const std::vector<double>&) {
    no_hdf5(g.file().path(), 3);
}
void write_attribute(const Group& g, const std::string&, const std::vector<std::int64_t>&) {
    no_hdf5(g.file().path(), 3);
}
void write_attribute(const Group& g, const std::string&, const std::string&) {
    no_hdf5(g.file().path(), 3);
}
std::vector<double> read_attribute_doubles(const Group& g, const std::string&) {
    no_hdf5(g.file().path(), 2);
}
std::string read_attribute_string(const Group& g, const std::string&) {
    no_hdf5(g.file().path(), 2);
}

} // namespace exasph::h5
