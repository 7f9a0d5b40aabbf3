#pragma once
#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "exasph/sfc/keys.hpp"
#include "exasph/util/box.hpp"
#include "exasph/util/error.hpp"

namespace exasph {

inline constexpr std::uint64_t kKeyEnd = std::uint64_t(1) << (3 * kKeyBitsPerAxis);

// The leaf size the global tree refines to: the requested bucket, grown with the total particle
// count so that the tree stays near 2^20 leaves. Every rank counts, reduces and walks all global
// leaves every step (0.5 us per leaf measured): with a fixed bucket that work grows with the whole
// machine and stops weak scaling (docs/scaling.md: bucket 128 at 32M particles per node, 2.6 %
// efficiency on 2,048 nodes in the model). Depends on the total only: the decomposition, and the
// gravity tree built on it, stay independent of the rank count. Below 2^20 x bucket particles
// (134M at 128) the bucket is the requested one.
inline std::uint64_t effective_global_bucket(std::uint64_t requested, std::uint64_t total) {
    return std::max(requested, total >> 20);
}

// Leaves of the global (top) tree, identical on every rank: leaf i covers the SFC keys
// [keys[i], keys[i+1]); each leaf is one octree cell (its key range is 8^k long and aligned).
// Invariant: keys[0] = 0, keys.back() = 2^63, strictly increasing.
class GlobalTree {
  public:
    GlobalTree() : keys_{0, kKeyEnd} {}

    // Restores leaves saved from another run (checkpoint); throws if they are not a valid tiling.
    void set_keys(std::vector<std::uint64_t> keys) {
        bool ok = keys.size() >= 2 && keys.front() == 0 && keys.back() == kKeyEnd;
        for (std::size_t i = 0; ok && i + 1 < keys.size(); ++i) {
            std::uint64_t size = keys[i + 1] - keys[i];
            ok = keys[i] < keys[i + 1] && (size & (size - 1)) == 0 && keys[i] % size == 0;
        }
        if (!ok)
            throw input_error("global tree leaves in the checkpoint are not a valid tiling", true);
        keys_ = std::move(keys);
    }

    std::size_t num_leaves() const { return keys_.size() - 1; }
    const std::vector<std::uint64_t>& keys() const { return keys_; }

    // The leaf holding `key`.
    std::uint32_t leaf_of(std::uint64_t key) const {
        auto it = std::upper_bound(keys_.begin(), keys_.end(), key);
        return static_cast<std::uint32_t>(it - keys_.begin() - 1);
    }
    // The same, trying leaf `hint` first: particles still in last step's SFC order mostly fall
    // into the leaf of the previous particle.
    std::uint32_t leaf_of(std::uint64_t key, std::uint32_t hint) const {
        if (std::size_t(hint) + 1 < keys_.size() && keys_[hint] <= key && key < keys_[hint + 1])
            return hint;
        return leaf_of(key);
    }

    // Octree level of a leaf (0 = root cell).
    int level(std::size_t leaf) const {
        std::uint64_t size = keys_[leaf + 1] - keys_[leaf];
        int l = kKeyBitsPerAxis;
        while (size > 1) {
            size >>= 3;
            --l;
        }
        return l;
    }

    // Rebuilds the leaves from global counts: a leaf with more than `bucket` particles is split
    // into its eight children; eight sibling leaves holding at most bucket/2 together merge into
    // their parent (the gap to `bucket` stops split/merge oscillation). Returns true on change.
    bool refine(const std::vector<std::uint64_t>& counts, std::uint64_t bucket) {
        std::vector<std::uint64_t> next;
        next.reserve(keys_.size());
        bool changed = false;
        const std::size_t n = num_leaves();
        for (std::size_t i = 0; i < n;) {
            if (mergeable(i, counts, bucket)) {
                next.push_back(keys_[i]);
                i += 8;
                changed = true;
                continue;
            }
            std::uint64_t size = keys_[i + 1] - keys_[i];
            if (counts[i] > bucket && size > 1) {
                for (int c = 0; c < 8; ++c) next.push_back(keys_[i] + c * (size / 8));
                changed = true;
            } else {
                next.push_back(keys_[i]);
            }
            ++i;
        }
        next.push_back(kKeyEnd);
        keys_.swap(next);
        return changed;
    }

    // Cell of a leaf as an axis-aligned box in physical coordinates.
    template <class T>
    void cell_box(std::size_t leaf, const Box<T>& box, CurveKind curve, T lo[3], T hi[3]) const {
        auto c =
            curve == CurveKind::hilbert ? hilbert_decode(keys_[leaf]) : morton_decode(keys_[leaf]);
        const int shift = kKeyBitsPerAxis - level(leaf);
        const std::uint32_t mask = ~((1u << shift) - 1u);
        for (int d = 0; d < 3; ++d) {
            const double scale = double(box.hi[d] - box.lo[d]) / double(kKeyAxisMax + 1);
            const std::uint32_t origin = c[d] & mask;
            lo[d] = T(box.lo[d] + origin * scale);
            hi[d] = T(box.lo[d] + (double(origin) + double(1u << shift)) * scale);
        }
    }

  private:
    bool mergeable(std::size_t i, const std::vector<std::uint64_t>& counts,
                   std::uint64_t bucket) const {
        if (i + 8 > num_leaves()) return false;
        std::uint64_t size = keys_[i + 1] - keys_[i];
        std::uint64_t parent = size * 8;
        if (parent > kKeyEnd || keys_[i] % parent != 0) return false;
        std::uint64_t total = 0;
        for (int c = 0; c < 8; ++c) {
            if (keys_[i + c + 1] - keys_[i + c] != size) return false;
            total += counts[i + c];
        }
        return 2 * total <= bucket;
    }

    std::vector<std::uint64_t> keys_;
};

// Contiguous leaf ranges per rank with balanced particle counts: rank r owns leaves
// [first_leaf[r], first_leaf[r+1]). Each boundary is the leaf boundary nearest to r N / P, so
// the imbalance is at most the largest leaf count. With `weight` (one integer per leaf), the
// boundaries balance the weights instead (domain/cost_balance.hpp).
struct Assignment {
    std::vector<std::uint32_t> first_leaf; // size P + 1
    std::vector<std::uint64_t> count;      // particles per rank
    std::vector<int> owner;                // owning rank per leaf
    std::vector<std::uint64_t> leaf_keys;  // the global leaves this assignment refers to
    std::vector<std::uint64_t> leaf_count; // global particle count per leaf

    // Owned particles of the most loaded rank over the mean (1 before any assignment).
    double imbalance() const {
        if (count.empty()) return 1.0;
        double total = 0, most = 0;
        for (auto v : count) total += double(v), most = std::max(most, double(v));
        return most / (total / double(count.size()));
    }
};

inline Assignment assign_leaves(const std::vector<std::uint64_t>& counts, int nranks,
                                const std::vector<std::uint64_t>& weight = {}) {
    const std::size_t nleaves = counts.size();
    const std::vector<std::uint64_t>& w = weight.empty() ? counts : weight;
    std::vector<std::uint64_t> cum(nleaves + 1, 0);
    for (std::size_t i = 0; i < nleaves; ++i) cum[i + 1] = cum[i] + w[i];
    const std::uint64_t total = cum.back();
    Assignment a;
    a.first_leaf.assign(nranks + 1, 0);
    a.first_leaf[nranks] = std::uint32_t(nleaves);
    for (int r = 1; r < nranks; ++r) {
        const double target = double(total) * r / nranks;
        auto it = std::lower_bound(cum.begin(), cum.end(), std::uint64_t(target));
        std::size_t b = std::size_t(it - cum.begin());
        if (b > 0 && target - double(cum[b - 1]) < double(cum[b]) - target) --b;
        a.first_leaf[r] = std::uint32_t(std::max<std::size_t>(b, a.first_leaf[r - 1]));
    }
    for (std::size_t i = 0; i < nleaves; ++i) cum[i + 1] = cum[i] + counts[i];
    a.count.resize(nranks);
    a.owner.resize(nleaves);
    for (int r = 0; r < nranks; ++r) {
        a.count[r] = cum[a.first_leaf[r + 1]] - cum[a.first_leaf[r]];
        for (std::uint32_t l = a.first_leaf[r]; l < a.first_leaf[r + 1]; ++l) a.owner[l] = r;
        if (a.count[r] == 0)
            throw input_error("domain decomposition: rank " + std::to_string(r) +
                                  " would own no particles (" + std::to_string(cum.back()) +
                                  " particles, " + std::to_string(nleaves) + " global leaves, " +
                                  std::to_string(nranks) +
                                  " ranks): use fewer ranks or a smaller --global-bucket",
                              true);
    }
    return a;
}

} // namespace exasph
