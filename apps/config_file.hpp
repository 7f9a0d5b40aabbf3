#pragma once
// --config FILE.toml (issue 22): run parameters from a TOML file whose keys are the parameter
// table's (as DIR/run.toml lists them, config/run_file.hpp). Each value goes through the same
// option, with the same checks, as on the command line; an option given on the command line
// overrides the file. Errors name the file, the line and the key.
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include <CLI/CLI.hpp>
#include <toml++/toml.h>

#include "exasph/config/parameter_text.hpp"
#include "exasph/config/run_file.hpp"
#include "exasph/util/error.hpp"

namespace exasph::cli {

[[noreturn]] inline void config_error(const std::string& file, const toml::source_region& where,
                                      const std::string& what) {
    throw input_error(file + ":" + std::to_string(where.begin.line) + ": " + what, true);
}

inline const Param* param_by_key(std::string_view key) {
    for (const auto& p : kParameters)
        if (key == p.key) return &p;
    return nullptr;
}

// A number as option text: integers as such, floats exactly and with a decimal point or an
// exponent (so that -w reads 10.0 as a time, 10 as a step count).
inline std::optional<std::string> number_text(const toml::node& n) {
    if (auto i = n.value_exact<std::int64_t>()) return std::to_string(*i);
    if (auto d = n.value_exact<double>()) return exact_number(*d, true);
    return std::nullopt;
}

// What a parameter's member takes, in words, for the wrong-type message.
template <class V>
const char* wanted_type() {
    if constexpr (std::is_same_v<V, bool>) return "true or false";
    if constexpr (std::is_floating_point_v<V>) return "a number";
    if constexpr (std::is_integral_v<V>) return "an integer";
    if constexpr (std::is_same_v<V, std::vector<std::string>>) return "a list of strings";
    return "a string";
}

// The option texts of a TOML value for parameter p, or an error message naming the type wanted.
inline std::vector<std::string> option_texts(const Param& p, const toml::node& n,
                                             std::string& error) {
    return std::visit(
        [&](const auto& m) -> std::vector<std::string> {
            using M = std::decay_t<decltype(m)>;
            if constexpr (std::is_same_v<M, CustomValue>) {
                if (auto s = n.value_exact<std::string>()) return {*s};
                if (auto t = number_text(n)) return {*t};
                error = "a string or a number";
                return {};
            } else {
                using V = std::decay_t<decltype(Config{}.*m)>;
                if constexpr (std::is_same_v<V, bool>) {
                    if (auto b = n.value_exact<bool>()) return {*b ? "true" : "false"};
                } else if constexpr (std::is_floating_point_v<V>) {
                    if (auto t = number_text(n)) return {*t};
                } else if constexpr (std::is_integral_v<V>) {
                    if (auto i = n.value_exact<std::int64_t>()) return {std::to_string(*i)};
                } else if constexpr (std::is_same_v<V, std::vector<std::string>>) {
                    if (auto s = n.value_exact<std::string>()) return {*s};
                    if (const toml::array* a = n.as_array()) {
                        std::vector<std::string> out;
                        for (const auto& e : *a)
                            if (auto s = e.value_exact<std::string>()) out.push_back(*s);
                        if (out.size() == a->size()) return out;
                    }
                } else if (auto s = n.value_exact<std::string>()) { // strings, enums
                    return {*s};
                }
                error = wanted_type<V>();
                return {};
            }
        },
        p.member);
}

// Reads `path` and hands every key that the command line did not give to its option.
inline void apply_config_file(CLI::App& app, const std::string& path) {
    toml::table table;
    try {
        table = toml::parse_file(path);
    } catch (const toml::parse_error& e) {
        config_error(path, e.source(), std::string(e.description()));
    }
    for (auto&& [key, node] : table) {
        const std::string name(key.str());
        const Param* p = param_by_key(name);
        if (!p)
            config_error(path, key.source(),
                         "unknown key '" + name + "' (the keys are those of an output's run.toml)");
        std::string wanted;
        const auto texts = option_texts(*p, node, wanted);
        if (!wanted.empty()) config_error(path, node.source(), "'" + name + "' takes " + wanted);
        CLI::Option* o = app.get_option(long_flag(*p));
        if (o->count() > 0) continue; // given on the command line: it overrides the file
        try {
            for (const auto& t : texts) o->add_result(t);
            o->run_callback();
        } catch (const CLI::Error& e) {
            config_error(path, node.source(), "'" + name + "': " + e.what());
        }
    }
}

} // namespace exasph::cli
