#pragma once
#include <algorithm>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#if defined(_OPENMP) && defined(__GLIBCXX__)
#include <parallel/algorithm>
#endif

#include "exasph/particles/particle_set.hpp"
#include "exasph/sfc/keys.hpp"

namespace exasph {

// On open axes the box is re-fitted to the particles each step so that SFC keys use the full
// 21-bit resolution; periodic axes keep their period.
template <class T>
void fit_open_axes(Box<T>& box, const ParticleSet<T>& ps) {
    for (int d = 0; d < 3; ++d) {
        if (box.periodic[d] || ps.size() == 0) continue;
        const auto& c = ps[component(Field::x, d)];
        T lo = std::numeric_limits<T>::max(), hi = std::numeric_limits<T>::lowest();
#pragma omp parallel for schedule(static) reduction(min : lo) reduction(max : hi)
        for (std::size_t i = 0; i < c.size(); ++i) {
            lo = std::min(lo, c[i]);
            hi = std::max(hi, c[i]);
        }
        T pad = T(1e-6) * std::max(hi - lo, T(1));
        box.lo[d] = lo - pad;
        box.hi[d] = hi + pad;
    }
}

// Insertion sort for items almost in order (between two steps most particles keep their place in
// the curve, and those that move go a few places): O(n + moves) instead of O(n log n). Gives up
// after `budget` moves (the items are then still a permutation, for a full sort to finish).
template <class Item, class Less>
bool insertion_sort_within(std::vector<Item>& a, const Less& before, std::size_t budget) {
    std::size_t moves = 0;
    for (std::size_t i = 1; i < a.size(); ++i) {
        if (!before(a[i], a[i - 1])) continue;
        const Item v = a[i];
        std::size_t j = i;
        do {
            a[j] = a[j - 1];
            --j;
        } while (j > 0 && before(v, a[j - 1]) && ++moves <= budget);
        a[j] = v;
        if (moves > budget) return false;
    }
    return true;
}

// Sorts the particles by `keys` (one per particle: their SFC keys), ties by persistent id, and
// returns the sorted keys (in the storage of `keys`). Scratch is kept small because the sync's
// peak is the run's peak memory: 16-byte sort items sorted in place, freed before the fields
// are permuted.
// The sort's scratch (16-byte items and the permutation), kept between calls where the sync runs
// every sub-step of block time steps: allocating its pages afresh each time costs more than the
// sort (page faults). Global steps free it (the sort is the step's memory peak).
struct SortScratch {
    struct Item {
        std::uint64_t key;
        std::uint32_t index;
    };
    std::vector<Item> items;
    std::vector<std::uint32_t> order;
};

template <class T>
std::vector<std::uint64_t> sort_by_keys(ParticleSet<T>& ps, std::vector<std::uint64_t> keys,
                                        SortScratch* kept = nullptr) {
    using Item = SortScratch::Item;
    const std::uint64_t* id = ps.id.data();
    auto before = [id](const Item& a, const Item& b) {
        return a.key != b.key ? a.key < b.key : id[a.index] < id[b.index];
    };
    const std::size_t n = keys.size();
    bool sorted = true; // the common case between two steps: nobody changed place
#pragma omp parallel for schedule(static) reduction(&& : sorted)
    for (std::size_t i = 1; i < n; ++i)
        sorted = sorted && (keys[i - 1] != keys[i] ? keys[i - 1] < keys[i] : id[i - 1] < id[i]);
    if (sorted) return keys;
    SortScratch local;
    SortScratch& scratch = kept ? *kept : local;
    std::vector<std::uint32_t>& order = scratch.order;
    order.resize(n);
    {
        std::vector<Item>& items = scratch.items;
        items.resize(n);
#pragma omp parallel for schedule(static)
        for (std::size_t i = 0; i < n; ++i) items[i] = {keys[i], static_cast<std::uint32_t>(i)};
        if (!insertion_sort_within(items, before, n / 8)) {
#if defined(_OPENMP) && defined(__GLIBCXX__)
            // In place (the default multiway mergesort copies the items).
            __gnu_parallel::sort(items.begin(), items.end(), before,
                                 __gnu_parallel::balanced_quicksort_tag());
#else
            std::sort(items.begin(), items.end(), before);
#endif
        }
#pragma omp parallel for schedule(static)
        for (std::size_t i = 0; i < n; ++i) {
            keys[i] = items[i].key;
            order[i] = items[i].index;
        }
    }
    if (!kept) std::vector<Item>().swap(scratch.items); // before the permutation's peak
    ps.permute(order);
    return keys;
}

// keys[i] = the SFC key of particle i < n. The curve is chosen once, outside the loop, so that
// the key arithmetic (all selects and bit operations) vectorises across particles.
template <class T>
void compute_sfc_keys(const T* x, const T* y, const T* z, std::size_t n, const Box<T>& box,
                      CurveKind kind, std::uint64_t* keys) {
    const auto m = static_cast<std::int64_t>(n);
    if (kind == CurveKind::hilbert) {
        const auto blocks = static_cast<std::int64_t>((n + kHilbertBlock - 1) / kHilbertBlock);
#pragma omp parallel for schedule(static)
        for (std::int64_t b = 0; b < blocks; ++b) {
            const std::size_t first = std::size_t(b) * kHilbertBlock;
            const std::size_t count = std::min(kHilbertBlock, n - first);
            std::uint32_t a[3][kHilbertBlock];
#pragma omp simd
            for (std::size_t k = 0; k < count; ++k) {
                a[0][k] = key_coordinate(x[first + k], box, 0);
                a[1][k] = key_coordinate(y[first + k], box, 1);
                a[2][k] = key_coordinate(z[first + k], box, 2);
            }
            hilbert_encode_block(a, count, keys + first);
        }
    } else {
#pragma omp parallel for simd schedule(static)
        for (std::int64_t i = 0; i < m; ++i)
            keys[i] = morton_encode(key_coordinate(x[i], box, 0), key_coordinate(y[i], box, 1),
                                    key_coordinate(z[i], box, 2));
    }
}

// Sorts the first n particles (all when n is omitted) along the space-filling curve, drops the
// rest, and returns the sorted keys. Equal keys are ordered by persistent id, so the order is
// unique: independent of threads and of the order in which migrated particles arrived.
template <class T>
std::vector<std::uint64_t> sort_along_curve(ParticleSet<T>& ps, const Box<T>& box, CurveKind kind,
                                            std::size_t n = std::size_t(-1)) {
    n = std::min(n, ps.size());
    std::vector<std::uint64_t> keys(n);
    compute_sfc_keys(ps.data(Field::x), ps.data(Field::y), ps.data(Field::z), n, box, kind,
                     keys.data());
    return sort_by_keys(ps, std::move(keys));
}

} // namespace exasph
