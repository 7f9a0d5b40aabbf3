#pragma once
#include <algorithm>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "exasph/util/mpi.hpp"

#include "exasph/domain/box_extent.hpp"
#include "exasph/domain/collectives.hpp"
#include "exasph/domain/cost_balance.hpp"
#include "exasph/domain/global_tree.hpp"
#include "exasph/domain/halo_discovery.hpp"
#include "exasph/domain/halo_exchange.hpp"
#include "exasph/domain/leaf_counts.hpp"
#include "exasph/domain/particle_exchange.hpp"
#include "exasph/domain/sfc_order.hpp"
#include "exasph/particles/particle_set.hpp"
#include "exasph/sfc/keys.hpp"
#include "exasph/tree/octree.hpp"

namespace exasph {

// Distributed domain (physics.md §11): the global top tree, the SFC-range assignment, migration,
// halo discovery and halo exchange; it moves the fields it is asked to (by role), never naming
// one. Requires: every rank calls init() (or restore()) once, then its collectives
// (count_particles) in the same order as the others; owned positions inside the box on its
// periodic axes; h > 0.
// The update sequence of a step (Simulation::sync_or_refresh):
//   1. count_particles(): SFC keys, the global leaves' counts and maximum h (one collective,
//      which may carry the run-control flags); nothing moves, so the caller may keep the state
//      or stop here (a vote) without calling distribute();
//   2. distribute(): the assignment of leaf ranges to ranks (by count or cost), migration, the
//      SFC sort of the owned particles (with every carried field), the local tree and its
//      bounds, halo discovery (with the skin when use_skin) and the exchange of the kHaloSync
//      fields; the global tree refined for the next step;
//   or, between syncs, refresh(): the trees' bounds of the moved particles and the kHaloSync
//      fields along the last sync's halo lists (no collective).
// sync() is 1 then 2. Guarantees after 2: owned particles [0, n_owned()) in SFC order (ties by
// id), halos [n_owned(), n_owned() + n_halo()) grouped by source rank, local_tree() over the
// owned, halo_tree() over the halos, every neighbour within 2 h (with the skin: plus the skin)
// of an owned particle among them; after refresh(), the same lists with current bounds.
template <class T>
class Domain {
  public:
    Domain(MPI_Comm comm, std::uint32_t global_bucket, std::uint32_t leaf_size, CurveKind curve)
        : coll_(comm), global_bucket_(global_bucket), leaf_size_(leaf_size), curve_(curve) {}

    // Start-up only (collectives here are not on the hot path): fits the open axes of the box to
    // all particles and refines the global tree until no leaf exceeds the global bucket size.
    void init(ParticleSet<T>& ps, Box<T>& box) {
        n_owned_ = ps.size();
        refit_box_to_particles(ps, n_owned_, box, coll_);
        for (int iter = 0; iter < 64; ++iter) {
            auto keys = compute_keys(ps, box);
            auto leaf = leaves_of(keys);
            auto counts =
                reduce_leaf_counts(ps.data(Field::h), leaf, tree_.num_leaves(), coll_).count;
            if (!tree_.refine(counts, bucket_for(counts))) {
                assign_leaves(counts, coll_.size()); // more ranks than leaves fail here, early
                return;
            }
        }
        throw Error("domain: the global tree did not converge");
    }

    // Restart: continues with the global tree of the run that wrote the checkpoint, so that the
    // decomposition (and with it the summation order) is the one the uninterrupted run had.
    void restore(ParticleSet<T>& ps, std::vector<std::uint64_t> leaf_keys) {
        n_owned_ = ps.size();
        tree_.set_keys(std::move(leaf_keys));
    }

    // Steps 1 and 2 of the update sequence.
    void sync(ParticleSet<T>& ps, const Box<T>& box) {
        count_particles(ps, box);
        distribute(ps, box);
    }

    // Step 1 (halos are dropped). With `flags` the collective carries them (every rank's raised
    // flags are seen by all after it), so a rank's vote needs no collective of its own; with
    // `cost` (one per owned particle, --balance cost) it sums the cost per leaf and distribute()
    // cuts the curve by cost (domain/cost_balance.hpp).
    void count_particles(ParticleSet<T>& ps, const Box<T>& box, ControlFlags* flags = nullptr,
                         const float* cost = nullptr) {
        ps.resize(n_owned_); // drop last step's halos
        coll_.record().start_step();
        keys_ = compute_keys(ps, box);
        leaf_ = leaves_of(keys_);
        counts_ =
            reduce_leaf_counts(ps.data(Field::h), leaf_, tree_.num_leaves(), coll_, flags, cost);
    }

    // Step 2.
    void distribute(ParticleSet<T>& ps, const Box<T>& box) {
        const auto& counts = counts_.count;
        asg_ = counts_.cost.empty() ? assign_leaves(counts, coll_.size())
                                    : assign_leaves_by_cost(counts, counts_.cost, coll_.size());
        asg_.leaf_keys = tree_.keys();
        asg_.leaf_count = counts;
        std::vector<int> dest(ps.size());
#pragma omp parallel for schedule(static)
        for (std::size_t i = 0; i < ps.size(); ++i) dest[i] = asg_.owner[leaf_[i]];
        const bool moved =
            migrate_particles(ps, dest, coll_.rank(), coll_.size(), asg_.count[coll_.rank()],
                              coll_.comm(), MessageTag::migrate, coll_.record());
        n_owned_ = ps.size();
        std::vector<int>().swap(dest); // the sort below is the step's memory peak
        std::vector<std::uint32_t>().swap(leaf_);
        // The keys computed above still belong to the particles when none left or arrived.
        SortScratch* kept = ps.carried() & kDerived ? &sort_scratch_ : nullptr; // block steps
        auto keys =
            moved ? sort_along_curve(ps, box, curve_) : sort_by_keys(ps, std::move(keys_), kept);
        std::vector<std::uint64_t>().swap(keys_);
        local_tree_.build(keys.data(), std::uint32_t(n_owned_), leaf_size_);
        local_tree_.update_bounds(ps.data(Field::x), ps.data(Field::y), ps.data(Field::z),
                                  ps.data(Field::h));
        std::vector<std::uint64_t>().swap(keys);
        discover_halos(ps, box);
        tree_.refine(counts, bucket_for(counts)); // for the next step; counts belong to this tree
    }

    // The sequence's refresh (--sync-every): the trees keep their structure (the searches stay
    // exact, their boxes only loosen).
    void refresh(ParticleSet<T>& ps) {
        coll_.record().start_step();
        local_tree_.update_bounds(ps.data(Field::x), ps.data(Field::y), ps.data(Field::z),
                                  ps.data(Field::h));
        if (plan_.partners.empty()) return;
        exchange_halos(ps, kHaloSync);
        halo_tree_.update_bounds(ps.data(Field::x), ps.data(Field::y), ps.data(Field::z),
                                 ps.data(Field::h));
    }
    // With a skin, halo discovery reaches kHaloSkinOverH x the smallest h further (the smallest
    // of the global leaves' maximum h): the halos stay sufficient while no particle has moved,
    // or grown its h, by more than skin() / 2 since the sync (sim/sync_schedule.hpp).
    static constexpr double kHaloSkinOverH = 0.5;
    void use_skin(bool on) {
        skin_on_ = on;
    }
    T skin() const {
        return skin_;
    }

    // Sends the fields carrying `roles` from owners to the halo copies.
    void exchange_halos(ParticleSet<T>& ps, std::uint8_t roles) {
        PostedHalos x = post_halos(ps, roles);
        finish_halos(ps, x);
    }
    // The same in two halves, for work in between (issue 23's overlap): post_halos() packs and
    // posts, finish_halos() waits and unpacks. The halos' fields are valid only after finishing.
    PostedHalos post_halos(const ParticleSet<T>& ps, std::uint8_t roles) {
        const double t0 = wall_seconds();
        PostedHalos x;
        if (!spare_.empty()) x = std::move(spare_.back()), spare_.pop_back();
        post_halo_fields(ps, plan_, FieldSelection{ps.fields(roles), false}, coll_.comm(),
                         MessageTag::halo, coll_.record(), x);
        coll_.record().halo_time(x.posted_at - t0, 0.0);
        return x;
    }
    void progress_halos(PostedHalos& x) {
        const double t0 = wall_seconds();
        progress_halo_fields(x);
        coll_.record().halo_time(wall_seconds() - t0, 0.0);
    }
    void finish_halos(ParticleSet<T>& ps, PostedHalos& x) {
        const double t0 = wall_seconds();
        finish_halo_fields(ps, n_owned_, plan_, x, coll_.record());
        coll_.record().halo_time(wall_seconds() - t0, t0 - x.posted_at);
        spare_.push_back(std::move(x)); // its buffers serve the next exchange
    }
    // Per owned particle: whether some rank receives it as a halo (from the last sync).
    const std::uint8_t* sent_flags() const {
        return sent_.data();
    }

    // Block time steps: each halo's value of v (owned, then halos) goes back to its owner, which
    // keeps the largest (return_halo_max).
    void return_halo_max(FieldArray<int>& v) {
        exasph::return_halo_max(v, n_owned_, plan_, coll_.comm(), MessageTag::halo_return,
                                coll_.record());
    }

    std::size_t n_owned() const {
        return n_owned_;
    }
    std::size_t n_halo() const {
        return plan_.n_halo;
    }
    const Octree<T>& local_tree() const {
        return local_tree_;
    }
    const Octree<T>& halo_tree() const {
        return halo_tree_;
    }
    const Assignment& assignment() const {
        return asg_;
    }
    // --balance cost: the last sync's summed cost per leaf of assignment() (else empty).
    const std::vector<double>& leaf_costs() const {
        return counts_.cost;
    }
    const GlobalTree& global_tree() const {
        return tree_;
    }
    Collectives& collectives() {
        return coll_;
    }
    const CommRecord& comm_record() const {
        return coll_.record();
    }
    MPI_Comm comm() const {
        return coll_.comm();
    }
    int rank() const {
        return coll_.rank();
    }
    int nranks() const {
        return coll_.size();
    }
    CurveKind curve() const {
        return curve_;
    }

  private:
    SortScratch sort_scratch_; // kept between syncs only with block time steps

    std::uint64_t bucket_for(const std::vector<std::uint64_t>& counts) const {
        std::uint64_t total = 0;
        for (std::uint64_t c : counts) total += c;
        return effective_global_bucket(global_bucket_, total);
    }

    std::vector<std::uint64_t> compute_keys(const ParticleSet<T>& ps, const Box<T>& box) const {
        std::vector<std::uint64_t> keys(n_owned_);
        compute_sfc_keys(ps.data(Field::x), ps.data(Field::y), ps.data(Field::z), n_owned_, box,
                         curve_, keys.data());
        return keys;
    }

    std::vector<std::uint32_t> leaves_of(const std::vector<std::uint64_t>& keys) const {
        std::vector<std::uint32_t> leaf(keys.size());
#pragma omp parallel
        {
            std::uint32_t hint = 0;
#pragma omp for schedule(static)
            for (std::size_t i = 0; i < keys.size(); ++i)
                hint = leaf[i] = tree_.leaf_of(keys[i], hint);
        }
        return leaf;
    }

    void discover_halos(ParticleSet<T>& ps, const Box<T>& box) {
        plan_ = HaloPlan{};
        halo_tree_.build(nullptr, 0, leaf_size_);
        skin_ = skin_on_ ? T(kHaloSkinOverH) * counts_.smallest_hmax() : T(0); // one rank too
        if (coll_.size() == 1) return;
        index_.build(tree_, counts_.hmax, asg_, box, curve_, skin_);
        plan_.partners = halo_partners(index_, asg_, coll_.rank(), box);
        plan_halo_sends(plan_, index_, local_tree_, ps.data(Field::x), ps.data(Field::y),
                        ps.data(Field::z), ps.data(Field::h), coll_.rank(), box);
        exchange_halo_counts(plan_, coll_.comm(), MessageTag::halo_count, coll_.record());
        sent_.assign(n_owned_, 0);
        for (const auto& list : plan_.send)
            for (std::uint32_t i : list) sent_[i] = 1;
        ps.resize(n_owned_ + plan_.n_halo);
        exchange_halo_fields(ps, n_owned_, plan_, FieldSelection{ps.fields(kHaloSync), true},
                             coll_.comm(), MessageTag::halo, coll_.record());
        // Sources own ascending key ranges and send in SFC order: the halos arrive sorted.
        std::vector<std::uint64_t> hkeys(plan_.n_halo);
        compute_sfc_keys(ps.data(Field::x) + n_owned_, ps.data(Field::y) + n_owned_,
                         ps.data(Field::z) + n_owned_, plan_.n_halo, box, curve_, hkeys.data());
        if (!std::is_sorted(hkeys.begin(), hkeys.end()))
            throw Error("domain: halos did not arrive in SFC order");
        halo_tree_.build(hkeys.data(), std::uint32_t(plan_.n_halo), leaf_size_,
                         std::uint32_t(n_owned_));
        halo_tree_.update_bounds(ps.data(Field::x), ps.data(Field::y), ps.data(Field::z),
                                 ps.data(Field::h));
    }

    Collectives coll_;
    std::uint32_t global_bucket_, leaf_size_;
    CurveKind curve_;
    GlobalTree tree_;
    Assignment asg_;
    LeafIndex<T> index_;
    bool skin_on_ = false;
    T skin_ = 0;
    HaloPlan plan_;
    std::vector<PostedHalos> spare_; // buffers of finished halo exchanges
    std::vector<std::uint8_t> sent_; // per owned particle: in some partner's send list
    Octree<T> local_tree_, halo_tree_;
    std::size_t n_owned_ = 0;
    // Between count_particles() and distribute(): keys, global leaf and leaf counts.
    std::vector<std::uint64_t> keys_;
    std::vector<std::uint32_t> leaf_;
    LeafCounts<T> counts_;
};

} // namespace exasph
