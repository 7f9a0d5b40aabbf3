#pragma once
// The command line of a run: every option of the parameter table with its checks, the case list
// in --help, and what follows the parse (the restart rule, the scheme's defaults). Used by
// exasph.cpp and by the command-line fuzzer (fuzz/fuzz_command_line.cpp), so both see one parser.
#include <string>

#include <CLI/CLI.hpp>

#include "cli_parameters.hpp"
#include "exasph/cases/registry.hpp"
#include "exasph/io/initial_conditions_file.hpp"
#include "exasph/io/particle_io.hpp"
#include "exasph/run/version.hpp"

namespace exasph::cli {

// --init: a case of the registry or something that names an HDF5 file.
inline CLI::Validator init_check() {
    return CLI::Validator(
        [](std::string& v) -> std::string {
            if (find_case(v) || names_a_file(v)) return {};
            return "unknown case '" + v + "' (known: " + case_names() + ", or a file *.h5)";
        },
        "CASE|FILE.h5");
}

// The cases and their --param keys, for the end of --help (from the case registry).
inline std::string cases_help() {
    std::string s = "Test cases (--init NAME; --param KEY=VALUE sets a case parameter):\n";
    for (const CaseInfo* c : case_registry()) {
        s += "  " + c->name + ": " + c->summary + " (" +
             (c->from_points ? "glass or --lattice, " : "") + "scheme " +
             std::string(choice_name(c->scheme)) + ")\n";
        for (const auto& p : c->params)
            s += "      " + p.key + " (" + format_number(p.default_value) + "): " + p.help + "\n";
    }
    return s;
}

inline void add_options(CLI::App& app, Config& cfg) {
    add_parameters(app, cfg);
    app.get_option("--init")->check(init_check());
    app.get_option("--restart")->check(CLI::ExistingPath);
    std::string fields;
    for (const auto& info : kFieldTable)
        if (info.roles & kSnapshot) fields += (fields.empty() ? "" : ",") + std::string(info.name);
    auto* f = app.get_option("--fields");
    f->description(f->get_description() + " (all: " + fields + ")");
    app.footer(cases_help());
    app.set_version_flag("--version", version_text());
}

// After a successful parse: the restart rule, then a new run's scheme defaults.
inline void finish_configuration(const CLI::App& app, Config& cfg) {
    check_restart_rule(app, cfg);
    if (cfg.restart_file.empty()) resolve_scheme(app, cfg, default_scheme(cfg.init));
}

} // namespace exasph::cli
