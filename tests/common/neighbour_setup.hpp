#pragma once
#include <cstdint>

#include "exasph/domain/sfc_order.hpp"
#include "exasph/particles/particle_set.hpp"
#include "exasph/tree/neighbour_lists.hpp"
#include "exasph/util/box.hpp"

namespace exasph::testref {

// Sorts the particles along the Hilbert curve and builds their neighbour lists with `crit`, as
// one rank's step does before the density (any kind of lists: CPU, or the GPU path's).
template <class Lists = NeighbourLists<double>>
void sort_and_find_neighbours(ParticleSet<double>& ps, const Box<double>& box,
                              NeighbourCriterion crit, Lists& nl) {
    auto keys = sort_along_curve(ps, box, CurveKind::hilbert);
    Octree<double> tree;
    tree.build(keys.data(), std::uint32_t(ps.size()), 64);
    SearchView<double> sv{ps.data(Field::x), ps.data(Field::y), ps.data(Field::z),
                          ps.data(Field::h)};
    tree.update_bounds(sv.x, sv.y, sv.z, sv.h);
    nl.build(tree, sv, box, crit, std::uint32_t(ps.size()));
}

} // namespace exasph::testref
