#pragma once
#include <algorithm>
#include <cstddef>
#include <limits>
#include <vector>

#include "exasph/domain/collectives.hpp"
#include "exasph/particles/particle_set.hpp"
#include "exasph/util/box.hpp"

namespace exasph {

// Local min/max of the first n positions as six SumMax elements (max of hi, max of -lo): reduced
// with other sums, they give every rank the particles' extent without a collective of its own.
template <class T>
void local_extent(const ParticleSet<T>& ps, std::size_t n, SumMax* out) {
    for (int d = 0; d < 3; ++d) {
        const T* c = ps.data(component(Field::x, d));
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
#pragma omp parallel for schedule(static) reduction(min : lo) reduction(max : hi)
        for (std::size_t i = 0; i < n; ++i) {
            lo = std::min(lo, double(c[i]));
            hi = std::max(hi, double(c[i]));
        }
        out[d] = {0.0, hi};
        out[3 + d].sum = 0.0;
        out[3 + d].set_min(lo);
    }
}

// Fits the open axes of the box to a reduced extent (periodic axes keep their period).
template <class T>
void apply_extent(Box<T>& box, const SumMax* ext) {
    for (int d = 0; d < 3; ++d) {
        if (box.periodic[d]) continue;
        double hi = ext[d].max, lo = ext[3 + d].min();
        double pad = 1e-6 * std::max(hi - lo, 1e-30) + 1e-300;
        box.lo[d] = T(lo - pad);
        box.hi[d] = T(hi + pad);
    }
}

// Fits the open axes of the box to the first n particles of every rank: one collective, none
// when every axis is periodic (start-up, and a sync whose box is older than the positions).
template <class T>
void refit_box_to_particles(const ParticleSet<T>& ps, std::size_t n, Box<T>& box,
                            Collectives& coll) {
    if (box.periodic[0] && box.periodic[1] && box.periodic[2]) return;
    std::vector<SumMax> ext(6);
    local_extent(ps, n, ext.data());
    coll.allreduce_sum_max(ext);
    apply_extent(box, ext.data());
}

// The box with its open axes unbounded: what a state check may assume of positions that moved
// since the box was last fitted (--diagnostics-every, --sync-every).
template <class T>
Box<T> with_open_axes_unbounded(Box<T> box) {
    for (int d = 0; d < 3; ++d)
        if (!box.periodic[d])
            box.lo[d] = std::numeric_limits<T>::lowest(), box.hi[d] = std::numeric_limits<T>::max();
    return box;
}

} // namespace exasph
