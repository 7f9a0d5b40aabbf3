#pragma once
#include <string>

#include "exasph/config/parameter_text.hpp"

namespace exasph {

// The run header's parameter lines, generated from the parameter table: every physics
// parameter (OnRestart::kept, except the case and -n, which the header names already), and the
// run-control parameters that differ from their defaults.
inline std::string physics_summary(const Config& cfg) {
    std::string s;
    for (const auto& p : kParameters) {
        if (p.restart != OnRestart::kept || std::string(p.key) == "init" ||
            std::string(p.key) == "side")
            continue;
        s += (s.empty() ? "" : ", ") + std::string(p.key) + " " + format_value(p, cfg);
    }
    return s;
}

inline std::string run_control_summary(const Config& cfg) {
    const Config defaults;
    std::string s;
    for (const auto& p : kParameters) {
        if (p.restart == OnRestart::kept) continue;
        const std::string v = format_value(p, cfg);
        if (v == format_value(p, defaults)) continue;
        s += (s.empty() ? "" : ", ") + std::string(p.key) + " " + v;
    }
    return s;
}

} // namespace exasph
