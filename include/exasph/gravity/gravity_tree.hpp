#pragma once
#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

#include "exasph/gravity/gravity_kern.hpp"
#include "exasph/gravity/gravity_node.hpp"
#include "exasph/tree/octree.hpp"
#include "exasph/util/error.hpp"

namespace exasph {

// Particles a gravity tree's leaves point into (positions, mass, h) with their SFC keys.
template <class T>
struct GravitySources {
    std::vector<T> x, y, z, m, h;
    std::vector<std::uint64_t> keys;

    std::size_t size() const { return x.size(); }
    void resize(std::size_t n) {
        for (auto* v : {&x, &y, &z, &m, &h}) v->resize(n);
        keys.resize(n);
    }
};

// Summary of the particles [b, e) of the arrays x, y, z, m, h.
template <class T>
LeafSummary<T> summarise_particles(const T* x, const T* y, const T* z, const T* m, const T* h,
                                   std::size_t b, std::size_t e) {
    LeafSummary<T> s;
    if (e <= b) return s;
    s.mp = particle_multipole(x, y, z, m, b, e);
    const T* pos[3] = {x, y, z};
    for (int d = 0; d < 3; ++d) {
        s.lo[d] = *std::min_element(pos[d] + b, pos[d] + e);
        s.hi[d] = *std::max_element(pos[d] + b, pos[d] + e);
    }
    s.hmax = *std::max_element(h + b, h + e);
    return s;
}

// Level of the octree cell covering a key range of length `size` (a power of 8).
inline int cell_level(std::uint64_t size) {
    int l = kKeyBitsPerAxis;
    for (; size > 1; size >>= 3) --l;
    return l;
}

// The gravity tree (physics.md §8): the global top tree over the global leaves (identical on every
// rank, from the leaf summaries), and below each leaf whose particles are here a subtree of the
// same octree cells the neighbour search uses. Built in two stages, because which remote leaves are
// needed is decided on the top tree alone:
//   build_top(leaf keys, summaries)  ->  top nodes, open_top_leaves() usable
//   add_subtrees(sources, ranges)    ->  complete tree, view() usable
// Invariant: nodes [0, num_top) are the top tree (node 0 the root); a top leaf node's `begin` is
// its global leaf index until add_subtrees links it to its subtree.
template <class T>
class GravityTree {
  public:
    void build_top(const std::vector<std::uint64_t>& leaf_keys,
                   const std::vector<LeafSummary<T>>& leaves, double theta,
                   const GravityImage& image) {
        theta_ = theta;
        image_ = image;
        periodic_ = image.len[0] > 0 || image.len[1] > 0 || image.len[2] > 0;
        const auto nl = std::uint32_t(leaf_keys.size() - 1);
        leaf_keys_ = leaf_keys;
        top_.build(leaf_keys.data(), nl, 1);
        const auto& tn = top_.nodes();
        nodes_.assign(tn.size(), {});
        leaf_node_.assign(nl, 0);
        for (std::size_t k = tn.size(); k-- > 0;) {
            auto& nd = nodes_[k];
            nd.first_child = tn[k].first_child;
            nd.num_children = tn[k].num_children;
            if (nd.first_child < 0) {
                leaf_node_[tn[k].begin] = std::uint32_t(k);
                static_cast<LeafSummary<T>&>(nd) = leaves[tn[k].begin];
            } else {
                combine_children(nd);
            }
            set_opening_radius(nd, theta_);
        }
        num_top_ = nodes_.size();
    }

    // Calls f(g) for every global leaf g in [first, last) that a particle inside [lo, hi] with
    // h <= hmax may open during its walk (a conservative superset).
    template <class F>
    void open_top_leaves(const T* lo, const T* hi, T hmax, std::uint32_t first, std::uint32_t last,
                         F&& f) const {
        const auto& tn = top_.nodes();
        std::vector<std::uint32_t> stack{0};
        while (!stack.empty()) {
            const std::uint32_t k = stack.back();
            stack.pop_back();
            const auto& nd = nodes_[k];
            if (tn[k].end <= first || tn[k].begin >= last || nd.mp.mass <= 0) continue;
            const bool may_open = periodic_ ? box_may_open<true>(nd, lo, hi, hmax, image_)
                                            : box_may_open<false>(nd, lo, hi, hmax, image_);
            if (!may_open) continue;
            if (nd.first_child < 0)
                f(tn[k].begin);
            else
                for (std::uint32_t c = 0; c < nd.num_children; ++c)
                    stack.push_back(nd.first_child + c);
        }
    }

    // Builds the subtree of every global leaf g with sources [src_begin[g], src_end[g]) (keys of
    // the sources sorted within each leaf) and links it below the top leaf.
    void add_subtrees(const GravitySources<T>& src, const std::vector<std::uint32_t>& src_begin,
                      const std::vector<std::uint32_t>& src_end, std::uint32_t bucket) {
        const auto nl = std::int64_t(leaf_node_.size());
        std::vector<std::vector<GravityNode<T>>> sub(nl);
#pragma omp parallel for schedule(dynamic, 8)
        for (std::int64_t g = 0; g < nl; ++g)
            if (src_end[g] > src_begin[g])
                sub[g] = build_subtree(src, src_begin[g], src_end[g],
                                       cell_level(leaf_keys_[g + 1] - leaf_keys_[g]), bucket);
        nodes_.resize(num_top_);
        groups_.clear();
        for (std::int64_t g = 0; g < nl; ++g) {
            if (sub[g].empty()) continue;
            const auto offset = std::int32_t(nodes_.size());
            for (auto nd : sub[g]) {
                if (nd.first_child >= 0)
                    nd.first_child += offset;
                else if (sub[g].size() > 1)
                    groups_.push_back(std::uint32_t(nodes_.size()));
                nodes_.push_back(nd);
            }
            if (sub[g].size() == 1) groups_.push_back(leaf_node_[g]);
            // The subtree root is the leaf's own cell: the top node takes over its children (or
            // its particles); its multipole stays the one every rank has.
            auto& leaf = nodes_[leaf_node_[g]];
            const auto& root = nodes_[offset];
            leaf.first_child = root.first_child;
            leaf.num_children = root.num_children;
            leaf.begin = root.begin;
            leaf.end = root.end;
        }
    }

    GravityTreeView<T> view(const GravitySources<T>& s) const {
        return {nodes_.data(), s.x.data(), s.y.data(), s.z.data(), s.m.data(), s.h.data()};
    }
    const std::vector<GravityNode<T>>& nodes() const {
        return nodes_;
    }
    // The particle leaves (each source in exactly one), in source order: the groups that share
    // one interaction list in the walk.
    const std::vector<std::uint32_t>& groups() const {
        return groups_;
    }
    std::size_t num_top() const {
        return num_top_;
    }

  private:
    std::vector<GravityNode<T>> build_subtree(const GravitySources<T>& s, std::uint32_t b,
                                              std::uint32_t e, int level,
                                              std::uint32_t bucket) const {
        Octree<T> oct;
        oct.build(s.keys.data() + b, e - b, bucket, b, level);
        const auto& on = oct.nodes();
        std::vector<GravityNode<T>> out(on.size());
        for (std::size_t k = on.size(); k-- > 0;) {
            auto& nd = out[k];
            nd.first_child = on[k].first_child;
            nd.num_children = on[k].num_children;
            if (nd.first_child < 0) {
                nd.begin = on[k].begin;
                nd.end = on[k].end;
                static_cast<LeafSummary<T>&>(nd) = summarise_particles(
                    s.x.data(), s.y.data(), s.z.data(), s.m.data(), s.h.data(), nd.begin, nd.end);
            } else {
                combine_children(nd, out.data());
            }
            set_opening_radius(nd, theta_);
        }
        return out;
    }

    void combine_children(GravityNode<T>& nd) const {
        combine_children(nd, nodes_.data());
    }

    // Multipole, box and hmax of an inner node from its (already complete) children.
    static void combine_children(GravityNode<T>& nd, const GravityNode<T>* all) {
        Multipole parts[8];
        bool any = false;
        nd.hmax = 0;
        for (std::uint32_t c = 0; c < nd.num_children; ++c) {
            const auto& ch = all[nd.first_child + c];
            parts[c] = ch.mp;
            if (ch.mp.mass <= 0) continue;
            for (int d = 0; d < 3; ++d) {
                nd.lo[d] = any ? std::min(nd.lo[d], ch.lo[d]) : ch.lo[d];
                nd.hi[d] = any ? std::max(nd.hi[d], ch.hi[d]) : ch.hi[d];
            }
            nd.hmax = std::max(nd.hmax, ch.hmax);
            any = true;
        }
        nd.mp = combine_multipoles(parts, int(nd.num_children));
    }

    double theta_ = 0.5;
    GravityImage image_{Box<double>{{0, 0, 0}, {1, 1, 1}, {false, false, false}}};
    bool periodic_ = false;
    Octree<T> top_;
    std::vector<std::uint64_t> leaf_keys_;
    std::vector<GravityNode<T>> nodes_;
    std::vector<std::uint32_t> leaf_node_; // top node of each global leaf
    std::vector<std::uint32_t> groups_;
    std::size_t num_top_ = 0;
};

} // namespace exasph
