// Fuzz harness: the checkpoint reader (--restart FILE). Input: the bytes of the file. It must
// be read into a configuration that validate_config accepts, or refused with an exasph::Error.
#include <cstdint>

#include "exasph/config/validate.hpp"
#include "exasph/io/checkpoint.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    exasph::fuzz::start_mpi_once();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = exasph::fuzz::scratch_file(data, size, "-checkpoint.h5");
    exasph::fuzz::expect_clear_refusal([&] {
        exasph::Config cfg;
        exasph::read_checkpoint<double>(path, cfg, MPI_COMM_WORLD);
        exasph::validate_config(cfg);
    });
    return 0;
}
