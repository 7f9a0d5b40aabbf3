#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "exasph/domain/global_tree.hpp"
#include "exasph/domain/halo_exchange.hpp"
#include "exasph/tree/octree.hpp"
#include "exasph/util/box.hpp"
#include "exasph/util/error.hpp"

namespace exasph {

// Relative slack on every reach test of the halo discovery, so that round-off in cell boxes and
// distances only ever adds halos, never loses one.
inline constexpr double kHaloSlack = 1e-6;

// Spatial index over the global leaves: their cells as boxes, their maximum h, their owners, and
// an octree over them for range queries. Identical on every rank. Every reach test adds `skin`
// (a length; --sync-every): halos found so stay sufficient while no particle has moved, or grown
// its h, by more than skin / 2 (Domain::skin()).
template <class T>
class LeafIndex {
  public:
    void build(const GlobalTree& gt, const std::vector<T>& leaf_hmax, const Assignment& asg,
               const Box<T>& box, CurveKind curve, T skin = 0) {
        const std::size_t n = gt.num_leaves();
        skin_ = skin;
        for (int d = 0; d < 3; ++d) {
            lo_[d].resize(n);
            hi_[d].resize(n);
        }
        for (std::size_t l = 0; l < n; ++l) {
            T lo[3], hi[3];
            gt.cell_box(l, box, curve, lo, hi);
            for (int d = 0; d < 3; ++d) {
                lo_[d][l] = lo[d];
                hi_[d][l] = hi[d];
            }
        }
        hmax_ = leaf_hmax;
        owner_ = asg.owner;
        std::vector<std::uint64_t> starts(gt.keys().begin(), gt.keys().end() - 1);
        tree_.build(starts.data(), std::uint32_t(n), 1);
        const T* lo[3] = {lo_[0].data(), lo_[1].data(), lo_[2].data()};
        const T* hi[3] = {hi_[0].data(), hi_[1].data(), hi_[2].data()};
        tree_.update_bounds(lo, hi, hmax_.data());
        // Owner of each node when all its leaves share one, else -1: lets walks skip own subtrees.
        const auto& nodes = tree_.nodes();
        node_owner_.assign(nodes.size(), -1);
        for (std::size_t k = nodes.size(); k-- > 0;) {
            const auto& nd = nodes[k];
            int o = owner_[nd.begin];
            if (nd.first_child < 0) {
                for (std::uint32_t l = nd.begin; l < nd.end; ++l) o = owner_[l] == o ? o : -1;
            } else {
                for (std::uint32_t c = 0; c < nd.num_children; ++c)
                    o = node_owner_[nd.first_child + c] == o ? o : -1;
            }
            node_owner_[k] = o;
        }
    }

    // Calls visit(leaf) for every leaf not owned by `me` whose cell lies within reach of the box
    // [qlo, qhi] (a point when qlo == qhi): distance below 2 max(qh, hmax_leaf) + skin.
    template <class F>
    void query(const T qlo[3], const T qhi[3], T qh, int me, const Box<T>& box, F&& visit) const {
        const auto& nodes = tree_.nodes();
        if (nodes.empty()) return;
        std::uint32_t stack[8 * 64];
        int top = 0;
        stack[top++] = 0;
        while (top > 0) {
            std::uint32_t k = stack[--top];
            const auto& nd = nodes[k];
            if (node_owner_[k] == me) continue;
            if (!within_reach(qlo, qhi, nd.lo, nd.hi, std::max(qh, nd.hmax), skin_, box)) continue;
            if (nd.first_child >= 0) {
                for (std::uint32_t c = 0; c < nd.num_children; ++c)
                    stack[top++] = std::uint32_t(nd.first_child) + c;
                continue;
            }
            for (std::uint32_t l = nd.begin; l < nd.end; ++l) {
                const T llo[3] = {lo_[0][l], lo_[1][l], lo_[2][l]};
                const T lhi[3] = {hi_[0][l], hi_[1][l], hi_[2][l]};
                if (owner_[l] != me &&
                    within_reach(qlo, qhi, llo, lhi, std::max(qh, hmax_[l]), skin_, box))
                    visit(l);
            }
        }
    }

    int owner(std::uint32_t leaf) const { return owner_[leaf]; }
    T skin() const { return skin_; }
    T hmax(std::uint32_t leaf) const { return hmax_[leaf]; }
    void cell(std::uint32_t leaf, T lo[3], T hi[3]) const {
        for (int d = 0; d < 3; ++d) {
            lo[d] = lo_[d][leaf];
            hi[d] = hi_[d][leaf];
        }
    }

    // Symmetric in its two boxes (the minimum image of -d is exactly -d): both ranks of a pair
    // decide the same way whether they exchange halos.
    static bool within_reach(const T alo[3], const T ahi[3], const T blo[3], const T bhi[3], T h,
                             T skin, const Box<T>& box) {
        T reach = (T(2) * h + skin) * T(1 + kHaloSlack);
        return box.box_distance2(alo, ahi, blo, bhi) < reach * reach;
    }

  private:
    std::vector<T> lo_[3], hi_[3], hmax_;
    T skin_ = 0;
    std::vector<int> owner_;
    std::vector<int> node_owner_;
    Octree<T> tree_;
};

// The foreign leaves within reach of one local group (LeafIndex::query on its box), as arrays
// (centre, half-width, hmax, owner), so that one vectorised loop applies query()'s reach test
// (LeafIndex::within_reach for a point: the same arithmetic) to a member particle and all of
// them at once.
template <class T>
struct NearLeaves {
    std::vector<T> c[3], e[3], hmax;
    std::vector<int> owner;
    std::vector<unsigned char> hit;

    std::size_t size() const { return owner.size(); }
    void clear() {
        for (int d = 0; d < 3; ++d) c[d].clear(), e[d].clear();
        hmax.clear();
        owner.clear();
    }
    void add(const LeafIndex<T>& index, std::uint32_t leaf) {
        T lo[3], hi[3];
        index.cell(leaf, lo, hi);
        for (int d = 0; d < 3; ++d) {
            c[d].push_back(T(0.5) * (lo[d] + hi[d]));
            e[d].push_back(T(0.5) * (hi[d] - lo[d]));
        }
        hmax.push_back(index.hmax(leaf));
        owner.push_back(index.owner(leaf));
    }
    // hit[k]: leaf k within reach of the point p with smoothing length ph.
    const unsigned char* reached(const T p[3], T ph, T skin, const PeriodicImage<T>& im) {
        const std::size_t n = size();
        hit.resize(n);
        const T *cx = c[0].data(), *cy = c[1].data(), *cz = c[2].data();
        const T *ex = e[0].data(), *ey = e[1].data(), *ez = e[2].data();
        const T* hm = hmax.data();
        unsigned char* out = hit.data();
#pragma omp simd
        for (std::size_t k = 0; k < n; ++k) {
            const T gx = std::max(T(0), std::abs(im(p[0] - cx[k], 0)) - ex[k]);
            const T gy = std::max(T(0), std::abs(im(p[1] - cy[k], 1)) - ey[k]);
            const T gz = std::max(T(0), std::abs(im(p[2] - cz[k], 2)) - ez[k]);
            const T reach = (T(2) * std::max(ph, hm[k]) + skin) * T(1 + kHaloSlack);
            out[k] = gx * gx + gy * gy + gz * gz < reach * reach;
        }
        return out;
    }
};

// Ranks that exchange halos with `me`: owners of leaves within reach of one of my leaves. The
// relation is symmetric, so both sides of every pair post matching sends and receives.
template <class T>
std::vector<int> halo_partners(const LeafIndex<T>& index, const Assignment& asg, int me,
                               const Box<T>& box) {
    std::vector<char> mark(asg.count.size(), 0);
    for (std::uint32_t l = asg.first_leaf[me]; l < asg.first_leaf[me + 1]; ++l) {
        T lo[3], hi[3];
        index.cell(l, lo, hi);
        index.query(lo, hi, index.hmax(l), me, box,
                    [&](std::uint32_t o) { mark[index.owner(o)] = 1; });
    }
    std::vector<int> partners;
    for (int r = 0; r < int(mark.size()); ++r)
        if (mark[r]) partners.push_back(r);
    return partners;
}

// Send lists: owned particle i goes to every other rank with a leaf within reach of x_i
// (2 max(h_i, hmax_leaf)), which covers every pair of the symmetric neighbour criterion.
// One query per group (local tree leaf) finds the foreign leaves within reach of its box and
// hmax, a superset of each member's (its x_i lies in the box, h_i <= hmax); each particle then
// tests only those (one tree walk per particle near a boundary took 4 % of a step at 2 x 1).
template <class T>
void plan_halo_sends(HaloPlan& plan, const LeafIndex<T>& index, const Octree<T>& local, const T* x,
                     const T* y, const T* z, const T* h, int me, const Box<T>& box) {
    const std::size_t np = plan.partners.size();
    std::vector<int> slot_of(1, -1);
    int max_rank = plan.partners.empty() ? 0 : plan.partners.back();
    slot_of.assign(std::size_t(max_rank) + 1, -1);
    for (std::size_t k = 0; k < np; ++k) slot_of[plan.partners[k]] = int(k);
    plan.send.assign(np, {});
    const auto& leaves = local.leaves();
    std::vector<std::vector<std::pair<int, std::uint32_t>>> found(leaves.size());
    bool unknown_partner = false;
#pragma omp parallel reduction(|| : unknown_partner)
    {
        NearLeaves<T> near;
        const PeriodicImage<T> im(box);
#pragma omp for schedule(dynamic, 4)
        for (std::size_t g = 0; g < leaves.size(); ++g) {
            const auto& nd = local.nodes()[leaves[g]];
            near.clear();
            index.query(nd.lo, nd.hi, nd.hmax, me, box,
                        [&](std::uint32_t l) { near.add(index, l); });
            for (std::uint32_t i = nd.begin; i < nd.end && near.size() > 0; ++i) {
                const T p[3] = {x[i], y[i], z[i]};
                const unsigned char* hit = near.reached(p, h[i], index.skin(), im);
                int ranks[64];
                int nr = 0;
                for (std::size_t k = 0; k < near.size(); ++k) {
                    const int o = near.owner[k];
                    if (!hit[k] || std::find(ranks, ranks + nr, o) != ranks + nr) continue;
                    if (nr < 64)
                        ranks[nr++] = o;
                    else
                        unknown_partner = true; // more than 64 ranks within 2h: reported below
                }
                for (int k = 0; k < nr; ++k) {
                    if (ranks[k] > max_rank || slot_of[ranks[k]] < 0)
                        unknown_partner = true;
                    else
                        found[g].push_back({slot_of[ranks[k]], i});
                }
            }
        }
    }
    if (unknown_partner)
        throw Error("halo discovery: a particle needs halos from a rank outside the partner "
                    "set or from more than 64 ranks");
    for (const auto& f : found)
        for (auto [slot, i] : f) plan.send[slot].push_back(i);
}

} // namespace exasph
