#pragma once
// The subcommands of the command line: `exasph glass`, `exasph exact`, `exasph render` and
// `exasph options`.
#include <cstdio>
#include <string>

#include "exasph/util/mpi.hpp"
#include <CLI/CLI.hpp>

#include "cli_app.hpp"
#include "exasph/exact/noh.hpp"
#include "exasph/exact/sedov.hpp"
#include "exasph/glass/glass.hpp"
#include "options_command.hpp"
#include "render_command.hpp"

// `exasph glass`: make a periodic glass block and report its density scatter.
struct GlassCommand {
    exasph::GlassParams params;
    std::string out = "glass.h5";
};

inline void add_glass_command(CLI::App& app, GlassCommand& gc) {
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

inline int run_glass(const GlassCommand& gc) {
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

inline void add_exact_command(CLI::App& app, ExactCommand& ec) {
    auto* sub = app.add_subcommand("exact", "Print an exact solution (r, rho, v, P, u)");
    sub->add_option("problem", ec.problem, "sedov or noh")
        ->required()
        ->check(CLI::IsMember({"sedov", "noh"}));
    sub->add_option("--t", ec.t, "Time")
        ->check(exasph::cli::sign_check(false))
        ->capture_default_str();
    sub->add_option("--gamma", ec.gamma, "Adiabatic index")
        ->check(CLI::Range(1.01, 6.9))
        ->capture_default_str();
    sub->add_option("--energy", ec.energy, "Sedov: blast energy (rho = 1)")
        ->check(exasph::cli::sign_check(false))
        ->capture_default_str();
    sub->add_option("--rmax", ec.rmax, "Largest radius printed")
        ->check(exasph::cli::sign_check(false))
        ->capture_default_str();
    sub->add_option("--points", ec.points, "Number of radii")
        ->check(CLI::Range(2, 1000000))
        ->capture_default_str();
}

// The table of an exact solution: `state(r)` at ec.points radii up to ec.rmax.
template <class State>
void print_table(const ExactCommand& ec, State state) {
    std::printf("# r rho v P u\n");
    for (int i = 0; i < ec.points; ++i) {
        const double r = ec.rmax * (i + 0.5) / ec.points;
        const auto st = state(r);
        std::printf("%.8e %.8e %.8e %.8e %.8e\n", r, st.rho, st.v, st.p, st.u);
    }
}

inline void print_sedov(const ExactCommand& ec) {
    exasph::SedovSolution s(ec.gamma);
    std::printf("# Sedov-Taylor, gamma %.6g, E %.6g, rho1 1, t %.6g: xi0 %.6f, shock radius "
                "%.6f, post-shock density %.6f\n",
                ec.gamma, ec.energy, ec.t, s.xi0(), s.shock_radius(ec.energy, 1, ec.t),
                (ec.gamma + 1) / (ec.gamma - 1));
    print_table(ec, [&](double r) { return s.at(r, ec.t, ec.energy, 1.0); });
}

inline void print_noh(const ExactCommand& ec) {
    exasph::NohSolution n{ec.gamma, 1.0, 1.0};
    std::printf("# Noh, gamma %.6g, rho0 1, v0 -1, t %.6g: shock radius %.6f, post-shock density "
                "%.6f\n",
                ec.gamma, ec.t, n.shock_radius(ec.t), n.post_shock_density());
    print_table(ec, [&](double r) { return n.at(r, ec.t); });
}

inline int run_exact(const ExactCommand& ec) {
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    if (rank != 0) return 0;
    ec.problem == "sedov" ? print_sedov(ec) : print_noh(ec);
    return 0;
}

// The whole command line: the run's options (cli_app.hpp) and the subcommands. Used by
// exasph.cpp and the command-line fuzzer.
struct CommandLine {
    exasph::Config cfg;
    CLI::App app{"exasph: smoothed-particle hydrodynamics (SPH-EXA mini-app physics); "
                 "runs alone or under mpirun",
                 "exasph"};
    GlassCommand glass;
    ExactCommand exact;
    RenderCommand render;
    std::string config_file; // --config (apps/config_file.hpp)
    CommandLine() {
        exasph::cli::add_options(app, cfg);
        app.add_option("--config", config_file,
                       "Run parameters from a TOML file, keys as in an output's run.toml (every "
                       "run writes one; the command line overrides the file)")
            ->check(CLI::ExistingFile)
            ->type_name("FILE.toml");
        add_glass_command(app, glass);
        add_exact_command(app, exact);
        add_render_command(app, render);
        add_options_command(app);
        app.require_subcommand(0, 1);
    }
};
