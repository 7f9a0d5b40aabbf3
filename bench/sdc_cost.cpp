// The cost of the silent-data-corruption defences (issue 21, acceptance 3) measured in one
// process: two copies of the same Sedov run with the default settings, one with --on-sdc off
// and one with rollback (state guard, seals inside the step, invariants, watchdog, a rollback
// point on disk every 10 steps), stepped in turn (A B A B ...) so that the host's drift hits
// both alike; prints each round's seconds per step and ratio, their medians, and the time of
// the checks alone (one step's seals, state check and seal on the particles of the run).
//   build/bench/sdc_cost [SIDE=100] [ROUNDS=7] [THREADS=2] [ROLLBACK_FIRST=0]  (SIDE 100: 10^6)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "exasph/util/mpi.hpp"

#include "exasph/cases/registry.hpp"
#include "exasph/config/scheme.hpp"
#include "exasph/run/setup.hpp"
#include "exasph/sim/simulation.hpp"
#include "exasph/sim/state_guard.hpp"
#include "exasph/sim/step_seals.hpp"

using namespace exasph;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

template <class F>
double timed(F&& f) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    return seconds_since(t0);
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// What the defences do to the particles in one step: the seals of sim/step_seals.hpp at every
// phase end and before the update and the h update, the state check and the seal.
double checks_of_one_step(const ParticleSet<double>& ps, std::size_t n, const Box<double>& box) {
    StepSeals<double> seals;
    StateGuard<double> guard;
    guard.seal(ps, n);
    return timed([&] {
        (void)guard.check(ps, n, box, 1e-4, false, true);
        seals.begin(5);
        for (std::size_t p = 0; p < kNumPhases; ++p) {
            if (p == kUpdate) (void)seals.before_update(ps, n);
            if (p == kSmoothingLength) (void)seals.before_h_update(ps, n);
            (void)seals.phase_ended(p, ps, n);
        }
        (void)seals.at_guard_seal(guard.seal(ps, n));
    });
}

// Each check's share: seconds per step of one hash pass over each set of fields times the
// passes a step makes of it (sim/step_seals.hpp; the state guard's check and seal are two more
// passes over the state).
void print_breakdown(const ParticleSet<double>& ps, std::size_t n) {
    struct Set {
        const char* name;
        std::vector<Field> fields;
        int passes;
    };
    using Seals = StepSeals<double>;
    const Set sets[] = {{"state: guard check and seal", ps.fields(kState), 2},
                        {"state: seals sync, update, h update", ps.fields(kState), 5},
                        {"density pass's fields", Seals::density_fields(ps), 2},
                        {"IAD matrices and strain", Seals::iad_fields(ps), 2},
                        {"accelerations", Seals::acceleration_fields(ps), 2}};
    std::printf("| check | fields | passes per step | s/step |\n|---|---|---|---|\n");
    for (const auto& set : sets) {
        std::vector<double> t;
        for (int k = 0; k < 5; ++k)
            t.push_back(timed([&] { (void)field_hash_sum(ps, set.fields, n); }));
        std::printf("| %s | %zu | %d | %.4f |\n", set.name, set.fields.size(), set.passes,
                    set.passes * median(t));
    }
}

} // namespace

int main(int argc, char** argv) {
    MPI_Init(&argc, &argv);
    Config cfg;
    cfg.init = "sedov";
    cfg.side = argc > 1 ? std::atoi(argv[1]) : 100;
    const int rounds = argc > 2 ? std::atoi(argv[2]) : 7;
    cfg.threads = argc > 3 ? std::atoi(argv[3]) : 2;
    cfg.out_dir = "/tmp";
    apply_scheme(cfg, default_scheme(cfg.init), [](const Param&) { return false; });
#ifdef _OPENMP
    omp_set_num_threads(cfg.threads);
#endif
    Config off = cfg;
    off.on_sdc = SdcPolicy::off;
    // The second run made is faster by a few per cent whichever it is (memory placement): the
    // fourth argument makes the rollback run first, and the true ratio lies between the two.
    const bool rollback_first = argc > 4 && std::atoi(argv[4]) == 1;
    std::optional<Simulation<double>> first, second;
    first.emplace(rollback_first ? cfg : off, make_case(cfg, MPI_COMM_WORLD));
    second.emplace(rollback_first ? off : cfg, make_case(cfg, MPI_COMM_WORLD));
    Simulation<double>& a = rollback_first ? *second : *first;
    Simulation<double>& b = rollback_first ? *first : *second;
    a.step(), b.step(); // the first step settles the volume weights: not timed
    std::vector<double> ta, tb, ratio, checks;
    std::printf("Sedov -n %d (%zu particles), default scheme, %d threads\n", cfg.side, a.n_owned(),
                cfg.threads);
    std::printf("| round | off s/step | rollback s/step | ratio | checks s/step "
                "|\n|---|---|---|---|---|\n");
    for (int r = 0; r < rounds; ++r) {
        ta.push_back(timed([&] { a.step(); }));
        tb.push_back(timed([&] { b.step(); }));
        if (b.recovered())
            std::printf("warning: a rollback in the clean run (%s)\n",
                        b.safety().summary().c_str());
        ratio.push_back(tb.back() / ta.back());
        checks.push_back(checks_of_one_step(b.particles(), b.n_owned(), b.box()));
        std::printf("| %d | %.4f | %.4f | %.4f | %.4f |\n", r + 1, ta.back(), tb.back(),
                    ratio.back(), checks.back());
    }
    std::printf("medians: off %.4f s/step, rollback %.4f s/step, ratio %.4f (overhead %.2f %%); "
                "the checks alone %.4f s/step (%.2f %% of the off step)\n",
                median(ta), median(tb), median(ratio), 100 * (median(ratio) - 1), median(checks),
                100 * median(checks) / median(ta));
    print_breakdown(b.particles(), b.n_owned());
    MPI_Finalize();
    return 0;
}
