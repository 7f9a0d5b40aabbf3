// The data-parallel primitives of CudaLauncher (sph/primitives.hpp) on CUB, which ships with the
// CUDA toolkit: scan and radix sort (stable); gather and scatter are one thread per element.
// Each call allocates its temporary device memory (CUB's storage, the sort's second buffers) and
// frees it on return: a domain on the device will want them kept between steps.
// Instantiated for every type of PrimitiveScalars and SortKeys, so that the host code links
// against them.
#include <cstddef>
#include <cstdint>
#include <tuple>

#include <cub/device/device_radix_sort.cuh>
#include <cub/device/device_scan.cuh>
#include <cuda_runtime.h>

#include "check.cuh"
#include "exasph/sph/cuda_launcher.hpp"
#include "exasph/tree/device_lists.hpp"
#include "grid.cuh"

namespace exasph {
namespace cuda_detail {

using cuda::blocks_for;
using cuda::kThreads;

template <class V>
V read_one(const V* at) {
    V v;
    cuda::check(cudaMemcpy(&v, at, sizeof(V), cudaMemcpyDefault), "reading a scan's end");
    return v;
}

template <class V>
__global__ void gather_kernel(const ParticleIndex* from, const V* in, V* out, std::size_t n) {
    const std::size_t i = std::size_t(blockIdx.x) * blockDim.x + threadIdx.x;
    if (i < n) out[i] = in[from[i]];
}

template <class V>
__global__ void scatter_kernel(const ParticleIndex* to, const V* in, V* out, std::size_t n) {
    const std::size_t i = std::size_t(blockIdx.x) * blockDim.x + threadIdx.x;
    if (i < n) out[to[i]] = in[i];
}

} // namespace cuda_detail

template <PrimitiveScalar V>
V CudaLauncher::exclusive_scan(const V* in, V* out, std::size_t n) {
    using namespace cuda_detail;
    if (n == 0) return V(0);
    const V last = read_one(in + n - 1); // before the scan: in may be out
    const auto items = static_cast<std::int64_t>(n);
    std::size_t bytes = 0;
    cuda::check(cub::DeviceScan::ExclusiveSum(nullptr, bytes, in, out, items), "sizing a scan");
    DeviceBuffer scratch; // tree/device_lists.hpp's device memory
    cuda::check(cub::DeviceScan::ExclusiveSum(scratch.reserve(bytes), bytes, in, out, items),
                "a scan");
    cuda::finish("a scan");
    return read_one(out + n - 1) + last;
}

template <SortKey K>
void CudaLauncher::sort_by_key(K* keys, ParticleIndex* order, std::size_t n) {
    using namespace cuda_detail;
    if (n < 2) return;
    DeviceBuffer other_keys, other_order, scratch; // the sort's second buffers, CUB's storage
    cub::DoubleBuffer<K> k(keys, static_cast<K*>(other_keys.reserve(n * sizeof(K))));
    cub::DoubleBuffer<ParticleIndex> v(
        order, static_cast<ParticleIndex*>(other_order.reserve(n * sizeof(ParticleIndex))));
    const auto items = static_cast<std::int64_t>(n);
    std::size_t bytes = 0;
    cuda::check(cub::DeviceRadixSort::SortPairs(nullptr, bytes, k, v, items), "sizing a sort");
    cuda::check(cub::DeviceRadixSort::SortPairs(scratch.reserve(bytes), bytes, k, v, items),
                "a sort");
    if (k.Current() != keys) // CUB leaves the result in whichever buffer the last pass wrote
        cuda::check(cudaMemcpy(keys, k.Current(), n * sizeof(K), cudaMemcpyDefault),
                    "copying sorted keys");
    if (v.Current() != order)
        cuda::check(cudaMemcpy(order, v.Current(), n * sizeof(ParticleIndex), cudaMemcpyDefault),
                    "copying a sorted permutation");
    cuda::finish("a sort");
}

template <PrimitiveScalar V>
void CudaLauncher::gather(const ParticleIndex* from, const V* in, V* out, std::size_t n) {
    using namespace cuda_detail;
    if (n == 0) return;
    gather_kernel<<<blocks_for(n), kThreads>>>(from, in, out, n);
    cuda::finish("a gather");
}

template <PrimitiveScalar V>
void CudaLauncher::scatter(const ParticleIndex* to, const V* in, V* out, std::size_t n) {
    using namespace cuda_detail;
    if (n == 0) return;
    scatter_kernel<<<blocks_for(n), kThreads>>>(to, in, out, n);
    cuda::finish("a scatter");
}

namespace cuda_detail {

// Every primitive for every listed type, by address in a static member of an explicitly
// instantiated class: each is then compiled and emitted here.
template <class List>
struct ScalarInstances;
template <class... V>
struct ScalarInstances<std::tuple<V...>> {
    static const std::tuple<V (*)(const V*, V*, std::size_t)...> scans;
    static const std::tuple<void (*)(const ParticleIndex*, const V*, V*, std::size_t)...> gathers,
        scatters;
};
template <class... V>
const std::tuple<V (*)(const V*, V*, std::size_t)...> ScalarInstances<std::tuple<V...>>::scans{
    &CudaLauncher::exclusive_scan<V>...};
template <class... V>
const std::tuple<void (*)(const ParticleIndex*, const V*, V*, std::size_t)...>
    ScalarInstances<std::tuple<V...>>::gathers{&CudaLauncher::gather<V>...};
template <class... V>
const std::tuple<void (*)(const ParticleIndex*, const V*, V*, std::size_t)...>
    ScalarInstances<std::tuple<V...>>::scatters{&CudaLauncher::scatter<V>...};
template struct ScalarInstances<PrimitiveScalars>;

template <class List>
struct SortInstances;
template <class... K>
struct SortInstances<std::tuple<K...>> {
    static const std::tuple<void (*)(K*, ParticleIndex*, std::size_t)...> sorts;
};
template <class... K>
const std::tuple<void (*)(K*, ParticleIndex*, std::size_t)...>
    SortInstances<std::tuple<K...>>::sorts{&CudaLauncher::sort_by_key<K>...};
template struct SortInstances<SortKeys>;

} // namespace cuda_detail
} // namespace exasph
