#pragma once
#include <string>

#include "exasph/cases/registry.hpp"
#include "exasph/config/scheme.hpp"

namespace exasph::testref {

// The configuration a user gets from `exasph --init NAME -n SIDE` with no physics option: the
// case's default scheme (config/scheme.hpp).
inline Config case_config(const std::string& name, int side) {
    Config cfg;
    cfg.init = name;
    cfg.side = side;
    apply_scheme(cfg, default_scheme(name));
    return cfg;
}

} // namespace exasph::testref
