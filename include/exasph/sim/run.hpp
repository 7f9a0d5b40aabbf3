#pragma once
#include <cmath>
#include <csignal>
#include <cstdarg>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <ostream>
#include <string>

#ifdef _OPENMP
#include <omp.h>
#endif

#include <mpi.h>

#include "exasph/build_info.hpp"
#include "exasph/sim/cases.hpp"
#include "exasph/sim/checkpoint.hpp"
#include "exasph/sim/checkpoint_interval.hpp"
#include "exasph/sim/simulation.hpp"
#include "exasph/sim/snapshot.hpp"
#include "exasph/util/memory.hpp"

namespace exasph {

inline std::string strprintf(const char* fmt, ...) {
    char buf[512];
    va_list ap;
    va_start(ap, fmt);
    std::vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    return buf;
}

inline int thread_count() {
#ifdef _OPENMP
    return omp_get_max_threads();
#else
    return 1;
#endif
}

// diagnostics.csv: one row per step with the SPEC 10 quantities and the phase times.
class DiagnosticsCsv {
  public:
    DiagnosticsCsv(const std::filesystem::path& path, bool append)
        : out_(path, append ? std::ios::app : std::ios::trunc) {
        if (!out_) throw Error("cannot write " + path.string(), 3);
        if (append && std::filesystem::file_size(path) > 0) return;
        out_ << "step,time,dt,n,ekin,eint,epot,etot,px,py,pz,lx,ly,lz,nc_min,nc_mean,nc_max,"
                "rho_max,l1_rho";
        for (auto name : kPhaseNames) out_ << ",t_" << name;
        out_ << "\n";
    }
    void write(const Diagnostics& d, const std::array<double, kNumPhases>& phases) {
        out_ << strprintf("%lld,%.17g,%.17g,%llu", (long long)d.step, d.time, d.dt,
                          (unsigned long long)d.n);
        for (double v : {d.ekin, d.eint, d.epot, d.etot, d.momentum[0], d.momentum[1],
                         d.momentum[2], d.angular_momentum[0], d.angular_momentum[1],
                         d.angular_momentum[2], d.nc_min, d.nc_mean, d.nc_max, d.rho_max, d.l1_rho})
            out_ << strprintf(",%.17g", v);
        for (double t : phases) out_ << strprintf(",%.6e", t);
        out_ << "\n";
        out_.flush();
        if (!out_) throw Error("write to diagnostics.csv failed", 3);
    }

  private:
    std::ofstream out_;
};

// Opens diagnostics.csv on rank 0 (appending when a restart continues in the same directory);
// every rank learns whether that worked (start-up broadcast).
inline std::unique_ptr<DiagnosticsCsv> open_diagnostics(const Config& cfg, bool root, bool append) {
    std::unique_ptr<DiagnosticsCsv> csv;
    std::string err;
    if (root) {
        std::filesystem::path dir(cfg.out_dir);
        std::error_code ec;
        std::filesystem::create_directories(dir, ec);
        if (ec)
            err = "--out: cannot create directory '" + cfg.out_dir + "': " + ec.message();
        else {
            try {
                csv = std::make_unique<DiagnosticsCsv>(dir / "diagnostics.csv", append);
            } catch (const Error& e) {
                err = e.what();
            }
        }
    }
    int ok = err.empty();
    MPI_Bcast(&ok, 1, MPI_INT, 0, MPI_COMM_WORLD);
    if (!ok) throw Error(root ? err : "cannot write the output directory", 3, true);
    return csv;
}

namespace detail {
inline volatile std::sig_atomic_t g_stop_signal = 0;
extern "C" inline void on_stop_signal(int signum) {
    g_stop_signal = signum;
}
} // namespace detail

// When snapshots and checkpoints are due (-w, --checkpoint-every N|auto, --checkpoint-minutes).
class OutputSchedule {
  public:
    // `mtbf_seconds`: the run's MTBF, used by --checkpoint-every auto.
    OutputSchedule(const Config& cfg, double t_now, double mtbf_seconds = 0)
        : cfg_(cfg), mtbf_(mtbf_seconds) {
        if (cfg.snapshot_every_time > 0)
            next_snapshot_time_ =
                (std::floor(t_now / cfg.snapshot_every_time) + 1) * cfg.snapshot_every_time;
        if (cfg.checkpoint_minutes > 0) interval_ = 60.0 * cfg.checkpoint_minutes;
    }
    bool checkpointing() const {
        return cfg_.checkpoint_every > 0 || cfg_.checkpoint_minutes > 0 || cfg_.checkpoint_auto;
    }
    // Wall-clock checkpoints; with auto, the first comes after the first step (it measures C).
    bool clock_due(double wall_now) const {
        if (cfg_.checkpoint_auto && interval_ <= 0) return true;
        return interval_ > 0 && wall_now - last_checkpoint_wall_ >= interval_;
    }
    // Records a checkpoint that took `cost` seconds; with auto, returns the new interval (else 0).
    double checkpoint_written(double wall_now, double cost) {
        last_checkpoint_wall_ = wall_now;
        if (!cfg_.checkpoint_auto) return 0;
        interval_ = young_daly_interval(std::max(cost, 1e-6), mtbf_);
        return interval_;
    }
    bool checkpoint_due(std::int64_t step) const {
        return cfg_.checkpoint_every > 0 && step % cfg_.checkpoint_every == 0;
    }
    // Every N steps, or at the first step at or after each multiple of T.
    bool snapshot_due(std::int64_t step, double t) {
        if (cfg_.snapshot_every_steps > 0) return step % cfg_.snapshot_every_steps == 0;
        if (cfg_.snapshot_every_time <= 0 || t < next_snapshot_time_ * (1 - 1e-12)) return false;
        while (next_snapshot_time_ <= t * (1 + 1e-12))
            next_snapshot_time_ += cfg_.snapshot_every_time;
        return true;
    }

  private:
    const Config& cfg_;
    double mtbf_ = 0;
    double interval_ = 0; // wall seconds between clock checkpoints (0: none)
    double next_snapshot_time_ = 0;
    double last_checkpoint_wall_ = wall_seconds();
};

// Builds the simulation from a test case, an initial-conditions file or a checkpoint.
inline std::unique_ptr<Simulation<double>> make_simulation(Config& cfg, std::string& units,
                                                           double& case_t_end) {
    int rank = 0, nranks = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &nranks);
    if (!cfg.restart_file.empty()) {
        auto cp = read_checkpoint<double>(cfg.restart_file, cfg, MPI_COMM_WORLD);
        units = cp.ic.units;
        case_t_end = cp.ic.t_end;
        return std::make_unique<Simulation<double>>(cfg, std::move(cp.ic), cp.rs);
    }
    auto ic = make_case<double>(cfg, MPI_COMM_WORLD, &std::cout);
    units = ic.units;
    case_t_end = ic.t_end;
    return std::make_unique<Simulation<double>>(cfg, std::move(ic));
}

// Runs a whole simulation as configured on all ranks of MPI_COMM_WORLD; rank 0 prints the
// header, one row per step and a summary. Returns the exit code; errors are thrown as Error.
// Checks the combinations of options the command line cannot (all ranks; input errors).
inline void check_output_options(const Config& cfg) {
    if (cfg.checkpoint_auto && !(cfg.mtbf_hours > 0))
        throw input_error("--checkpoint-every auto needs --mtbf HOURS (the MTBF of one node)",
                          true);
    if (!cfg.checkpoint_auto && cfg.mtbf_hours > 0)
        throw input_error("--mtbf is used only with --checkpoint-every auto", true);
    if (cfg.checkpoint_auto && cfg.checkpoint_minutes > 0)
        throw input_error("--checkpoint-every auto and --checkpoint-minutes exclude each other",
                          true);
}

inline int run(Config cfg, std::ostream& out) {
    check_output_options(cfg);
#ifdef _OPENMP
    if (cfg.threads > 0) omp_set_num_threads(cfg.threads);
#endif
    int rank = 0, nranks = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &nranks);
    const bool root = rank == 0;
    auto fields = snapshot_field_list(cfg.snapshot_fields, cfg.av_limiter);
    std::string units;
    double case_t_end = 0;
    auto sim_ptr = make_simulation(cfg, units, case_t_end);
    Simulation<double>& sim = *sim_ptr;
    cfg.G = sim.gravitational_constant(); // outputs record the G the run uses
    // Optional fields the run does not carry (phi without gravity, alpha without the AV switch)
    // leave the default list; asked for by name they are an error.
    for (Field f : std::vector<Field>(fields)) {
        if (sim.particles().enabled(f)) continue;
        if (!cfg.snapshot_fields.empty())
            throw input_error("-f: field '" + std::string(field_info(f).name) +
                                  "' is not carried by this run (" + optional_field_needs(f) + ")",
                              true);
        std::erase(fields, f);
    }
    const double t_end = cfg.t_end > 0 ? cfg.t_end : (cfg.steps < 0 ? case_t_end : -1.0);
    if (t_end <= 0 && cfg.steps < 0)
        throw input_error("no end: give -s STEPS or --t-end T (the initial conditions set none)",
                          true);
    auto csv = open_diagnostics(cfg, root, !cfg.restart_file.empty());

    const std::uint64_t n = sim.diagnostics().n;
    if (root) {
        out << "exasph " << kVersion << " (" << kBuildInfo << ")\n";
        out << strprintf("%s %s, %llu particles, %d ranks x %d threads, ng0 %g, ngmax %d, "
                         "sinc n %g, courant %g, alpha %g, global bucket %d%s\n",
                         cfg.restart_file.empty() ? "case" : "restart of", cfg.init.c_str(),
                         (unsigned long long)n, nranks, thread_count(), cfg.ng0, cfg.ngmax,
                         cfg.kernel_exponent, cfg.courant, cfg.alpha, cfg.global_bucket,
                         cfg.G > 0 ? strprintf(", gravity G %g theta %g", cfg.G, cfg.theta).c_str()
                                   : "");
        if (!cfg.restart_file.empty())
            out << strprintf("continuing from %s at step %lld, t = %.6e\n",
                             cfg.restart_file.c_str(), (long long)sim.step_count(), sim.time());
        out << (t_end > 0 ? strprintf("until t = %g", t_end) : std::string())
            << (t_end > 0 && cfg.steps >= 0 ? " or " : "")
            << (cfg.steps >= 0 ? strprintf("until step %lld", (long long)cfg.steps) : std::string())
            << ", output in " << cfg.out_dir << "/\n";
        out << strprintf("%6s %12s %11s %16s %16s %6s %11s %9s %9s\n", "step", "t", "dt", "E_tot",
                         "L_z", "imbal", "halo avg/mx", "s/step", "ETA s");
    }
    if (t_end > 0) sim.set_end_time(t_end);
    double mtbf = 0;
    if (cfg.checkpoint_auto) {
        const int nodes = count_nodes(MPI_COMM_WORLD);
        mtbf = run_mtbf_seconds(cfg.mtbf_hours, nodes);
        if (root)
            out << strprintf("checkpoints: auto (Young/Daly sqrt(2 C M)), MTBF %g h per node x %d "
                             "node(s): M = %.1f s\n",
                             cfg.mtbf_hours, nodes, mtbf);
    }
    OutputSchedule schedule(cfg, sim.time(), mtbf);
    detail::g_stop_signal = 0;
    std::signal(SIGINT, detail::on_stop_signal);
    std::signal(SIGTERM, detail::on_stop_signal);
    const double wall0 = wall_seconds();
    const std::int64_t step0 = sim.step_count();
    double output_wall = 0;
    std::int64_t last_checkpoint = -1;
    bool warned_ngmax = false;
    auto done = [&] {
        if (cfg.steps >= 0 && sim.step_count() >= cfg.steps) return true;
        return t_end > 0 && sim.time() >= t_end * (1 - 1e-12);
    };
    auto checkpoint = [&] {
        double w = wall_seconds();
        std::string path = write_checkpoint(sim, cfg, units, MPI_COMM_WORLD);
        const double cost = wall_seconds() - w;
        output_wall += cost;
        const double interval = schedule.checkpoint_written(wall_seconds(), cost);
        last_checkpoint = sim.step_count();
        if (root) out << strprintf("checkpoint %s (%.3f s)\n", path.c_str(), cost);
        if (root && interval > 0)
            out << strprintf("checkpoint interval: C = %.3f s, M = %.1f s -> every %.1f s of wall "
                             "time\n",
                             cost, mtbf, interval);
    };
    while (!done()) {
        if (detail::g_stop_signal) sim.raise_flag(kStopRequested);
        if (root && schedule.clock_due(wall_seconds())) sim.raise_flag(kCheckpointByClock);
        double w0 = wall_seconds();
        sim.step();
        double wstep = wall_seconds() - w0;
        if (sim.recovered()) {
            if (!sim.sdc_detail().empty())
                std::cerr << "exasph: rank " << rank << ": " << sim.sdc_detail() << "\n";
            if (root) out << "silent data corruption: " << sim.sdc_summary() << "\n";
            continue;
        }
        const auto& d = sim.diagnostics();
        if (!std::isfinite(d.etot)) {
            sim.particles().validate(); // names the particle when a state field went bad
            throw Error("total energy is not finite at step " + std::to_string(d.step), 1, true);
        }
        if (!warned_ngmax && sim.max_list_length() > std::uint32_t(cfg.ngmax)) {
            std::cerr << "warning: rank " << rank << ": a particle has " << sim.max_list_length()
                      << " neighbours, more than ngmax = " << cfg.ngmax
                      << "; lists were enlarged (no truncation)\n";
            warned_ngmax = true;
        }
        if (root) {
            double mean_wall = (wall_seconds() - wall0) / double(sim.step_count() - step0);
            std::string eta = t_end > 0 && d.dt > 0
                                  ? strprintf("%9.1f", (t_end - d.time) / d.dt * mean_wall)
                                  : strprintf("%9s", "-");
            out << strprintf("%6lld %12.6e %11.4e %16.9e %16.9e %6.3f %5.2f/%5.2f %9.3f ",
                             (long long)d.step, d.time, d.dt, d.etot, d.angular_momentum[2],
                             sim.imbalance(), d.halo_ratio_mean, d.halo_ratio_max, wstep)
                << eta
                << (d.l1_rho >= 0 ? strprintf("  L1(rho) %.4f rho_max %.3f", d.l1_rho, d.rho_max)
                                  : std::string())
                << "\n";
            csv->write(d, sim.phase_times());
        }
        if (schedule.snapshot_due(sim.step_count(), sim.time())) {
            double w = wall_seconds();
            std::string path = write_snapshot(sim, cfg, units, fields, MPI_COMM_WORLD);
            output_wall += wall_seconds() - w;
            if (root) out << strprintf("snapshot %s (%.3f s)\n", path.c_str(), wall_seconds() - w);
        }
        const bool stop = sim.flag(kStopRequested);
        if (schedule.checkpoint_due(sim.step_count()) || sim.flag(kCheckpointByClock) || stop)
            checkpoint();
        if (stop) {
            if (root) out << "stopped by a signal after step " << sim.step_count() << "\n";
            return 128 + (detail::g_stop_signal ? int(detail::g_stop_signal) : SIGTERM);
        }
    }
    if (schedule.checkpointing() && last_checkpoint != sim.step_count()) checkpoint();
    const double wall = wall_seconds() - wall0 - output_wall;
    const double steps = double(sim.step_count() - step0);
    const double rate = steps > 0 ? double(n) * steps / wall : 0.0;
    const int cores = nranks * thread_count();
    double rss = double(peak_rss_bytes());
    MPI_Allreduce(MPI_IN_PLACE, &rss, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD); // output time
    if (!root) return 0;
    out << strprintf("done: %lld steps, t = %.6e, wall %.3f s (+ %.3f s output)\n",
                     (long long)steps, sim.time(), wall, output_wall);
    out << strprintf("particle-steps/s %.4e, per core %.4e (%d ranks x %d threads), "
                     "peak RSS %.1f B/particle (all ranks)\n",
                     rate, rate / cores, nranks, thread_count(), rss / double(n));
    out << "seconds per step by phase (rank 0):";
    for (std::size_t i = 0; i < kNumPhases; ++i)
        out << strprintf(" %s %.4f", std::string(kPhaseNames[i]).c_str(),
                         steps > 0 ? sim.total_phase_times()[i] / steps : 0.0);
    out << "\n";
    return 0;
}

} // namespace exasph
