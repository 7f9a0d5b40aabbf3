// exasph command line: the parameter table (config/parameters.hpp) -> Config -> run().
#include <algorithm>
#include <csignal>
#include <cstdlib>
#include <iostream>
#include <string>

#include "exasph/util/mpi.hpp"
#include <CLI/CLI.hpp>

#include "cli_app.hpp"
#include "config_file.hpp"
#include "exasph/io/h5_file.hpp"
#include "exasph/run/run.hpp"
#include "exasph/util/memory.hpp"
#include "subcommands.hpp"

namespace {

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
    CommandLine cl;
    CLI::App& app = cl.app;
    exasph::Config& cfg = cl.cfg;
    if (const int code = parse(app, argc, argv, rank); code >= 0) return code;
    try {
        if (app.got_subcommand("glass")) return finish(run_glass(cl.glass));
        if (app.got_subcommand("exact")) return finish(run_exact(cl.exact));
        if (app.got_subcommand("render")) return finish(run_render(cl.render));
        if (app.got_subcommand("options")) return finish(run_options(app));
        if (!cl.config_file.empty()) exasph::cli::apply_config_file(app, cl.config_file);
        exasph::cli::finish_configuration(app, cfg);
        return finish(exasph::run(cfg, std::cout));
    } catch (const exasph::Error& e) {
        return finish_with_error(e.what(), e.exit_code(), e.all_ranks());
    } catch (const std::exception& e) {
        return finish_with_error(std::string("internal error: ") + e.what(), 1, false);
    }
}
