#pragma once
#include <algorithm>
#include <bit>
#include <cstdint>
#include <vector>

#include "exasph/tree/candidate_boxes.hpp"
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

// Calls f(l) for each set bit l of the first n bits of `words`, in ascending order.
template <class F>
EXASPH_INLINE void for_each_bit(const std::uint64_t* words, std::size_t n, F&& f) {
    for (std::size_t w = 0; w < (n + 63) / 64; ++w)
        for (std::uint64_t word = words[w]; word != 0; word &= word - 1)
            f(64 * w + std::size_t(std::countr_zero(word)));
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
    const std::uint64_t* reached = reached_leaf_bits(boxes, nleaves, pos, hi, symmetric, im);
    const std::uint32_t* leaf_begin = boxes.begin.data();
    const std::uint32_t* leaf_size = boxes.size.data();
    std::uint32_t bits = 0;
    for_each_bit(reached, nleaves, [&](std::size_t l) { bits += leaf_size[l]; });
    const std::size_t r0 = rec.size();
    const std::size_t bytes = (nleaves + 7) / 8 + (bits + 7) / 8;
    rec.resize(r0 + bytes + codec::kReadPad);
    codec::BitWriter out(rec.data() + r0);
    for (std::size_t l = 0; l < nleaves; l += 32) {
        const std::size_t n = std::min<std::size_t>(32, nleaves - l);
        out.put(std::uint32_t(reached[l / 64] >> (l % 64)) & std::uint32_t((1ull << n) - 1),
                unsigned(n));
    }
    out.align();
    std::uint32_t count = 0;
    for_each_bit(reached, nleaves, [&](std::size_t l) {
        const std::uint32_t b = leaf_begin[l], e = b + leaf_size[l];
        count += boxes.wraps[l] ? scan_leaf<true>(b, e, p, pos, hi, symmetric, im, i, out)
                                : scan_leaf<false>(b, e, p, pos, hi, symmetric, im, i, out);
    });
    out.align();
    rec.resize(r0 + bytes);
    return count;
}

} // namespace exasph
