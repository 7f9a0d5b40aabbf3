#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <type_traits>
#include <vector>

#if defined(__AVX512F__)
#include <immintrin.h>
#endif
#ifdef _OPENMP
#include <omp.h>
#endif

#include "exasph/tree/neighbour_codec.hpp"
#include "exasph/tree/neighbour_search.hpp"
#include "exasph/tree/neighbour_span.hpp"

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
    // `ngmax` is the neighbour count above which Result::exceeded reports (SPEC 2); lists are
    // never truncated.
    explicit NeighbourLists(std::uint32_t ngmax = 150) : ngmax_(ngmax) {}

    struct Result {
        std::uint32_t max_count = 0; // longest list
        bool exceeded = false;       // max_count > ngmax
    };

    Result build(const Octree<T>& owned, const Octree<T>* halos, const SearchView<T>& p,
                 const Box<T>& box, NeighbourCriterion crit, std::uint32_t n_owned) {
        T hmax = owned.empty() ? T(0) : owned.nodes()[0].hmax;
        if (halos && !halos->empty()) hmax = std::max(hmax, halos->nodes()[0].hmax);
        check_periodic_reach(box, hmax);
        set_groups(owned, n_owned);
        max_count_ = search_all(owned, halos, p, box, crit);
        return {max_count_, max_count_ > ngmax_};
    }

    // Without halos (one rank, or tests).
    Result build(const Octree<T>& tree, const SearchView<T>& p, const Box<T>& box,
                 NeighbourCriterion crit, std::uint32_t n) {
        return build(tree, nullptr, p, box, crit, n);
    }

    // Particles with lists: [0, size()), in groups [group_begin(g), group_end(g)).
    std::size_t size() const { return group_first_.empty() ? 0 : group_first_.back(); }
    std::size_t num_groups() const { return records_.size(); }
    std::uint32_t group_begin(std::size_t g) const { return group_first_[g]; }
    std::uint32_t group_end(std::size_t g) const { return group_first_[g + 1]; }
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
            ncand_ = codec::get_varint(rec_);
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

        NeighbourSpan next() {
            const std::uint8_t* reached = rec_;
            const std::uint8_t* hits = rec_ + (ncand_ + 7) / 8;
            std::uint64_t pos = 0;
            std::uint32_t count = 0;
            std::uint32_t* out = index_.data();
            for (std::uint32_t w = 0; w < ncand_; w += 64) {
                std::uint64_t word = codec::load_word(reached + w / 8, std::min(64u, ncand_ - w));
                while (word) {
                    const std::uint32_t l = w + std::uint32_t(std::countr_zero(word));
                    word &= word - 1;
                    const std::uint32_t first = first_[l], size = size_[l];
                    for (std::uint32_t o = 0; o < size; o += 32) {
                        const unsigned n = std::min(32u, size - o);
                        count += codec::expand_mask(codec::load_bits(hits, pos + o, n), first + o,
                                                    out + count);
                    }
                    pos += size;
                }
            }
            rec_ = hits + (pos + 7) / 8;
            return {out, count};
        }

      private:
        const NeighbourLists& nl_;
        std::vector<std::uint32_t> index_;
        std::vector<std::uint32_t> first_, size_;
        const std::uint8_t* rec_ = nullptr;
        std::uint32_t ncand_ = 0;
    };

    // Frees the lists' memory (their pages go back to the system) until the next build: the
    // step's passes are done with them before the domain sync, the step's other memory peak.
    void release() {
        for (auto& a : arenas_) a.release();
        records_.clear();
        group_first_.clear();
    }

    // The list of particle i (tests, error messages: decodes its group up to i).
    std::vector<std::uint32_t> list(std::uint32_t i) const {
        const auto g = std::size_t(std::upper_bound(group_first_.begin(), group_first_.end(), i) -
                                   group_first_.begin() - 1);
        Decoder dec(*this);
        dec.start(g);
        for (std::uint32_t j = group_begin(g); j < i; ++j) dec.next();
        NeighbourSpan s = dec.next();
        return {s.index, s.index + s.count};
    }

  private:
    // The owned tree's leaves are the groups; they must tile [0, n_owned) in order.
    void set_groups(const Octree<T>& owned, std::uint32_t n_owned) {
        const auto& leaves = owned.leaves();
        group_first_.assign(1, 0);
        for (std::uint32_t l : leaves) {
            const auto& nd = owned.nodes()[l];
            if (nd.begin != group_first_.back())
                throw std::logic_error("neighbour lists: the tree's leaves do not tile the "
                                       "particles");
            group_first_.push_back(nd.end);
        }
        if (group_first_.back() != n_owned)
            throw std::logic_error("neighbour lists: the tree does not hold the owned particles");
        records_.assign(leaves.size(), nullptr);
    }

    std::uint32_t search_all(const Octree<T>& owned, const Octree<T>* halos, const SearchView<T>& p,
                             const Box<T>& box, NeighbourCriterion crit) {
        const auto& leaves = owned.leaves();
        const PeriodicImage<T> image(box);
        int threads = 1;
#ifdef _OPENMP
        threads = omp_get_max_threads();
#endif
        arenas_.resize(std::size_t(threads));
        for (auto& a : arenas_) a.reset();
        std::uint32_t max_count = 0;
        bool out_of_order = false;
#pragma omp parallel reduction(max : max_count) reduction(|| : out_of_order)
        {
            int tid = 0;
#ifdef _OPENMP
            tid = omp_get_thread_num();
#endif
            codec::Arena& arena = arenas_[std::size_t(tid)];
            std::vector<const OctreeNode<T>*> candidates;
            CandidateBoxes boxes;
            std::vector<std::uint8_t> rec;
#pragma omp for schedule(dynamic, 4)
            for (std::size_t l = 0; l < leaves.size(); ++l) {
                const auto& group = owned.nodes()[leaves[l]];
                candidates.clear();
                collect_leaves(owned, group, box, crit, candidates);
                if (halos) collect_leaves(*halos, group, box, crit, candidates);
                boxes.assign(candidates);
                rec.clear();
                out_of_order |= !encode_candidates(candidates, rec);
                for (std::uint32_t i = group.begin; i < group.end; ++i) {
                    std::uint32_t c = encode_neighbours(candidates, boxes, p, image, crit, i, rec);
                    max_count = std::max(max_count, c);
                }
                records_[l] = arena.store(rec);
            }
        }
        if (out_of_order)
            throw std::logic_error("neighbour lists: candidate leaves out of particle order");
        return max_count;
    }

    // Record header: the candidate leaves as (gap, size) pairs. Leaves come from depth-first
    // walks of the owned tree and then of the halo tree (indices after the owned), so they are
    // ascending; returns false if not.
    static bool encode_candidates(const std::vector<const OctreeNode<T>*>& candidates,
                                  std::vector<std::uint8_t>& rec) {
        codec::put_varint(rec, std::uint32_t(candidates.size()));
        std::uint32_t end = 0;
        for (const auto* leaf : candidates) {
            if (leaf->begin < end) return false;
            // Most candidates follow the previous one directly: the size carries a "gap follows"
            // flag, so such a leaf takes one byte.
            const std::uint32_t gap = leaf->begin - end;
            codec::put_varint(rec, (leaf->end - leaf->begin) << 1 | (gap != 0 ? 1u : 0u));
            if (gap != 0) codec::put_varint(rec, gap);
            end = leaf->end;
        }
        return true;
    }

    // Leaves of `tree` that may hold a neighbour of some particle of `group`.
    static void collect_leaves(const Octree<T>& tree, const OctreeNode<T>& group, const Box<T>& box,
                               NeighbourCriterion crit, std::vector<const OctreeNode<T>*>& out) {
        const auto& nodes = tree.nodes();
        if (nodes.empty()) return;
        std::uint32_t stack[8 * 64];
        int top = 0;
        stack[top++] = 0;
        while (top > 0) {
            const auto& nd = nodes[stack[--top]];
            T reach = T(2) * (crit == NeighbourCriterion::symmetric ? std::max(group.hmax, nd.hmax)
                                                                    : group.hmax);
            if (box_distance2(group, nd, box) >= reach * reach) continue;
            if (nd.first_child < 0) {
                out.push_back(&nd);
                continue;
            }
            for (std::uint32_t c = nd.num_children; c-- > 0;)
                stack[top++] = static_cast<std::uint32_t>(nd.first_child) + c;
        }
    }

    // The minimum image (PeriodicImage, util/box.hpp) with the period and half-period hoisted
    // into scalars by the caller, so that the distance loops vectorise.
    static T wrap(T d, T len, T half) {
        d = d > half ? d - len : d;
        return d < -half ? d + len : d;
    }

    // The candidate leaves' boxes as arrays (centre, inflated half-width, hmax), so that one
    // vectorised loop tests a particle against all of them (node_distance2, same arithmetic).
    struct CandidateBoxes {
        std::vector<T> c[3], e[3], hmax;
        std::vector<unsigned char> reached;
        void assign(const std::vector<const OctreeNode<T>*>& leaves) {
            const std::size_t n = leaves.size();
            for (int d = 0; d < 3; ++d) c[d].resize(n), e[d].resize(n);
            hmax.resize(n);
            reached.resize(n);
            for (std::size_t l = 0; l < n; ++l) {
                for (int d = 0; d < 3; ++d) {
                    c[d][l] = T(0.5) * (leaves[l]->lo[d] + leaves[l]->hi[d]);
                    e[d][l] = T(0.5) * (leaves[l]->hi[d] - leaves[l]->lo[d]) * T(kPruneInflate);
                }
                hmax[l] = leaves[l]->hmax;
            }
        }
    };

    // Particle i's part of the group record, appended to `rec`: the bitmap of the candidate
    // leaves whose boxes come within reach, then one bit per particle of those leaves (in
    // candidate order) telling whether it is a neighbour. Returns the neighbour count.
    static std::uint32_t encode_neighbours(const std::vector<const OctreeNode<T>*>& candidates,
                                           CandidateBoxes& boxes, const SearchView<T>& p,
                                           const PeriodicImage<T>& im, NeighbourCriterion crit,
                                           std::uint32_t i, std::vector<std::uint8_t>& rec) {
        const T pos[3] = {p.x[i], p.y[i], p.z[i]};
        const T hi = p.h[i];
        const bool symmetric = crit == NeighbourCriterion::symmetric;
        const T lx = im.len[0], ly = im.len[1], lz = im.len[2];
        const T hx = im.half[0], hy = im.half[1], hz = im.half[2];
        // Which leaf boxes come within reach of the particle (branch-free, vectorised).
        const std::size_t nleaves = candidates.size();
        const T *cx = boxes.c[0].data(), *cy = boxes.c[1].data(), *cz = boxes.c[2].data();
        const T *ex = boxes.e[0].data(), *ey = boxes.e[1].data(), *ez = boxes.e[2].data();
        const T* lh = boxes.hmax.data();
        unsigned char* reached = boxes.reached.data();
#pragma omp simd
        for (std::size_t l = 0; l < nleaves; ++l) {
            T gx = std::abs(wrap(cx[l] - pos[0], lx, hx)) - ex[l];
            T gy = std::abs(wrap(cy[l] - pos[1], ly, hy)) - ey[l];
            T gz = std::abs(wrap(cz[l] - pos[2], lz, hz)) - ez[l];
            gx = gx > T(0) ? gx : T(0);
            gy = gy > T(0) ? gy : T(0);
            gz = gz > T(0) ? gz : T(0);
            T reach = T(2) * (symmetric ? std::max(hi, lh[l]) : hi);
            reached[l] = gx * gx + gy * gy + gz * gz < reach * reach;
        }
        std::size_t bits = 0;
        for (std::size_t l = 0; l < nleaves; ++l)
            bits += reached[l] ? std::size_t(candidates[l]->end - candidates[l]->begin) : 0;
        const std::size_t r0 = rec.size();
        const std::size_t bytes = (nleaves + 7) / 8 + (bits + 7) / 8;
        rec.resize(r0 + bytes + codec::kReadPad);
        codec::BitWriter out(rec.data() + r0);
        for (std::size_t l = 0; l < nleaves; l += 32) {
            const std::size_t n = std::min<std::size_t>(32, nleaves - l);
            std::uint32_t word = 0;
            for (std::size_t k = 0; k < n; ++k) word |= std::uint32_t(reached[l + k]) << k;
            out.put(word, unsigned(n));
        }
        out.align();
        std::uint32_t count = 0;
        for (std::size_t l = 0; l < nleaves; ++l) {
            if (!reached[l]) continue;
            const OctreeNode<T>* leaf = candidates[l];
#if defined(__AVX512F__) && defined(__AVX512VL__)
            if constexpr (std::is_same_v<T, double>) {
                count +=
                    scan_leaf_avx512(leaf->begin, leaf->end, p, pos, hi, symmetric, im, i, out);
                continue;
            }
#endif
            // A branch-free distance pass that the compiler vectorises, then the flags packed
            // into bits.
            constexpr std::uint32_t kChunk = 32;
            unsigned char hit[kChunk];
            for (std::uint32_t b = leaf->begin; b < leaf->end; b += kChunk) {
                const std::uint32_t n = std::min(kChunk, leaf->end - b);
                const T *xb = p.x + b, *yb = p.y + b, *zb = p.z + b, *hb = p.h + b;
#pragma omp simd
                for (std::uint32_t k = 0; k < n; ++k) {
                    T dx = wrap(xb[k] - pos[0], lx, hx);
                    T dy = wrap(yb[k] - pos[1], ly, hy);
                    T dz = wrap(zb[k] - pos[2], lz, hz);
                    T r2 = dx * dx + dy * dy + dz * dz;
                    T hh = symmetric ? std::max(hi, hb[k]) : hi;
                    hit[k] = (r2 < T(4) * hh * hh) & (b + k != i);
                }
                std::uint32_t word = 0;
                for (std::uint32_t k = 0; k < n; ++k) word |= std::uint32_t(hit[k]) << k;
                out.put(word, n);
                count += std::uint32_t(std::popcount(word));
            }
        }
        out.align();
        rec.resize(r0 + bytes);
        return count;
    }

#if defined(__AVX512F__) && defined(__AVX512VL__)
    // The leaf scan above with AVX-512: eight candidates per step, the hit mask of the compare
    // appended to the record as it is. The same arithmetic as the portable loop (the minimum
    // image, then r2 < 4 max(h_a, h_b)^2).
    static std::uint32_t scan_leaf_avx512(std::uint32_t begin, std::uint32_t end,
                                          const SearchView<double>& p, const double pos[3],
                                          double hi, bool symmetric,
                                          const PeriodicImage<double>& im, std::uint32_t self,
                                          codec::BitWriter& out) {
        const __m512d px = _mm512_set1_pd(pos[0]), py = _mm512_set1_pd(pos[1]),
                      pz = _mm512_set1_pd(pos[2]), vhi = _mm512_set1_pd(hi);
        const __m512d len[3] = {_mm512_set1_pd(im.len[0]), _mm512_set1_pd(im.len[1]),
                                _mm512_set1_pd(im.len[2])};
        const __m512d half[3] = {_mm512_set1_pd(im.half[0]), _mm512_set1_pd(im.half[1]),
                                 _mm512_set1_pd(im.half[2])};
        auto wrap8 = [&](__m512d d, int axis) {
            __mmask8 above = _mm512_cmp_pd_mask(d, half[axis], _CMP_GT_OQ);
            d = _mm512_mask_sub_pd(d, above, d, len[axis]);
            __mmask8 below =
                _mm512_cmp_pd_mask(d, _mm512_sub_pd(_mm512_setzero_pd(), half[axis]), _CMP_LT_OQ);
            return _mm512_mask_add_pd(d, below, d, len[axis]);
        };
        std::uint32_t count = 0;
        for (std::uint32_t b = begin; b < end; b += 8) {
            const std::uint32_t n = std::min<std::uint32_t>(8, end - b);
            const __mmask8 valid = __mmask8((1u << n) - 1);
            __m512d dx = wrap8(_mm512_sub_pd(_mm512_maskz_loadu_pd(valid, p.x + b), px), 0);
            __m512d dy = wrap8(_mm512_sub_pd(_mm512_maskz_loadu_pd(valid, p.y + b), py), 1);
            __m512d dz = wrap8(_mm512_sub_pd(_mm512_maskz_loadu_pd(valid, p.z + b), pz), 2);
            __m512d r2 = _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(dx, dx), _mm512_mul_pd(dy, dy)),
                                       _mm512_mul_pd(dz, dz));
            __m512d hh =
                symmetric ? _mm512_max_pd(vhi, _mm512_maskz_loadu_pd(valid, p.h + b)) : vhi;
            __m512d reach2 = _mm512_mul_pd(_mm512_mul_pd(_mm512_set1_pd(4.0), hh), hh);
            __mmask8 hit = _mm512_mask_cmp_pd_mask(valid, r2, reach2, _CMP_LT_OQ);
            if (self >= b && self < b + n) hit &= __mmask8(~(1u << (self - b)));
            out.put(hit, n);
            count += std::uint32_t(__builtin_popcount(hit));
        }
        return count;
    }
#endif

    std::uint32_t ngmax_;
    std::uint32_t max_count_ = 0;
    std::vector<std::uint32_t> group_first_;   // first particle of each group, then n_owned
    std::vector<const std::uint8_t*> records_; // one record per group
    std::vector<codec::Arena> arenas_;         // one per thread: the records' storage
};

} // namespace exasph
