// Tree gravity (issue 6) on the Evrard sphere (rho ~ 1/r) made from a lattice, one rank.
//   build/bench/bench_gravity [--benchmark_filter=...]
// bm_gravity: time of one gravity pass (top tree, subtrees, walk); arguments: lattice side
// (particles ~ 0.52 side^3), gravity leaf size, theta x 100; items/s = particles per second.
// bm_force_error: RMS and largest relative acceleration error against direct summation
// (counters rms, max) for theta x 100 on the side-28 sphere (11,536 particles; an even side
// keeps a particle off the centre, where the force vanishes and relative errors mean nothing).
#include <benchmark/benchmark.h>
#include <mpi.h>

#include "../tests/common/direct_gravity.hpp"
#include "exasph/cases/evrard.hpp"
#include "exasph/cases/jeans.hpp"
#include "exasph/domain/domain.hpp"
#include "exasph/gravity/gravity_solver.hpp"
#include "exasph/kernel/sinc_kernel.hpp"

using namespace exasph;

namespace {

// Times solver passes over the particles of `ic` on one rank, with the interaction counts.
void time_passes(benchmark::State& state, InitialConditions<double>& ic, double theta,
                 std::uint32_t leaf) {
    auto& ps = ic.particles;
    Domain<double> dom(MPI_COMM_SELF, 128, 64, CurveKind::hilbert);
    dom.init(ps, ic.box);
    dom.sync(ps, ic.box);
    KernelTable<double> kernel(sinc_kernel(6));
    GravitySolver<double> solver(kernel, 1.0, theta, leaf);
    for (auto _ : state)
        solver.compute(ps, dom.n_owned(), dom.assignment(), ic.box, dom.curve(), dom.collectives());
    state.SetItemsProcessed(state.iterations() * std::int64_t(dom.n_owned()));
    state.counters["particles"] = double(dom.n_owned());
    state.counters["multipoles"] = solver.multipoles_per_particle();
    state.counters["pairs"] = solver.pairs_per_particle();
}

// One pass on an Evrard sphere from a lattice of side range(0), leaf size range(1), theta
// range(2) / 100.
void bm_gravity(benchmark::State& state) {
    EvrardParams ep;
    ep.side = int(state.range(0));
    auto ic = make_evrard<double>(
        ep, CaseContext::one_rank(UnitCubePoints::lattice(std::uint64_t(ep.side))));
    time_passes(state, ic, double(state.range(2)) / 100.0, std::uint32_t(state.range(1)));
}

// One pass in a periodic box (minimum image + Ewald correction): the Jeans case's perturbed
// lattice of side range(0), leaf size 16, theta range(1) / 100.
void bm_gravity_periodic(benchmark::State& state) {
    JeansParams jp;
    jp.side = int(state.range(0));
    auto ic = make_jeans<double>(
        jp, CaseContext::one_rank(UnitCubePoints::lattice(std::uint64_t(jp.side))));
    time_passes(state, ic, double(state.range(1)) / 100.0, 16);
}

void bm_force_error(benchmark::State& state) {
    EvrardParams ep;
    ep.side = 28;
    auto ic = make_evrard<double>(ep, CaseContext::one_rank(UnitCubePoints::lattice(28)));
    auto& ps = ic.particles;
    Domain<double> dom(MPI_COMM_SELF, 128, 64, CurveKind::hilbert);
    dom.init(ps, ic.box);
    dom.sync(ps, ic.box);
    KernelTable<double> kernel(sinc_kernel(6));
    GravitySolver<double> solver(kernel, 1.0, double(state.range(0)) / 100.0, 16);
    const auto ref = testref::direct_gravity(ps, dom.n_owned(), solver.softening().view());
    for (auto _ : state) {
        for (Field f : {Field::ax, Field::ay, Field::az})
            std::fill(ps[f].begin(), ps[f].end(), 0.0);
        solver.compute(ps, dom.n_owned(), dom.assignment(), ic.box, dom.curve(), dom.collectives());
    }
    double rms = 0, mx = 0;
    for (std::size_t i = 0; i < dom.n_owned(); ++i) {
        const double e = std::hypot(ps[Field::ax][i] - ref[i].ax, ps[Field::ay][i] - ref[i].ay,
                                    ps[Field::az][i] - ref[i].az) /
                         std::hypot(ref[i].ax, ref[i].ay, ref[i].az);
        rms += e * e;
        mx = std::max(mx, e);
    }
    state.counters["rms"] = std::sqrt(rms / double(dom.n_owned()));
    state.counters["max"] = mx;
    state.counters["multipoles"] = solver.multipoles_per_particle();
    state.counters["pairs"] = solver.pairs_per_particle();
}

} // namespace

BENCHMARK(bm_gravity_periodic)
    ->ArgsProduct({{24, 48}, {50}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

BENCHMARK(bm_force_error)->DenseRange(20, 80, 10)->Unit(benchmark::kMillisecond)->UseRealTime();

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
