// exasph command line: options -> Config -> run().
#include <algorithm>
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>
#include <mpi.h>

#include "exasph/build_info.hpp"
#include "exasph/cases/file_case.hpp"
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

std::string case_list() {
    std::string s;
    for (const auto& n : exasph::case_names()) s += (s.empty() ? "" : ", ") + n;
    return s;
}

// --init: a known case name or something that names an HDF5 file.
CLI::Validator init_check() {
    return CLI::Validator(
        [](std::string& v) -> std::string {
            const auto& names = exasph::case_names();
            if (std::find(names.begin(), names.end(), v) != names.end()) return {};
            if (exasph::names_a_file(v)) return {};
            return "unknown case '" + v + "' (known: " + case_list() + ", or a file *.h5)";
        },
        "CASE|FILE.h5");
}

// -w N (every N steps) or -w T (every T of physical time).
void parse_write_every(const std::string& v, exasph::Config& cfg) {
    std::size_t used = 0;
    double x = 0;
    try {
        x = std::stod(v, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used != v.size() || !(x > 0))
        throw CLI::ValidationError("-w", "'" + v + "' is not a positive step count or time");
    if (v.find_first_of(".eE") == std::string::npos)
        cfg.snapshot_every_steps = std::int64_t(x);
    else
        cfg.snapshot_every_time = x;
}

void add_options(CLI::App& app, exasph::Config& cfg) {
    app.add_option("--init", cfg.init,
                   "Initial conditions: a test case (" + case_list() +
                       ") or an HDF5 file *.h5 (docs/file-format.md)")
        ->check(init_check())
        ->capture_default_str();
    app.add_option("-n", cfg.side, "Particles per axis (about n^3 particles)")
        ->check(CLI::Range(2, 1000))
        ->capture_default_str();
    app.add_option("-s,--steps", cfg.steps,
                   "Stop after step N (counted from the start of the simulation, across restarts)")
        ->check(sign_check(true));
    app.add_option("--t-end", cfg.t_end,
                   "Physical end time; with -s the run stops at whichever comes first "
                   "(default: the case's end time when -s is not given)")
        ->check(sign_check(false));
    app.add_option("--out", cfg.out_dir,
                   "Output directory (diagnostics.csv, snapshots, checkpoints)")
        ->capture_default_str();
    app.add_option_function<std::string>(
           "-w,--write-every", [&cfg](const std::string& v) { parse_write_every(v, cfg); },
           "Snapshots: every N steps (an integer), or every T of physical time (a number "
           "with a decimal point or exponent, written at the first step at or after each "
           "multiple of T)")
        ->type_name("N|T");
    app.add_option("-f,--fields", cfg.snapshot_fields,
                   "Snapshot fields, comma-separated (default: x,y,z,vx,vy,vz,h,m,u,rho,p,c,ax,"
                   "ay,az,du,nc); x,y,z are always written")
        ->delimiter(',');
    app.add_option("--checkpoint-every", cfg.checkpoint_every,
                   "Write a checkpoint every N steps (also at the end of the run)")
        ->check(sign_check(false));
    app.add_option("--checkpoint-minutes", cfg.checkpoint_minutes,
                   "Write a checkpoint every M minutes of wall-clock time")
        ->check(sign_check(false));
    app.add_option("--restart", cfg.restart_file,
                   "Continue the run saved in this checkpoint (any rank count); physics "
                   "options come from the checkpoint")
        ->check(CLI::ExistingFile);
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
    if (!cfg.restart_file.empty()) {
        for (const char* opt :
             {"--init", "-n", "--ng0", "--ngmax", "--kernel-exponent", "--courant", "--alpha",
              "--global-bucket", "--leaf-size", "--curve"})
            if (app.count(opt) > 0)
                return finish_with_error(std::string(opt) +
                                             " cannot be changed on --restart (the checkpoint "
                                             "holds the physics parameters)",
                                         2, true);
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
