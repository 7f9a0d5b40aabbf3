#pragma once
// The names the recipe edits of fuzz/h5_recipe.hpp aim at: every attribute exasph writes or
// reads on a file's root (the run attributes, "param:KEY" of every parameter, the checkpoint's
// own) and every particle field, plus a name no reader knows.
#include <string>
#include <vector>

#include "exasph/config/parameters.hpp"
#include "exasph/particles/field_list.hpp"

namespace exasph::fuzz {

inline std::vector<std::string> recipe_names() {
    std::vector<std::string> names = {"box_lo",       "box_hi",
                                      "periodic",     "eos",
                                      "gamma",        "dt0",
                                      "t_end",        "units",
                                      "format",       "checksum",
                                      "time",         "step",
                                      "dt_m1",        "sound_speed",
                                      "stir_coeff",   "stir_accel_rms",
                                      "stir_t_corr",  "stir_energy_in",
                                      "leaf_keys",    "case_params",
                                      "code_version", "unknown"};
    for (const auto& p : kParameters) names.push_back(std::string("param:") + p.key);
    for (const auto& f : kFieldTable) names.emplace_back(f.name);
    names.emplace_back("id");
    return names;
}

} // namespace exasph::fuzz
