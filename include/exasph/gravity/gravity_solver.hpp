#pragma once
#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "exasph/domain/message_tag.hpp"
#include "exasph/util/mpi.hpp"

#include "exasph/domain/collectives.hpp"
#include "exasph/domain/global_tree.hpp"
#include "exasph/domain/sfc_order.hpp"
#include "exasph/gravity/gravity_group_kern.hpp"
#include "exasph/gravity/gravity_periodicity.hpp"
#include "exasph/gravity/gravity_tree.hpp"
#include "exasph/gravity/leaf_summary_sums.hpp"
#include "exasph/particles/particle_set.hpp"
#include "exasph/sfc/keys.hpp"
#include "exasph/util/error.hpp"

namespace exasph {

// Distributed self-gravity (physics.md §8) on the domain's decomposition:
//  1. each rank summarises the global leaves it owns; one collective (sum/max) gives every rank
//     every leaf's multipole, box and hmax, hence the same top tree;
//  2. each rank decides from the top tree alone which remote leaves its walks may open, and each
//     owner decides the same for every other rank, so both sides know what moves without
//     exchanging counts; the particles of those leaves move point to point;
//  3. every leaf whose particles are here gets its subtree and each owned particle walks the tree.
// A walk sees the same nodes on any number of ranks: the result does not depend on rank count.
template <class T>
class GravitySolver {
  public:
    GravitySolver(const KernelTable<T>& kernel, double G, double theta, std::uint32_t bucket)
        : soft_(kernel), G_(G), theta_(theta), bucket_(bucket) {
        if (!(theta > 0 && theta < 1))
            throw input_error("--theta must be in (0, 1), got " + std::to_string(theta), true);
    }

    double G() const { return G_; }
    std::size_t remote_sources() const { return remote_; } // received in the last call
    double multipoles_per_particle() const { return multipoles_per_particle_; } // mean, last call
    double pairs_per_particle() const { return pairs_per_particle_; }
    const SofteningTable<T>& softening() const { return soft_; }

    // Adds G times the gravitational acceleration to ax, ay, az of the owned particles [0, n) and
    // sets their potential phi (with `active`, block time steps: of those with active[i] != 0;
    // the tree holds all). The particles are in the order of the domain's last sync (SFC order,
    // each rank owning the leaves of `asg`); `box` is the box of that sync.
    void compute(ParticleSet<T>& ps, std::size_t n, const Assignment& asg, const Box<T>& box,
                 CurveKind curve, Collectives& coll, const std::uint8_t* active = nullptr) {
        const int me = coll.rank();
        const auto nl = std::uint32_t(asg.leaf_keys.size() - 1);
        const std::uint32_t f0 = asg.first_leaf[me], f1 = asg.first_leaf[me + 1];
        auto own = owned_leaf_ranges(ps, n, asg, box, curve, f0, f1);
        auto summaries = reduce_summaries(ps, asg, own, f0, f1, coll);
        periodicity_.prepare(box);
        tree_.build_top(asg.leaf_keys, summaries, theta_, periodicity_.image());
        auto need = leaves_needed_here(summaries, asg, me, nl);
        auto received = exchange_sources(ps, asg, summaries, need, own, coll);
        const std::size_t self_offset =
            assemble_sources(ps, asg, need, own, received, box, curve, me);
        tree_.add_subtrees(src_, src_begin_, src_end_, bucket_);
        walk(ps, n, self_offset, active);
    }

  private:
    struct Range {
        std::uint32_t begin = 0, end = 0;
    };

    // Owned particles of each of this rank's leaves [f0, f1) (indexed by g - f0).
    std::vector<Range> owned_leaf_ranges(const ParticleSet<T>& ps, std::size_t n,
                                         const Assignment& asg, const Box<T>& box, CurveKind curve,
                                         std::uint32_t f0, std::uint32_t f1) {
        keys_.resize(n);
        compute_sfc_keys(ps.data(Field::x), ps.data(Field::y), ps.data(Field::z), n, box, curve,
                         keys_.data());
        std::vector<Range> own(f1 - f0);
        for (std::uint32_t g = f0; g < f1; ++g) {
            auto b = std::lower_bound(keys_.begin(), keys_.end(), asg.leaf_keys[g]);
            auto e = std::lower_bound(b, keys_.end(), asg.leaf_keys[g + 1]);
            own[g - f0] = {std::uint32_t(b - keys_.begin()), std::uint32_t(e - keys_.begin())};
        }
        const bool tiles = own.empty() ? n == 0 : own.front().begin == 0 && own.back().end == n;
        if (!tiles) throw Error("gravity: owned particles are not the ones of the domain's leaves");
        return own;
    }

    std::vector<LeafSummary<T>> reduce_summaries(const ParticleSet<T>& ps, const Assignment& asg,
                                                 const std::vector<Range>& own, std::uint32_t f0,
                                                 std::uint32_t f1, Collectives& coll) {
        const std::size_t nl = asg.leaf_keys.size() - 1;
        std::vector<SumMax> buf(nl * kLeafSummarySums);
        for (std::uint32_t g = f0; g < f1; ++g) {
            const Range r = own[g - f0];
            if (r.end == r.begin) continue;
            pack_leaf_summary(summarise_particles(ps.data(Field::x), ps.data(Field::y),
                                                  ps.data(Field::z), ps.data(Field::m),
                                                  ps.data(Field::h), r.begin, r.end),
                              &buf[g * kLeafSummarySums]);
        }
        coll.allreduce_sum_max(buf);
        std::vector<LeafSummary<T>> out(nl);
        for (std::size_t g = 0; g < nl; ++g)
            out[g] = unpack_leaf_summary<T>(&buf[g * kLeafSummarySums]);
        return out;
    }

    // Remote leaves that walks of this rank's particles may open.
    std::vector<char> leaves_needed_here(const std::vector<LeafSummary<T>>& sm,
                                         const Assignment& asg, int me, std::uint32_t nl) const {
        std::vector<char> need(nl, 0);
        const std::uint32_t f0 = asg.first_leaf[me], f1 = asg.first_leaf[me + 1];
        for (std::uint32_t p = f0; p < f1; ++p) {
            if (!(sm[p].mp.mass > 0)) continue;
            auto mark = [&](std::uint32_t g) { need[g] = 1; };
            tree_.open_top_leaves(sm[p].lo, sm[p].hi, sm[p].hmax, 0, f0, mark);
            tree_.open_top_leaves(sm[p].lo, sm[p].hi, sm[p].hmax, f1, nl, mark);
        }
        return need;
    }

    // Sends the particles of this rank's leaves that other ranks' walks may open (decided here by
    // the same rule the receivers apply) and receives the ones marked in `need`.
    std::vector<std::vector<double>>
    exchange_sources(const ParticleSet<T>& ps, const Assignment& asg,
                     const std::vector<LeafSummary<T>>& sm, const std::vector<char>& need,
                     const std::vector<Range>& own, Collectives& coll) {
        const int me = coll.rank(), np = coll.size();
        const std::uint32_t f0 = asg.first_leaf[me], f1 = asg.first_leaf[me + 1];
        std::vector<std::vector<double>> recv(np), send(np);
        std::vector<MPI_Request> reqs;
        remote_ = 0;
        for (int s = 0; s < np; ++s) {
            if (s == me) continue;
            std::uint64_t count = 0;
            for (std::uint32_t g = asg.first_leaf[s]; g < asg.first_leaf[s + 1]; ++g)
                if (need[g]) count += asg.leaf_count[g];
            if (count == 0) continue;
            remote_ += count;
            recv[s].resize(count * 5);
            reqs.emplace_back();
            MPI_Irecv(recv[s].data(), int(recv[s].size()), MPI_DOUBLE, s,
                      mpi_tag(MessageTag::gravity), coll.comm(), &reqs.back());
            coll.record().received(s, Traffic::gravity, recv[s].size() * sizeof(double));
        }
        std::vector<char> send_leaf(f1 - f0);
        const T* f[5] = {ps.data(Field::x), ps.data(Field::y), ps.data(Field::z), ps.data(Field::m),
                         ps.data(Field::h)};
        for (int r = 0; r < np; ++r) {
            if (r == me) continue;
            std::fill(send_leaf.begin(), send_leaf.end(), 0);
            for (std::uint32_t p = asg.first_leaf[r]; p < asg.first_leaf[r + 1]; ++p)
                if (sm[p].mp.mass > 0)
                    tree_.open_top_leaves(sm[p].lo, sm[p].hi, sm[p].hmax, f0, f1,
                                          [&](std::uint32_t g) { send_leaf[g - f0] = 1; });
            for (std::uint32_t g = f0; g < f1; ++g) {
                if (!send_leaf[g - f0]) continue;
                for (std::uint32_t i = own[g - f0].begin; i < own[g - f0].end; ++i)
                    for (int k = 0; k < 5; ++k) send[r].push_back(double(f[k][i]));
            }
            if (send[r].empty()) continue;
            reqs.emplace_back();
            MPI_Isend(send[r].data(), int(send[r].size()), MPI_DOUBLE, r,
                      mpi_tag(MessageTag::gravity), coll.comm(), &reqs.back());
            coll.record().sent(r, Traffic::gravity, send[r].size() * sizeof(double));
        }
        wait_all(reqs, coll.record());
        return recv;
    }

    // Sources in global leaf order: owned leaves from the particle set, needed remote leaves from
    // the received buffers. Returns the source index of owned particle 0.
    std::size_t assemble_sources(const ParticleSet<T>& ps, const Assignment& asg,
                                 const std::vector<char>& need, const std::vector<Range>& own,
                                 const std::vector<std::vector<double>>& received,
                                 const Box<T>& box, CurveKind curve, int me) {
        const auto nl = std::uint32_t(asg.leaf_keys.size() - 1);
        const int np = int(asg.first_leaf.size()) - 1;
        src_begin_.assign(nl, 0);
        src_end_.assign(nl, 0);
        std::vector<std::size_t> cursor(np, 0);
        std::size_t total = 0;
        for (std::uint32_t g = 0; g < nl; ++g)
            if (asg.owner[g] == me || need[g]) total += asg.leaf_count[g];
        src_.resize(total);
        T* dst[5] = {src_.x.data(), src_.y.data(), src_.z.data(), src_.m.data(), src_.h.data()};
        const T* f[5] = {ps.data(Field::x), ps.data(Field::y), ps.data(Field::z), ps.data(Field::m),
                         ps.data(Field::h)};
        std::size_t pos = 0, self_offset = 0;
        for (std::uint32_t g = 0; g < nl; ++g) {
            const int o = asg.owner[g];
            src_begin_[g] = std::uint32_t(pos);
            if (o == me) {
                if (g == asg.first_leaf[me]) self_offset = pos;
                for (std::uint32_t i = own[g - asg.first_leaf[me]].begin;
                     i < own[g - asg.first_leaf[me]].end; ++i, ++pos) {
                    for (int k = 0; k < 5; ++k) dst[k][pos] = f[k][i];
                    src_.keys[pos] = keys_[i]; // computed by owned_leaf_ranges
                }
            } else if (need[g]) {
                const double* b = received[o].data();
                for (std::uint64_t c = 0; c < asg.leaf_count[g]; ++c, ++pos, cursor[o] += 5) {
                    for (int k = 0; k < 5; ++k) dst[k][pos] = T(b[cursor[o] + k]);
                    src_.keys[pos] = sfc_key(dst[0][pos], dst[1][pos], dst[2][pos], box, curve);
                }
            }
            src_end_[g] = std::uint32_t(pos);
        }
        return self_offset;
    }

    // One tree walk per group (leaf of the gravity tree) of owned particles, then every particle
    // of the group evaluates the group's list.
    void walk(ParticleSet<T>& ps, std::size_t n, std::size_t self_offset,
              const std::uint8_t* active) {
        const auto tv = tree_.view(src_);
        const auto soft = soft_.view();
        T *ax = ps.data(Field::ax), *ay = ps.data(Field::ay), *az = ps.data(Field::az);
        ps.enable(Field::phi);
        T* phi = ps.data(Field::phi);
        const T *x = ps.data(Field::x), *y = ps.data(Field::y), *z = ps.data(Field::z),
                *h = ps.data(Field::h);
        const auto& nodes = tree_.nodes();
        groups_.clear();
        for (std::uint32_t g : tree_.groups()) // the owned groups (with an active particle)
            if (nodes[g].begin >= self_offset && nodes[g].end <= self_offset + n &&
                (!active || std::count(active + (nodes[g].begin - self_offset),
                                       active + (nodes[g].end - self_offset),
                                       0) < nodes[g].end - nodes[g].begin))
                groups_.push_back(g);
        const double G = G_;
        const GravityImage img = periodicity_.image();
        const bool periodic = periodicity_.periodic();
        const EwaldTable::View ewald = periodic ? periodicity_.ewald() : EwaldTable::View{};
        // The particle's own images and the background (phi_c(0), physics.md §8).
        const double self_phi = periodic ? ewald.phi_at_origin() : 0.0;
        const T* mass = ps.data(Field::m);
        int missing = 0;
        double multipoles = 0, pairs = 0;
        const auto ng = std::int64_t(groups_.size());
#pragma omp parallel reduction(max : missing) reduction(+ : multipoles, pairs)
        {
            GravityInteractionList list;
#pragma omp for schedule(dynamic, 2)
            for (std::int64_t k = 0; k < ng; ++k) {
                const GravityNode<T>& grp = nodes[groups_[k]];
                periodic ? collect_interactions<true>(tv, grp, img, list)
                         : collect_interactions<false>(tv, grp, img, list);
                if (list.missing) missing = 1;
                std::uint32_t npairs = 0;
                for (std::size_t r = 0; r < list.ranges.size(); r += 2)
                    npairs += list.ranges[r + 1] - list.ranges[r];
                for (std::uint32_t j = grp.begin; j < grp.end; ++j) {
                    const std::size_t i = j - self_offset;
                    if (active && !active[i]) continue;
                    const double xi = double(x[i]), yi = double(y[i]), zi = double(z[i]),
                                 hi = double(h[i]);
                    const GravityField f =
                        periodic ? evaluate_interactions<true>(list, tv, soft, xi, yi, zi, hi, j,
                                                               img, ewald)
                                 : evaluate_interactions<false>(list, tv, soft, xi, yi, zi, hi, j,
                                                                img, ewald);
                    ax[i] += T(G * f.ax);
                    ay[i] += T(G * f.ay);
                    az[i] += T(G * f.az);
                    phi[i] = T(G * (f.phi + self_phi * double(mass[i])));
                }
                multipoles += double(list.nodes.size()) * (grp.end - grp.begin);
                pairs += double(npairs) * (grp.end - grp.begin);
            }
        }
        multipoles_per_particle_ = n > 0 ? multipoles / double(n) : 0.0;
        pairs_per_particle_ = n > 0 ? pairs / double(n) : 0.0;
        if (missing)
            throw Error("gravity: a tree walk needed a remote leaf that was not exchanged");
    }

    SofteningTable<T> soft_;
    double G_, theta_;
    GravityPeriodicity periodicity_;
    std::uint32_t bucket_;
    GravityTree<T> tree_;
    GravitySources<T> src_;
    std::vector<std::uint32_t> src_begin_, src_end_;
    std::vector<std::uint64_t> keys_;
    std::vector<std::uint32_t> groups_; // gravity-tree leaves of owned particles
    std::size_t remote_ = 0;
    double multipoles_per_particle_ = 0, pairs_per_particle_ = 0;
};

} // namespace exasph
