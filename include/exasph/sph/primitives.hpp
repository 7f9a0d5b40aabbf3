#pragma once
#include <algorithm>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <tuple>
#include <utility>
#include <vector>

#if defined(_OPENMP) && defined(__GLIBCXX__)
#include <parallel/algorithm>
#endif
#ifdef _OPENMP
#include <omp.h>
#endif

#include "exasph/particles/particle_index.hpp"

// Data-parallel primitives of the launchers (sph/launch.hpp), beside the per-particle kernels:
// what a domain kept on the device is written on (SFC keys sorted with a permutation, every
// carried field reordered by it, counts turned into offsets). Every launcher provides, with the
// same results:
//   exclusive_scan(in, out, n) -> total     out[i] = in[0] + ... + in[i - 1]; in == out allowed
//   sort_by_key(keys, order, n)             keys[0, n) ascending, order[] permuted alongside;
//                                           equal keys keep their input order (stable)
//   gather(from, in, out, n)                out[i] = in[from[i]]
//   scatter(to, in, out, n)                 out[to[i]] = in[i] (to[] without repeats)
// Requires: the arrays hold n elements (gather's `in` and scatter's `out` as many as the indices
// reach), are readable where the launcher runs (CUDA: device or managed memory), and gather and
// scatter's in and out do not overlap. Guarantees: done, and visible to the host, on return;
// integer scans and the sort give the same bits on every launcher and thread count.
namespace exasph {

// The element types of the primitives (the CUDA launcher instantiates each: src/cuda/primitives.cu)
// and the sort's key types (unsigned integers, radix-sortable on the device; SFC keys are 64-bit).
using PrimitiveScalars =
    std::tuple<float, double, std::int32_t, std::uint32_t, std::int64_t, std::uint64_t>;
using SortKeys = std::tuple<std::uint32_t, std::uint64_t>;
template <class V, class List>
inline constexpr bool kAmong = false;
template <class V, class... Listed>
inline constexpr bool kAmong<V, std::tuple<Listed...>> = (std::same_as<V, Listed> || ...);
template <class V>
concept PrimitiveScalar = kAmong<V, PrimitiveScalars>;
template <class K>
concept SortKey = kAmong<K, SortKeys>;

// The primitives on this rank's OpenMP threads (the CPU launcher and the GPU path's host one).
struct OmpPrimitives {
    template <PrimitiveScalar V>
    static V exclusive_scan(const V* in, V* out, std::size_t n) {
        std::vector<V> before(threads() + 1, V(0)); // sum of the chunks of threads < t
#pragma omp parallel
        {
            const auto [lo, hi] = chunk(n);
            V mine(0);
            for (std::size_t i = lo; i < hi; ++i) mine += in[i];
            before[thread() + 1] = mine;
#pragma omp barrier
#pragma omp single
            for (std::size_t t = 1; t < before.size(); ++t) before[t] += before[t - 1];
            V running = before[thread()];
            for (std::size_t i = lo; i < hi; ++i) {
                const V v = in[i]; // read before the write: in == out allowed
                out[i] = running;
                running += v;
            }
        }
        return before.back();
    }

    template <SortKey K>
    static void sort_by_key(K* keys, ParticleIndex* order, std::size_t n) {
        struct Item {
            K key;
            ParticleIndex value;
        };
        std::vector<Item> items(n);
        const auto m = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static)
        for (std::int64_t i = 0; i < m; ++i) items[i] = {keys[i], order[i]};
        const auto by_key = [](const Item& a, const Item& b) { return a.key < b.key; };
#if defined(_OPENMP) && defined(__GLIBCXX__)
        __gnu_parallel::stable_sort(items.begin(), items.end(), by_key);
#else
        std::stable_sort(items.begin(), items.end(), by_key);
#endif
#pragma omp parallel for schedule(static)
        for (std::int64_t i = 0; i < m; ++i) {
            keys[i] = items[i].key;
            order[i] = items[i].value;
        }
    }

    template <PrimitiveScalar V>
    static void gather(const ParticleIndex* from, const V* in, V* out, std::size_t n) {
        const auto m = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static)
        for (std::int64_t i = 0; i < m; ++i) out[i] = in[from[i]];
    }

    template <PrimitiveScalar V>
    static void scatter(const ParticleIndex* to, const V* in, V* out, std::size_t n) {
        const auto m = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static)
        for (std::int64_t i = 0; i < m; ++i) out[to[i]] = in[i];
    }

  private:
#ifdef _OPENMP
    static std::size_t threads() {
        return std::size_t(omp_get_max_threads());
    }
    static std::size_t thread() {
        return std::size_t(omp_get_thread_num());
    }
    static std::size_t team() {
        return std::size_t(omp_get_num_threads());
    }
#else
    static std::size_t threads() {
        return 1;
    }
    static std::size_t thread() {
        return 0;
    }
    static std::size_t team() {
        return 1;
    }
#endif
    // This thread's contiguous share [lo, hi) of [0, n) (the scan's two passes use the same).
    static std::pair<std::size_t, std::size_t> chunk(std::size_t n) {
        const std::size_t per = (n + team() - 1) / team();
        const std::size_t lo = std::min(n, thread() * per);
        return {lo, std::min(n, lo + per)};
    }
};

} // namespace exasph
