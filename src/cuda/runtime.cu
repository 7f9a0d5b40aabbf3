// The CUDA runtime functions of util/cuda_runtime.hpp, for a build with the CUDA backend.
#include <string>

#include <cuda_runtime.h>

#include "check.cuh"
#include "exasph/util/cuda_runtime.hpp"
#include "exasph/util/error.hpp"
#include "exasph/util/field_memory.hpp"

namespace exasph::cuda {
namespace {

std::string g_reason;

// Managed memory: one address for host and device; pages migrate to whichever touches them.
void* allocate_managed(std::size_t bytes) {
    void* p = nullptr;
    if (cudaMallocManaged(&p, bytes == 0 ? 1 : bytes) != cudaSuccess) return nullptr;
    return p;
}
void release_managed(void* p) {
    cudaFree(p);
}

} // namespace

bool built() {
    return true;
}

int visible_devices() {
    int count = 0;
    const cudaError_t e = cudaGetDeviceCount(&count);
    if (e != cudaSuccess) {
        g_reason = std::string("CUDA runtime: ") + cudaGetErrorString(e);
        cudaGetLastError(); // clear it: the CPU path goes on
        return 0;
    }
    g_reason = count == 0 ? "no CUDA device is visible" : "";
    return count;
}

std::string no_device_reason() {
    return g_reason;
}

std::string use_device(int rank) {
    const int count = visible_devices();
    if (count == 0)
        throw input_error("--backend cuda: no CUDA device is visible (" + g_reason +
                              "); use --backend cpu or auto",
                          true);
    const int device = rank % count;
    check(cudaSetDevice(device), "selecting the device");
    cudaDeviceProp prop{};
    check(cudaGetDeviceProperties(&prop, device), "reading the device's properties");
    install_field_memory({allocate_managed, release_managed, "cuda managed"});
    return std::string(prop.name) + " (device " + std::to_string(device) + " of " +
           std::to_string(count) + ", " + std::to_string(prop.totalGlobalMem >> 30) + " GiB, sm_" +
           std::to_string(prop.major) + std::to_string(prop.minor) + ")";
}

} // namespace exasph::cuda
