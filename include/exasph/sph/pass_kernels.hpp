#pragma once
#include <type_traits>

#include "exasph/sph/block_kern.hpp"
#include "exasph/sph/density_kern.hpp"
#include "exasph/sph/diagnostics_kern.hpp"
#include "exasph/sph/field_hash_kern.hpp"
#include "exasph/sph/iad_kern.hpp"
#include "exasph/sph/momentum_energy_kern.hpp"
#include "exasph/sph/skin_kern.hpp"
#include "exasph/sph/softening_correction_kern.hpp"
#include "exasph/sph/state_check_kern.hpp"
#include "exasph/sph/stir_kern.hpp"
#include "exasph/sph/update_kern.hpp"

// The one list of the kernels that the passes (sph/passes.hpp, sph/block_passes.hpp) hand to a
// launcher, by how they are launched. From it come the CUDA launcher's instantiations
// (src/cuda/passes.cu), the check that every kernel a pass launches on the CUDA launcher is
// listed (CudaLauncher's constraints: a missing entry fails the compile, in nvcc's build of
// passes.cu, which runs every pass once with that launcher) and the device compile test
// (tests/device/kernels_device.cu). A pass that gains a kernel adds it here, once.
namespace exasph {

template <class... Kernels>
struct KernelList {};

template <class Kernel, class List>
inline constexpr bool kListed = false;
template <class Kernel, class... Kernels>
inline constexpr bool kListed<Kernel, KernelList<Kernels...>> = (std::is_same_v<Kernel, Kernels> ||
                                                                 ...);

template <class... A, class... B, class... C>
KernelList<A..., B..., C...> join(KernelList<A...>, KernelList<B...>, KernelList<C...> = {});

// The momentum-energy kernel as the step hands it over: in StoreResultKernel, which keeps each
// particle's own Courant limit with block time steps (and reduces it with global steps); every
// combination of terms, AV-switch field and volume elements (compute_momentum_energy's
// dispatch).
template <class T, class N, PairTerms kTerms>
using MomentumEnergyOf =
    KernelList<StoreResultKernel<MomentumEnergyKernel<T, kTerms, false, false, N>, T>,
               StoreResultKernel<MomentumEnergyKernel<T, kTerms, false, true, N>, T>,
               StoreResultKernel<MomentumEnergyKernel<T, kTerms, true, false, N>, T>,
               StoreResultKernel<MomentumEnergyKernel<T, kTerms, true, true, N>, T>>;

// Working precision T, derived fields stored as N.
template <class T, class N>
struct PassKernelsOf {
    // k(i, neighbours of i) for every list (for_each_neighbourhood).
    using neighbours =
        decltype(join(KernelList<DensityEosKernel<T, N>, IadKernel<T, N>, SofteningZetaKernel<T, N>,
                                 SofteningForceKernel<T, N>, RungNeedKernel<T, N>>{},
                      join(MomentumEnergyOf<T, N, PairTerms::plain>{},
                           MomentumEnergyOf<T, N, PairTerms::limited>{}),
                      MomentumEnergyOf<T, N, PairTerms::any>{}));
    // k(i) for the first n particles (for_each) ...
    using each = KernelList<PressAxisKernel<T, N>, EnergyUpdateKernel<T, N>,
                            SmoothingLengthKernel<T, N>, ViscosityKernel<T, N>,
                            VolumeWeightKernel<T, N>, StirKernel<T, N>, DriftKernel<T, N>>;
    // ... or for the listed ones (for_each_of: block time steps' active particles).
    using each_of = KernelList<SmoothingLengthKernel<T, N>, ViscosityKernel<T, N>,
                               VolumeWeightKernel<T, N>, OwnStepLimitKernel<T, N>>;
    // The same, reduced (reduce, reduce_of).
    using reduce =
        KernelList<AccelerationStepKernel<T, N>, SkinUseKernel<T, N>, OpenStepKernel<T, N>>;
    using reduce_of = KernelList<CloseStepKernel<T, N>>;
    // Reduced along the fixed tree (reduce_tree: the same bits on every launcher).
    using reduce_tree = KernelList<DiagnosticsKernel<T, N>>;
};

// Both storages of the derived fields (float, double), and the kernels that read no derived
// field.
template <class T>
struct PassKernels {
    using F = PassKernelsOf<T, float>;
    using D = PassKernelsOf<T, double>;
    using neighbours = decltype(join(typename F::neighbours{}, typename D::neighbours{}));
    using each = decltype(join(typename F::each{}, typename D::each{}));
    using each_of = decltype(join(typename F::each_of{}, typename D::each_of{}));
    using reduce =
        decltype(join(typename F::reduce{}, typename D::reduce{},
                      KernelList<ValueKernel<T, MinOf<double>>, ValueKernel<T, MaxOf<double>>,
                                 FieldHashKernel, GuardSealKernel, GuardCheckKernel<T>>{}));
    using reduce_of = decltype(join(typename F::reduce_of{}, typename D::reduce_of{}));
    using reduce_tree = decltype(join(typename F::reduce_tree{}, typename D::reduce_tree{}));
};

} // namespace exasph
