#pragma once
// Particles sorted along the curve with their octree and symmetric neighbour lists, and a walk
// over every decoded list and its prefixes: the fixtures of the SPH pass tests
// (tests/unit/sph/test_density.cpp, test_pair_loops.cpp).
#include <cstddef>
#include <cstdint>

#include <gtest/gtest.h>

#include "exasph/domain/sfc_order.hpp"
#include "exasph/sph/passes.hpp"

namespace exasph::testref {

struct Prepared {
    ParticleSet<double> ps;
    Box<double> box;
    Octree<double> tree;
    NeighbourLists<double> nl;
};

void prepare(Prepared& s) {
    auto keys = sort_along_curve(s.ps, s.box, CurveKind::hilbert);
    s.tree.build(keys.data(), std::uint32_t(s.ps.size()), 64);
    SearchView<double> sv{s.ps.data(Field::x), s.ps.data(Field::y), s.ps.data(Field::z),
                          s.ps.data(Field::h)};
    s.tree.update_bounds(sv.x, sv.y, sv.z, sv.h);
    s.nl.build(s.tree, sv, s.box, NeighbourCriterion::symmetric, std::uint32_t(s.ps.size()));
}

// Decodes every particle's list: on_list(a, list) once per particle, then on_prefix(a, part) for
// the whole list and, for one particle in 50, every prefix of it (every remainder of the vector
// loops). Stops at the first fatal failure; returns the prefixes checked.
template <class OnList, class OnPrefix>
std::size_t for_each_list_prefix(const NeighbourLists<double>& nl, OnList&& on_list,
                                 OnPrefix&& on_prefix) {
    NeighbourLists<double>::Decoder dec(nl);
    std::size_t checked = 0;
    for (std::size_t g = 0; g < nl.num_groups(); ++g) {
        dec.start(g);
        for (std::uint32_t slot = nl.group_begin(g); slot < nl.group_end(g); ++slot) {
            const std::uint32_t a = nl.member(slot);
            const ContiguousSpan nb = dec.next();
            on_list(a, nb);
            const std::uint32_t first = a % 50 == 0 ? 0 : nb.count;
            for (std::uint32_t len = first; len <= nb.count; ++len, ++checked) {
                on_prefix(a, ContiguousSpan{nb.index, len, nb.wraps});
                if (::testing::Test::HasFatalFailure()) return checked;
            }
        }
    }
    return checked;
}

} // namespace exasph::testref
