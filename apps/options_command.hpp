#pragma once
// `exasph options`: every run option as a Markdown table (option, meaning with its unit,
// default), from the command line that the parameter table generates (apps/cli_app.hpp), so that
// the user guide's table (docs/user-guide.md, checked by the CTest docs_options) cannot drift.
#include <algorithm>
#include <cstdio>
#include <string>

#include "exasph/util/mpi.hpp"
#include <CLI/CLI.hpp>

#include "exasph/cases/registry.hpp"
#include "exasph/config/parameter_text.hpp"
#include "exasph/config/scheme.hpp"

inline void add_options_command(CLI::App& app) {
    app.add_subcommand("options", "Print every run option as a Markdown table (option, meaning, "
                                  "default): the table of docs/user-guide.md");
}

// "-s,--steps" -> "`-s`, `--steps`"
inline std::string markdown_flags(const std::string& flags) {
    std::string out;
    std::size_t start = 0;
    while (start <= flags.size()) {
        const std::size_t comma = std::min(flags.find(',', start), flags.size());
        out += (out.empty() ? "`" : ", `") + flags.substr(start, comma - start) + "`";
        start = comma + 1;
    }
    return out;
}

// A table cell: '|' would end it early.
inline std::string markdown_cell(std::string text) {
    for (std::size_t at = text.find('|'); at != std::string::npos; at = text.find('|', at + 2))
        text.replace(at, 1, "\\|");
    return text;
}

// The default column: the value, "off" for a flag, "the scheme's" where --scheme sets it and
// "the case's" for the scheme itself.
inline std::string markdown_default(const CLI::Option& o) {
    for (const auto& p : exasph::kParameters) {
        if (exasph::long_flag(p) != o.get_name()) continue;
        if (exasph::set_by_scheme(p.key)) return "the scheme's";
        if (std::string_view(p.key) == "scheme") return "the case's";
    }
    return o.get_expected_min() == 0 ? "off" : o.get_default_str();
}

inline std::string options_markdown(const CLI::App& app) {
    std::string out = "| option | meaning | default |\n|---|---|---|\n";
    for (const CLI::Option* o : app.get_options()) {
        const std::string flags = o->get_name(false, true);
        if (flags == "-h,--help" || flags == "--version") continue;
        out += "| " + markdown_flags(flags) + " | " + markdown_cell(o->get_description()) + " | " +
               markdown_cell(markdown_default(*o)) + " |\n";
    }
    return out;
}

// The test cases (--init NAME) with their start, scheme and --param keys.
inline std::string cases_markdown() {
    std::string out = "| case | what | start, scheme | `--param` keys (default) |\n"
                      "|---|---|---|---|\n";
    for (const exasph::CaseInfo* c : exasph::case_registry()) {
        std::string keys;
        for (const auto& p : c->params)
            keys += (keys.empty() ? "" : "; ") + p.key + " (" +
                    exasph::format_number(p.default_value) + "): " + p.help;
        out += "| `" + c->name + "` | " + markdown_cell(c->summary) + " | " +
               (c->from_points ? "glass or `--lattice`, " : "its own lattice, ") +
               std::string(exasph::choice_name(c->scheme)) + " | " + markdown_cell(keys) + " |\n";
    }
    return out;
}

inline int run_options(const CLI::App& app) {
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    if (rank == 0) std::fputs((options_markdown(app) + "\n" + cases_markdown()).c_str(), stdout);
    return 0;
}
