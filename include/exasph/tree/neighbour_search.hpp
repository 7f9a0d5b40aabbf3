#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

#if defined(__AVX512F__)
#include <immintrin.h>
#endif

#include "exasph/tree/octree.hpp"
#include "exasph/util/box.hpp"
#include "exasph/util/error.hpp"

namespace exasph {

// Which pairs are neighbours (SPEC 2).
//  gather:    r_ab < 2 h_a                (enough for density and IAD)
//  symmetric: r_ab < 2 max(h_a, h_b)      (needed for exact conservation in momentum-energy)
enum class NeighbourCriterion { gather, symmetric };

// Read-only positions and smoothing lengths for the search.
template <class T>
struct SearchView {
    const T* x;
    const T* y;
    const T* z;
    const T* h;
};

// Squared minimum-image distance between particles i and j. Shared by the tree search and the
// brute-force reference so that both decide ties identically.
template <class T>
inline T pair_distance2(const SearchView<T>& p, const Box<T>& box, std::uint32_t i,
                        std::uint32_t j) {
    T dx = box.min_image(p.x[j] - p.x[i], 0);
    T dy = box.min_image(p.y[j] - p.y[i], 1);
    T dz = box.min_image(p.z[j] - p.z[i], 2);
    return dx * dx + dy * dy + dz * dz;
}

template <class T>
inline bool is_neighbour(T r2, T hi, T hj, NeighbourCriterion crit) {
    T hh = crit == NeighbourCriterion::symmetric ? std::max(hi, hj) : hi;
    return r2 < T(4) * hh * hh;
}

// Round-off slack of tree pruning: half-widths grow by this factor, so that a particle on a box
// face is never pruned.
inline constexpr double kPruneInflate = 1.000000001;

// Squared minimum-image distance from a point to a node's box (conservative).
template <class T>
inline T node_distance2(const OctreeNode<T>& nd, const T p[3], const Box<T>& box) {
    return box.box_distance2(nd.lo, nd.hi, p, p, T(kPruneInflate));
}

// Squared minimum-image distance between two nodes' boxes (conservative).
template <class T>
inline T box_distance2(const OctreeNode<T>& a, const OctreeNode<T>& b, const Box<T>& box) {
    return box.box_distance2(a.lo, a.hi, b.lo, b.hi, T(kPruneInflate));
}

// Neighbours of particle i (self excluded), in tree order. Writes at most `cap` indices to `out`
// and returns the true count, which may exceed `cap`.
template <class T>
std::uint32_t find_neighbours(const Octree<T>& tree, const SearchView<T>& p, const Box<T>& box,
                              NeighbourCriterion crit, std::uint32_t i, std::uint32_t* out,
                              std::uint32_t cap) {
    const auto& nodes = tree.nodes();
    if (nodes.empty()) return 0;
    const T pos[3] = {p.x[i], p.y[i], p.z[i]};
    const T hi = p.h[i];
    std::uint32_t count = 0;
    std::uint32_t stack[8 * 64];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const auto& nd = nodes[stack[--top]];
        T reach = T(2) * (crit == NeighbourCriterion::symmetric ? std::max(hi, nd.hmax) : hi);
        if (node_distance2(nd, pos, box) >= reach * reach) continue;
        if (nd.first_child >= 0) {
            for (std::uint32_t c = nd.num_children; c-- > 0;)
                stack[top++] = static_cast<std::uint32_t>(nd.first_child) + c;
            continue;
        }
        for (std::uint32_t j = nd.begin; j < nd.end; ++j) {
            if (j == i) continue;
            if (!is_neighbour(pair_distance2(p, box, i, j), hi, p.h[j], crit)) continue;
            if (count < cap) out[count] = j;
            ++count;
        }
    }
    return count;
}

// The search radius must stay below half of every period for the minimum image to be the only
// image within reach.
template <class T>
void check_periodic_reach(const Box<T>& box, T hmax) {
    for (int d = 0; d < 3; ++d) {
        if (box.periodic[d] && T(4) * hmax >= box.length(d))
            throw input_error(
                "smoothing length h = " + std::to_string(hmax) +
                " is too large for the periodic box: 2h must be below half the period " +
                std::to_string(box.length(d)) + " (use more particles)");
    }
}

// Neighbour lists of the particles of `owned` (the local tree), searched in `owned` and, when
// given, in `halos` (a tree over the halo particles appended after the owned ones), with a fixed
// stride. A particle with more neighbours than the stride is never truncated: the stride grows
// and the search is repeated (reported by the caller through `grew`).
template <class T>
class NeighbourLists {
  public:
    explicit NeighbourLists(std::uint32_t stride = 150) : stride_(stride) {}

    struct Result {
        std::uint32_t max_count = 0;
        bool grew = false;
    };

    Result build(const Octree<T>& owned, const Octree<T>* halos, const SearchView<T>& p,
                 const Box<T>& box, NeighbourCriterion crit, std::uint32_t n_owned) {
        Result res;
        T hmax = owned.empty() ? T(0) : owned.nodes()[0].hmax;
        if (halos && !halos->empty()) hmax = std::max(hmax, halos->nodes()[0].hmax);
        check_periodic_reach(box, hmax);
        for (;;) {
            count_.resize(n_owned);
            index_.resize(static_cast<std::size_t>(n_owned) * stride_);
            std::uint32_t max_count = search_all(owned, halos, p, box, crit);
            res.max_count = max_count;
            if (max_count <= stride_) return res;
            stride_ = (max_count + 15) / 16 * 16;
            res.grew = true;
        }
    }

    // Without halos (one rank, or tests).
    Result build(const Octree<T>& tree, const SearchView<T>& p, const Box<T>& box,
                 NeighbourCriterion crit, std::uint32_t n) {
        return build(tree, nullptr, p, box, crit, n);
    }

    std::uint32_t stride() const { return stride_; }
    std::size_t size() const { return count_.size(); }
    std::uint32_t count(std::uint32_t i) const { return count_[i]; }
    const std::uint32_t* list(std::uint32_t i) const {
        return index_.data() + static_cast<std::size_t>(i) * stride_;
    }

  private:
    // One tree walk per leaf group (DESIGN: "one tree walk serves a whole group"): the walk
    // collects the leaves within reach of the group's box, then each particle of the group tests
    // only those leaves' boxes and particles.
    std::uint32_t search_all(const Octree<T>& owned, const Octree<T>* halos, const SearchView<T>& p,
                             const Box<T>& box, NeighbourCriterion crit) {
        const auto& leaves = owned.leaves();
        const PeriodicImage<T> image(box);
        std::uint32_t max_count = 0;
#pragma omp parallel reduction(max : max_count)
        {
            std::vector<const OctreeNode<T>*> candidates;
            CandidateBoxes boxes;
            std::vector<std::uint32_t> found;
#pragma omp for schedule(dynamic, 4)
            for (std::size_t l = 0; l < leaves.size(); ++l) {
                const auto& group = owned.nodes()[leaves[l]];
                candidates.clear();
                collect_leaves(owned, group, box, crit, candidates);
                if (halos) collect_leaves(*halos, group, box, crit, candidates);
                std::size_t reachable = 0;
                for (const auto* leaf : candidates) reachable += leaf->end - leaf->begin;
                found.resize(reachable + 1);
                boxes.assign(candidates);
                for (std::uint32_t i = group.begin; i < group.end; ++i) {
                    std::uint32_t c =
                        neighbours_in(candidates, boxes, p, image, crit, i, found.data());
                    std::uint32_t* out = index_.data() + std::size_t(i) * stride_;
                    std::copy(found.data(), found.data() + std::min(c, stride_), out);
                    count_[i] = std::min(c, stride_);
                    max_count = std::max(max_count, c);
                }
            }
        }
        return max_count;
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

    // Neighbours of particle i among the candidate leaves, in candidate order, written to `out`
    // (room for every candidate particle); returns the count.
    static std::uint32_t neighbours_in(const std::vector<const OctreeNode<T>*>& candidates,
                                       CandidateBoxes& boxes, const SearchView<T>& p,
                                       const PeriodicImage<T>& im, NeighbourCriterion crit,
                                       std::uint32_t i, std::uint32_t* out) {
        const T pos[3] = {p.x[i], p.y[i], p.z[i]};
        const T hi = p.h[i];
        const bool symmetric = crit == NeighbourCriterion::symmetric;
        const T lx = im.len[0], ly = im.len[1], lz = im.len[2];
        const T hx = im.half[0], hy = im.half[1], hz = im.half[2];
        std::uint32_t count = 0;
        // Within a leaf: a branch-free distance pass that the compiler vectorises, then a
        // branch-free compaction (every index is written, the count advances on a hit).
        constexpr std::uint32_t kChunk = 256;
        unsigned char hit[kChunk];
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
        for (std::size_t l = 0; l < nleaves; ++l) {
            if (!reached[l]) continue;
            const OctreeNode<T>* leaf = candidates[l];
#if defined(__AVX512F__) && defined(__AVX512VL__)
            if constexpr (std::is_same_v<T, double>) {
                count = scan_leaf_avx512(leaf->begin, leaf->end, p, pos, hi, symmetric, im, i, out,
                                         count);
                continue;
            }
#endif
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
                for (std::uint32_t k = 0; k < n; ++k) {
                    out[count] = b + k;
                    count += hit[k];
                }
            }
        }
        return count;
    }

#if defined(__AVX512F__) && defined(__AVX512VL__)
    // The leaf scan above with AVX-512: eight candidates per step, and the hits' indices
    // compressed straight into `out` (vpcompressd) instead of a scalar compaction pass. The same
    // arithmetic as the portable loop (the minimum image, then r2 < 4 max(h_a, h_b)^2).
    static std::uint32_t scan_leaf_avx512(std::uint32_t begin, std::uint32_t end,
                                          const SearchView<double>& p, const double pos[3],
                                          double hi, bool symmetric,
                                          const PeriodicImage<double>& im, std::uint32_t self,
                                          std::uint32_t* out, std::uint32_t count) {
        const __m512d px = _mm512_set1_pd(pos[0]), py = _mm512_set1_pd(pos[1]),
                      pz = _mm512_set1_pd(pos[2]), vhi = _mm512_set1_pd(hi);
        const __m512d len[3] = {_mm512_set1_pd(im.len[0]), _mm512_set1_pd(im.len[1]),
                                _mm512_set1_pd(im.len[2])};
        const __m512d half[3] = {_mm512_set1_pd(im.half[0]), _mm512_set1_pd(im.half[1]),
                                 _mm512_set1_pd(im.half[2])};
        const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
        auto wrap8 = [&](__m512d d, int axis) {
            __mmask8 above = _mm512_cmp_pd_mask(d, half[axis], _CMP_GT_OQ);
            d = _mm512_mask_sub_pd(d, above, d, len[axis]);
            __mmask8 below =
                _mm512_cmp_pd_mask(d, _mm512_sub_pd(_mm512_setzero_pd(), half[axis]), _CMP_LT_OQ);
            return _mm512_mask_add_pd(d, below, d, len[axis]);
        };
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
            __m256i idx = _mm256_add_epi32(_mm256_set1_epi32(int(b)), lane);
            _mm256_mask_compressstoreu_epi32(out + count, hit, idx);
            count += std::uint32_t(__builtin_popcount(hit));
        }
        return count;
    }
#endif

    std::uint32_t stride_;
    std::vector<std::uint32_t> count_;
    std::vector<std::uint32_t> index_;
};

} // namespace exasph
