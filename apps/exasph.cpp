// exasph command line: options -> Config -> run().
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>
#include <mpi.h>

#include "exasph/build_info.hpp"
#include "exasph/sim/cases.hpp"
#include "exasph/sim/run.hpp"
#include "exasph/sph/sinc_kernel.hpp"

namespace {

// Checks that an option's value is a number above (or, with allow_zero, at least) zero, with a
// message that says so in words.
CLI::Validator sign_check(bool allow_zero) {
    return CLI::Validator(
        [allow_zero](std::string& s) -> std::string {
            double v = 0;
            try {
                std::size_t used = 0;
                v = std::stod(s, &used);
                if (used != s.size()) return "'" + s + "' is not a number";
            } catch (const std::exception&) {
                return "'" + s + "' is not a number";
            }
            if (allow_zero ? v < 0 : v <= 0)
                return "value " + s + (allow_zero ? " is negative" : " must be positive");
            return {};
        },
        allow_zero ? "NONNEGATIVE" : "POSITIVE");
}

void add_options(CLI::App& app, exasph::Config& cfg) {
    app.add_option("--init", cfg.init, "Initial conditions: name of a test case")
        ->check(CLI::IsMember(exasph::case_names()))
        ->capture_default_str();
    app.add_option("-n", cfg.side, "Particles per axis (about n^3 particles)")
        ->check(CLI::Range(2, 1000))
        ->capture_default_str();
    app.add_option("-s,--steps", cfg.steps, "Number of steps to run")->check(sign_check(true));
    app.add_option("--t-end", cfg.t_end,
                   "Physical end time; with -s the run stops at whichever comes first "
                   "(default: the case's end time when -s is not given)")
        ->check(sign_check(false));
    app.add_option("--out", cfg.out_dir, "Output directory (diagnostics.csv)")
        ->capture_default_str();
    app.add_option("--ng0", cfg.ng0, "Target number of neighbours")
        ->check(CLI::Range(10.0, 1000.0))
        ->capture_default_str();
    app.add_option("--ngmax", cfg.ngmax, "Neighbour cap; exceeding it is reported")
        ->check(CLI::Range(10, 4000))
        ->capture_default_str();
    app.add_option("--kernel-exponent", cfg.kernel_exponent, "Sinc kernel exponent n")
        ->check(CLI::Range(exasph::kSincExponentMin, exasph::kSincExponentMax))
        ->capture_default_str();
    app.add_option("--courant", cfg.courant, "Courant factor K_cour")
        ->check(CLI::Range(1e-6, 1.0))
        ->capture_default_str();
    app.add_option("--alpha", cfg.alpha, "Artificial viscosity alpha")
        ->check(CLI::Range(0.0, 10.0))
        ->capture_default_str();
    app.add_option("--threads", cfg.threads, "OpenMP threads (default: OMP_NUM_THREADS or all)")
        ->check(CLI::Range(1, 4096));
    app.add_option("--global-bucket", cfg.global_bucket,
                   "Global tree leaf size: the unit of MPI load balance (particles)")
        ->check(CLI::Range(1, 1 << 20))
        ->capture_default_str();
    app.add_option("--leaf-size", cfg.bucket_size, "Local octree leaf size (particles)")
        ->check(CLI::Range(1, 4096))
        ->capture_default_str();
    std::map<std::string, exasph::CurveKind> curves{{"hilbert", exasph::CurveKind::hilbert},
                                                    {"morton", exasph::CurveKind::morton}};
    app.add_option("--curve", cfg.curve, "Space-filling curve: hilbert or morton")
        ->transform(CLI::CheckedTransformer(curves, CLI::ignore_case));
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
        MPI_Finalize();
        return code;
    }
    std::cerr << "exasph: error on rank " << rank << ": " << msg << "\n";
    MPI_Abort(MPI_COMM_WORLD, code);
    return code;
}

} // namespace

int main(int argc, char** argv) {
    int provided = 0;
    MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    exasph::Config cfg;
    CLI::App app{"exasph: smoothed-particle hydrodynamics (SPH-EXA mini-app physics); "
                 "runs alone or under mpirun",
                 "exasph"};
    add_options(app, cfg);
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        int code = rank == 0 ? app.exit(e) : 0;
        MPI_Finalize();
        return code;
    } catch (const CLI::CallForVersion& e) {
        int code = rank == 0 ? app.exit(e) : 0;
        MPI_Finalize();
        return code;
    } catch (const CLI::ParseError& e) {
        return finish_with_error(std::string(e.what()) + " (see exasph --help)", 2, true);
    }
    if (cfg.ngmax < cfg.ng0)
        return finish_with_error("--ngmax " + std::to_string(cfg.ngmax) +
                                     " must be at least --ng0 " + std::to_string(cfg.ng0),
                                 2, true);
    try {
        int code = exasph::run(cfg, std::cout);
        MPI_Finalize();
        return code;
    } catch (const exasph::Error& e) {
        return finish_with_error(e.what(), e.exit_code(), e.all_ranks());
    } catch (const std::exception& e) {
        return finish_with_error(std::string("internal error: ") + e.what(), 1, false);
    }
}
