#pragma once
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "exasph/util/mpi.hpp"

#include "exasph/cases/registry.hpp"
#include "exasph/config/config.hpp"
#include "exasph/glass/glass_cache.hpp"
#include "exasph/io/checkpoint.hpp"
#include "exasph/io/initial_conditions_file.hpp"
#include "exasph/io/restart_source.hpp"
#include "exasph/sim/simulation.hpp"

namespace exasph {

// What a case gets from this run (cases/case_context.hpp): its rank's share, the sum over the
// ranks of `comm`, and the points (a lattice with --lattice, else tiles of the cached glass).
inline CaseContext case_context(const Config& cfg, MPI_Comm comm, std::ostream* log) {
    CaseContext ctx;
    MPI_Comm_rank(comm, &ctx.rank);
    MPI_Comm_size(comm, &ctx.nranks);
    ctx.sum_over_ranks = [comm](double x) {
        MPI_Allreduce(MPI_IN_PLACE, &x, 1, MPI_DOUBLE, MPI_SUM, comm);
        return x;
    };
    const auto side = std::uint64_t(cfg.side);
    const bool lattice = cfg.lattice;
    const double ng0 = cfg.ng0;
    ctx.points = [side, lattice, ng0, comm, log] {
        if (lattice) return UnitCubePoints::lattice(side);
        const auto b = glass_block_side(side);
        return UnitCubePoints::tiled_glass(side, b, glass_block(b, ng0, comm, log));
    };
    ctx.slab_points = [side, lattice, ng0, comm, log] {
        const auto layers = slab_layers(side);
        if (lattice) return UnitCubePoints::lattice(side, layers);
        return UnitCubePoints::tiled_glass(side, layers, glass_block(layers, ng0, comm, log),
                                           layers);
    };
    return ctx;
}

// The initial conditions --init names: a case of the registry or an HDF5 file. Each rank of
// `comm` makes only its share of the particles.
inline InitialConditions<double> make_case(const Config& cfg, MPI_Comm comm = MPI_COMM_WORLD,
                                           std::ostream* log = nullptr) {
    if (names_a_file(cfg.init)) {
        if (!cfg.case_params.empty())
            throw input_error("--param " + cfg.case_params.front() +
                                  ": initial conditions from a file take no case parameters",
                              true);
        return read_initial_conditions<double>(cfg.init, comm, cfg.ng0, cfg.open_box);
    }
    if (cfg.open_box)
        throw input_error("--open-box: only for initial conditions from a GADGET-layout file, not "
                          "a test case",
                          true);
    const CaseInfo* c = find_case(cfg.init);
    if (!c)
        throw input_error("--init: unknown case '" + cfg.init + "' (known: " + case_names() +
                              ", or an HDF5 file *.h5)",
                          true);
    const CaseRequest req{cfg.side, cfg.ng0, cfg.G, cfg.case_params};
    return c->make(req, case_context(cfg, comm, log));
}

// A run's simulation (its SPH passes on launcher L) with what the outputs need of its initial
// conditions.
template <class L>
struct RunStart {
    std::unique_ptr<Simulation<double, L>> sim;
    std::string units;
    double case_t_end = 0; // 0: none
};

// Builds the simulation from a test case, an initial-conditions file or a checkpoint (which
// restores the physics parameters of cfg).
template <class L>
RunStart<L> start_run(Config& cfg, MPI_Comm comm, std::ostream* log) {
    if (!cfg.restart_file.empty()) {
        auto cp = read_restart<double>(cfg, comm, log);
        RunStart<L> r{nullptr, cp.ic.units, cp.ic.t_end};
        r.sim = std::make_unique<Simulation<double, L>>(cfg, std::move(cp.ic), cp.rs, comm);
        return r;
    }
    auto ic = make_case(cfg, comm, log);
    RunStart<L> r{nullptr, ic.units, ic.t_end};
    r.sim = std::make_unique<Simulation<double, L>>(cfg, std::move(ic), comm);
    return r;
}

// The snapshot fields of -f: optional fields the run does not carry (phi without gravity,
// alpha without the AV switch) leave the default list; asked for by name they are an error.
inline std::vector<Field> run_snapshot_fields(const Config& cfg, const ParticleSet<double>& ps) {
    auto fields = snapshot_field_list(cfg.snapshot_fields, cfg.av_limiter);
    for (Field f : std::vector<Field>(fields)) {
        if (ps.enabled(f)) continue;
        if (!cfg.snapshot_fields.empty())
            throw input_error("-f: field '" + std::string(field_info(f).name) +
                                  "' is not carried by this run (" + optional_field_needs(f) + ")",
                              true);
        std::erase(fields, f);
    }
    return fields;
}

} // namespace exasph
