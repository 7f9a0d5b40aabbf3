// The CUDA launcher instantiated for every kernel that the passes of sph/passes.hpp hand it, in
// the working precision double and both storages of the derived fields (float, double): the
// host code (Simulation<double, CudaLauncher>) links against these. A pass that gains a kernel
// adds its line here; the linker names any that is missing.
#include "exasph/sph/block_kern.hpp"
#include "exasph/sph/density_kern.hpp"
#include "exasph/sph/iad_kern.hpp"
#include "exasph/sph/momentum_energy_kern.hpp"
#include "exasph/sph/skin_kern.hpp"
#include "exasph/sph/softening_correction_kern.hpp"
#include "exasph/sph/stir_kern.hpp"
#include "exasph/sph/update_kern.hpp"
#include "launch.cuh"

namespace exasph {

#define EXASPH_CUDA_FOR_EACH(...)                                                                  \
    template void CudaLauncher::for_each<__VA_ARGS__>(std::size_t, const __VA_ARGS__&);
#define EXASPH_CUDA_REDUCE(...)                                                                    \
    template ResultOf<__VA_ARGS__> CudaLauncher::reduce<__VA_ARGS__>(std::size_t,                  \
                                                                     const __VA_ARGS__&);
#define EXASPH_CUDA_NEIGHBOURS(...)                                                                \
    template ResultOf<__VA_ARGS__> CudaLauncher::for_each_neighbourhood<double, __VA_ARGS__>(      \
        const DeviceLists<double>&, const __VA_ARGS__&);
#define EXASPH_CUDA_FOR_EACH_OF(...)                                                               \
    template void CudaLauncher::for_each_of<__VA_ARGS__>(const std::uint32_t*, std::size_t,        \
                                                         const __VA_ARGS__&);
#define EXASPH_CUDA_REDUCE_OF(...)                                                                 \
    template ResultOf<__VA_ARGS__> CudaLauncher::reduce_of<__VA_ARGS__>(                           \
        const std::uint32_t*, std::size_t, const __VA_ARGS__&);
// A particle-wise pass that runs over all particles or the active ones (ParticleRange).
#define EXASPH_CUDA_FOR_EACH_IN(...)                                                               \
    EXASPH_CUDA_FOR_EACH(__VA_ARGS__) EXASPH_CUDA_FOR_EACH_OF(__VA_ARGS__)

// The momentum-energy kernel as Simulation hands it over: in StoreResultKernel, which keeps each
// particle's own Courant limit with block time steps (and reduces it with global steps).
#define EXASPH_CUDA_MOMENTUM_AS(...)                                                               \
    EXASPH_CUDA_NEIGHBOURS(StoreResultKernel<MomentumEnergyKernel<__VA_ARGS__>, double>)
#define EXASPH_CUDA_MOMENTUM_TERMS(TERMS, N)                                                       \
    EXASPH_CUDA_MOMENTUM_AS(double, PairTerms::TERMS, false, false, N)                             \
    EXASPH_CUDA_MOMENTUM_AS(double, PairTerms::TERMS, false, true, N)                              \
    EXASPH_CUDA_MOMENTUM_AS(double, PairTerms::TERMS, true, false, N)                              \
    EXASPH_CUDA_MOMENTUM_AS(double, PairTerms::TERMS, true, true, N)
#define EXASPH_CUDA_MOMENTUM(N)                                                                    \
    EXASPH_CUDA_MOMENTUM_TERMS(plain, N)                                                           \
    EXASPH_CUDA_MOMENTUM_TERMS(limited, N)                                                         \
    EXASPH_CUDA_MOMENTUM_TERMS(any, N)

#define EXASPH_CUDA_PASSES(N)                                                                      \
    EXASPH_CUDA_NEIGHBOURS(DensityEosKernel<double, N>)                                            \
    EXASPH_CUDA_NEIGHBOURS(IadKernel<double, N>)                                                   \
    EXASPH_CUDA_NEIGHBOURS(SofteningZetaKernel<double, N>)                                         \
    EXASPH_CUDA_NEIGHBOURS(SofteningForceKernel<double, N>)                                        \
    EXASPH_CUDA_MOMENTUM(N)                                                                        \
    EXASPH_CUDA_FOR_EACH(PressAxisKernel<double, N>)                                               \
    EXASPH_CUDA_FOR_EACH(EnergyUpdateKernel<double, N>)                                            \
    EXASPH_CUDA_FOR_EACH_IN(SmoothingLengthKernel<double, N>)                                      \
    EXASPH_CUDA_FOR_EACH_IN(ViscosityKernel<double, N>)                                            \
    EXASPH_CUDA_FOR_EACH_IN(VolumeWeightKernel<double, N>)                                         \
    EXASPH_CUDA_FOR_EACH(StirKernel<double, N>)                                                    \
    EXASPH_CUDA_REDUCE(AccelerationStepKernel<double, N>)                                          \
    EXASPH_CUDA_REDUCE(SkinUseKernel<double, N>)                                                   \
    EXASPH_CUDA_BLOCK_STEPS(N)

// Block time steps (sph/block_passes.hpp).
#define EXASPH_CUDA_BLOCK_STEPS(N)                                                                 \
    EXASPH_CUDA_FOR_EACH_OF(OwnStepLimitKernel<double, N>)                                         \
    EXASPH_CUDA_REDUCE_OF(CloseStepKernel<double, N>)                                              \
    EXASPH_CUDA_NEIGHBOURS(RungNeedKernel<double, N>)                                              \
    EXASPH_CUDA_REDUCE(OpenStepKernel<double, N>)                                                  \
    EXASPH_CUDA_FOR_EACH(DriftKernel<double, N>)

EXASPH_CUDA_PASSES(float)
EXASPH_CUDA_PASSES(double)
EXASPH_CUDA_REDUCE(ValueKernel<double, MinOf<double>>)
EXASPH_CUDA_REDUCE(ValueKernel<double, MaxOf<double>>)

} // namespace exasph
