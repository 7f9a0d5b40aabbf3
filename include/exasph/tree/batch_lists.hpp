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

    // The particle of each slot when only the owned particles i with active[i] != 0 get lists
    // (block time steps): their indices, ascending; without `active`, all n (the identity, kept
    // as an empty list). Returns the number of slots.
    static std::uint32_t select_members(const std::uint8_t* active, std::uint32_t n,
                                        std::vector<std::uint32_t>& members) {
        members.clear();
        if (!active) return n;
        for (std::uint32_t i = 0; i < n; ++i)
            if (active[i]) members.push_back(i);
        const auto slots = std::uint32_t(members.size());
        if (slots == n) members.clear(); // all active
        return slots;
    }
};

// The GPU path's neighbour lists kept in host memory: the layout and the search of the device
// (tree/batch_search.hpp), run by OpenMP. The host launcher of the GPU path (sph/launch.hpp) reads
// them, so that CI runs the GPU path's logic without a GPU. Same interface as NeighbourLists:
// with `active`, lists only for the active particles, slot s holding particle member(s).
template <class T>
class BatchLists {
  public:
    explicit BatchLists(std::uint32_t ngmax = 150) : ngmax_(ngmax) {}

    struct Result {
        std::uint32_t max_count = 0;
        bool exceeded = false;
        std::uint64_t pairs = 0; // sum of the list lengths: the pair terms of one pass
    };

    Result build(const Octree<T>& owned, const Octree<T>* halos, const SearchView<T>& p,
                 const Box<T>& box, NeighbourCriterion crit, std::uint32_t n_owned,
                 const std::uint8_t* active = nullptr) {
        T hmax = owned.empty() ? T(0) : owned.nodes()[0].hmax;
        if (halos && !halos->empty()) hmax = std::max(hmax, halos->nodes()[0].hmax);
        check_periodic_reach(box, hmax);
        const TreeView<T> own{owned.nodes().data(), std::uint32_t(owned.nodes().size())};
        const TreeView<T> halo =
            halos ? TreeView<T>{halos->nodes().data(), std::uint32_t(halos->nodes().size())}
                  : TreeView<T>{};
        const bool sym = crit == NeighbourCriterion::symmetric;
        const auto n = std::int64_t(BatchLayout::select_members(active, n_owned, members_));
        count_.resize(std::size_t(n));
        std::uint64_t pairs = 0;
#pragma omp parallel for schedule(dynamic, 64) reduction(+ : pairs)
        for (std::int64_t s = 0; s < n; ++s) {
            count_[s] =
                search_particle(own, halo, p, box, sym, member(std::uint32_t(s)), nullptr, 1, 0);
            pairs += count_[s];
        }
        max_count_ = BatchLayout::size_batches(count_, offset_);
        index_.assign(offset_.back(), 0);
#pragma omp parallel for schedule(dynamic, 64)
        for (std::int64_t s = 0; s < n; ++s) {
            const NeighbourSpan sp = span(std::uint32_t(s));
            search_particle(own, halo, p, box, sym, member(std::uint32_t(s)),
                            const_cast<std::uint32_t*>(sp.index), kBatch, sp.count);
        }
        return {max_count_, max_count_ > ngmax_, pairs};
    }

    Result build(const Octree<T>& tree, const SearchView<T>& p, const Box<T>& box,
                 NeighbourCriterion crit, std::uint32_t n) {
        return build(tree, nullptr, p, box, crit, n);
    }

    // Slots (particles with a list).
    std::size_t size() const {
        return count_.size();
    }
    std::uint32_t member(std::uint32_t s) const {
        return members_.empty() ? s : members_[s];
    }
    std::uint32_t max_count() const {
        return max_count_;
    }
    // The list of slot s.
    NeighbourSpan span(std::uint32_t s) const {
        return BatchLayout::span(index_.data(), offset_.data(), count_.data(), s);
    }
    // The list of particle i (empty when it has none).
    std::vector<std::uint32_t> list(std::uint32_t i) const {
        if (!members_.empty()) {
            const auto it = std::lower_bound(members_.begin(), members_.end(), i);
            if (it == members_.end() || *it != i) return {};
            i = std::uint32_t(it - members_.begin());
        }
        if (i >= count_.size()) return {};
        const NeighbourSpan s = span(i);
        std::vector<std::uint32_t> out(s.count);
        for (std::uint32_t n = 0; n < s.count; ++n) out[n] = s[n];
        return out;
    }
    std::size_t bytes() const {
        return index_.capacity() * 4 + count_.capacity() * 4 + offset_.capacity() * 8 +
               members_.capacity() * 4;
    }
    void release() {
        index_ = {};
        count_.clear();
        members_.clear();
    }

  private:
    std::uint32_t ngmax_;
    std::uint32_t max_count_ = 0;
    std::vector<std::uint32_t> count_;   // list length per particle
    std::vector<std::uint64_t> offset_;  // first slot per batch, then the total
    std::vector<std::uint32_t> index_;   // the interleaved lists
    std::vector<std::uint32_t> members_; // particle of each slot (empty: the identity)
};

} // namespace exasph
