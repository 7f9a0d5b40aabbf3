// Fuzz harness: the HDF5 initial-conditions reader (--init FILE.h5, docs/file-format.md).
// Input: the bytes of the file. It must be read, or refused with an exasph::Error.
#include <cstdint>

#include "exasph/io/initial_conditions_file.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    exasph::fuzz::start_mpi_once();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = exasph::fuzz::scratch_file(data, size, "-ic.h5");
    exasph::fuzz::expect_clear_refusal(
        [&] { exasph::read_initial_conditions<double>(path, MPI_COMM_WORLD); });
    return 0;
}
