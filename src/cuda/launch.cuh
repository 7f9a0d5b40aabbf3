#pragma once
// The definitions of CudaLauncher (sph/cuda_launcher.hpp): one thread per particle calling the
// kernel functor of sph/ by value; a result is reduced by the kernel's Reduction per block in
// shared memory and over the blocks on the host. Every call ends with the device synchronised.
#include <algorithm>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

#include <cuda_runtime.h>

#include "check.cuh"
#include "exasph/sph/cuda_launcher.hpp"
#include "grid.cuh"

namespace exasph {
namespace cuda_detail {

using cuda::blocks_for;
using cuda::kThreads;

// Reduction R of the block's values v, written by thread 0 to out[blockIdx.x]: the fold of one
// run of reduce_tree's fixed tree (sph/reduction.hpp), neighbours first as the host's
// TreeRunFold does it (raw shared storage: a value type with default member initialisers
// cannot be a __shared__ array).
template <class R>
__device__ inline void block_reduce(typename R::value_type v, typename R::value_type* out) {
    using V = typename R::value_type;
    __shared__ alignas(V) unsigned char raw[kThreads * sizeof(V)];
    V* part = reinterpret_cast<V*>(raw);
    part[threadIdx.x] = v;
    __syncthreads();
    for (unsigned s = 1; s < kThreads; s *= 2) {
        if ((threadIdx.x & (2 * s - 1)) == 0)
            part[threadIdx.x] = R::combine(part[threadIdx.x], part[threadIdx.x + s]);
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
__global__ void particles_reduce(Kernel k, std::uint32_t n, ResultOf<Kernel>* out) {
    using R = ReductionOf<Kernel>;
    const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
    block_reduce<R>(i < n ? R::combine(R::identity(), k(i)) : R::identity(), out);
}

// The particles idx[0, n) (block time steps: the active ones; idx in managed memory).
template <class Kernel>
__global__ void particles_of(Kernel k, const std::uint32_t* idx, std::uint32_t n) {
    const std::uint32_t s = blockIdx.x * blockDim.x + threadIdx.x;
    if (s < n) k(idx[s]);
}

template <class Kernel>
__global__ void particles_of_reduce(Kernel k, const std::uint32_t* idx, std::uint32_t n,
                                    ResultOf<Kernel>* out) {
    using R = ReductionOf<Kernel>;
    const std::uint32_t s = blockIdx.x * blockDim.x + threadIdx.x;
    block_reduce<R>(s < n ? R::combine(R::identity(), k(idx[s])) : R::identity(), out);
}

// Block b folds run b of the values k(i) ...
template <class Kernel>
__global__ void tree_leaves(Kernel k, std::uint32_t n, ResultOf<Kernel>* out) {
    using R = ReductionOf<Kernel>;
    const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
    block_reduce<R>(i < n ? k(i) : R::identity(), out);
}

// ... and, on the later levels, run b of the values in[0, n).
template <class R>
__global__ void tree_level(const typename R::value_type* in, std::uint32_t n,
                           typename R::value_type* out) {
    const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
    block_reduce<R>(i < n ? in[i] : R::identity(), out);
}

// Slot s of the lists is particle member[s] (member null: s); `out` only for a kernel that
// reduces.
template <class Kernel, class Out>
__global__ void neighbourhoods(Kernel k, const std::uint32_t* index, const std::uint64_t* offset,
                               const std::uint32_t* count, const std::uint32_t* member,
                               std::uint32_t n, Out* out) {
    const std::uint32_t s = blockIdx.x * blockDim.x + threadIdx.x;
    const auto visit = [&] {
        const NeighbourSpan nb = BatchLayout::span(index, offset, count, s);
        return k(member ? member[s] : s, nb);
    };
    if constexpr (kReduces<Kernel>) {
        using R = ReductionOf<Kernel>;
        block_reduce<R>(s < n ? R::combine(R::identity(), visit()) : R::identity(), out);
    } else if (s < n) {
        visit();
    }
}

// Per-block results of reduction R on the device, combined on the host in block order.
template <class R>
class BlockResults {
  public:
    using V = typename R::value_type;
    explicit BlockResults(unsigned blocks) : host_(blocks) {
        cuda::check(cudaMalloc(&dev_, std::max(1u, blocks) * sizeof(V)),
                    "allocating the reduction buffer");
    }
    ~BlockResults() { cudaFree(dev_); }
    BlockResults(const BlockResults&) = delete;
    BlockResults& operator=(const BlockResults&) = delete;
    V* device() { return dev_; }
    V combined() {
        cuda::check(
            cudaMemcpy(host_.data(), dev_, host_.size() * sizeof(V), cudaMemcpyDeviceToHost),
            "reading a reduction");
        V total = R::identity();
        for (const V& v : host_) total = R::combine(total, v);
        return total;
    }

  private:
    std::vector<V> host_;
    V* dev_ = nullptr;
};

} // namespace cuda_detail

template <class Kernel>
requires kListed<Kernel, CudaLauncher::Listed::each>
void CudaLauncher::for_each(std::size_t n, const Kernel& k) {
    if (n == 0) return;
    cuda_detail::particles<<<cuda_detail::blocks_for(n), cuda_detail::kThreads>>>(k,
                                                                                  std::uint32_t(n));
    cuda::finish("running a particle pass");
}

template <class Kernel>
requires kListed<Kernel, CudaLauncher::Listed::reduce> ResultOf<Kernel>
CudaLauncher::reduce(std::size_t n, const Kernel& k) {
    using R = ReductionOf<Kernel>;
    if (n == 0) return R::identity();
    const unsigned blocks = cuda_detail::blocks_for(n);
    cuda_detail::BlockResults<R> results(blocks);
    cuda_detail::particles_reduce<<<blocks, cuda_detail::kThreads>>>(k, std::uint32_t(n),
                                                                     results.device());
    cuda::finish("running a particle reduction");
    return results.combined();
}

template <class Kernel>
requires kListed<Kernel, CudaLauncher::Listed::each_of>
void CudaLauncher::for_each_of(const std::uint32_t* idx, std::size_t n, const Kernel& k) {
    if (n == 0) return;
    cuda_detail::particles_of<<<cuda_detail::blocks_for(n), cuda_detail::kThreads>>>(
        k, idx, std::uint32_t(n));
    cuda::finish("running a pass over the active particles");
}

template <class Kernel>
requires kListed<Kernel, CudaLauncher::Listed::reduce_of> ResultOf<Kernel>
CudaLauncher::reduce_of(const std::uint32_t* idx, std::size_t n, const Kernel& k) {
    using R = ReductionOf<Kernel>;
    if (n == 0) return R::identity();
    const unsigned blocks = cuda_detail::blocks_for(n);
    cuda_detail::BlockResults<R> results(blocks);
    cuda_detail::particles_of_reduce<<<blocks, cuda_detail::kThreads>>>(k, idx, std::uint32_t(n),
                                                                        results.device());
    cuda::finish("running a reduction over the active particles");
    return results.combined();
}

template <class Kernel>
requires kListed<Kernel, CudaLauncher::Listed::reduce_tree> ResultOf<Kernel>
CudaLauncher::reduce_tree(std::size_t n, const Kernel& k) {
    using R = ReductionOf<Kernel>;
    using V = ResultOf<Kernel>;
    static_assert(kTreeFan == cuda_detail::kThreads, "a block folds one run of the tree");
    if (n == 0) return R::identity();
    std::size_t m = tree_runs(n); // values on the current level
    DeviceBuffer level, next;
    V* values = static_cast<V*>(level.reserve(m * sizeof(V)));
    V* folded = static_cast<V*>(next.reserve(tree_runs(m) * sizeof(V)));
    cuda_detail::tree_leaves<<<unsigned(m), cuda_detail::kThreads>>>(k, std::uint32_t(n), values);
    for (; m > 1; m = tree_runs(m)) {
        cuda_detail::tree_level<R>
            <<<unsigned(tree_runs(m)), cuda_detail::kThreads>>>(values, std::uint32_t(m), folded);
        std::swap(values, folded);
    }
    cuda::finish("running a tree reduction");
    V total;
    cuda::check(cudaMemcpy(&total, values, sizeof(V), cudaMemcpyDeviceToHost),
                "reading a tree reduction");
    return total;
}

template <class T, class Kernel>
requires kListed<Kernel, CudaLauncher::Listed::neighbours> ResultOf<Kernel>
CudaLauncher::for_each_neighbourhood(const DeviceLists<T>& nl, const Kernel& k) {
    const std::size_t n = nl.size();
    const unsigned blocks = cuda_detail::blocks_for(n);
    if constexpr (kReduces<Kernel>) {
        using R = ReductionOf<Kernel>;
        if (n == 0) return R::identity();
        cuda_detail::BlockResults<R> results(blocks);
        cuda_detail::neighbourhoods<<<blocks, cuda_detail::kThreads>>>(
            k, nl.index(), nl.offset(), nl.count(), nl.member(), std::uint32_t(n),
            results.device());
        cuda::finish("running a neighbour pass");
        return results.combined();
    } else {
        if (n == 0) return;
        cuda_detail::neighbourhoods<<<blocks, cuda_detail::kThreads>>>(
            k, nl.index(), nl.offset(), nl.count(), nl.member(), std::uint32_t(n),
            static_cast<char*>(nullptr));
        cuda::finish("running a neighbour pass");
    }
}

} // namespace exasph
