#pragma once
// The definitions of CudaLauncher (sph/cuda_launcher.hpp): one thread per particle calling the
// kernel functor of sph/ by value; a result is reduced to its minimum per block in shared memory
// and over the blocks on the host. Every call ends with the device synchronised.
#include <algorithm>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <vector>

#include <cuda_runtime.h>
#include <math_constants.h>

#include "check.cuh"
#include "exasph/sph/cuda_launcher.hpp"

namespace exasph {
namespace cuda_detail {

constexpr unsigned kThreads = 128;

inline unsigned blocks_for(std::size_t n) {
    return unsigned((n + kThreads - 1) / kThreads);
}

// The minimum of v over the block, written by thread 0 to out[blockIdx.x].
__device__ inline void block_min(double v, double* out) {
    __shared__ double part[kThreads];
    part[threadIdx.x] = v;
    __syncthreads();
    for (unsigned s = kThreads / 2; s > 0; s /= 2) {
        if (threadIdx.x < s) part[threadIdx.x] = fmin(part[threadIdx.x], part[threadIdx.x + s]);
        __syncthreads();
    }
    if (threadIdx.x == 0) out[blockIdx.x] = part[0];
}

template <class Kernel>
__global__ void particles(Kernel k, std::uint32_t n) {
    const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i < n) k(i);
}

template <class Kernel>
__global__ void particles_min(Kernel k, std::uint32_t n, double* out) {
    const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
    block_min(i < n ? double(k(i)) : CUDART_INF, out);
}

// The particles idx[0, n) (block time steps: the active ones; idx in managed memory).
template <class Kernel>
__global__ void particles_of(Kernel k, const std::uint32_t* idx, std::uint32_t n) {
    const std::uint32_t s = blockIdx.x * blockDim.x + threadIdx.x;
    if (s < n) k(idx[s]);
}

template <class Kernel>
__global__ void particles_of_min(Kernel k, const std::uint32_t* idx, std::uint32_t n, double* out) {
    const std::uint32_t s = blockIdx.x * blockDim.x + threadIdx.x;
    block_min(s < n ? double(k(idx[s])) : CUDART_INF, out);
}

// Slot s of the lists is particle member[s] (member null: s).
template <class Kernel>
__global__ void neighbourhoods(Kernel k, const std::uint32_t* index, const std::uint64_t* offset,
                               const std::uint32_t* count, const std::uint32_t* member,
                               std::uint32_t n, double* out) {
    const std::uint32_t s = blockIdx.x * blockDim.x + threadIdx.x;
    constexpr bool kMin = kReduces<Kernel>;
    double v = CUDART_INF;
    if (s < n) {
        const NeighbourSpan nb = BatchLayout::span(index, offset, count, s);
        const std::uint32_t i = member ? member[s] : s;
        if constexpr (kMin)
            v = double(k(i, nb));
        else
            k(i, nb);
    }
    if constexpr (kMin) block_min(v, out);
}

// Per-block minima on the device, their minimum on the host.
class BlockMinima {
  public:
    explicit BlockMinima(unsigned blocks) : host_(blocks) {
        cuda::check(cudaMalloc(&dev_, std::max(1u, blocks) * sizeof(double)),
                    "allocating the reduction buffer");
    }
    ~BlockMinima() { cudaFree(dev_); }
    double* device() { return dev_; }
    double least() {
        cuda::check(
            cudaMemcpy(host_.data(), dev_, host_.size() * sizeof(double), cudaMemcpyDeviceToHost),
            "reading a reduction");
        double m = std::numeric_limits<double>::infinity();
        for (double v : host_) m = std::min(m, v);
        return m;
    }

  private:
    std::vector<double> host_;
    double* dev_ = nullptr;
};

inline void finish(const char* what) {
    cuda::check(cudaGetLastError(), what);
    cuda::check(cudaDeviceSynchronize(), what);
}

} // namespace cuda_detail

template <class Kernel>
void CudaLauncher::for_each(std::size_t n, const Kernel& k) {
    if (n == 0) return;
    cuda_detail::particles<<<cuda_detail::blocks_for(n), cuda_detail::kThreads>>>(k,
                                                                                  std::uint32_t(n));
    cuda_detail::finish("running a particle pass");
}

template <class Kernel>
double CudaLauncher::reduce_min(std::size_t n, const Kernel& k) {
    if (n == 0) return std::numeric_limits<double>::infinity();
    const unsigned blocks = cuda_detail::blocks_for(n);
    cuda_detail::BlockMinima minima(blocks);
    cuda_detail::particles_min<<<blocks, cuda_detail::kThreads>>>(k, std::uint32_t(n),
                                                                  minima.device());
    cuda_detail::finish("running a particle reduction");
    return minima.least();
}

template <class Kernel>
void CudaLauncher::for_each_of(const std::uint32_t* idx, std::size_t n, const Kernel& k) {
    if (n == 0) return;
    cuda_detail::particles_of<<<cuda_detail::blocks_for(n), cuda_detail::kThreads>>>(
        k, idx, std::uint32_t(n));
    cuda_detail::finish("running a pass over the active particles");
}

template <class Kernel>
double CudaLauncher::reduce_min_of(const std::uint32_t* idx, std::size_t n, const Kernel& k) {
    if (n == 0) return std::numeric_limits<double>::infinity();
    const unsigned blocks = cuda_detail::blocks_for(n);
    cuda_detail::BlockMinima minima(blocks);
    cuda_detail::particles_of_min<<<blocks, cuda_detail::kThreads>>>(k, idx, std::uint32_t(n),
                                                                     minima.device());
    cuda_detail::finish("running a reduction over the active particles");
    return minima.least();
}

template <class T, class Kernel>
double CudaLauncher::for_each_neighbourhood(const DeviceLists<T>& nl, const Kernel& k) {
    const std::size_t n = nl.size();
    if (n == 0) return std::numeric_limits<double>::infinity();
    const unsigned blocks = cuda_detail::blocks_for(n);
    cuda_detail::BlockMinima minima(kReduces<Kernel> ? blocks : 0);
    cuda_detail::neighbourhoods<<<blocks, cuda_detail::kThreads>>>(
        k, nl.index(), nl.offset(), nl.count(), nl.member(), std::uint32_t(n), minima.device());
    cuda_detail::finish("running a neighbour pass");
    return kReduces<Kernel> ? minima.least() : std::numeric_limits<double>::infinity();
}

} // namespace exasph
