#pragma once
#include <string>
#include <vector>

#include "exasph/cases/file_case.hpp"
#include "exasph/cases/square_patch.hpp"
#include "exasph/sim/config.hpp"
#include "exasph/util/error.hpp"

namespace exasph {

// Names accepted by --init.
inline const std::vector<std::string>& case_names() {
    static const std::vector<std::string> names{"square-patch"};
    return names;
}

// Each rank makes only its share of the particles.
template <class T>
InitialConditions<T> make_case(const Config& cfg, int rank = 0, int nranks = 1) {
    if (cfg.init == "square-patch") {
        SquarePatchParams sp;
        sp.side = cfg.side;
        sp.ng0 = cfg.ng0;
        return make_square_patch<T>(sp, rank, nranks);
    }
    if (names_a_file(cfg.init)) return read_initial_conditions<T>(cfg.init, MPI_COMM_WORLD);
    std::string known;
    for (const auto& n : case_names()) known += (known.empty() ? "" : ", ") + n;
    throw input_error("--init: unknown case '" + cfg.init + "' (known: " + known +
                          ", or an HDF5 file *.h5)",
                      true);
}

} // namespace exasph
