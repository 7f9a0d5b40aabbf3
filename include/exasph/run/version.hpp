#pragma once
// The line that says what a binary is: version, build options and the pair loops' instruction
// set. --version prints it, the run header starts with it and run.toml records it.
#include <string>

#include "exasph/build_info.hpp"
#include "exasph/sph/pair_loop_isa.hpp"

namespace exasph {

inline std::string version_text() {
    return std::string("exasph ") + kVersion + " (" + kBuildInfo + ", pair loops " + kPairLoopIsa +
           ")";
}

} // namespace exasph
