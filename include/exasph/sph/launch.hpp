#pragma once
#include <algorithm>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

#include "exasph/tree/batch_lists.hpp"
#include "exasph/tree/neighbour_groups.hpp"
#include "exasph/tree/neighbour_lists.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

#include "exasph/sph/primitives.hpp"
#include "exasph/sph/reduction.hpp"

// Launchers: how a per-particle kernel runs over the particles. A kernel is a functor with an
// EXASPH_HD call operator, k(i) for particle-wise kernels or k(i, neighbours of i) for
// neighbour passes, that may return a value reduced as its member type Reduction says
// (sph/reduction.hpp: MinOf, MaxOf, SumOf, FirstIndexWhere). Every launcher provides:
//   for_each(n, k), for_each_of(idx, n, k)       k(i) for i < n, or for i in idx[0, n)
//   reduce(n, k), reduce_of(idx, n, k)           the same, returning the kernel's reduction
//   reduce_tree(n, k)                            reduce(n, k) combined along the fixed tree of
//                                                sph/reduction.hpp: the same bits everywhere
//   for_each_neighbourhood(lists, k)             k(i, neighbours) for every list, returning the
//                                                reduction when the kernel has one
// and the data-parallel primitives of sph/primitives.hpp (scan, sort by key, gather, scatter).
// Requires: a kernel writes only its own particle's slots (calls run in any order, in parallel).
// Guarantees: every call has returned (and its writes are visible to the host) when the
// launcher returns; min, max and first-index results do not depend on the order of the calls.
// The passes (sph/passes.hpp) take the launcher as a template parameter, so that the same
// kernels run on another backend by adding a launcher here, not by touching the kernels.
namespace exasph {

// openmp: the CPU path (compact lists, OmpLauncher); gpu_host: the GPU path's lists and search
// run by OpenMP on the host (GpuHostLauncher: tests the GPU path without a GPU); cuda: on the
// device (src/cuda/).
enum class Backend { openmp, gpu_host, cuda };

// Reduction R over this rank's threads: each thread runs part() (a worksharing loop that
// returns its share) and the shares are combined in thread order.
template <class R, class Part>
typename R::value_type reduce_over_threads(const Part& part) {
    using V = typename R::value_type;
#ifdef _OPENMP
    constexpr int kMostThreads = 1024;
    V share[kMostThreads];
    int threads = 1;
#pragma omp parallel
    {
#pragma omp single
        threads = omp_get_num_threads();
        const V mine = part(); // the worksharing loop's barrier follows the single's
        if (omp_get_thread_num() < kMostThreads) share[omp_get_thread_num()] = mine;
    }
    V total = R::identity();
    for (int t = 0; t < threads && t < kMostThreads; ++t) total = R::combine(total, share[t]);
    return total;
#else
    return part();
#endif
}

// Particle-wise kernels and the primitives on the OpenMP threads of this rank (static schedule).
struct OmpParticleLoops : OmpPrimitives {
    template <class Kernel>
    static void for_each(std::size_t n, const Kernel& k) {
        const auto nn = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static)
        for (std::int64_t i = 0; i < nn; ++i) k(ParticleIndex(i));
    }

    // The particles idx[0, n) (block time steps: the active ones).
    template <class Kernel>
    static void for_each_of(const ParticleIndex* idx, std::size_t n, const Kernel& k) {
        const auto nn = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static)
        for (std::int64_t s = 0; s < nn; ++s) k(idx[s]);
    }

    template <class Kernel>
    static ResultOf<Kernel> reduce_of(const ParticleIndex* idx, std::size_t n, const Kernel& k) {
        return reduce_slots(n, k, [idx](std::int64_t s) { return idx[s]; });
    }

    template <class Kernel>
    static ResultOf<Kernel> reduce(std::size_t n, const Kernel& k) {
        return reduce_slots(n, k, [](std::int64_t s) { return ParticleIndex(s); });
    }

    // The kernel's reduction over [0, n) along the fixed tree (kTreeFan, sph/reduction.hpp).
    template <class Kernel>
    static ResultOf<Kernel> reduce_tree(std::size_t n, const Kernel& k) {
        using R = ReductionOf<Kernel>;
        static_assert(kReduces<Kernel>, "a reduction needs a kernel with a Reduction");
        std::vector<ResultOf<Kernel>> level =
            fold_tree_level<R>(n, [&k](std::size_t i) { return k(ParticleIndex(i)); });
        while (level.size() > 1) {
            const std::vector<ResultOf<Kernel>> below = std::move(level);
            level = fold_tree_level<R>(below.size(), [&below](std::size_t i) { return below[i]; });
        }
        return level.empty() ? R::identity() : level[0];
    }

  private:
    // One level of the tree: the values value(0) .. value(n - 1) folded kTreeFan at a time.
    template <class R, class Value>
    static std::vector<typename R::value_type> fold_tree_level(std::size_t n, const Value& value) {
        std::vector<typename R::value_type> folded(tree_runs(n));
        const auto runs = static_cast<std::int64_t>(folded.size());
#pragma omp parallel for schedule(static)
        for (std::int64_t r = 0; r < runs; ++r) {
            TreeRunFold<R> run;
            const std::size_t first = std::size_t(r) * kTreeFan;
            for (std::size_t i = first; i < first + kTreeFan; ++i)
                run.add(i < n ? value(i) : R::identity());
            folded[std::size_t(r)] = run.value();
        }
        return folded;
    }

    // The kernel's reduction over particles particle(s), s in [0, n).
    template <class Kernel, class Particle>
    static ResultOf<Kernel> reduce_slots(std::size_t n, const Kernel& k, Particle particle) {
        using R = ReductionOf<Kernel>;
        static_assert(kReduces<Kernel>, "a reduction needs a kernel with a Reduction");
        const auto nn = static_cast<std::int64_t>(n);
        return reduce_over_threads<R>([&] {
            auto part = R::identity();
#pragma omp for schedule(static)
            for (std::int64_t s = 0; s < nn; ++s) part = R::combine(part, k(particle(s)));
            return part;
        });
    }
};

// The result of a neighbour pass over per-thread parts: the kernel's reduction, or nothing.
template <class Kernel, class Part>
ResultOf<Kernel> neighbour_pass(const Part& part) {
    if constexpr (kReduces<Kernel>) {
        return reduce_over_threads<ReductionOf<Kernel>>(part);
    } else {
#pragma omp parallel
        part();
    }
}

// Calls k(i, span) and folds its result (if any) into `part`.
template <class Kernel, class Span>
void visit_neighbourhood(const Kernel& k, std::uint32_t i, Span span,
                         std::conditional_t<kReduces<Kernel>, ResultOf<Kernel>, bool>& part) {
    if constexpr (kReduces<Kernel>)
        part = ReductionOf<Kernel>::combine(part, k(i, span));
    else
        k(i, span);
}

// The identity of the kernel's reduction (false for a kernel without one: a placeholder).
template <class Kernel>
constexpr auto reduction_start() {
    if constexpr (kReduces<Kernel>)
        return ReductionOf<Kernel>::identity();
    else
        return false;
}

// OpenMP threads of this rank: static schedule over particles, dynamic over leaf groups.
struct OmpLauncher : OmpParticleLoops {
    static constexpr Backend kBackend = Backend::openmp;
    static constexpr bool kSplitsGroups = true; // takes NeighbourGroups: overlaps halo exchanges
    template <class T>
    using Lists = NeighbourLists<T>;

    // Every particle with a list, in parallel over the leaf groups (each thread expands its
    // groups' lists into its own buffer).
    template <class T, class Kernel>
    static ResultOf<Kernel> for_each_neighbourhood(const NeighbourLists<T>& nl, const Kernel& k) {
        return for_groups(nl, nullptr, nl.num_groups(), k);
    }
    // Only the listed groups (a pass split around a halo exchange in flight).
    template <class T, class Kernel>
    static ResultOf<Kernel> for_each_neighbourhood(const NeighbourGroups<T>& part,
                                                   const Kernel& k) {
        return for_groups(*part.lists, part.groups.data(), part.groups.size(), k);
    }

  private:
    // Groups which[0, n) of the lists (which == nullptr: groups 0 .. n - 1).
    template <class T, class Kernel>
    static ResultOf<Kernel> for_groups(const NeighbourLists<T>& nl, const std::uint32_t* which,
                                       std::size_t n, const Kernel& k) {
        const auto groups = static_cast<std::int64_t>(n);
        return neighbour_pass<Kernel>([&] {
            auto part = reduction_start<Kernel>();
            typename NeighbourLists<T>::Decoder dec(nl);
#pragma omp for schedule(dynamic, 8)
            for (std::int64_t w = 0; w < groups; ++w) {
                const std::size_t g = which ? which[w] : std::size_t(w);
                dec.start(g);
                const auto end = nl.group_end(g);
                for (std::uint32_t s = nl.group_begin(g); s < end; ++s)
                    visit_neighbourhood(k, nl.member(s), dec.next(), part);
            }
            return part;
        });
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
    static ResultOf<Kernel> for_each_neighbourhood(const BatchLists<T>& nl, const Kernel& k) {
        const auto n = static_cast<std::int64_t>(nl.size());
        return neighbour_pass<Kernel>([&] {
            auto part = reduction_start<Kernel>();
#pragma omp for schedule(dynamic, kBatch)
            for (std::int64_t s = 0; s < n; ++s) {
                const auto slot = std::uint32_t(s);
                visit_neighbourhood(k, nl.member(slot), nl.span(slot), part);
            }
            return part;
        });
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
