#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

#include "exasph/tree/leaf_scan.hpp"
#include "exasph/tree/neighbour_codec.hpp"
#include "exasph/tree/neighbour_search.hpp"
#include "exasph/util/annotate.hpp"

// The search-and-encode steps of NeighbourLists (tree/neighbour_lists.hpp): the candidate
// leaves of a group and each particle's part of the group record.
namespace exasph {

// Record header: the number of candidate leaves and whether any of them wraps
// (CandidateBoxes::wraps: whether some pair of the group may need the minimum image), then the
// leaves as (gap, size) pairs. Leaves come from depth-first walks of the owned tree and then of
// the halo tree (indices after the owned), so they are ascending; returns false if not.
template <class T>
bool encode_candidates(const std::vector<const OctreeNode<T>*>& candidates, bool wraps,
                       std::vector<std::uint8_t>& rec) {
    codec::put_varint(rec, std::uint32_t(candidates.size()) << 1 | (wraps ? 1u : 0u));
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
template <class T>
void collect_leaves(const Octree<T>& tree, const OctreeNode<T>& group, const Box<T>& box,
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

// The candidate leaves' boxes as arrays (centre, inflated half-width, hmax), so that one
// vectorised loop tests a particle against all of them (node_distance2, same arithmetic), and
// their particle ranges (read per particle without chasing the node pointers: that loop took
// 16 % of the search on Zen 2). `wraps[l]`: whether some particle of leaf l may lie more than
// half a period from some particle of the group along a periodic axis (from the tight boxes;
// fl(x_b - x_a) <= fl(hi_l - lo_g) as rounding is monotonic), i.e. whether the minimum image
// can change a distance; where it cannot, the leaf scan skips it (the same bits, less work: the
// image was half the scan's arithmetic).
template <class T>
struct CandidateBoxes {
    std::vector<T> c[3], e[3], hmax;
    std::vector<std::uint32_t> begin, size;
    std::vector<unsigned char> reached, wraps;
    void assign(const std::vector<const OctreeNode<T>*>& leaves, const OctreeNode<T>& group,
                const PeriodicImage<T>& im) {
        const std::size_t n = leaves.size();
        for (int d = 0; d < 3; ++d) c[d].resize(n), e[d].resize(n);
        hmax.resize(n);
        begin.resize(n);
        size.resize(n);
        reached.resize(n);
        wraps.resize(n);
        for (std::size_t l = 0; l < n; ++l) {
            for (int d = 0; d < 3; ++d) {
                c[d][l] = T(0.5) * (leaves[l]->lo[d] + leaves[l]->hi[d]);
                e[d][l] = T(0.5) * (leaves[l]->hi[d] - leaves[l]->lo[d]) * T(kPruneInflate);
            }
            hmax[l] = leaves[l]->hmax;
            begin[l] = leaves[l]->begin;
            size[l] = leaves[l]->end - leaves[l]->begin;
            bool w = false;
            for (int d = 0; d < 3; ++d) {
                const T far =
                    std::max(leaves[l]->hi[d] - group.lo[d], group.hi[d] - leaves[l]->lo[d]);
                w |= im.len[d] > T(0) && !(far <= im.half[d]);
            }
            wraps[l] = w;
        }
    }
};

// Which candidate leaf boxes come within reach of the particle at pos with smoothing length hi
// (branch-free, vectorised): flags in boxes.reached.
template <class T>
EXASPH_INLINE const unsigned char* mark_reached_leaves(CandidateBoxes<T>& boxes,
                                                       std::size_t nleaves, const T (&pos)[3], T hi,
                                                       bool symmetric, const PeriodicImage<T>& im) {
    const T lx = im.len[0], ly = im.len[1], lz = im.len[2];
    const T hx = im.half[0], hy = im.half[1], hz = im.half[2];
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
    return reached;
}

// Particle i's part of the group record, appended to `rec`: the bitmap of the candidate
// leaves whose boxes come within reach, then one bit per particle of those leaves (in
// candidate order) telling whether it is a neighbour. Returns the neighbour count.
template <class T>
std::uint32_t encode_neighbours(CandidateBoxes<T>& boxes, const SearchView<T>& p,
                                const PeriodicImage<T>& im, NeighbourCriterion crit,
                                std::uint32_t i, std::vector<std::uint8_t>& rec) {
    const T pos[3] = {p.x[i], p.y[i], p.z[i]};
    const T hi = p.h[i];
    const bool symmetric = crit == NeighbourCriterion::symmetric;
    const std::size_t nleaves = boxes.size.size(); // the candidate leaves
    const unsigned char* reached = mark_reached_leaves(boxes, nleaves, pos, hi, symmetric, im);
    const std::uint32_t* leaf_begin = boxes.begin.data();
    const std::uint32_t* leaf_size = boxes.size.data();
    std::uint32_t bits = 0;
#pragma omp simd reduction(+ : bits)
    for (std::size_t l = 0; l < nleaves; ++l) bits += reached[l] ? leaf_size[l] : 0u;
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
        const std::uint32_t b = leaf_begin[l], e = b + leaf_size[l];
        count += boxes.wraps[l] ? scan_leaf<true>(b, e, p, pos, hi, symmetric, im, i, out)
                                : scan_leaf<false>(b, e, p, pos, hi, symmetric, im, i, out);
    }
    out.align();
    rec.resize(r0 + bytes);
    return count;
}

} // namespace exasph
