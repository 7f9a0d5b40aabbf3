#pragma once
#include <cmath>
#include <csignal>
#include <filesystem>
#include <iostream>
#include <memory>
#include <ostream>
#include <string>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "exasph/util/mpi.hpp"

#include "exasph/build_info.hpp"
#include "exasph/config/run_file.hpp"
#include "exasph/config/validate.hpp"
#include "exasph/io/checkpoint.hpp"
#include "exasph/io/csv_table.hpp"
#include "exasph/io/snapshot.hpp"
#include "exasph/io/xdmf.hpp"
#include "exasph/run/backend.hpp"
#include "exasph/run/diagnostics_table.hpp"
#include "exasph/run/output_schedule.hpp"
#include "exasph/run/run_report.hpp"
#include "exasph/run/setup.hpp"
#include "exasph/util/memory.hpp"

namespace exasph {

// Opens diagnostics.csv on rank 0 (appending when a restart continues in the same directory);
// every rank learns whether that worked (start-up broadcast).
// A restart (append) continues the table after step `restart_step` (keep_rows_through).
inline std::unique_ptr<CsvTable> open_diagnostics(const Config& cfg, bool root, bool append,
                                                  std::int64_t restart_step) {
    std::unique_ptr<CsvTable> csv;
    std::string err;
    if (root) {
        std::filesystem::path dir(cfg.out_dir);
        std::error_code ec;
        std::filesystem::create_directories(dir, ec);
        if (ec)
            err = "--out: cannot create directory '" + cfg.out_dir + "': " + ec.message();
        else {
            try {
                if (append) keep_rows_through(dir / "diagnostics.csv", restart_step);
                csv = std::make_unique<CsvTable>(
                    dir / "diagnostics.csv", append,
                    diagnostics_columns(cfg.timesteps == TimeStepping::block));
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

// DIR/run.toml (rank 0): the run's parameters as resolved, which --config reads back
// (config/run_file.hpp); written under a temporary name and renamed.
inline void write_run_file(const Config& cfg) {
    const std::string path = (std::filesystem::path(cfg.out_dir) / "run.toml").string();
    write_text_file_atomically(path, run_file_text(cfg, version_text()));
}

namespace detail {
inline volatile std::sig_atomic_t g_stop_signal = 0;
extern "C" inline void on_stop_signal(int signum) {
    g_stop_signal = signum;
}
} // namespace detail

// A whole simulation as configured, on all ranks of MPI_COMM_WORLD, its SPH passes on launcher
// L (run/backend.hpp): setup (constructor), the loop of steps with its outputs (loop()), the
// summary. Rank 0 prints the header, one row per step and the summary.
template <class L>
class RunDriver {
  public:
    RunDriver(Config cfg, std::ostream& out, const std::string& backend)
        : cfg_(std::move(cfg)), out_(out) {
        validate_config(cfg_);
#ifdef _OPENMP
        if (cfg_.threads > 0) omp_set_num_threads(cfg_.threads);
#endif
        MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
        MPI_Comm_size(MPI_COMM_WORLD, &nranks_);
        auto start = start_run<L>(cfg_, MPI_COMM_WORLD, &std::cout);
        sim_ = std::move(start.sim);
        units_ = start.units;
        cfg_.G = sim_->gravitational_constant(); // outputs record the G the run uses
        cfg_.stir_mach = sim_->stir_mach();      // and the stirring
        fields_ = run_snapshot_fields(cfg_, sim_->particles());
        t_end_ = cfg_.t_end > 0 ? cfg_.t_end : (cfg_.steps < 0 ? start.case_t_end : -1.0);
        if (t_end_ <= 0 && cfg_.steps < 0)
            throw input_error("no end: give -s STEPS or --t-end T (the initial conditions set "
                              "none)",
                              true);
        csv_ = open_diagnostics(cfg_, root(), !cfg_.restart_file.empty(), sim_->step_count());
        if (root()) write_run_file(cfg_);
        if (root()) print_header(out_, cfg_, *sim_, nranks_, t_end_, backend);
        if (t_end_ > 0) sim_->set_end_time(t_end_);
        schedule_ = std::make_unique<OutputSchedule>(cfg_, sim_->time(), auto_checkpoint_mtbf());
    }

    // Steps until the end, a signal or an error (thrown as Error). Returns the exit code.
    int loop() {
        detail::g_stop_signal = 0;
        std::signal(SIGINT, detail::on_stop_signal);
        std::signal(SIGTERM, detail::on_stop_signal);
        wall0_ = wall_seconds();
        step0_ = sim_->step_count();
        collectives0_ = sim_->collective_count(), syncs0_ = sim_->domain_syncs();
        while (!done()) {
            if (detail::g_stop_signal) sim_->raise_flag(kStopRequested);
            if (root() && schedule_->clock_due(wall_seconds()))
                sim_->raise_flag(kCheckpointByClock);
            const double w0 = wall_seconds();
            sim_->step();
            if (sim_->recovered()) {
                report_recovery();
                continue;
            }
            check_step();
            if (sim_->step_count() == step0_ + 1) { // the halo line leaves out the first step
                const CommRecord& rec = sim_->domain().comm_record();
                first_halo_ = {rec.halo_exposed_seconds(), rec.halo_behind_compute_seconds()};
            }
            updates_ += sim_->diagnostics().work.active; // global steps: every step's the same
            if (sim_->summed()) { // --diagnostics-every: the summed steps stand for all
                compute_.sum += sim_->diagnostics().work.compute_sum;
                compute_.max += sim_->diagnostics().work.compute_max;
                ++compute_steps_;
            }
            if (const std::string notice = sim_->safety().take_notice(); root() && !notice.empty())
                out_ << "sdc watchdog: " << notice << "\n";
            if (root() && sim_->summed()) {
                const double mean = (wall_seconds() - wall0_) / double(sim_->step_count() - step0_);
                print_step(out_, *sim_, wall_seconds() - w0, mean, t_end_);
                csv_->write(diagnostics_row(sim_->diagnostics(), sim_->phase_times(),
                                            cfg_.timesteps == TimeStepping::block));
            }
            if (schedule_->snapshot_due(sim_->step_count(), sim_->time())) snapshot();
            const bool stop = sim_->flag(kStopRequested);
            if (schedule_->checkpoint_due(sim_->step_count()) || sim_->flag(kCheckpointByClock) ||
                (stop && kHaveHdf5)) // without HDF5: no checkpoint
                checkpoint();
            if (stop) {
                if (root()) out_ << "stopped by a signal after step " << sim_->step_count() << "\n";
                return 128 + (detail::g_stop_signal ? int(detail::g_stop_signal) : SIGTERM);
            }
        }
        if (schedule_->checkpointing() && last_checkpoint_ != sim_->step_count()) checkpoint();
        return 0;
    }

    // Rank 0 prints the summary (peak memory summed over the ranks: an output-time collective).
    void summary() {
        const double wall = wall_seconds() - wall0_ - output_wall_;
        double rss = double(peak_rss_bytes());
        MPI_Allreduce(MPI_IN_PLACE, &rss, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
        const double steps = double(sim_->step_count() - step0_);
        const CommRecord& rec = sim_->domain().comm_record();
        const CommSummary comm = summarise_comm(rec, MPI_COMM_WORLD, first_halo_);
        if (cfg_.comm_report)
            write_comm_matrix(std::filesystem::path(cfg_.out_dir) / "comm_matrix.csv", rec, steps,
                              MPI_COMM_WORLD);
        if (root()) print_summary(out_, *sim_, steps, updates_, wall, output_wall_, nranks_, rss);
        if (root() && (cfg_.sync_every > 1 || cfg_.diagnostics_every > 1))
            out_ << strprintf("collectives: %.2f per step; domain syncs in %lld of %.0f steps, "
                              "diagnostics summed in %.0f\n",
                              double(sim_->collective_count() - collectives0_) / steps,
                              (long long)(sim_->domain_syncs() - syncs0_), steps, compute_steps_);
        if (root() && nranks_ > 1)
            print_comm_summary(out_, comm, sim_->diagnostics(), steps,
                               {compute_.sum / nranks_ * steps / std::max(compute_steps_, 1.0),
                                compute_.max * steps / std::max(compute_steps_, 1.0)},
                               sim_->imbalance());
    }

  private:
    bool root() const {
        return rank_ == 0;
    }

    bool done() const {
        if (cfg_.steps >= 0 && sim_->step_count() >= cfg_.steps) return true;
        return t_end_ > 0 && sim_->time() >= t_end_ * (1 - 1e-12);
    }

    // --checkpoint-every auto: the run's MTBF from the nodes' (0 otherwise).
    double auto_checkpoint_mtbf() {
        if (!cfg_.checkpoint_auto) return 0;
        const int nodes = count_nodes(MPI_COMM_WORLD);
        mtbf_ = run_mtbf_seconds(cfg_.mtbf_hours, nodes);
        if (root())
            out_ << strprintf("checkpoints: auto (Young/Daly sqrt(2 C M)), MTBF %g h per node x "
                              "%d node(s): M = %.1f s\n",
                              cfg_.mtbf_hours, nodes, mtbf_);
        return mtbf_;
    }

    void report_recovery() {
        if (!sim_->safety().detail().empty())
            std::cerr << "exasph: rank " << rank_ << ": " << sim_->safety().detail() << "\n";
        if (root()) out_ << "silent data corruption: " << sim_->safety().summary() << "\n";
    }

    // A step whose energy is not finite ends the run (naming the particle when a state field
    // went bad); a list above ngmax is reported once.
    void check_step() {
        const auto& d = sim_->diagnostics();
        if (!std::isfinite(d.etot)) {
            sim_->particles().validate();
            throw Error("total energy is not finite at step " + std::to_string(d.step), 1, true);
        }
        if (!warned_ngmax_ && sim_->max_list_length() > std::uint32_t(cfg_.ngmax)) {
            std::cerr << "warning: rank " << rank_ << ": a particle has " << sim_->max_list_length()
                      << " neighbours, more than ngmax = " << cfg_.ngmax
                      << "; lists were enlarged (no truncation)\n";
            warned_ngmax_ = true;
        }
    }

    void snapshot() {
        const double w = wall_seconds();
        const std::string path =
            write_snapshot(sim_->output_state(), cfg_, units_, fields_, MPI_COMM_WORLD);
        output_wall_ += wall_seconds() - w;
        if (root()) out_ << strprintf("snapshot %s (%.3f s)\n", path.c_str(), wall_seconds() - w);
    }

    void checkpoint() {
        const double w = wall_seconds();
        const std::string path =
            write_checkpoint(sim_->output_state(), cfg_, units_, MPI_COMM_WORLD);
        const double cost = wall_seconds() - w;
        output_wall_ += cost;
        const double interval = schedule_->checkpoint_written(wall_seconds(), cost);
        last_checkpoint_ = sim_->step_count();
        sim_->sync_next_step(); // as a restart from it does (--sync-every: bit for bit)
        if (root()) out_ << strprintf("checkpoint %s (%.3f s)\n", path.c_str(), cost);
        if (root() && interval > 0)
            out_ << strprintf("checkpoint interval: C = %.3f s, M = %.1f s -> every %.1f s of "
                              "wall time\n",
                              cost, mtbf_, interval);
    }

    Config cfg_;
    std::ostream& out_;
    int rank_ = 0, nranks_ = 1;
    std::unique_ptr<Simulation<double, L>> sim_;
    std::string units_;
    std::vector<Field> fields_;
    double t_end_ = -1, mtbf_ = 0, wall0_ = 0, output_wall_ = 0;
    double updates_ = 0;                     // particle updates since this process started stepping
    std::array<double, 2> first_halo_{0, 0}; // halo seconds after the first step (summary)
    SumMax compute_{0, 0}; // compute seconds per step, summed over ranks / of the slowest, summed
    double compute_steps_ = 0; // the steps whose diagnostics were summed
    std::unique_ptr<CsvTable> csv_;
    std::unique_ptr<OutputSchedule> schedule_;
    std::int64_t step0_ = 0, last_checkpoint_ = -1, collectives0_ = 0, syncs0_ = 0;
    bool warned_ngmax_ = false;
};

template <class L>
int run_on(Config cfg, std::ostream& out, const std::string& backend) {
    RunDriver<L> driver(std::move(cfg), out, backend);
    const int code = driver.loop();
    if (code == 0) driver.summary();
    return code;
}

// Runs a whole simulation on the backend that --backend picks; returns the exit code (errors
// are thrown as Error).
inline int run(Config cfg, std::ostream& out) {
    const BackendPick pick = pick_backend(cfg.backend, MPI_COMM_WORLD);
#if EXASPH_HAVE_CUDA
    if (pick.backend == Backend::cuda) return run_on<CudaLauncher>(std::move(cfg), out, pick.line);
#endif
    return run_on<OmpLauncher>(std::move(cfg), out, pick.line);
}

} // namespace exasph
