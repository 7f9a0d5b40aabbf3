// Compiles every kernel of the passes' list (sph/pass_kernels.hpp) as device code, in both
// working precisions and both storages of the derived fields: what the CUDA launcher calls.
// Built by test_kernels_nvcc.sh with warnings as errors; nothing here runs.
#include <cstdint>

#include "exasph/sph/pass_kernels.hpp"

using namespace exasph;

namespace {

template <class Kernel>
__global__ void neighbour_pass(Kernel k, const std::uint32_t* lists, std::uint32_t count,
                               std::uint32_t n, double* out) {
    const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= n) return;
    // Interleaved lists: neighbour j of particle i at lists[j * n + i].
    const NeighbourSpan nb{lists + i, count, n};
    if constexpr (kReduces<Kernel>)
        reinterpret_cast<ResultOf<Kernel>*>(out)[i] = k(i, nb); // out: 8 bytes per particle
    else
        k(i, nb);
}

template <class Kernel>
__global__ void particle_pass(Kernel k, std::uint32_t n, double* out) {
    const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= n) return;
    if constexpr (kReduces<Kernel>)
        reinterpret_cast<ResultOf<Kernel>*>(out)[i] = k(i);
    else
        k(i);
}

template <class... K>
void neighbour_passes(KernelList<K...>, const std::uint32_t* lists, double* out) {
    (neighbour_pass<<<1, 32>>>(K{}, lists, 8, 32, out), ...);
}

template <class... K>
void particle_passes(KernelList<K...>, double* out) {
    (particle_pass<<<1, 32>>>(K{}, 32, out), ...);
}

// Every kernel of the lists P.
template <class P>
void instantiate(const std::uint32_t* lists, double* out) {
    neighbour_passes(typename P::neighbours{}, lists, out);
    particle_passes(typename P::each{}, out);
    particle_passes(typename P::each_of{}, out);
    particle_passes(typename P::reduce{}, out);
    particle_passes(typename P::reduce_of{}, out);
    particle_passes(typename P::reduce_tree{}, out);
}

} // namespace

void instantiate_all(const std::uint32_t* lists, double* out) {
    instantiate<PassKernels<double>>(lists, out);
    instantiate<PassKernelsOf<float, float>>(lists, out); // single-precision working fields
}
