#pragma once
// The command line's run options, generated from the parameter table (config/parameters.hpp).
#include <cctype>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include <CLI/CLI.hpp>

#include "exasph/config/parameter_text.hpp"
#include "exasph/config/scheme.hpp"
#include "exasph/util/error.hpp"

namespace exasph::cli {

// Checks that an option's value is a number above (or, with allow_zero, at least) zero, with a
// message that says so in words.
inline CLI::Validator sign_check(bool allow_zero) {
    return CLI::Validator(
        [allow_zero](std::string& s) -> std::string {
            const auto x = parse_number(s);
            if (!x) return "'" + s + "' is not a number";
            const double v = *x;
            if (allow_zero ? v < 0 : v <= 0)
                return "value " + s + (allow_zero ? " is negative" : " must be positive");
            return {};
        },
        allow_zero ? "NONNEGATIVE" : "POSITIVE");
}

template <class V>
void apply_range(CLI::Option* o, const ValueRange& r) {
    if (r.kind == ValueRange::closed) {
        if constexpr (std::is_integral_v<V>)
            o->check(CLI::Range(std::int64_t(r.lo), std::int64_t(r.hi)));
        else
            o->check(CLI::Range(r.lo, r.hi));
    }
    if (r.kind == ValueRange::positive) o->check(sign_check(false));
    if (r.kind == ValueRange::nonnegative) o->check(sign_check(true));
}

// An enum parameter takes one of its names (config/choices.hpp), in any case.
template <class E>
CLI::Option* add_choice(CLI::App& app, const Param& p, const std::string& help, E& value) {
    std::vector<std::string> names;
    for (const auto& [name, v] : Choices<E>::values) names.emplace_back(name);
    return app
        .add_option_function<std::string>(
            p.flags,
            [&value, flag = long_flag(p)](std::string s) {
                for (char& ch : s) ch = char(std::tolower(static_cast<unsigned char>(ch)));
                const auto e = choice_from_name<E>(s);
                if (!e)
                    throw CLI::ValidationError(flag,
                                               "'" + s + "' is not one of " + choice_list<E>());
                value = *e;
            },
            help)
        ->check(CLI::IsMember(names, CLI::ignore_case))
        ->default_str(p.show_default ? std::string(choice_name(value)) : std::string());
}

inline CLI::Option* add_custom(CLI::App& app, const Param& p, const std::string& help,
                               const CustomValue& c, Config& cfg) {
    const std::string flag = long_flag(p);
    return app
        .add_option_function<std::string>(
            p.flags,
            [c, flag, &cfg](const std::string& v) {
                try {
                    c.parse(v, cfg);
                } catch (const std::invalid_argument& e) {
                    throw CLI::ValidationError(flag, e.what());
                }
            },
            help)
        ->type_name(c.type_name);
}

// One CLI11 option for one parameter, by the type of the member it sets.
inline CLI::Option* add_parameter(CLI::App& app, const Param& p, Config& cfg) {
    const std::string help =
        std::string(p.help) + (*p.unit ? std::string(" [") + p.unit + "]" : std::string());
    return std::visit(
        [&](const auto& m) -> CLI::Option* {
            using M = std::decay_t<decltype(m)>;
            if constexpr (std::is_same_v<M, CustomValue>) {
                return add_custom(app, p, help, m, cfg);
            } else {
                auto& v = cfg.*m;
                using V = std::decay_t<decltype(v)>;
                if constexpr (std::is_same_v<V, bool>)
                    return app.add_flag(p.flags, v, help);
                else if constexpr (std::is_enum_v<V>)
                    return add_choice(app, p, help, v);
                else {
                    CLI::Option* o = app.add_option(p.flags, v, help);
                    if constexpr (std::is_same_v<V, std::vector<std::string>>)
                        if (p.delimiter) o->delimiter(p.delimiter);
                    apply_range<V>(o, p.range);
                    // A scheme's parameter has no one default: its help says each scheme's.
                    if (p.show_default && !set_by_scheme(p.key)) o->capture_default_str();
                    return o;
                }
            }
        },
        p.member);
}

// Every parameter of the table as an option of `app`, writing into `cfg`.
inline void add_parameters(CLI::App& app, Config& cfg) {
    for (const auto& p : kParameters) add_parameter(app, p, cfg);
}

// The restart rule (OnRestart): with --restart, a parameter that the checkpoint holds, or that
// only shapes the initial conditions, may not be given. Every other one is honoured.
inline void check_restart_rule(const CLI::App& app, const Config& cfg) {
    if (cfg.restart_file.empty()) return;
    for (const auto& p : kParameters) {
        if (p.restart == OnRestart::given || app.count(long_flag(p)) == 0) continue;
        throw input_error(long_flag(p) + " cannot be changed on --restart (" +
                              (p.restart == OnRestart::kept
                                   ? "the checkpoint holds the physics parameters"
                                   : "the checkpoint holds the particles") +
                              ")",
                          true);
    }
}

// The formulation of a new run: the scheme given with --scheme, else `case_default`; the
// parameters given explicitly keep their values. (A restart restores them from the checkpoint.)
inline void resolve_scheme(const CLI::App& app, Config& cfg, Scheme case_default) {
    const Scheme s = app.count("--scheme") > 0 ? cfg.scheme : case_default;
    apply_scheme(cfg, s, [&app](const Param& p) { return app.count(long_flag(p)) > 0; });
}

} // namespace exasph::cli
