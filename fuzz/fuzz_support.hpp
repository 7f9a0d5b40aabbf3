#pragma once
// What the fuzz harnesses share: MPI started once per process, the input written to a scratch
// file (the readers take paths, as in a run), and the rule that decides a finding.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <string>

#include <unistd.h>

#include "exasph/util/error.hpp"
#include "exasph/util/mpi.hpp"

namespace exasph::fuzz {

// The input as a file of this process (a RAM-backed directory when there is one).
inline std::string scratch_file(const std::uint8_t* data, std::size_t size, const char* suffix) {
    const char* dir = std::getenv("EXASPH_FUZZ_DIR");
    if (!dir) dir = access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp";
    const std::string path =
        std::string(dir) + "/exasph-fuzz-" + std::to_string(::getpid()) + suffix;
    std::ofstream(path, std::ios::binary | std::ios::trunc)
        .write(reinterpret_cast<const char*>(data), std::streamsize(size));
    static std::string last; // one scratch file per process: removed when it ends
    if (last.empty()) std::atexit([] { std::remove(last.c_str()); });
    last = path;
    return path;
}

// A reader may refuse an input only with exasph::Error, whose one-line message is what the user
// sees (exit 2). Anything else (std::out_of_range from .at(), bad_alloc from a size read from
// the file, a crash) would reach the user as "internal error" or worse: a finding.
template <class F>
void expect_clear_refusal(F&& read) {
    try {
        read();
    } catch (const Error&) {
    } catch (const std::exception& e) {
        std::fprintf(stderr, "fuzz finding: not an exasph::Error: %s\n", e.what());
        std::abort();
    }
}

} // namespace exasph::fuzz
