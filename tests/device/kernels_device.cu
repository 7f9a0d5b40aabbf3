// Compiles every per-particle kernel of sph/ (the *_kern.hpp functors) as device code, in both
// precisions: what a CUDA launcher will call. Built by test_kernels_nvcc.sh with warnings as
// errors; nothing here runs.
#include <cstdint>

#include "exasph/sph/block_kern.hpp"
#include "exasph/sph/density_kern.hpp"
#include "exasph/sph/iad_kern.hpp"
#include "exasph/sph/momentum_energy_kern.hpp"
#include "exasph/sph/skin_kern.hpp"
#include "exasph/sph/update_kern.hpp"

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

template <class T>
void instantiate(ParticleView<T> p, Box<T> box, KernelView<T> kv, const std::uint32_t* lists,
                 double* out) {
    neighbour_pass<<<1, 32>>>(DensityEosKernel<T>{p, box, kv, EosParams{}, false}, lists, 8, 32,
                              out);
    neighbour_pass<<<1, 32>>>(IadKernel<T>{p, box, kv, true}, lists, 8, 32, out);
    Dissipation<T> d;
    using Terms = PairTerms;
    neighbour_pass<<<1, 32>>>(
        MomentumEnergyKernel<T, Terms::any, true, true>{p, box, kv, d, T(0.2)}, lists, 8, 32, out);
    neighbour_pass<<<1, 32>>>(
        MomentumEnergyKernel<T, Terms::limited, true, true>{p, box, kv, d, T(0.2)}, lists, 8, 32,
        out);
    neighbour_pass<<<1, 32>>>(
        MomentumEnergyKernel<T, Terms::plain, false, false>{p, box, kv, d, T(0.2)}, lists, 8, 32,
        out);
    particle_pass<<<1, 32>>>(PressAxisKernel<T>{p, box, T(1), T(1), 0}, 32, out);
    particle_pass<<<1, 32>>>(EnergyUpdateKernel<T>{p, T(1), T(1)}, 32, out);
    particle_pass<<<1, 32>>>(SmoothingLengthKernel<T>{p, T(100)}, 32, out);
    particle_pass<<<1, 32>>>(ViscosityKernel<T>{p, T(1), T(0.05), T(1), T(0.2)}, 32, out);
    particle_pass<<<1, 32>>>(VolumeWeightKernel<T>{p}, 32, out);
    particle_pass<<<1, 32>>>(AccelerationStepKernel<T>{p, 0.2}, 32, out);
    particle_pass<<<1, 32>>>(SkinUseKernel<T>{p, nullptr, T(1e-3), T(1e-3), T(100)}, 32, out);
    // Block time steps (sph/block_kern.hpp).
    particle_pass<<<1, 32>>>(OwnStepLimitKernel<T>{p, 0.0, 1e-3, 0.1, 2.0}, 32, out);
    particle_pass<<<1, 32>>>(CloseStepKernel<T>{p, 1e-3, 1.0, 0, false}, 32, out);
    neighbour_pass<<<1, 32>>>(RungNeedKernel<T>{p, nullptr}, lists, 8, 32, out);
    particle_pass<<<1, 32>>>(OpenStepKernel<T>{p, nullptr, nullptr, 1e-3, 0}, 32, out);
    particle_pass<<<1, 32>>>(DriftKernel<T>{p, box, T(1e-3), 1, 1e-3}, 32, out);
}

} // namespace

void instantiate_all(const std::uint32_t* lists, double* out) {
    instantiate(ParticleView<double>{}, Box<double>{}, KernelView<double>{}, lists, out);
    instantiate(ParticleView<float>{}, Box<float>{}, KernelView<float>{}, lists, out);
}
