#pragma once
// The errors of the HDF5 wrappers (src/io/h5_file.cpp, h5_attributes.cpp): one line naming the
// file and the object, as an exasph::Error with the exit code of its kind.
#include <string>

#include "exasph/io/h5_file.hpp"

namespace exasph::h5 {

// Throws "PATH: WHAT" with exit code `code`; `all_ranks`: every rank of the communicator fails
// the same way, so the run ends cleanly instead of aborting.
[[noreturn]] void fail(const std::string& path, const std::string& what, int code,
                       bool all_ranks = false);
// The object `name` of group g as a path in its file ("/Step#0/x").
std::string where(const Group& g, const std::string& name);
// A write into g's file failed: exit code 3, and the file is not closed again (File::mark_failed).
[[noreturn]] void fail_write(const Group& g, const std::string& what);

} // namespace exasph::h5
