#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

#include "exasph/tree/batch_search.hpp"
#include "exasph/tree/neighbour_span.hpp"
#include "exasph/tree/octree.hpp"

namespace exasph {

// Where the interleaved lists of the GPU path live: batch b's block starts at offset[b] and holds
// the longest list of its kBatch particles times kBatch slots. Shared by the host lists below and
// the device lists (tree/device_lists.hpp), which size them the same way: count first, then
// size, then write (never truncated).
struct BatchLayout {
    // The span of particle i in `index` (the lists' storage).
    EXASPH_HD static NeighbourSpan span(const std::uint32_t* index, const std::uint64_t* offset,
                                        const std::uint32_t* count, std::uint32_t i) {
        return {index + offset[i / kBatch] + i % kBatch, count[i], kBatch};
    }

    // offset[b]: the first slot of batch b (a prefix sum of kBatch x each batch's longest list),
    // then the total. Returns the longest list.
    static std::uint32_t size_batches(const std::vector<std::uint32_t>& count,
                                      std::vector<std::uint64_t>& offset) {
        const std::size_t batches = (count.size() + kBatch - 1) / kBatch;
        offset.assign(batches + 1, 0);
        std::uint32_t longest = 0;
        for (std::size_t b = 0; b < batches; ++b) {
            const auto first = count.begin() + std::ptrdiff_t(b * kBatch);
            const auto last =
                count.begin() + std::ptrdiff_t(std::min(count.size(), (b + 1) * kBatch));
            const std::uint32_t width = *std::max_element(first, last);
            longest = std::max(longest, width);
            offset[b + 1] = offset[b] + std::uint64_t(width) * kBatch;
        }
        return longest;
    }
};

// The GPU path's neighbour lists kept in host memory: the layout and the search of the device
// (tree/batch_search.hpp), run by OpenMP. The host launcher of the GPU path (sph/launch.hpp) reads
// them, so that CI runs the GPU path's logic without a GPU. Same interface as NeighbourLists.
template <class T>
class BatchLists {
  public:
    explicit BatchLists(std::uint32_t ngmax = 150) : ngmax_(ngmax) {}

    struct Result {
        std::uint32_t max_count = 0;
        bool exceeded = false;
    };

    Result build(const Octree<T>& owned, const Octree<T>* halos, const SearchView<T>& p,
                 const Box<T>& box, NeighbourCriterion crit, std::uint32_t n_owned) {
        T hmax = owned.empty() ? T(0) : owned.nodes()[0].hmax;
        if (halos && !halos->empty()) hmax = std::max(hmax, halos->nodes()[0].hmax);
        check_periodic_reach(box, hmax);
        const TreeView<T> own{owned.nodes().data(), std::uint32_t(owned.nodes().size())};
        const TreeView<T> halo =
            halos ? TreeView<T>{halos->nodes().data(), std::uint32_t(halos->nodes().size())}
                  : TreeView<T>{};
        const bool sym = crit == NeighbourCriterion::symmetric;
        count_.resize(n_owned);
        const auto n = std::int64_t(n_owned);
#pragma omp parallel for schedule(dynamic, 64)
        for (std::int64_t i = 0; i < n; ++i)
            count_[i] = search_particle(own, halo, p, box, sym, std::uint32_t(i), nullptr, 1, 0);
        max_count_ = BatchLayout::size_batches(count_, offset_);
        index_.assign(offset_.back(), 0);
#pragma omp parallel for schedule(dynamic, 64)
        for (std::int64_t i = 0; i < n; ++i) {
            const NeighbourSpan s = span(std::uint32_t(i));
            search_particle(own, halo, p, box, sym, std::uint32_t(i),
                            const_cast<std::uint32_t*>(s.index), kBatch, s.count);
        }
        return {max_count_, max_count_ > ngmax_};
    }

    Result build(const Octree<T>& tree, const SearchView<T>& p, const Box<T>& box,
                 NeighbourCriterion crit, std::uint32_t n) {
        return build(tree, nullptr, p, box, crit, n);
    }

    std::size_t size() const {
        return count_.size();
    }
    std::uint32_t max_count() const {
        return max_count_;
    }
    NeighbourSpan span(std::uint32_t i) const {
        return BatchLayout::span(index_.data(), offset_.data(), count_.data(), i);
    }
    std::vector<std::uint32_t> list(std::uint32_t i) const {
        const NeighbourSpan s = span(i);
        std::vector<std::uint32_t> out(s.count);
        for (std::uint32_t n = 0; n < s.count; ++n) out[n] = s[n];
        return out;
    }
    std::size_t bytes() const {
        return index_.capacity() * 4 + count_.capacity() * 4 + offset_.capacity() * 8;
    }
    void release() {
        index_ = {};
        count_.clear();
    }

  private:
    std::uint32_t ngmax_;
    std::uint32_t max_count_ = 0;
    std::vector<std::uint32_t> count_;  // list length per particle
    std::vector<std::uint64_t> offset_; // first slot per batch, then the total
    std::vector<std::uint32_t> index_;  // the interleaved lists
};

} // namespace exasph
