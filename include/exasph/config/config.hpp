#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "exasph/sfc/curve_kind.hpp"

namespace exasph {

// Closed choices of the command line (their names: config/choices.hpp).
enum class SdcPolicy { rollback, abort, off };     // --on-sdc
enum class RollbackStore { disk, memory };         // --sdc-rollback-store
enum class Scheme { std_sph, ve, wc, pe, sh };     // --scheme (config/scheme.hpp)
enum class BackendChoice { cpu, cuda, automatic }; // --backend (run/backend.hpp)
enum class TimeStepping { global, block };         // --timesteps (sim/block_clock.hpp)
enum class Balance { count, cost };                // --balance (domain/cost_balance.hpp)

// Everything a run is configured with. Each member that the command line sets is declared
// once more, with its flag, help, unit and restart rule, in the parameter table
// (config/parameters.hpp): CLI options, --help, the restart rule, checkpoint attributes and the
// run header all come from that table.
struct Config {
    std::string init = "square-patch"; // case name or initial-conditions file
    int side = 30;                     // particles per axis (-n)
    std::int64_t steps = -1;           // -s; < 0: not given
    double t_end = -1.0;               // --t-end; < 0: not given
    std::string out_dir = "exasph-output";
    bool comm_report = false; // OUT/comm_matrix.csv at the end
    // The formulation: a scheme names the values of the parameters from alpha to
    // volume_elements (config/scheme.hpp); Config{} is the std scheme.
    Scheme scheme = Scheme::std_sph;
    double ng0 = 100;             // target neighbour count (physics.md §2)
    int ngmax = 150;              // neighbour cap: exceeding it is reported
    double kernel_exponent = 6;   // sinc exponent n (physics.md §1)
    double courant = 0.2;         // K_cour (physics.md §7)
    double alpha = 1.0;           // artificial viscosity (physics.md §6); maximum with --av-switch
    bool av_switch = false;       // evolve alpha per particle (Morris & Monaghan)
    double alpha_min = 0.05;      // AV switch: floor of alpha
    double conductivity = 0.0;    // artificial conductivity alpha_u (0: off)
    bool av_limiter = false;      // viscosity from limited midpoint-reconstructed velocities
    bool volume_elements = false; // generalised volume elements X = (m/rho)^0.7
    bool energy_weights = false;  // with them, X = m u (pressure-energy SPH) instead
    double tensile_stress = 0.0;  // artificial stress for negative pressures (Monaghan 2000)
    int tensile_exponent = 4;     // n of the stress's (W(r)/W(dp))^n
    double tensile_stress_positive = 0.0; // the artificial stress's eps for positive pressures
    bool torque_free = false;             // pair forces without net torque (angular momentum)
    bool double_precision = false;        // rho, P, c, P/(Om k^2), C, S, nc in double, not float
    double G = -1.0;        // gravitational constant (--G); < 0: the case's (0: no gravity)
    double theta = 0.5;     // Barnes-Hut opening angle (physics.md §8)
    double accel_eps = 0.2; // gravity time-step factor: dt <= sqrt(accel_eps h / |a|) (§7)
    TimeStepping timesteps = TimeStepping::global; // one global dt, or power-of-two rungs
    bool no_timestep_limiter = false; // testing: block steps without the neighbour limiter
    bool no_halo_overlap = false; // benchmarks: each halo exchange waited for before the next pass
    int gravity_leaf_size = 16;   // gravity-tree leaf size: one interaction list per leaf
    double stir_mach = -1.0;      // --stir-mach; < 0: the case's (0: no stirring)
    int stir_seed = 1;            // --stir-seed: the stirring's random sequence
    SdcPolicy on_sdc = SdcPolicy::rollback; // silent data corruption
    int sdc_rollback_every = 10;            // steps between rollback points
    // Disk by default: the copy in memory would add ~112 B to the ~300 B a particle needs.
    RollbackStore sdc_rollback_store = RollbackStore::disk;
    std::string sdc_rollback_dir;                     // empty: out_dir
    std::string inject_fault;                         // STEP:FIELD:ID:BIT (tests)
    int threads = 0;                                  // 0: OpenMP default
    BackendChoice backend = BackendChoice::automatic; // where the SPH passes run
    int leaf_size = 64;                               // local octree leaf size
    int global_bucket = 128;          // global (top) tree leaf size: the unit of MPI load balance
    Balance balance = Balance::count; // cut the SFC by particle counts or by expected work
    int sync_every = 1;               // most steps between domain syncs (sim/sync_schedule.hpp)
    int diagnostics_every = 1;        // steps between the diagnostics sums (and rows)
    CurveKind curve = CurveKind::hilbert;
    bool lattice = false;  // glass cases: regular lattice instead of the (cached) glass
    bool open_box = false; // GADGET-layout files: open boundaries instead of [0, BoxSize)
    std::vector<std::string> case_params; // --param KEY=VALUE: case parameters

    // Output and restart (issue 4).
    std::int64_t snapshot_every_steps = -1;   // -w N
    double snapshot_every_time = -1.0;        // -w T
    std::vector<std::string> snapshot_fields; // -f; empty: the snapshot fields of the field list
    std::int64_t checkpoint_every = -1;       // --checkpoint-every N
    double checkpoint_minutes = -1.0;         // --checkpoint-minutes M
    bool checkpoint_auto = false;             // --checkpoint-every auto (Young/Daly)
    double mtbf_hours = -1.0;                 // --mtbf H: MTBF of one node, hours
    std::string restart_file;                 // --restart FILE
};

} // namespace exasph
