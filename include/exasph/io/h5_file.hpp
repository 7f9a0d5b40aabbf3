#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "exasph/util/mpi.hpp"

namespace exasph::h5 {

// Thin RAII wrappers over parallel HDF5 (MPI-IO driver, collective transfers). All functions are
// collective over the file's communicator unless stated. Failures throw exasph::Error naming the
// file and the object: exit code 2 when reading input, 3 when writing output.
using Id = std::int64_t; // hid_t

class File {
  public:
    // Truncates. user_block: bytes reserved before HDF5's own (a power of 2, >= 512; 0: none)
    // for a header of exasph's (io/file_seal.hpp).
    static File create(const std::string& path, MPI_Comm comm, std::uint64_t user_block = 0);
    static File open_read(const std::string& path, MPI_Comm comm); // input: errors exit 2
    File(File&& o) noexcept;
    File& operator=(File&&) = delete;
    File(const File&) = delete;
    ~File();
    void close();
    Id id() const { return id_; }
    const std::string& path() const { return path_; }
    MPI_Comm comm() const { return comm_; }
    // After a failed write (a full disk) close() does not close the file: HDF5 1.10 cannot
    // close a file whose final flush fails (H5Fclose fails half-way, and any later close of
    // it, HDF5's own at MPI_Finalize included, dereferences freed memory). See
    // write_failed().
    void mark_failed() const { failed_ = true; }

  private:
    File(Id id, std::string path, MPI_Comm comm) : id_(id), path_(std::move(path)), comm_(comm) {}
    Id id_;
    std::string path_;
    MPI_Comm comm_;
    mutable bool failed_ = false;
};

// A group of the file ("/" is the root), opened or created.
class Group {
  public:
    Group(const File& f, const std::string& name, bool create);
    Group(Group&& o) noexcept;
    Group(const Group&) = delete;
    ~Group();
    Id id() const { return id_; }
    const std::string& name() const { return name_; }
    const File& file() const { return file_; }

  private:
    const File& file_;
    Id id_;
    std::string name_;
};

// Whether a write into some file failed in this process: the process must then end without
// MPI_Finalize, where HDF5 would crash closing that file (File::mark_failed).
bool write_failed();

bool has_link(const Group& g, const std::string& name);
bool has_attribute(const Group& g, const std::string& name);
// Names of the members of a group (e.g. to find the Step#N groups).
std::vector<std::string> member_names(const Group& g);

// 1-D dataset of n_global elements; this rank writes `count` elements at `offset`.
void write_doubles(const Group& g, const std::string& name, const double* data, std::uint64_t count,
                   std::uint64_t offset, std::uint64_t n_global);
void write_u64(const Group& g, const std::string& name, const std::uint64_t* data,
               std::uint64_t count, std::uint64_t offset, std::uint64_t n_global);
// 2-D dataset of n_global rows of `width` doubles; this rank writes `count` rows at `offset`.
void write_double_rows(const Group& g, const std::string& name, const double* data,
                       std::uint64_t count, std::uint64_t width, std::uint64_t offset,
                       std::uint64_t n_global);

// Length of a 1-D floating-point (or, with integer = true, integer) dataset; throws Error (exit 2)
// naming the dataset when it is missing, not 1-D or of the wrong type.
std::uint64_t dataset_length(const Group& g, const std::string& name, bool integer = false);
// Rows of a dataset of N rows of `width` values (N x width; width 1: 1-D), checked likewise.
std::uint64_t dataset_rows(const Group& g, const std::string& name, std::uint64_t width,
                           bool integer = false);
std::vector<double> read_doubles(const Group& g, const std::string& name, std::uint64_t offset,
                                 std::uint64_t count);
std::vector<std::uint64_t> read_u64(const Group& g, const std::string& name, std::uint64_t offset,
                                    std::uint64_t count);
// Rows [offset, offset + count) of an N x width dataset, row after row.
std::vector<double> read_double_rows(const Group& g, const std::string& name, std::uint64_t offset,
                                     std::uint64_t count, std::uint64_t width);

// Attributes (written by every rank with identical values; HDF5 stores them once).
void write_attribute(const Group& g, const std::string& name, double v);
void write_attribute(const Group& g, const std::string& name, std::int64_t v);
void write_attribute(const Group& g, const std::string& name, const std::vector<double>& v);
void write_attribute(const Group& g, const std::string& name, const std::vector<std::int64_t>& v);
void write_attribute(const Group& g, const std::string& name, const std::string& v);
std::vector<double> read_attribute_doubles(const Group& g, const std::string& name);
std::string read_attribute_string(const Group& g, const std::string& name);

} // namespace exasph::h5
