#pragma once
#include "exasph/domain/collectives.hpp"
#include "exasph/gravity/gravity_node.hpp"

namespace exasph {

// A leaf's summary as SumMax elements, so that one collective (sum / max) combines every rank's
// part of every leaf: sums carry mass, com[3], q[6], s[10], d2; maxima hi[3], -lo[3], hmax.
inline constexpr int kLeafSummarySums = 21;

template <class T>
void pack_leaf_summary(const LeafSummary<T>& s, SumMax* b) {
    b[0].sum = s.mp.mass;
    for (int d = 0; d < 3; ++d) {
        b[1 + d].sum = s.mp.com[d];
        b[d].max = s.hi[d];
        b[3 + d].set_min(double(s.lo[d]));
    }
    for (int k = 0; k < 6; ++k) b[4 + k].sum = s.mp.q[k];
    for (int k = 0; k < 10; ++k) b[10 + k].sum = s.mp.s[k];
    b[20].sum = s.mp.d2;
    b[6].max = s.hmax;
}

// The reduced summary (mass 0: a leaf without particles, left empty).
template <class T>
LeafSummary<T> unpack_leaf_summary(const SumMax* b) {
    LeafSummary<T> s;
    if (!(b[0].sum > 0)) return s;
    s.mp.mass = b[0].sum;
    for (int d = 0; d < 3; ++d) {
        s.mp.com[d] = b[1 + d].sum;
        s.hi[d] = T(b[d].max);
        s.lo[d] = T(b[3 + d].min());
    }
    for (int k = 0; k < 6; ++k) s.mp.q[k] = b[4 + k].sum;
    for (int k = 0; k < 10; ++k) s.mp.s[k] = b[10 + k].sum;
    s.mp.d2 = b[20].sum;
    s.hmax = T(b[6].max);
    return s;
}

} // namespace exasph
