// The fault-injection map of issue 21 (docs/resilience.md): single-bit flips in random fields
// (state and derived) of random particles at random phases of random steps of a small Sedov
// run with the default settings, each run in-process to the end and classified against the
// clean run:
//   recovered  detected, rolled back, final fields within 1e-6 of the clean run's
//   harmless   not detected, final fields within 1e-6 (each field's scale: its largest |value|)
//   stopped    the run ended with an exasph::Error (a clear message)
//   silent     not detected and some final field beyond 1e-6: a silent wrong answer
//   wrong      detected but the final fields still differ (a failed recovery)
//   internal   ended with another exception (an unclear message)
// Usage: fault_map [TRIALS=1000] [SIDE=10] [STEPS=12] [SEED=21] [CSV]; prints the map as a
// Markdown table (field x phase: silent / all) and the totals per class.
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "exasph/util/mpi.hpp"

#include "exasph/cases/registry.hpp"
#include "exasph/config/scheme.hpp"
#include "exasph/run/setup.hpp"
#include "exasph/sim/simulation.hpp"

using namespace exasph;

namespace {

constexpr Field kCompared[] = {Field::x,  Field::y, Field::z, Field::vx, Field::vy,
                               Field::vz, Field::u, Field::h, Field::rho};
using Final = std::map<std::uint64_t, std::array<double, 9>>;

struct Outcome {
    std::string error; // "" when the run ended normally
    bool clear_error = false;
    std::int64_t recoveries = 0;
    Final fields;
};

Outcome run(const Config& cfg, int steps, std::vector<Field>* carried = nullptr) {
    Outcome o;
    try {
        Simulation<double> sim(cfg, make_case(cfg, MPI_COMM_SELF), MPI_COMM_SELF);
        while (sim.step_count() < steps) sim.step();
        const auto& ps = sim.particles();
        for (std::size_t i = 0; i < sim.n_owned(); ++i)
            for (std::size_t k = 0; k < 9; ++k) o.fields[ps.id[i]][k] = ps.value(kCompared[k], i);
        o.recoveries = sim.safety().recoveries();
        if (carried)
            for (const auto& info : kFieldTable)
                if (ps.enabled(info.field)) carried->push_back(info.field);
    } catch (const Error& e) {
        o.error = e.what();
        o.clear_error = true;
    } catch (const std::exception& e) {
        o.error = e.what();
    }
    return o;
}

// Largest change of any compared field over the field's scale (its largest |value|).
double worst_change(const Final& a, const Final& clean) {
    std::array<double, 9> scale{};
    for (const auto& [id, f] : clean)
        for (std::size_t k = 0; k < 9; ++k) scale[k] = std::max(scale[k], std::abs(f[k]));
    double worst = a.size() == clean.size() ? 0.0 : INFINITY;
    for (const auto& [id, c] : clean) {
        auto it = a.find(id);
        if (it == a.end()) return INFINITY;
        for (std::size_t k = 0; k < 9; ++k) {
            const double d = std::abs(it->second[k] - c[k]) / scale[k];
            worst = d == d ? std::max(worst, d) : INFINITY;
        }
    }
    return worst;
}

std::string classify(const Outcome& o, const Final& clean) {
    if (!o.error.empty()) return o.clear_error ? "stopped" : "internal";
    const bool same = worst_change(o.fields, clean) <= 1e-6;
    if (o.recoveries > 0) return same ? "recovered" : "wrong";
    return same ? "harmless" : "silent";
}

} // namespace

int main(int argc, char** argv) {
    MPI_Init(&argc, &argv);
    const int trials = argc > 1 ? std::atoi(argv[1]) : 1000;
    const int side = argc > 2 ? std::atoi(argv[2]) : 10;
    const int steps = argc > 3 ? std::atoi(argv[3]) : 12;
    std::mt19937_64 rng(argc > 4 ? std::stoull(argv[4]) : 21);
    std::ofstream csv(argc > 5 ? argv[5] : "/dev/null");
    csv << "step,phase,field,id,bit,class,recoveries,error\n";
    Config cfg;
    cfg.init = "sedov";
    cfg.side = side;
    cfg.lattice = true;
    cfg.threads = 1;
    apply_scheme(cfg, default_scheme(cfg.init), [](const Param&) { return false; });
    std::vector<Field> fields;
    const Outcome clean = run(cfg, steps, &fields);
    if (!clean.error.empty() || clean.recoveries > 0) {
        std::fprintf(stderr, "fault_map: the clean run failed: %s\n", clean.error.c_str());
        return 1;
    }
    std::map<std::string, std::map<std::string, std::array<int, 2>>> map; // field, phase
    std::map<std::string, int> totals;
    for (int t = 0; t < trials; ++t) {
        const int step = 2 + int(rng() % std::uint64_t(steps - 2));
        const int phase = int(rng() % (kNumPhases + 1)) - 1; // -1: the start of the step
        const Field f = fields[rng() % fields.size()];
        const std::uint64_t id = rng() % std::uint64_t(side * side * side);
        const int bit = int(rng() % 64);
        const std::string fname(field_info(f).name);
        const std::string pname = phase < 0 ? "start" : std::string(kPhaseNames[phase]);
        Config c = cfg;
        c.inject_fault = std::to_string(step) + ":" + fname + ":" + std::to_string(id) + ":" +
                         std::to_string(bit) + (phase < 0 ? "" : ":" + pname);
        const Outcome o = run(c, steps);
        const std::string cls = classify(o, clean.fields);
        ++totals[cls];
        auto& cell = map[fname][pname];
        ++cell[1];
        if (cls == "silent" || cls == "wrong" || cls == "internal") ++cell[0];
        csv << step << "," << pname << "," << fname << "," << id << "," << bit << "," << cls << ","
            << o.recoveries << ",\"" << o.error << "\"\n";
    }
    std::printf("| field | start | ");
    for (auto p : kPhaseNames) std::printf("%s | ", std::string(p).c_str());
    std::printf("\n|---|---|");
    for (std::size_t p = 0; p < kNumPhases; ++p) std::printf("---|");
    std::printf("\n");
    for (const auto& [fname, row] : map) {
        std::printf("| %s | ", fname.c_str());
        for (int p = -1; p < int(kNumPhases); ++p) {
            auto it = row.find(p < 0 ? "start" : std::string(kPhaseNames[p]));
            if (it == row.end())
                std::printf("- | ");
            else
                std::printf("%d/%d | ", it->second[0], it->second[1]);
        }
        std::printf("\n");
    }
    std::printf("\n%d trials (Sedov -n %d lattice, %d steps, default settings):", trials, side,
                steps);
    for (const auto& [cls, n] : totals) std::printf(" %s %d", cls.c_str(), n);
    std::printf("\n");
    MPI_Finalize();
    return 0;
}
