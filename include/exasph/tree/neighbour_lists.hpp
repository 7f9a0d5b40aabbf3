#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <type_traits>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "exasph/tree/neighbour_codec.hpp"
#include "exasph/tree/neighbour_encode.hpp"
#include "exasph/tree/neighbour_search.hpp"
#include "exasph/tree/neighbour_span.hpp"
#include "exasph/util/annotate.hpp"

namespace exasph {

// Neighbour lists of the owned particles (the local tree), searched in `owned` and, when given,
// in `halos` (a tree over the halo particles appended after the owned ones).
//
// Storage (DESIGN: compact neighbour lists). The search runs per leaf group: one tree walk finds
// the candidate leaves of the group, each particle of the group then tests those leaves' boxes
// and scans the leaves within reach. The lists are kept in exactly that form, one byte record per
// group:
//   varint ncand, then per candidate leaf (ascending in particle index): varint 2 size + g, and
//   if g = 1 a varint gap to the previous leaf's end (g = 0: no gap);
//   per particle of the group, in order: a bitmap of the candidate leaves it reached (ncand bits,
//   whole bytes), then one bit per particle of the reached leaves (1: a neighbour; whole bytes).
// About 70 B per particle at ng0 = 100 (Sedov glass) instead of 4 B per list slot (600 B at
// ngmax = 150).
// Decoder expands a particle's list into indices in the order of the search (candidate order,
// ascending within a leaf), so the SPH sums see the same neighbours in the same order.
template <class T>
class NeighbourLists {
  public:
    // `ngmax` is the neighbour count above which Result::exceeded reports (physics.md §2); lists
    // are never truncated.
    explicit NeighbourLists(std::uint32_t ngmax = 150) : ngmax_(ngmax) {}

    struct Result {
        std::uint32_t max_count = 0; // longest list
        bool exceeded = false;       // max_count > ngmax
        std::uint64_t pairs = 0;     // sum of the list lengths: the pair terms of one pass
    };

    // `active` (block time steps): only the owned particles i with active[i] != 0 get lists
    // (nullptr: all of them).
    Result build(const Octree<T>& owned, const Octree<T>* halos, const SearchView<T>& p,
                 const Box<T>& box, NeighbourCriterion crit, std::uint32_t n_owned,
                 const std::uint8_t* active = nullptr) {
        T hmax = owned.empty() ? T(0) : owned.nodes()[0].hmax;
        if (halos && !halos->empty()) hmax = std::max(hmax, halos->nodes()[0].hmax);
        check_periodic_reach(box, hmax);
        set_groups(owned, n_owned, active);
        max_count_ = search_all(owned, halos, p, box, crit);
        return {max_count_, max_count_ > ngmax_, pairs_};
    }

    // Without halos (one rank, or tests).
    Result build(const Octree<T>& tree, const SearchView<T>& p, const Box<T>& box,
                 NeighbourCriterion crit, std::uint32_t n) {
        return build(tree, nullptr, p, box, crit, n);
    }

    // Slots [0, size()), in groups [group_begin(g), group_end(g)); slot s holds the list of
    // particle member(s) (s itself unless the lists are of an active subset).
    std::size_t size() const { return group_first_.empty() ? 0 : group_first_.back(); }
    std::size_t num_groups() const { return records_.size(); }
    std::uint32_t group_begin(std::size_t g) const { return group_first_[g]; }
    std::uint32_t group_end(std::size_t g) const { return group_first_[g + 1]; }
    std::uint32_t member(std::uint32_t s) const { return members_.empty() ? s : members_[s]; }
    // Whether group g's search reached a halo leaf (its passes then need the halos' fields).
    bool group_reads_halos(std::size_t g) const { return reads_halos_[g] != 0; }
    std::uint64_t pairs() const { return pairs_; }
    std::uint32_t max_count() const { return max_count_; }
    // Bytes held by the lists (records and group tables).
    std::size_t bytes() const {
        std::size_t b = records_.capacity() * sizeof(const std::uint8_t*) +
                        group_first_.capacity() * sizeof(std::uint32_t);
        for (const auto& a : arenas_) b += a.bytes();
        return b;
    }

    // Expands the lists of one group's particles, in order: start(g), then next() once per
    // particle of the group. One decoder per thread; the span is valid until the next call.
    class Decoder {
      public:
        explicit Decoder(const NeighbourLists& nl)
            : nl_(nl), index_(std::size_t(nl.max_count_) + 64) {}

        void start(std::size_t g) {
            rec_ = nl_.records_[g];
            const std::uint32_t head = codec::get_varint(rec_);
            ncand_ = head >> 1;
            wraps_ = (head & 1u) != 0;
            first_.resize(ncand_);
            size_.resize(ncand_);
            std::uint32_t end = 0;
            for (std::uint32_t l = 0; l < ncand_; ++l) {
                const std::uint32_t v = codec::get_varint(rec_);
                size_[l] = v >> 1;
                first_[l] = end + ((v & 1u) ? codec::get_varint(rec_) : 0u);
                end = first_[l] + size_[l];
            }
        }

        // Not inlined into the pass's loop: there the SPH kernel's values kept registers
        // from the decoder's loop, which spilled (a call per particle costs less: density,
        // IAD 2.5 % faster on Zen 2).
        EXASPH_NOINLINE ContiguousSpan next() {
            const std::uint8_t* reached = rec_;
            const std::uint8_t* hits = rec_ + (ncand_ + 7) / 8;
            std::uint64_t pos = 0;
            std::uint32_t count = 0;
            std::uint32_t* out = index_.data();
            // (locals: through `out`'s stores the vectors' data would be reloaded every leaf)
            const std::uint32_t *firsts = first_.data(), *sizes = size_.data();
            for (std::uint32_t w = 0; w < ncand_; w += 64) {
                std::uint64_t word = codec::load_word(reached + w / 8, std::min(64u, ncand_ - w));
                while (word) {
                    const std::uint32_t l = w + std::uint32_t(std::countr_zero(word));
                    word &= word - 1;
                    const std::uint32_t first = firsts[l], size = sizes[l];
                    for (std::uint32_t o = 0; o < size; o += 32) {
                        const unsigned n = std::min(32u, size - o);
                        count += codec::expand_mask32(codec::load_bits(hits, pos + o, n), first + o,
                                                      out + count);
                    }
                    pos += size;
                }
            }
            rec_ = hits + (pos + 7) / 8;
            return {out, count, wraps_};
        }

      private:
        const NeighbourLists& nl_;
        std::vector<std::uint32_t> index_;
        std::vector<std::uint32_t> first_, size_;
        const std::uint8_t* rec_ = nullptr;
        std::uint32_t ncand_ = 0;
        bool wraps_ = true;
    };

    // Frees the lists' memory (their pages go back to the system) until the next build: the
    // step's passes are done with them before the domain sync, the step's other memory peak.
    void release() {
        for (auto& a : arenas_) a.release();
        records_.clear();
        group_first_.clear();
        std::vector<std::uint32_t>().swap(members_);
    }

    // The list of particle i (tests, error messages: decodes its group up to i's slot).
    std::vector<std::uint32_t> list(std::uint32_t i) const {
        std::uint32_t slot = i;
        if (!members_.empty()) {
            const auto it = std::lower_bound(members_.begin(), members_.end(), i);
            if (it == members_.end() || *it != i) return {};
            slot = std::uint32_t(it - members_.begin());
        }
        const auto g =
            std::size_t(std::upper_bound(group_first_.begin(), group_first_.end(), slot) -
                        group_first_.begin() - 1);
        Decoder dec(*this);
        dec.start(g);
        for (std::uint32_t j = group_begin(g); j < slot; ++j) dec.next();
        const ContiguousSpan s = dec.next();
        return {s.index, s.index + s.count};
    }

  private:
    // The owned tree's leaves are the groups; they must tile [0, n_owned) in order. With an
    // active subset, only the leaves holding active particles, and only those particles.
    void set_groups(const Octree<T>& owned, std::uint32_t n_owned, const std::uint8_t* active) {
        const auto& leaves = owned.leaves();
        group_first_.assign(1, 0);
        group_leaf_.clear();
        members_.clear();
        std::uint32_t end = 0;
        for (std::uint32_t l : leaves) {
            const auto& nd = owned.nodes()[l];
            if (nd.begin != end)
                throw std::logic_error("neighbour lists: the tree's leaves do not tile the "
                                       "particles");
            end = nd.end;
            std::uint32_t count = nd.end - nd.begin;
            if (active) {
                count = 0;
                for (std::uint32_t i = nd.begin; i < nd.end; ++i)
                    if (active[i]) members_.push_back(i), ++count;
                if (count == 0) continue;
            }
            group_leaf_.push_back(l);
            group_first_.push_back(group_first_.back() + count);
        }
        if (end != n_owned)
            throw std::logic_error("neighbour lists: the tree does not hold the owned particles");
        if (active && members_.size() == n_owned) members_.clear(); // all active: the identity
        records_.assign(group_leaf_.size(), nullptr);
        reads_halos_.assign(group_leaf_.size(), 0);
    }

    std::uint32_t search_all(const Octree<T>& owned, const Octree<T>* halos, const SearchView<T>& p,
                             const Box<T>& box, NeighbourCriterion crit) {
        const PeriodicImage<T> image(box);
        int threads = 1;
#ifdef _OPENMP
        threads = omp_get_max_threads();
#endif
        arenas_.resize(std::size_t(threads));
        for (auto& a : arenas_) a.reset();
        std::uint32_t max_count = 0;
        std::uint64_t pairs = 0;
        bool out_of_order = false;
#pragma omp parallel reduction(max : max_count) reduction(|| : out_of_order) reduction(+ : pairs)
        {
            int tid = 0;
#ifdef _OPENMP
            tid = omp_get_thread_num();
#endif
            codec::Arena& arena = arenas_[std::size_t(tid)];
            std::vector<const OctreeNode<T>*> candidates;
            CandidateBoxes<T> boxes;
            std::vector<std::uint8_t> rec;
#pragma omp for schedule(dynamic, 4)
            for (std::size_t g = 0; g < group_leaf_.size(); ++g) {
                const auto& group = owned.nodes()[group_leaf_[g]];
                candidates.clear();
                collect_leaves(owned, group, box, crit, candidates);
                const std::size_t owned_candidates = candidates.size();
                if (halos) collect_leaves(*halos, group, box, crit, candidates);
                reads_halos_[g] = candidates.size() > owned_candidates;
                boxes.assign(candidates, group, image);
                rec.clear();
                out_of_order |= !encode_candidates(candidates, boxes.any_wraps, rec);
                for (std::uint32_t s = group_begin(g); s < group_end(g); ++s) {
                    const std::uint32_t c =
                        encode_neighbours(boxes, p, image, crit, member(s), rec);
                    max_count = std::max(max_count, c);
                    pairs += c;
                }
                records_[g] = arena.store(rec);
            }
        }
        if (out_of_order)
            throw std::logic_error("neighbour lists: candidate leaves out of particle order");
        pairs_ = pairs;
        return max_count;
    }

    std::uint32_t ngmax_;
    std::uint32_t max_count_ = 0;
    std::uint64_t pairs_ = 0;
    std::vector<std::uint32_t> group_first_;   // first slot of each group, then size()
    std::vector<std::uint32_t> group_leaf_;    // the owned tree's leaf of each group
    std::vector<std::uint32_t> members_;       // particle of each slot (empty: the identity)
    std::vector<const std::uint8_t*> records_; // one record per group
    std::vector<std::uint8_t> reads_halos_;    // per group: a halo leaf among its candidates
    std::vector<codec::Arena> arenas_;         // one per thread: the records' storage
};

} // namespace exasph
