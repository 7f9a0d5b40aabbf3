#pragma once
#include <array>
#include <string>
#include <vector>

#include "exasph/io/csv_table.hpp"
#include "exasph/sim/diagnostics.hpp"
#include "exasph/sim/phases.hpp"

namespace exasph {

// The columns of diagnostics.csv: the physics.md §10 quantities of a step, then the seconds of each
// phase (t_NAME).
// With block time steps (`rungs`) also active_rK: the active particles of rung K in the step.
inline std::vector<CsvColumn> diagnostics_columns(bool rungs) {
    std::vector<CsvColumn> c{
        {"step", CsvFormat::integer}, {"time"}, {"dt"}, {"n", CsvFormat::integer}};
    for (const char* name : {"ekin", "eint", "epot", "etot", "px", "py", "pz", "lx", "ly", "lz",
                             "nc_min", "nc_mean", "nc_max", "rho_max", "l1_rho", "e_stir"})
        c.push_back({name});
    // the particles with forces this step (all, or the active ones with block time steps), the
    // pair terms of one neighbour pass over them, and the shortest rung in use (block steps)
    for (const char* name : {"active", "pairs", "rung_max"})
        c.push_back({name, CsvFormat::integer});
    // the slowest rank's compute seconds (wall time outside MPI waits) over the mean rank's
    c.push_back({"compute_imbalance"});
    for (int k = 0; rungs && k <= kMaxRung; ++k)
        c.push_back({"active_r" + std::to_string(k), CsvFormat::integer});
    for (auto name : kPhaseNames) c.push_back({"t_" + std::string(name), CsvFormat::timing});
    return c;
}

inline std::vector<double>
diagnostics_row(const Diagnostics& d, const std::array<double, kNumPhases>& phases, bool rungs) {
    // clang-format off
    std::vector<double> row{double(d.step), d.time, d.dt, double(d.n),
                            d.ekin, d.eint, d.epot, d.etot,
                            d.momentum[0], d.momentum[1], d.momentum[2],
                            d.angular_momentum[0], d.angular_momentum[1], d.angular_momentum[2],
                            d.nc_min, d.nc_mean, d.nc_max, d.rho_max, d.l1_rho, d.e_stir,
                            d.work.active, d.work.pairs, d.work.rung_max,
                            d.work.compute_imbalance(d.nranks)};
    // clang-format on
    if (rungs) row.insert(row.end(), d.work.by_rung.begin(), d.work.by_rung.end());
    row.insert(row.end(), phases.begin(), phases.end());
    return row;
}

} // namespace exasph
