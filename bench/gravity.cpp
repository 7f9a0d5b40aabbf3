// Tree gravity (issue 6): time of one gravity pass (top tree, subtrees, walk) on the Evrard
// sphere (rho ~ 1/r) made from a lattice, one rank.
//   build/bench/bench_gravity [--benchmark_filter=...]
// Arguments: lattice side (particles ~ 0.52 side^3), gravity leaf size, theta x 100.
// items/s = particles per second.
#include <benchmark/benchmark.h>
#include <mpi.h>

#include "exasph/cases/evrard.hpp"
#include "exasph/domain/domain.hpp"
#include "exasph/gravity/gravity_solver.hpp"
#include "exasph/sph/sinc_kernel.hpp"

using namespace exasph;

namespace {

void bm_gravity(benchmark::State& state) {
    EvrardParams ep;
    ep.side = int(state.range(0));
    auto ic = make_evrard<double>(ep, UnitCubePoints::lattice(std::uint64_t(ep.side)), 0, 1,
                                  MPI_COMM_SELF);
    auto& ps = ic.particles;
    Domain<double> dom(MPI_COMM_SELF, 128, 64, CurveKind::hilbert);
    dom.init(ps, ic.box);
    dom.sync(ps, ic.box);
    KernelTable<double> kernel(sinc_kernel(6));
    GravitySolver<double> solver(kernel, 1.0, double(state.range(2)) / 100.0,
                                 std::uint32_t(state.range(1)));
    for (auto _ : state)
        solver.compute(ps, dom.n_owned(), dom.assignment(), ic.box, dom.curve(), dom.collectives());
    state.SetItemsProcessed(state.iterations() * std::int64_t(dom.n_owned()));
    state.counters["particles"] = double(dom.n_owned());
    state.counters["multipoles"] = solver.multipoles_per_particle();
    state.counters["pairs"] = solver.pairs_per_particle();
}

} // namespace

BENCHMARK(bm_gravity)
    ->ArgsProduct({{27}, {4, 8, 16, 32, 64}, {50}})
    ->ArgsProduct({{27, 58, 124}, {16}, {50}})
    ->ArgsProduct({{58}, {16}, {30, 40, 60, 70}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

int main(int argc, char** argv) {
    MPI_Init(&argc, &argv);
    benchmark::Initialize(&argc, argv);
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    MPI_Finalize();
    return 0;
}
