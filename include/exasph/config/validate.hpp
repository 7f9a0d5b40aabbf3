#pragma once
#include <string>

#include "exasph/build_info.hpp"
#include "exasph/config/choices.hpp"
#include "exasph/config/config.hpp"
#include "exasph/util/error.hpp"

namespace exasph {

// The option of cfg that needs HDF5 files (snapshots, checkpoints, restarts, initial conditions
// from a file), or "" if none.
inline std::string option_needing_files(const Config& cfg) {
    if (cfg.snapshot_every_steps > 0 || cfg.snapshot_every_time > 0) return "-w";
    if (cfg.checkpoint_every > 0 || cfg.checkpoint_auto) return "--checkpoint-every";
    if (cfg.checkpoint_minutes > 0) return "--checkpoint-minutes";
    if (!cfg.restart_file.empty()) return "--restart";
    if (cfg.init.size() > 3 && cfg.init.ends_with(".h5")) return "--init " + cfg.init;
    return "";
}

// The combinations of parameters that no single option's check can see (all ranks; input
// errors, exit code 2).
inline void validate_config(const Config& cfg) {
    if (cfg.ngmax < cfg.ng0)
        throw input_error("--ngmax " + std::to_string(cfg.ngmax) + " must be at least --ng0 " +
                              format_number(cfg.ng0),
                          true);
    if (cfg.energy_weights && !cfg.volume_elements)
        throw input_error("--energy-weights chooses the weights of the volume elements: it needs "
                          "--volume-elements (or --scheme pe)",
                          true);
    if (cfg.checkpoint_auto && !(cfg.mtbf_hours > 0))
        throw input_error("--checkpoint-every auto needs --mtbf HOURS (the MTBF of one node)",
                          true);
    if (!cfg.checkpoint_auto && cfg.mtbf_hours > 0)
        throw input_error("--mtbf is used only with --checkpoint-every auto", true);
    if (cfg.checkpoint_auto && cfg.checkpoint_minutes > 0)
        throw input_error("--checkpoint-every auto and --checkpoint-minutes exclude each other",
                          true);
    if (cfg.timesteps == TimeStepping::block && (cfg.sync_every > 1 || cfg.diagnostics_every > 1))
        throw input_error(std::string(cfg.sync_every > 1 ? "--sync-every" : "--diagnostics-every") +
                              " above 1 needs global time steps (--timesteps global)",
                          true);
    if (const std::string opt = option_needing_files(cfg); !kHaveHdf5 && !opt.empty())
        throw input_error(opt + ": this build has no HDF5, which snapshots, checkpoints and "
                                "initial-condition files need (configure with -DEXASPH_HDF5=ON)",
                          true);
}

} // namespace exasph
