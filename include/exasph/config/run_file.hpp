#pragma once
// DIR/run.toml (issue 22): every parameter of the table with the value the run uses, as TOML
// that `exasph --config DIR/run.toml` reads back (apps/config_file.hpp) to repeat the run.
#include <cstdio>
#include <string>
#include <type_traits>
#include <vector>

#include "exasph/config/parameters.hpp"

namespace exasph {

inline std::string toml_string(const std::string& s) {
    std::string out = "\"";
    for (char c : s) {
        if (c == '"' || c == '\\') out += '\\';
        if (c == '\n') {
            out += "\\n";
            continue;
        }
        out += c;
    }
    return out + "\"";
}

// One parameter's value as a TOML value ("" when it is not set: a sentinel default).
inline std::string toml_value(const Param& p, const Config& cfg) {
    return std::visit(
        [&](const auto& m) -> std::string {
            using M = std::decay_t<decltype(m)>;
            if constexpr (std::is_same_v<M, CustomValue>) {
                const std::string t = m.option_text(cfg);
                return t.empty() ? t : toml_string(t);
            } else {
                const auto& v = cfg.*m;
                using V = std::decay_t<decltype(v)>;
                if constexpr (std::is_same_v<V, bool>)
                    return v ? "true" : "false";
                else if constexpr (std::is_same_v<V, std::string>)
                    return toml_string(v);
                else if constexpr (std::is_same_v<V, std::vector<std::string>>) {
                    std::string s;
                    for (const auto& e : v) s += (s.empty() ? "" : ", ") + toml_string(e);
                    return "[" + s + "]";
                } else if constexpr (std::is_enum_v<V>)
                    return toml_string(std::string(choice_name(v)));
                else if constexpr (std::is_floating_point_v<V>)
                    return exact_number(v);
                else
                    return std::to_string(v);
            }
        },
        p.member);
}

// Whether run.toml lists p: not a sentinel left at its default ("not given"), and, for a
// restart, only what the restart's own command line may set (the checkpoint holds the rest).
inline bool listed_in_run_file(const Param& p, const Config& cfg) {
    if (!cfg.restart_file.empty() && p.restart != OnRestart::given) return false;
    if (!p.show_default && toml_value(p, cfg) == toml_value(p, Config{})) return false;
    return !toml_value(p, cfg).empty();
}

// The file's text: a header naming the code's version, then one `key = value` per parameter in
// the table's order, its help as a comment.
inline std::string run_file_text(const Config& cfg, const std::string& version) {
    std::string s = "# The parameters of this run, written by " + version +
                    ".\n# Repeat it with: exasph --config run.toml (options given on the "
                    "command line override these).\n\n";
    for (const auto& p : kParameters)
        if (listed_in_run_file(p, cfg))
            s += std::string(p.key) + " = " + toml_value(p, cfg) + " # " + p.help +
                 (*p.unit ? std::string(" [") + p.unit + "]" : std::string()) + "\n";
    return s;
}

} // namespace exasph
