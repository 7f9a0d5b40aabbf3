#pragma once
#include <functional>
#include <utility>

#include "exasph/cases/unit_cube_points.hpp"

namespace exasph {

// What a case maker gets from the run that it does not make itself: which share of the particles
// this rank makes, the one start-up collective a case may need (a sum over all ranks), and the
// points that glass cases are made from (a relaxed glass, or a lattice with --lattice). The run
// (sim/setup.hpp) fills it; cases therefore depend on neither the simulation nor MPI.
struct CaseContext {
    int rank = 0;
    int nranks = 1;
    std::function<double(double)> sum_over_ranks = [](double x) { return x; };
    std::function<UnitCubePoints()> points;
    // A thin slab of the same spacing, slab_layers(side) points thick (the 2D-like cases).
    std::function<UnitCubePoints()> slab_points;

    // One rank, from the given points (tests, benchmarks).
    static CaseContext one_rank(UnitCubePoints pts) {
        CaseContext c;
        c.points = [pts] { return pts; };
        c.slab_points = [pts] {
            return UnitCubePoints::lattice(pts.side(), slab_layers(pts.side()));
        };
        return c;
    }
};

} // namespace exasph
