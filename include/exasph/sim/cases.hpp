#pragma once
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "exasph/cases/evrard.hpp"
#include "exasph/cases/file_case.hpp"
#include "exasph/cases/noh.hpp"
#include "exasph/cases/sedov.hpp"
#include "exasph/cases/square_patch.hpp"
#include "exasph/sim/config.hpp"
#include "exasph/sim/glass.hpp"
#include "exasph/util/error.hpp"

namespace exasph {

// Names accepted by --init.
inline const std::vector<std::string>& case_names() {
    static const std::vector<std::string> names{"square-patch", "sedov", "noh", "evrard"};
    return names;
}

// Applies --param KEY=VALUE overrides: `known` maps each key of the case to its variable.
inline void apply_case_params(const Config& cfg,
                              const std::vector<std::pair<std::string, double*>>& known) {
    for (const auto& kv : cfg.case_params) {
        const auto eq = kv.find('=');
        const std::string key = kv.substr(0, eq);
        std::string names;
        for (const auto& k : known) names += (names.empty() ? "" : ", ") + k.first;
        auto it = std::find_if(known.begin(), known.end(), [&](auto& k) { return k.first == key; });
        if (eq == std::string::npos || it == known.end())
            throw input_error("--param " + kv + ": case " + cfg.init + " has the parameters " +
                                  (names.empty() ? "(none)" : names) + " (use KEY=VALUE)",
                              true);
        double v = 0;
        std::size_t used = 0;
        try {
            v = std::stod(kv.substr(eq + 1), &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (used == 0 || used != kv.size() - eq - 1 || !std::isfinite(v) || !(v > 0))
            throw input_error("--param " + kv + ": the value must be a positive number", true);
        *it->second = v;
    }
}

// The points a case is made from: a regular lattice, or tiles of a cached periodic glass.
inline UnitCubePoints case_points(const Config& cfg, MPI_Comm comm, std::ostream* log) {
    const auto side = std::uint64_t(cfg.side);
    if (cfg.lattice) return UnitCubePoints::lattice(side);
    const auto b = glass_block_side(side);
    return UnitCubePoints::tiled_glass(side, b, glass_block(b, cfg.ng0, comm, log));
}

// Each rank of `comm` makes only its share of the particles.
template <class T>
InitialConditions<T> make_case(const Config& cfg, MPI_Comm comm = MPI_COMM_WORLD,
                               std::ostream* log = nullptr) {
    int rank = 0, nranks = 1;
    MPI_Comm_rank(comm, &rank);
    MPI_Comm_size(comm, &nranks);
    if (cfg.init == "square-patch") {
        SquarePatchParams sp;
        sp.side = cfg.side;
        sp.ng0 = cfg.ng0;
        apply_case_params(cfg, {{"omega", &sp.omega},
                                {"sound_speed", &sp.sound_speed},
                                {"dt0", &sp.dt0},
                                {"t_end", &sp.t_end}});
        return make_square_patch<T>(sp, rank, nranks);
    }
    if (cfg.init == "sedov") {
        SedovParams sp;
        sp.side = cfg.side;
        sp.ng0 = cfg.ng0;
        apply_case_params(cfg, {{"gamma", &sp.gamma},
                                {"energy", &sp.energy},
                                {"width", &sp.width},
                                {"u0", &sp.u0},
                                {"dt0", &sp.dt0},
                                {"t_end", &sp.t_end}});
        return make_sedov<T>(sp, case_points(cfg, comm, log), rank, nranks, comm);
    }
    if (cfg.init == "noh") {
        NohParams np;
        np.side = cfg.side;
        np.ng0 = cfg.ng0;
        apply_case_params(cfg, {{"gamma", &np.gamma},
                                {"radius", &np.radius},
                                {"speed", &np.speed},
                                {"u0", &np.u0},
                                {"dt0", &np.dt0},
                                {"t_end", &np.t_end}});
        return make_noh<T>(np, case_points(cfg, comm, log), rank, nranks);
    }
    if (cfg.init == "evrard") {
        EvrardParams ep;
        ep.side = cfg.side;
        ep.ng0 = cfg.ng0;
        apply_case_params(cfg, {{"gamma", &ep.gamma},
                                {"mass", &ep.mass},
                                {"radius", &ep.radius},
                                {"u0", &ep.u0},
                                {"dt0", &ep.dt0},
                                {"t_end", &ep.t_end}});
        if (cfg.G >= 0) ep.G = cfg.G;
        return make_evrard<T>(ep, case_points(cfg, comm, log), rank, nranks, comm);
    }
    if (names_a_file(cfg.init)) {
        apply_case_params(cfg, {});
        return read_initial_conditions<T>(cfg.init, comm);
    }
    std::string known;
    for (const auto& n : case_names()) known += (known.empty() ? "" : ", ") + n;
    throw input_error("--init: unknown case '" + cfg.init + "' (known: " + known +
                          ", or an HDF5 file *.h5)",
                      true);
}

} // namespace exasph
