#pragma once
#include <string>
#include <string_view>
#include <type_traits>
#include <variant>
#include <vector>

#include "exasph/config/parameters.hpp"

namespace exasph {

// The longest of a parameter's flags ("--steps" of "-s,--steps"): the name messages use.
inline std::string long_flag(const Param& p) {
    std::string_view f(p.flags);
    const auto comma = f.rfind(',');
    return std::string(comma == std::string_view::npos ? f : f.substr(comma + 1));
}

// A parameter's value as text (the run header): numbers as %g, flags as on/off, lists
// comma-separated, enums by name.
inline std::string format_value(const Param& p, const Config& cfg) {
    return std::visit(
        [&](const auto& m) -> std::string {
            using M = std::decay_t<decltype(m)>;
            if constexpr (std::is_same_v<M, CustomValue>) {
                return m.format(cfg);
            } else {
                const auto& v = cfg.*m;
                using V = std::decay_t<decltype(v)>;
                if constexpr (std::is_same_v<V, bool>)
                    return v ? "on" : "off";
                else if constexpr (std::is_same_v<V, std::string>)
                    return v;
                else if constexpr (std::is_same_v<V, std::vector<std::string>>) {
                    std::string s;
                    for (const auto& e : v) s += (s.empty() ? "" : ",") + e;
                    return s;
                } else if constexpr (std::is_enum_v<V>)
                    return std::string(choice_name(v));
                else
                    return format_number(double(v));
            }
        },
        p.member);
}

} // namespace exasph
