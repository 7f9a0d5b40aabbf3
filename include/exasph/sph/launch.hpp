#pragma once
#include <algorithm>
#include <cstdint>
#include <limits>
#include <type_traits>

#include "exasph/tree/batch_lists.hpp"
#include "exasph/tree/neighbour_groups.hpp"
#include "exasph/tree/neighbour_lists.hpp"

// Launchers: how a per-particle kernel runs over the particles. A kernel is a functor with an
// EXASPH_HD call operator, k(i) for particle-wise kernels or k(i, neighbours of i) for
// neighbour passes, that may return a number; a launcher calls it for every particle and, where
// asked, returns the minimum of the results. The passes (sph/passes.hpp) take the launcher as a
// template parameter, so that the same kernels run on another backend by adding a launcher
// here, not by touching the kernels.
namespace exasph {

// openmp: the CPU path (compact lists, OmpLauncher); gpu_host: the GPU path's lists and search
// run by OpenMP on the host (GpuHostLauncher: tests the GPU path without a GPU); cuda: on the
// device (src/cuda/).
enum class Backend { openmp, gpu_host, cuda };

// Particle-wise kernels on the OpenMP threads of this rank (static schedule).
struct OmpParticleLoops {
    template <class Kernel>
    static void for_each(std::size_t n, const Kernel& k) {
        const auto nn = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static)
        for (std::int64_t i = 0; i < nn; ++i) k(std::uint32_t(i));
    }

    // The particles idx[0, n) (block time steps: the active ones).
    template <class Kernel>
    static void for_each_of(const std::uint32_t* idx, std::size_t n, const Kernel& k) {
        const auto nn = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static)
        for (std::int64_t s = 0; s < nn; ++s) k(idx[s]);
    }

    template <class Kernel>
    static double reduce_min_of(const std::uint32_t* idx, std::size_t n, const Kernel& k) {
        const auto nn = static_cast<std::int64_t>(n);
        double least = std::numeric_limits<double>::infinity();
#pragma omp parallel for schedule(static) reduction(min : least)
        for (std::int64_t s = 0; s < nn; ++s) least = std::min(least, double(k(idx[s])));
        return least;
    }

    template <class Kernel>
    static double reduce_min(std::size_t n, const Kernel& k) {
        const auto nn = static_cast<std::int64_t>(n);
        double least = std::numeric_limits<double>::infinity();
#pragma omp parallel for schedule(static) reduction(min : least)
        for (std::int64_t i = 0; i < nn; ++i) least = std::min(least, double(k(std::uint32_t(i))));
        return least;
    }
};

// Whether a neighbour kernel returns a number for the launcher to reduce (kernels are templates
// on the span: ContiguousSpan from the CPU lists, NeighbourSpan from the interleaved ones).
template <class Kernel>
inline constexpr bool kReduces =
    !std::is_void_v<std::invoke_result_t<const Kernel&, std::uint32_t, NeighbourSpan>>;

// OpenMP threads of this rank: static schedule over particles, dynamic over leaf groups.
struct OmpLauncher : OmpParticleLoops {
    static constexpr Backend kBackend = Backend::openmp;
    static constexpr bool kSplitsGroups = true; // takes NeighbourGroups: overlaps halo exchanges
    template <class T>
    using Lists = NeighbourLists<T>;

    // Every particle with a list, in parallel over the leaf groups (each thread expands its
    // groups' lists into its own buffer). Returns the minimum of the kernel's results if it
    // returns a number (else +infinity).
    template <class T, class Kernel>
    static double for_each_neighbourhood(const NeighbourLists<T>& nl, const Kernel& k) {
        return for_groups(nl, nullptr, nl.num_groups(), k);
    }
    // Only the listed groups (a pass split around a halo exchange in flight).
    template <class T, class Kernel>
    static double for_each_neighbourhood(const NeighbourGroups<T>& part, const Kernel& k) {
        return for_groups(*part.lists, part.groups.data(), part.groups.size(), k);
    }

  private:
    // Groups which[0, n) of the lists (which == nullptr: groups 0 .. n - 1).
    template <class T, class Kernel>
    static double for_groups(const NeighbourLists<T>& nl, const std::uint32_t* which, std::size_t n,
                             const Kernel& k) {
        const auto groups = static_cast<std::int64_t>(n);
        double least = std::numeric_limits<double>::infinity();
#pragma omp parallel reduction(min : least)
        {
            typename NeighbourLists<T>::Decoder dec(nl);
#pragma omp for schedule(dynamic, 8)
            for (std::int64_t w = 0; w < groups; ++w) {
                const std::size_t g = which ? which[w] : std::size_t(w);
                dec.start(g);
                const auto end = nl.group_end(g);
                for (std::uint32_t s = nl.group_begin(g); s < end; ++s) {
                    if constexpr (kReduces<Kernel>)
                        least = std::min(least, double(k(nl.member(s), dec.next())));
                    else
                        k(nl.member(s), dec.next());
                }
            }
        }
        return least;
    }
};

// The GPU path on the host: the device's interleaved lists and search (BatchLists), one list
// slot (particle member(s)) per iteration as one CUDA thread would run it. Same kernels, same
// results as OmpLauncher (the lists hold the same neighbours in the same order).
struct GpuHostLauncher : OmpParticleLoops {
    static constexpr Backend kBackend = Backend::gpu_host;
    static constexpr bool kSplitsGroups = false; // whole passes: no halo overlap
    template <class T>
    using Lists = BatchLists<T>;

    template <class T, class Kernel>
    static double for_each_neighbourhood(const BatchLists<T>& nl, const Kernel& k) {
        const auto n = static_cast<std::int64_t>(nl.size());
        double least = std::numeric_limits<double>::infinity();
#pragma omp parallel for schedule(dynamic, kBatch) reduction(min : least)
        for (std::int64_t s = 0; s < n; ++s) {
            const auto slot = std::uint32_t(s);
            if constexpr (kReduces<Kernel>)
                least = std::min(least, double(k(nl.member(slot), nl.span(slot))));
            else
                k(nl.member(slot), nl.span(slot));
        }
        return least;
    }
};

// The launcher of a backend, chosen once at compile time.
template <Backend B>
struct LauncherFor;
template <>
struct LauncherFor<Backend::openmp> {
    using type = OmpLauncher;
};
template <>
struct LauncherFor<Backend::gpu_host> {
    using type = GpuHostLauncher;
};
using DefaultLauncher = LauncherFor<Backend::openmp>::type;

} // namespace exasph
