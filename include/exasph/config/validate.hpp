#pragma once
#include <string>

#include "exasph/config/choices.hpp"
#include "exasph/config/config.hpp"
#include "exasph/util/error.hpp"

namespace exasph {

// The combinations of parameters that no single option's check can see (all ranks; input
// errors, exit code 2).
inline void validate_config(const Config& cfg) {
    if (cfg.ngmax < cfg.ng0)
        throw input_error("--ngmax " + std::to_string(cfg.ngmax) + " must be at least --ng0 " +
                              format_number(cfg.ng0),
                          true);
    if (cfg.checkpoint_auto && !(cfg.mtbf_hours > 0))
        throw input_error("--checkpoint-every auto needs --mtbf HOURS (the MTBF of one node)",
                          true);
    if (!cfg.checkpoint_auto && cfg.mtbf_hours > 0)
        throw input_error("--mtbf is used only with --checkpoint-every auto", true);
    if (cfg.checkpoint_auto && cfg.checkpoint_minutes > 0)
        throw input_error("--checkpoint-every auto and --checkpoint-minutes exclude each other",
                          true);
}

} // namespace exasph
