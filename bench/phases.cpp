// Per-phase micro-benchmarks on a periodic, perturbed lattice of side^3 particles (ideal gas,
// random velocities): SFC sort, tree build, neighbour search, density, IAD, momentum-energy,
// and the domain's sync and halo exchange (meaningful under mpirun -np 2 or more).
//   build/bench/bench_phases [--benchmark_filter=...]
// items/s = particles per second for the phase.
#include <map>
#include <memory>
#include <random>

#include <benchmark/benchmark.h>
#include <mpi.h>

#include "exasph/domain/domain.hpp"
#include "exasph/domain/sfc_order.hpp"
#include "exasph/kernel/sinc_kernel.hpp"
#include "exasph/sph/passes.hpp"

using namespace exasph;

namespace {

struct Setup {
    ParticleSet<double> ps;
    Box<double> box;
    std::vector<std::uint64_t> keys;
    Octree<double> tree;
    NeighbourLists<double> nl;
    KernelTable<double> kernel{sinc_kernel(6)};

    explicit Setup(int side) {
        const std::uint64_t n1 = side, n = n1 * n1 * n1;
        box.lo = {0, 0, 0};
        box.hi = {1, 1, 1};
        box.periodic = {true, true, true};
        ps.resize(n);
        std::mt19937_64 rng(5);
        std::uniform_real_distribution<double> jitter(-0.2, 0.2), vel(-1, 1);
        const double dx = 1.0 / side;
        for (std::uint64_t i = 0; i < n; ++i) {
            ps.id[i] = i;
            double c[3] = {double(i / (n1 * n1)), double((i / n1) % n1), double(i % n1)};
            for (int d = 0; d < 3; ++d) {
                double x = (c[d] + 0.5 + jitter(rng)) * dx;
                ps[static_cast<Field>(int(Field::x) + d)][i] = x - std::floor(x);
                ps[static_cast<Field>(int(Field::vx) + d)][i] = vel(rng);
            }
            ps[Field::m][i] = 1.0 / double(n);
            ps[Field::h][i] = 0.5 * dx * std::cbrt(3.0 * 100 / (4 * M_PI));
            ps[Field::u][i] = 1.0;
        }
        keys = sort_along_curve(ps, box, CurveKind::hilbert);
        build_tree();
        search();
        compute_density(ps, nl, box, kernel.view(), EosParams{});
        compute_iad(ps, nl, box, kernel.view());
    }
    void build_tree() {
        tree.build(keys.data(), std::uint32_t(ps.size()), 64);
        tree.update_bounds(ps.data(Field::x), ps.data(Field::y), ps.data(Field::z),
                           ps.data(Field::h));
    }
    void search() {
        SearchView<double> sv{ps.data(Field::x), ps.data(Field::y), ps.data(Field::z),
                              ps.data(Field::h)};
        nl.build(tree, sv, box, NeighbourCriterion::symmetric, std::uint32_t(ps.size()));
    }
};

Setup& setup(int side) {
    static std::map<int, std::unique_ptr<Setup>> cache;
    auto& s = cache[side];
    if (!s) s = std::make_unique<Setup>(side);
    return *s;
}

void BM_SfcSort(benchmark::State& st) {
    Setup& s = setup(int(st.range(0)));
    for (auto _ : st) benchmark::DoNotOptimize(sort_along_curve(s.ps, s.box, CurveKind::hilbert));
    st.SetItemsProcessed(st.iterations() * s.ps.size());
}
void BM_TreeBuild(benchmark::State& st) {
    Setup& s = setup(int(st.range(0)));
    for (auto _ : st) s.build_tree();
    st.SetItemsProcessed(st.iterations() * s.ps.size());
}
void BM_NeighbourSearch(benchmark::State& st) {
    Setup& s = setup(int(st.range(0)));
    for (auto _ : st) s.search();
    st.SetItemsProcessed(st.iterations() * s.ps.size());
}
void BM_Density(benchmark::State& st) {
    Setup& s = setup(int(st.range(0)));
    for (auto _ : st) compute_density(s.ps, s.nl, s.box, s.kernel.view());
    st.SetItemsProcessed(st.iterations() * s.ps.size());
}
void BM_Iad(benchmark::State& st) {
    Setup& s = setup(int(st.range(0)));
    for (auto _ : st) compute_iad(s.ps, s.nl, s.box, s.kernel.view());
    st.SetItemsProcessed(st.iterations() * s.ps.size());
}
void BM_MomentumEnergy(benchmark::State& st) {
    Setup& s = setup(int(st.range(0)));
    for (auto _ : st) compute_momentum_energy(s.ps, s.nl, s.box, s.kernel.view());
    st.SetItemsProcessed(st.iterations() * s.ps.size());
}

// Domain sync (migration, sort, trees, halo discovery) and one halo exchange, on all ranks of
// MPI_COMM_WORLD; fixed iteration counts keep the ranks in step.
void BM_DomainSyncAndHaloExchange(benchmark::State& st) {
    int rank = 0, nranks = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &nranks);
    Setup& s = setup(int(st.range(0)));
    ParticleSet<double> ps = s.ps;
    std::vector<std::uint32_t> mine;
    for (std::uint32_t i = 0; i < ps.size(); ++i)
        if (int(i % nranks) == rank) mine.push_back(i);
    ps.permute(mine);
    Box<double> box = s.box;
    Domain<double> domain(MPI_COMM_WORLD, 128, 64, CurveKind::hilbert);
    domain.init(ps, box);
    for (auto _ : st) {
        domain.sync(ps, box);
        domain.exchange_halos(ps, kHaloDensity);
    }
    st.SetItemsProcessed(st.iterations() * s.ps.size());
    st.counters["halo_ratio"] = double(domain.n_halo()) / double(domain.n_owned());
}

class Silent : public benchmark::BenchmarkReporter {
  public:
    bool ReportContext(const Context&) override { return true; }
    void ReportRuns(const std::vector<Run>&) override {}
};

} // namespace

BENCHMARK(BM_SfcSort)->Arg(30)->Arg(50)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TreeBuild)->Arg(30)->Arg(50)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_NeighbourSearch)->Arg(30)->Arg(50)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Density)->Arg(30)->Arg(50)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Iad)->Arg(30)->Arg(50)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MomentumEnergy)->Arg(30)->Arg(50)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DomainSyncAndHaloExchange)
    ->Arg(30)
    ->Arg(50)
    ->Iterations(10)
    ->Unit(benchmark::kMillisecond);

int main(int argc, char** argv) {
    int provided = 0;
    MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
    benchmark::Initialize(&argc, argv);
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    if (rank == 0)
        benchmark::RunSpecifiedBenchmarks();
    else {
        Silent silent; // other ranks take part (halo exchange) but do not print
        benchmark::RunSpecifiedBenchmarks(&silent);
    }
    benchmark::Shutdown();
    MPI_Finalize();
    return 0;
}
