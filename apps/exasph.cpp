// exasph command line: the parameter table (config/parameters.hpp) -> Config -> run().
#include <algorithm>
#include <csignal>
#include <cstdlib>
#include <iostream>
#include <string>

#include "exasph/util/mpi.hpp"
#include <CLI/CLI.hpp>

#include "cli_parameters.hpp"
#include "exasph/build_info.hpp"
#include "exasph/cases/registry.hpp"
#include "exasph/io/h5_file.hpp"
#include "exasph/io/initial_conditions_file.hpp"
#include "exasph/run/run.hpp"
#include "exasph/util/memory.hpp"
#include "subcommands.hpp"

namespace {

// --init: a case of the registry or something that names an HDF5 file.
CLI::Validator init_check() {
    return CLI::Validator(
        [](std::string& v) -> std::string {
            if (exasph::find_case(v) || exasph::names_a_file(v)) return {};
            return "unknown case '" + v + "' (known: " + exasph::case_names() + ", or a file *.h5)";
        },
        "CASE|FILE.h5");
}

// The cases and their --param keys, for the end of --help (from the case registry).
std::string cases_help() {
    std::string s = "Test cases (--init NAME; --param KEY=VALUE sets a case parameter):\n";
    for (const exasph::CaseInfo* c : exasph::case_registry()) {
        s += "  " + c->name + ": " + c->summary + " (" +
             (c->from_points ? "glass or --lattice, " : "") + "scheme " +
             std::string(exasph::choice_name(c->scheme)) + ")\n";
        for (const auto& p : c->params)
            s += "      " + p.key + " (" + exasph::format_number(p.default_value) + "): " + p.help +
                 "\n";
    }
    return s;
}

void add_options(CLI::App& app, exasph::Config& cfg) {
    exasph::cli::add_parameters(app, cfg);
    app.get_option("--init")->check(init_check());
    app.get_option("--restart")->check(CLI::ExistingPath);
    std::string fields;
    for (const auto& info : exasph::kFieldTable)
        if (info.roles & exasph::kSnapshot)
            fields += (fields.empty() ? "" : ",") + std::string(info.name);
    auto* f = app.get_option("--fields");
    f->description(f->get_description() + " (all: " + fields + ")");
    app.footer(cases_help());
    app.set_version_flag("--version", std::string("exasph ") + exasph::kVersion + " (" +
                                          exasph::kBuildInfo + ")");
}

// Ends the run after an error: errors seen by every rank end cleanly (rank 0 reports); an error
// on one rank of several aborts them all, so that no rank waits forever in a collective.
int finish_with_error(const std::string& msg, int code, bool all_ranks) {
    int rank = 0, nranks = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &nranks);
    std::cout.flush();
    if (nranks == 1 || all_ranks) {
        if (rank == 0) std::cerr << "exasph: error: " << msg << "\n";
        if (exasph::h5::write_failed()) { // HDF5 would crash closing that file in MPI_Finalize
            std::cerr.flush();
            std::_Exit(code);
        }
        MPI_Finalize();
        return code;
    }
    std::cerr << "exasph: error on rank " << rank << ": " << msg << "\n";
    MPI_Abort(MPI_COMM_WORLD, code);
    return code;
}

int finish(int code) {
    MPI_Finalize();
    return code;
}

// Parses the command line; returns an exit code when the process should end now (help,
// version, bad options), else -1.
int parse(CLI::App& app, int argc, char** argv, int rank) {
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return finish(rank == 0 ? app.exit(e) : 0);
    } catch (const CLI::CallForVersion& e) {
        return finish(rank == 0 ? app.exit(e) : 0);
    } catch (const CLI::ParseError& e) {
        return finish_with_error(std::string(e.what()) + " (see exasph --help)", 2, true);
    }
    return -1;
}

} // namespace

int main(int argc, char** argv) {
    exasph::map_large_blocks();
    int provided = 0;
    // A file-size limit (ulimit -f) reached while writing: the write fails and the run ends
    // with exit 3 as on a full disk, instead of being killed by SIGXFSZ.
    std::signal(SIGXFSZ, SIG_IGN);
    MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    exasph::Config cfg;
    CLI::App app{"exasph: smoothed-particle hydrodynamics (SPH-EXA mini-app physics); "
                 "runs alone or under mpirun",
                 "exasph"};
    add_options(app, cfg);
    GlassCommand glass_cmd;
    ExactCommand exact_cmd;
    add_glass_command(app, glass_cmd);
    add_exact_command(app, exact_cmd);
    app.require_subcommand(0, 1);
    if (const int code = parse(app, argc, argv, rank); code >= 0) return code;
    try {
        if (app.got_subcommand("glass")) return finish(run_glass(glass_cmd));
        if (app.got_subcommand("exact")) return finish(run_exact(exact_cmd));
        exasph::cli::check_restart_rule(app, cfg);
        if (cfg.restart_file.empty())
            exasph::cli::resolve_scheme(app, cfg, exasph::default_scheme(cfg.init));
        return finish(exasph::run(cfg, std::cout));
    } catch (const exasph::Error& e) {
        return finish_with_error(e.what(), e.exit_code(), e.all_ranks());
    } catch (const std::exception& e) {
        return finish_with_error(std::string("internal error: ") + e.what(), 1, false);
    }
}
