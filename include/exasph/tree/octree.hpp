#pragma once
#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

#include "exasph/sfc/morton.hpp"
#include "exasph/util/error.hpp"

namespace exasph {

// One octree node: a contiguous range of SFC-sorted particles, its children (contiguous in the
// node array) and the tight bounding box and maximum h of its particles.
template <class T>
struct OctreeNode {
    std::uint32_t begin = 0, end = 0; // particle range [begin, end)
    std::int32_t first_child = -1;    // -1 for a leaf
    std::uint32_t num_children = 0;   // non-empty children only
    T lo[3] = {0, 0, 0};
    T hi[3] = {0, 0, 0};
    T hmax = 0;
};

// Octree built from SFC keys sorted ascending: every 3-bit digit of a Morton or Hilbert key names
// an octant, so a node of level l is a run of keys sharing their top 3l bits. Leaves hold at most
// `bucket_size` particles (or are at the deepest level).
// Invariant: node 0 is the root; children follow their parent in the array; `leaves` lists the
// leaf nodes in SFC order and their ranges tile [0, n).
template <class T>
class Octree {
  public:
    // Builds over the particles [offset, offset + n), whose sorted keys are keys[0, n). With
    // `start_level` > 0 all keys must lie in one cell of that level, which becomes the root.
    void build(const std::uint64_t* keys, std::uint32_t n, std::uint32_t bucket_size,
               std::uint32_t offset = 0, int start_level = 0) {
        if (bucket_size == 0) throw Error("octree: bucket size must be positive");
        nodes_.clear();
        leaves_.clear();
        if (n == 0) return;
        nodes_.push_back({0, n, -1, 0, {}, {}, 0});
        split(0, keys, start_level, bucket_size);
        for (auto& nd : nodes_) {
            nd.begin += offset;
            nd.end += offset;
        }
        for (std::uint32_t i = 0; i < nodes_.size(); ++i)
            if (nodes_[i].first_child < 0) leaves_.push_back(i);
        std::sort(leaves_.begin(), leaves_.end(), [&](std::uint32_t a, std::uint32_t b) {
            return nodes_[a].begin < nodes_[b].begin;
        });
    }

    // Tight bounding boxes and maximum h, leaves from the particles, inner nodes from children.
    void update_bounds(const T* x, const T* y, const T* z, const T* h) {
        const T* pos[3] = {x, y, z};
        update_bounds(pos, pos, h);
    }

    // Same for items that are boxes [lo, hi] (e.g. the cells of the global tree's leaves).
    void update_bounds(const T* const lo[3], const T* const hi[3], const T* h) {
#pragma omp parallel for schedule(static)
        for (std::size_t l = 0; l < leaves_.size(); ++l) {
            auto& nd = nodes_[leaves_[l]];
            for (int d = 0; d < 3; ++d) {
                nd.lo[d] = std::numeric_limits<T>::max();
                nd.hi[d] = std::numeric_limits<T>::lowest();
            }
            nd.hmax = 0;
            for (std::uint32_t i = nd.begin; i < nd.end; ++i) {
                for (int d = 0; d < 3; ++d) {
                    nd.lo[d] = std::min(nd.lo[d], lo[d][i]);
                    nd.hi[d] = std::max(nd.hi[d], hi[d][i]);
                }
                nd.hmax = std::max(nd.hmax, h[i]);
            }
        }
        // Children come after their parent, so a reverse sweep visits children first.
        for (std::size_t k = nodes_.size(); k-- > 0;) {
            auto& nd = nodes_[k];
            if (nd.first_child < 0) continue;
            const auto& c0 = nodes_[nd.first_child];
            std::copy(c0.lo, c0.lo + 3, nd.lo);
            std::copy(c0.hi, c0.hi + 3, nd.hi);
            nd.hmax = c0.hmax;
            for (std::uint32_t c = 1; c < nd.num_children; ++c) {
                const auto& ch = nodes_[nd.first_child + c];
                for (int d = 0; d < 3; ++d) {
                    nd.lo[d] = std::min(nd.lo[d], ch.lo[d]);
                    nd.hi[d] = std::max(nd.hi[d], ch.hi[d]);
                }
                nd.hmax = std::max(nd.hmax, ch.hmax);
            }
        }
    }

    bool empty() const {
        return nodes_.empty();
    }
    const std::vector<OctreeNode<T>>& nodes() const {
        return nodes_;
    }
    const std::vector<std::uint32_t>& leaves() const {
        return leaves_;
    }

  private:
    void split(std::uint32_t node, const std::uint64_t* keys, int level, std::uint32_t bucket) {
        std::uint32_t b = nodes_[node].begin, e = nodes_[node].end;
        if (e - b <= bucket || level == kKeyBitsPerAxis) return;
        int shift = 3 * (kKeyBitsPerAxis - level - 1);
        std::uint32_t first = static_cast<std::uint32_t>(nodes_.size());
        std::uint32_t lo = b;
        for (std::uint64_t digit = 0; digit < 8 && lo < e; ++digit) {
            // End of this octant: first key whose digit at this level exceeds `digit`.
            std::uint64_t prefix = keys[lo] >> (shift + 3);
            std::uint64_t limit = ((prefix << 3) | digit) + 1;
            const std::uint64_t* it = std::lower_bound(keys + lo, keys + e, limit << shift);
            std::uint32_t hi = static_cast<std::uint32_t>(it - keys);
            if (hi > lo) nodes_.push_back({lo, hi, -1, 0, {}, {}, 0});
            lo = hi;
        }
        nodes_[node].first_child = static_cast<std::int32_t>(first);
        nodes_[node].num_children = static_cast<std::uint32_t>(nodes_.size()) - first;
        for (std::uint32_t c = first; c < first + nodes_[node].num_children; ++c)
            split(c, keys, level + 1, bucket);
    }

    std::vector<OctreeNode<T>> nodes_;
    std::vector<std::uint32_t> leaves_;
};

} // namespace exasph
