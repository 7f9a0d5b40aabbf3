// The CUDA launcher instantiated for every kernel of sph/pass_kernels.hpp (working precision
// double, both storages of the derived fields): the host code (Simulation<double,
// CudaLauncher>) links against these. Nothing here names a kernel: adding a pass kernel is one
// entry in that list, and run_every_pass() below does not compile if a pass launches a kernel
// that the list lacks.
#include <cstddef>
#include <cstdint>
#include <tuple>

#include "exasph/sph/block_passes.hpp"
#include "exasph/sph/pass_kernels.hpp"
#include "exasph/sph/passes.hpp"
#include "launch.cuh"

namespace exasph {
namespace cuda_detail {

// How a listed kernel is launched: the lists of sph/pass_kernels.hpp.
enum class Launch { each, each_of, reduce, reduce_of, reduce_tree, neighbours };

// The launcher's function for kernel K launched as `how`.
template <Launch how, class K>
constexpr auto launcher_function() {
    if constexpr (how == Launch::each) return &CudaLauncher::for_each<K>;
    if constexpr (how == Launch::each_of) return &CudaLauncher::for_each_of<K>;
    if constexpr (how == Launch::reduce) return &CudaLauncher::reduce<K>;
    if constexpr (how == Launch::reduce_of) return &CudaLauncher::reduce_of<K>;
    if constexpr (how == Launch::reduce_tree) return &CudaLauncher::reduce_tree<K>;
    if constexpr (how == Launch::neighbours)
        return &CudaLauncher::for_each_neighbourhood<double, K>;
}

// The launcher's function for every kernel of a list, by address in a static member of an
// explicitly instantiated class: each function is then compiled and emitted here.
template <Launch how, class List>
struct Instances;
template <Launch how, class... K>
struct Instances<how, KernelList<K...>> {
    static const std::tuple<decltype(launcher_function<how, K>())...> table;
};
template <Launch how, class... K>
const std::tuple<decltype(launcher_function<how, K>())...> Instances<how, KernelList<K...>>::table{
    launcher_function<how, K>()...};

using Listed = CudaLauncher::Listed;
template struct Instances<Launch::each, Listed::each>;
template struct Instances<Launch::each_of, Listed::each_of>;
template struct Instances<Launch::reduce, Listed::reduce>;
template struct Instances<Launch::reduce_of, Listed::reduce_of>;
template struct Instances<Launch::reduce_tree, Listed::reduce_tree>;
template struct Instances<Launch::neighbours, Listed::neighbours>;

// Every pass of sph/passes.hpp and sph/block_passes.hpp once on the CUDA launcher, as the step
// calls it (never run): a pass whose kernel is not in the list fails CudaLauncher's constraint
// here, in nvcc's compile, not only at link time.
[[maybe_unused]] void run_every_pass(ParticleSet<double>& ps, const DeviceLists<double>& nl) {
    using L = CudaLauncher;
    const Box<double> box{};
    const KernelView<double> k{};
    const ParticleRange all(ps.size());
    compute_density<L>(ps, nl, box, k);
    compute_iad<L>(ps, nl, box, k);
    compute_momentum_energy<L>(ps, nl, box, k, Dissipation<double>{}, 0.2,
                               store_results_in<double>(nullptr));
    compute_softening_zeta<L>(ps, nl, SofteningView<double>{}, 1.0);
    add_softening_correction<L>(ps, nl, k);
    update_state<L>(ps, ps.size(), box, 1.0, 1.0);
    update_smoothing_lengths<L>(ps, all, 100.0);
    update_viscosity<L>(ps, all, 1.0, 0.05, 1.0);
    add_stirring<L>(ps, ps.size(), StirModes{});
    update_volume_weights<L>(ps, all, false);
    settle_volume_weights<L>(ps, nl, box, k, EosParams{}, ps.size(), false, [] {});
    (void)acceleration_time_step_min<L>(ps, ps.size(), 0.2);
    (void)skin_use_max<L>(ps, ps.size(), nullptr, 1.0, 1.0, 100.0);
    limit_own_steps<L>(ps, all, 1.0, 1.0, 0.2, 2.0);
    (void)own_step_extremes<L>(ps, ps.size());
    close_steps<L>(ps, all, 1.0, 1.0, 0, false);
    add_rung_needs<L>(ps, nl, nullptr);
    (void)open_steps<L>(ps, ps.size(), nullptr, nullptr, 1.0, 0);
    drift<L>(ps, ps.size(), box, 1.0, 0, 1.0);
}

} // namespace cuda_detail
} // namespace exasph
