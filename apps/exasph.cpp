// exasph command line: options -> Config -> run().
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>
#include <mpi.h>

#include "exasph/build_info.hpp"
#include "exasph/cases/file_case.hpp"
#include "exasph/exact/noh.hpp"
#include "exasph/exact/sedov.hpp"
#include "exasph/sim/cases.hpp"
#include "exasph/sim/glass.hpp"
#include "exasph/sim/run.hpp"
#include "exasph/sph/sinc_kernel.hpp"
#include "exasph/util/memory.hpp"

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
    std::string snapshot_default;
    for (const auto& info : exasph::kFieldTable)
        if (info.roles & exasph::kSnapshot)
            snapshot_default += (snapshot_default.empty() ? "" : ",") + std::string(info.name);
    app.add_option("-f,--fields", cfg.snapshot_fields,
                   "Snapshot fields, comma-separated (default: " + snapshot_default +
                       ", phi only with gravity); x,y,z are always written")
        ->delimiter(',');
    app.add_option_function<std::string>(
           "--checkpoint-every",
           [&cfg](const std::string& v) {
               if (v == "auto") {
                   cfg.checkpoint_auto = true;
                   return;
               }
               std::size_t used = 0;
               long long n = -1;
               try {
                   n = std::stoll(v, &used);
               } catch (const std::exception&) {
               }
               if (used != v.size() || n <= 0)
                   throw CLI::ValidationError("--checkpoint-every",
                                              "expects a positive step count or auto, got " + v);
               cfg.checkpoint_every = n;
           },
           "Write a checkpoint every N steps (also at the end of the run), or 'auto': every "
           "sqrt(2 C M) s of wall time (Young/Daly) from the measured checkpoint cost C and the "
           "run's MTBF M = --mtbf / nodes")
        ->type_name("N|auto");
    app.add_option("--mtbf", cfg.mtbf_hours,
                   "With --checkpoint-every auto: mean time between failures of one node, hours")
        ->check(CLI::PositiveNumber);
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
    app.add_flag("--av-switch", cfg.av_switch,
                 "Per-particle artificial viscosity (Morris & Monaghan): alpha between "
                 "--alpha-min and --alpha, raised by compression");
    app.add_flag("--volume-elements", cfg.volume_elements,
                 "Generalised volume elements X = (m/rho)^0.7 instead of standard SPH volumes");
    app.add_option("--conductivity", cfg.conductivity,
                   "Artificial conductivity coefficient alpha_u (Price 2008); 0 is off")
        ->check(CLI::Range(0.0, 10.0))
        ->capture_default_str();
    app.add_flag("--av-limiter", cfg.av_limiter,
                 "Artificial viscosity from velocities reconstructed linearly to each pair's "
                 "midpoint with a van Leer slope limiter (Rosswog 2015): no dissipation in "
                 "smooth compression, full at shocks");
    app.add_option("--alpha-min", cfg.alpha_min, "AV switch: smallest alpha")
        ->check(CLI::Range(0.0, 10.0))
        ->capture_default_str();
    app.add_option("--G", cfg.G,
                   "Gravitational constant: self-gravity on the tree (SPEC 8) for any case in an "
                   "open box; 0 turns it off (default: the case's, 1 for evrard, else off)")
        ->check(CLI::Range(0.0, 1e300));
    app.add_option("--theta", cfg.theta, "Gravity: Barnes-Hut opening angle")
        ->check(CLI::Range(0.05, 0.95))
        ->capture_default_str();
    app.add_option("--accel-eps", cfg.accel_eps,
                   "Gravity: time step at most sqrt(eps h / |a|) per particle")
        ->check(CLI::Range(1e-6, 10.0))
        ->capture_default_str();
    app.add_option("--on-sdc", cfg.on_sdc,
                   "Silent data corruption (state changed between steps, broken invariants, "
                   "conservation watchdog): rollback to the last verified state (see "
                   "--sdc-rollback-store), abort, or off (no checks)")
        ->check(CLI::IsMember({"rollback", "abort", "off"}))
        ->capture_default_str();
    app.add_option("--sdc-rollback-store", cfg.sdc_rollback_store,
                   "Where --on-sdc rollback keeps the verified state (every 10 steps): disk "
                   "(one file per rank, ~112 B/particle, in --sdc-rollback-dir, removed at the "
                   "end) or memory (a copy of the state: ~112 B/particle more RAM, no I/O)")
        ->check(CLI::IsMember({"memory", "disk"}))
        ->capture_default_str();
    app.add_option("--sdc-rollback-dir", cfg.sdc_rollback_dir,
                   "Directory of the disk rollback point, e.g. node-local scratch on a cluster "
                   "(default: the --out directory)");
    app.add_option("--inject-fault", cfg.inject_fault,
                   "Testing: flip bit BIT of state field FIELD of particle ID at the start of "
                   "step STEP, once (STEP:FIELD:ID:BIT)");
    app.add_option("--threads", cfg.threads, "OpenMP threads (default: OMP_NUM_THREADS or all)")
        ->check(CLI::Range(1, 4096));
    app.add_option(
        "--param", cfg.case_params,
        "Case parameter KEY=VALUE (repeatable): sedov gamma, energy, width, u0, dt0, "
        "t_end; noh gamma, radius, speed, u0, dt0, t_end; evrard gamma, mass, radius, u0 "
        "(in G M / R), dt0, t_end; square-patch omega, sound_speed, dt0, t_end");
    app.add_flag("--lattice", cfg.lattice,
                 "sedov, noh, evrard: start from a regular lattice instead of a relaxed glass");
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

// `exasph glass`: make a periodic glass block and report its density scatter.
struct GlassCommand {
    exasph::GlassParams params;
    std::string out = "glass.h5";
};

void add_glass_command(CLI::App& app, GlassCommand& gc) {
    auto* sub = app.add_subcommand("glass", "Make a relaxed periodic glass in [-0.5, 0.5)^3 "
                                            "(initial-conditions layout, usable with --init)");
    sub->add_option("-n", gc.params.side, "Particles per axis")
        ->check(CLI::Range(8, 400))
        ->capture_default_str();
    sub->add_option("--out", gc.out, "Output file")->capture_default_str();
    sub->add_option("--ng0", gc.params.ng0, "Target number of neighbours")
        ->check(CLI::Range(10.0, 1000.0))
        ->capture_default_str();
    sub->add_option("--tolerance", gc.params.tolerance, "Target relative density scatter")
        ->check(CLI::Range(1e-4, 0.5))
        ->capture_default_str();
    sub->add_option("--max-steps", gc.params.max_steps, "Relaxation steps at most")
        ->check(CLI::Range(1, 1000000))
        ->capture_default_str();
}

int run_glass(const GlassCommand& gc) {
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    auto g = exasph::make_glass(gc.params, MPI_COMM_WORLD);
    exasph::write_glass(gc.out, g, gc.params.ng0, MPI_COMM_WORLD);
    if (rank == 0)
        std::printf("glass %s: %d^3 particles, density scatter %.4f %% after %lld steps\n",
                    gc.out.c_str(), gc.params.side, 100 * g.scatter, (long long)g.steps);
    return 0;
}

// `exasph exact sedov|noh --t T`: the exact solution as a table of r, rho, v, P, u.
struct ExactCommand {
    std::string problem;
    double t = 0.09;
    double gamma = 5.0 / 3.0;
    double energy = 1.0;
    double rmax = 0.5;
    int points = 200;
};

void add_exact_command(CLI::App& app, ExactCommand& ec) {
    auto* sub = app.add_subcommand("exact", "Print an exact solution (r, rho, v, P, u)");
    sub->add_option("problem", ec.problem, "sedov or noh")
        ->required()
        ->check(CLI::IsMember({"sedov", "noh"}));
    sub->add_option("--t", ec.t, "Time")->check(sign_check(false))->capture_default_str();
    sub->add_option("--gamma", ec.gamma, "Adiabatic index")
        ->check(CLI::Range(1.01, 6.9))
        ->capture_default_str();
    sub->add_option("--energy", ec.energy, "Sedov: blast energy (rho = 1)")
        ->check(sign_check(false))
        ->capture_default_str();
    sub->add_option("--rmax", ec.rmax, "Largest radius printed")
        ->check(sign_check(false))
        ->capture_default_str();
    sub->add_option("--points", ec.points, "Number of radii")
        ->check(CLI::Range(2, 1000000))
        ->capture_default_str();
}

int run_exact(const ExactCommand& ec) {
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    if (rank != 0) return 0;
    if (ec.problem == "sedov") {
        exasph::SedovSolution s(ec.gamma);
        std::printf("# Sedov-Taylor, gamma %.6g, E %.6g, rho1 1, t %.6g: xi0 %.6f, shock radius "
                    "%.6f, post-shock density %.6f\n",
                    ec.gamma, ec.energy, ec.t, s.xi0(), s.shock_radius(ec.energy, 1, ec.t),
                    (ec.gamma + 1) / (ec.gamma - 1));
        std::printf("# r rho v P u\n");
        for (int i = 0; i < ec.points; ++i) {
            double r = ec.rmax * (i + 0.5) / ec.points;
            auto st = s.at(r, ec.t, ec.energy, 1.0);
            std::printf("%.8e %.8e %.8e %.8e %.8e\n", r, st.rho, st.v, st.p, st.u);
        }
        return 0;
    }
    exasph::NohSolution n{ec.gamma, 1.0, 1.0};
    std::printf("# Noh, gamma %.6g, rho0 1, v0 -1, t %.6g: shock radius %.6f, post-shock density "
                "%.6f\n",
                ec.gamma, ec.t, n.shock_radius(ec.t), n.post_shock_density());
    std::printf("# r rho v P u\n");
    for (int i = 0; i < ec.points; ++i) {
        double r = ec.rmax * (i + 0.5) / ec.points;
        auto st = n.at(r, ec.t);
        std::printf("%.8e %.8e %.8e %.8e %.8e\n", r, st.rho, st.v, st.p, st.u);
    }
    return 0;
}

int main(int argc, char** argv) {
    exasph::map_large_blocks();
    int provided = 0;
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
    try {
        int code = -1;
        if (app.got_subcommand("glass")) code = run_glass(glass_cmd);
        if (app.got_subcommand("exact")) code = run_exact(exact_cmd);
        if (code >= 0) {
            MPI_Finalize();
            return code;
        }
    } catch (const exasph::Error& e) {
        return finish_with_error(e.what(), e.exit_code(), e.all_ranks());
    }
    if (!cfg.restart_file.empty()) {
        for (const char* opt :
             {"--init", "-n", "--ng0", "--ngmax", "--kernel-exponent", "--courant", "--alpha",
              "--global-bucket", "--leaf-size", "--curve", "--av-switch", "--alpha-min",
              "--volume-elements", "--conductivity", "--av-limiter"})
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
