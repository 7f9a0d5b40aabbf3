#pragma once
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <ostream>
#include <string>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "exasph/config/summary.hpp"
#include "exasph/io/comm_matrix.hpp"
#include "exasph/run/version.hpp"
#include "exasph/sim/simulation.hpp"

// What rank 0 prints of a run: the header, one row per step and the summary.
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

// Version, case, particles, ranks x threads, every physics parameter and the run-control
// parameters that differ from their defaults (config/summary.hpp), the end and the column titles.
template <class T, class L>
void print_header(std::ostream& out, const Config& cfg, const Simulation<T, L>& sim, int nranks,
                  double t_end, const std::string& backend) {
    const bool restart = !cfg.restart_file.empty();
    out << version_text() << "\n";
    out << strprintf("%s %s, %llu particles, %d ranks x %d threads\n",
                     restart ? "restart of" : "case", cfg.init.c_str(),
                     (unsigned long long)sim.diagnostics().n, nranks, thread_count());
    out << "backend: " << backend << "\n";
    out << "physics: " << physics_summary(cfg) << "\n";
    const std::string control = run_control_summary(cfg);
    if (!control.empty()) out << "run control: " << control << "\n";
    if (restart)
        out << strprintf("continuing from %s at step %lld, t = %.6e\n", cfg.restart_file.c_str(),
                         (long long)sim.step_count(), sim.time());
    out << (t_end > 0 ? strprintf("until t = %g", t_end) : std::string())
        << (t_end > 0 && cfg.steps >= 0 ? " or " : "")
        << (cfg.steps >= 0 ? strprintf("until step %lld", (long long)cfg.steps) : std::string())
        << ", output in " << cfg.out_dir << "/\n";
    out << strprintf("%6s %12s %11s %16s %16s %6s %11s %9s %9s\n", "step", "t", "dt", "E_tot",
                     "L_z", "imbal", "halo avg/mx", "s/step", "ETA s");
}

// One step: t, dt, E_tot, L_z, imbalance, halo ratios, wall seconds, the estimated time left.
template <class T, class L>
void print_step(std::ostream& out, const Simulation<T, L>& sim, double wall_step, double mean_wall,
                double t_end) {
    const auto& d = sim.diagnostics();
    const std::string eta = t_end > 0 && d.dt > 0
                                ? strprintf("%9.1f", (t_end - d.time) / d.dt * mean_wall)
                                : strprintf("%9s", "-");
    out << strprintf("%6lld %12.6e %11.4e %16.9e %16.9e %6.3f %5.2f/%5.2f %9.3f ",
                     (long long)d.step, d.time, d.dt, d.etot, d.angular_momentum[2],
                     sim.imbalance(), d.halo_ratio_mean, d.halo_ratio_max, wall_step)
        << eta
        << (d.l1_rho >= 0 ? strprintf("  L1(rho) %.4f rho_max %.3f", d.l1_rho, d.rho_max)
                          : std::string())
        << "\n";
}

// Steps, wall time, particle-steps per second (per core), peak memory per particle and the
// seconds per step of each phase.
// `updates`: the particles advanced, summed over the steps (with block time steps, the active
// ones of each sub-step).
template <class T, class L>
void print_summary(std::ostream& out, const Simulation<T, L>& sim, double steps, double updates,
                   double wall, double output_wall, int nranks, double rss_bytes) {
    const double n = double(sim.diagnostics().n);
    const double rate = steps > 0 ? updates / wall : 0.0;
    out << strprintf("done: %lld steps, t = %.6e, wall %.3f s (+ %.3f s output)\n",
                     (long long)steps, sim.time(), wall, output_wall);
    if (const auto bound = sim.block_work_bound())
        out << strprintf("block time steps: %.4e particle updates (%.1f per particle); with the "
                         "limits at each block's start, global steps would take %.1f steps and "
                         "every particle at its own limit %.1f updates (at most %.2fx fewer)\n",
                         updates, updates / n, bound->global_steps, bound->own_limit_updates,
                         bound->global_steps / bound->own_limit_updates);
    out << strprintf("particle-steps/s %.4e, per core %.4e (%d ranks x %d threads), "
                     "peak RSS %.1f B/particle (all ranks)\n",
                     rate, rate / (nranks * thread_count()), nranks, thread_count(), rss_bytes / n);
    out << "seconds per step by phase (rank 0):";
    for (std::size_t i = 0; i < kNumPhases; ++i)
        out << strprintf(" %s %.4f", std::string(kPhaseNames[i]).c_str(),
                         steps > 0 ? sim.total_phase_times()[i] / steps : 0.0);
    out << "\n";
}

// Several ranks: the point-to-point traffic per rank (CommRecord, over this run's steps) and the
// last step's halo ratio; the load balance: each step's compute seconds (outside MPI waits) of
// the slowest rank and of the mean rank, summed over the steps (`compute`: mean rank, slowest).
inline void print_comm_summary(std::ostream& out, const CommSummary& c, const Diagnostics& d,
                               double steps, SumMax compute, double count_imbalance) {
    const double per = steps > 0 ? 1.0 / (steps * 1e6) : 0.0; // MB per step
    out << strprintf("communication: halo peers per rank mean %.1f max %.0f; halo ratio mean "
                     "%.3f max %.3f (last step); MB sent per step: halos per rank mean %.3g max "
                     "%.3g, migration %.3g, gravity %.3g (all ranks)\n",
                     c.halo_peers_mean, c.halo_peers_max, d.halo_ratio_mean, d.halo_ratio_max,
                     c.halo_bytes_mean * per, c.halo_bytes_max * per, c.migration_bytes * per,
                     c.gravity_bytes * per);
    const double later = steps > 1 ? 1.0 / (steps - 1) : 0.0; // per step after the first
    out << strprintf("halo exchanges of the SPH passes: %.4g s per step in them (packing, "
                     "waiting, unpacking), %.4g s in flight behind computation (mean rank, steps "
                     "after the first)\n",
                     c.halo_exposed * later, c.halo_behind_compute * later);
    const double mean = compute.sum, lost = compute.max > 0 ? 1 - mean / compute.max : 0;
    out << strprintf("load balance: compute seconds per step, slowest rank %.4g, mean %.4g "
                     "(max/mean %.3f: %.1f %% of the compute time waits for the slowest); owned "
                     "particles max/mean %.3f (last step)\n",
                     steps > 0 ? compute.max / steps : 0.0, steps > 0 ? mean / steps : 0.0,
                     mean > 0 ? compute.max / mean : 1.0, 100 * lost, count_imbalance);
}

} // namespace exasph
