// A build without the CUDA backend (EXASPH_CUDA off, or no nvcc when it was configured).
#include "exasph/util/cuda_runtime.hpp"
#include "exasph/util/error.hpp"

namespace exasph::cuda {

bool built() {
    return false;
}
int visible_devices() {
    return 0;
}
std::string no_device_reason() {
    return "this build has no CUDA backend (nvcc was not found when it was configured, or "
           "-DEXASPH_CUDA=OFF)";
}
std::string use_device(int) {
    throw input_error("--backend cuda: " + no_device_reason(), true);
}

} // namespace exasph::cuda
