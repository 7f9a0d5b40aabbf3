// exasph command line: options -> Config -> run().
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>

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
    app.add_option("--leaf-size", cfg.bucket_size, "Octree leaf size (particles)")
        ->check(CLI::Range(1, 4096))
        ->capture_default_str();
    std::map<std::string, exasph::CurveKind> curves{{"hilbert", exasph::CurveKind::hilbert},
                                                    {"morton", exasph::CurveKind::morton}};
    app.add_option("--curve", cfg.curve, "Space-filling curve: hilbert or morton")
        ->transform(CLI::CheckedTransformer(curves, CLI::ignore_case));
    app.set_version_flag("--version", std::string("exasph ") + exasph::kVersion + " (" +
                                          exasph::kBuildInfo + ")");
}

} // namespace

int main(int argc, char** argv) {
    exasph::Config cfg;
    CLI::App app{"exasph: smoothed-particle hydrodynamics (SPH-EXA mini-app physics)", "exasph"};
    add_options(app, cfg);
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::cerr << "exasph: error: " << e.what() << " (see exasph --help)\n";
        return 2;
    }
    if (cfg.ngmax < cfg.ng0) {
        std::cerr << "exasph: error: --ngmax " << cfg.ngmax << " must be at least --ng0 " << cfg.ng0
                  << "\n";
        return 2;
    }
    try {
        return exasph::run(cfg, std::cout);
    } catch (const exasph::Error& e) {
        std::cout.flush();
        std::cerr << "exasph: error: " << e.what() << "\n";
        return e.exit_code();
    } catch (const std::exception& e) {
        std::cout.flush();
        std::cerr << "exasph: internal error: " << e.what() << "\n";
        return 1;
    }
}
