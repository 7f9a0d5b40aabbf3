#pragma once
#include <cstddef>
#include <cstdint>

#include "exasph/sph/launch.hpp"
#include "exasph/sph/pass_kernels.hpp"
#include "exasph/tree/device_lists.hpp"

// The CUDA backend's launcher (the interface of sph/launch.hpp): one CUDA thread per particle,
// the kernels of sph/ called as they are. Particle fields and kernel tables are in managed memory
// (util/cuda_runtime.hpp), so the views the passes build hold pointers the device reads; each call
// ends synchronised, so host code after it sees the results. Declared here, defined in
// src/cuda/launch.cuh and instantiated for every kernel of the passes in src/cuda/passes.cu (nvcc);
// only a build with EXASPH_CUDA links it.
namespace exasph {

struct CudaLauncher {
    static constexpr Backend kBackend = Backend::cuda;
    static constexpr bool kSplitsGroups = false; // whole passes: no halo overlap
    template <class T>
    using Lists = DeviceLists<T>;

    // Each takes only the kernels of sph/pass_kernels.hpp (the ones src/cuda/passes.cu
    // instantiates): a pass that launches another does not compile.
    using Listed = PassKernels<double>;
    template <class Kernel>
    requires kListed<Kernel, Listed::each>
    static void for_each(std::size_t n, const Kernel& k);
    template <class Kernel>
    requires kListed<Kernel, Listed::reduce>
    static ResultOf<Kernel> reduce(std::size_t n, const Kernel& k);
    // The particles idx[0, n) (block time steps' active ones): idx must be device-readable
    // (FieldArray, managed memory).
    template <class Kernel>
    requires kListed<Kernel, Listed::each_of>
    static void for_each_of(const std::uint32_t* idx, std::size_t n, const Kernel& k);
    template <class Kernel>
    requires kListed<Kernel, Listed::reduce_of>
    static ResultOf<Kernel> reduce_of(const std::uint32_t* idx, std::size_t n, const Kernel& k);
    // Along the fixed tree of sph/reduction.hpp (a block of kTreeFan threads per run, each level
    // on the device; only the last value is copied to the host).
    template <class Kernel>
    requires kListed<Kernel, Listed::reduce_tree>
    static ResultOf<Kernel> reduce_tree(std::size_t n, const Kernel& k);
    template <class T, class Kernel>
    requires kListed<Kernel, Listed::neighbours>
    static ResultOf<Kernel> for_each_neighbourhood(const DeviceLists<T>& nl, const Kernel& k);

    // The primitives of sph/primitives.hpp (CUB's scan and radix sort; src/cuda/primitives.cu
    // instantiates them for every PrimitiveScalar and SortKey).
    template <PrimitiveScalar V>
    static V exclusive_scan(const V* in, V* out, std::size_t n);
    template <SortKey K>
    static void sort_by_key(K* keys, ParticleIndex* order, std::size_t n);
    template <PrimitiveScalar V>
    static void gather(const ParticleIndex* from, const V* in, V* out, std::size_t n);
    template <PrimitiveScalar V>
    static void scatter(const ParticleIndex* to, const V* in, V* out, std::size_t n);
};

template <>
struct LauncherFor<Backend::cuda> {
    using type = CudaLauncher;
};

} // namespace exasph
