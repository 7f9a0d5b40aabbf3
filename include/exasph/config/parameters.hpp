#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <type_traits>
#include <variant>
#include <vector>

#include "exasph/config/choices.hpp"
#include "exasph/config/config.hpp"
#include "exasph/config/custom_values.hpp"
#include "exasph/config/param_types.hpp"

namespace exasph {

// clang-format off
inline const std::array kParameters{
    // Initial conditions
    Param{"--init", "init", "Initial conditions: a test case, or an HDF5 file *.h5 or *.hdf5 in "
          "exasph's layout or the GADGET layout of other codes (gas only; docs/file-format.md)",
          "", OnRestart::kept, &Config::init},
    Param{"-n", "side", "Particles per axis (about n^3 particles)", "", OnRestart::kept,
          &Config::side, in_range(2, 1000)},
    Param{"--param", "case_params", "Case parameter KEY=VALUE (repeatable; the keys of each case "
          "are listed below)", "", OnRestart::initial, &Config::case_params, {}, false},
    Param{"--lattice", "lattice", "Glass cases (marked 'glass or --lattice' in the list of "
          "cases): start from a regular lattice instead of a relaxed glass", "",
          OnRestart::initial, &Config::lattice},
    Param{"--open-box", "open_box", "Initial conditions from another code's GADGET-layout "
          "file: open boundaries around the particles instead of the periodic box [0, BoxSize)",
          "", OnRestart::initial, &Config::open_box},
    // Physics
    Param{"--scheme", "scheme", "Formulation: std (the paper's: standard SPH volumes, alpha "
          "viscosity on every approaching pair, no conductivity), ve (generalised volume "
          "elements, slope-limited viscosity, conductivity 1: the recommended one), wc (std "
          "for weakly compressible liquids under tension: artificial stress 0.3 with exponent "
          "6, torque-free forces, double-precision derived fields, 250 neighbours), pe (ve "
          "for contact discontinuities at rest: energy weights X = m u, no conductivity, 200 "
          "neighbours) or sh (ve for shear flows: the AV switch, no conductivity); options "
          "given beside it override its values (default: the case's scheme, wc for "
          "square-patch, pe for isobaric-cube, sh for kelvin-helmholtz and wind-cloud, ve for "
          "the others and for files)", "",
          OnRestart::kept,
          &Config::scheme, {}, false},
    Param{"--ng0", "ng0", "Target number of neighbours (set by --scheme: 250 wc, 200 pe, else "
          "100)", "",
          OnRestart::kept, &Config::ng0, in_range(10, 1000)},
    Param{"--ngmax", "ngmax", "Neighbour cap; exceeding it is reported (lists are never "
          "truncated) (set by --scheme: 375 wc, 300 pe, else 150)", "", OnRestart::kept,
          &Config::ngmax,
          in_range(10, 4000)},
    Param{"--kernel-exponent", "kernel_exponent", "Sinc kernel exponent n", "", OnRestart::kept,
          &Config::kernel_exponent, in_range(3, 12)},
    Param{"--courant", "courant", "Courant factor K_cour", "", OnRestart::kept, &Config::courant,
          in_range(1e-6, 1)},
    Param{"--alpha", "alpha", "Artificial viscosity alpha (the maximum with --av-switch)", "",
          OnRestart::kept, &Config::alpha, in_range(0, 10)},
    Param{"--av-switch", "av_switch", "Per-particle artificial viscosity (Morris & Monaghan): "
          "alpha between --alpha-min and --alpha, raised by compression (on in the sh scheme)",
          "", OnRestart::kept,
          &Config::av_switch},
    Param{"--alpha-min", "alpha_min", "AV switch: smallest alpha", "", OnRestart::kept,
          &Config::alpha_min, in_range(0, 10)},
    Param{"--conductivity", "conductivity", "Artificial conductivity coefficient alpha_u "
          "(Price 2008); 0 is off (set by --scheme: 1 ve, else 0)", "", OnRestart::kept,
          &Config::conductivity, in_range(0, 10)},
    Param{"--av-limiter", "av_limiter", "Artificial viscosity from velocities reconstructed "
          "linearly to each pair's midpoint with a van Leer slope limiter (Rosswog 2015): no "
          "dissipation in smooth compression, full at shocks (on in the ve, pe and sh "
          "schemes)", "",
          OnRestart::kept, &Config::av_limiter},
    Param{"--volume-elements", "volume_elements", "Generalised volume elements X = (m/rho)^0.7 "
          "instead of standard SPH volumes (on in the ve, pe and sh schemes)", "",
          OnRestart::kept,
          &Config::volume_elements},
    Param{"--energy-weights", "energy_weights", "With --volume-elements: the weights X = m u "
          "(pressure-energy SPH, Saitoh & Makino 2013; Hopkins 2013), so that P = (gamma - 1) "
          "sum_b m_b u_b W_ab is smooth across a contact discontinuity in pressure balance; "
          "ideal gas with u > 0 only (on in the pe scheme)", "", OnRestart::kept,
          &Config::energy_weights},
    Param{"--tensile-stress", "tensile_stress", "Artificial stress against the tensile "
          "instability (Monaghan 2000): pairs of particles under negative pressure repel with "
          "eps |P|/rho^2 (W(r)/W(dp))^n; acts only where P < 0 (weakly compressible fluids); 0 "
          "is off (set by --scheme: 0.3 wc, else 0)", "", OnRestart::kept,
          &Config::tensile_stress, in_range(0, 1)},
    Param{"--tensile-exponent", "tensile_exponent", "Artificial stress: the exponent n of "
          "(W(r)/W(dp))^n, how sharply the repulsion is confined to pairs closer than the mean "
          "spacing dp (Monaghan 2000: 4; set by --scheme: 6 wc, else 4)", "", OnRestart::kept,
          &Config::tensile_exponent,
          in_range(1, 15)},
    Param{"--tensile-stress-positive", "tensile_stress_positive", "Artificial stress: its eps "
          "between particles under positive pressure, R = eps P/rho^2 (W(r)/W(dp))^n, so that "
          "close pairs repel under compression too (the square patch's closest pairs are under "
          "P > 0); 0 is off (set by --scheme: 0.03 wc, else 0)", "", OnRestart::kept,
          &Config::tensile_stress_positive, in_range(0, 1)},
    Param{"--torque-free", "torque_free", "Pressure and viscous pair forces that exert no "
          "net torque (angular momentum conserved to the precision of the stored IAD matrix): "
          "the IAD matrix from the pressure term's own weights X_b/k_a, artificial viscosity "
          "along the pair axis, and the artificial stress with a matrix of its own (+72 "
          "B/particle)", "",
          OnRestart::kept, &Config::torque_free},
    Param{"--double-precision", "double_precision", "Store the derived fields (rho, P, c, "
          "P/(Omega k^2), the IAD matrix, neighbour counts; the strain rate with --av-limiter) "
          "in double instead of single precision (+44 B/particle, +24 with the limiter): "
          "their rounding then seeds no asymmetry larger than double round-off, as the "
          "square patch's z-symmetry needs (on in the wc scheme)",
          "",
          OnRestart::kept, &Config::double_precision},
    Param{"--G", "G", "Gravitational constant: self-gravity on the tree (docs/physics.md §8) for "
          "any case in an open box; 0 turns it off (default: the case's, 1 for evrard, else off)",
          "code units", OnRestart::kept, &Config::G, in_range(0, 1e300), false},
    Param{"--theta", "theta", "Gravity: Barnes-Hut opening angle", "", OnRestart::kept,
          &Config::theta, in_range(0.05, 0.95)},
    Param{"--accel-eps", "accel_eps", "Gravity: time step at most sqrt(eps h / |a|) per particle",
          "", OnRestart::kept, &Config::accel_eps, in_range(1e-6, 10)},
    Param{"--timesteps", "timesteps", "Time stepping: global (every particle advances with the "
          "smallest step, the Press and Adams-Bashforth scheme of docs/physics.md §7) or block "
          "(each particle on its own power-of-two rung dt_max / 2^k, up to 2^24 rungs apart, kick-drift-kick "
          "leapfrog; only active particles are searched and computed; a limiter keeps "
          "neighbours within 2 rungs and wakes inactive particles, Saitoh & Makino 2009)",
          "", OnRestart::kept, &Config::timesteps},
    Param{"--no-timestep-limiter", "no_timestep_limiter", "Testing: block time steps without "
          "the neighbour limiter, to show the failure it prevents (a shock entering cold gas "
          "on long steps)", "", OnRestart::kept, &Config::no_timestep_limiter},
    Param{"--gravity-leaf-size", "gravity_leaf_size", "Gravity tree leaf size: one interaction "
          "list per leaf (particles)", "", OnRestart::kept, &Config::gravity_leaf_size,
          in_range(1, 4096)},
    Param{"--stir-mach", "stir_mach", "Driven turbulence: stir a periodic box with an "
          "Ornstein-Uhlenbeck force on the largest scales (1 < |k| L / 2 pi < 3, solenoidal) "
          "whose strength aims at this rms Mach number; 0 turns it off (default: the case's, "
          "0.3 for turbulence, else off)", "", OnRestart::kept, &Config::stir_mach,
          in_range(0, 10), false},
    Param{"--stir-seed", "stir_seed", "Driven turbulence: seed of the stirring's random "
          "sequence", "", OnRestart::kept, &Config::stir_seed, in_range(0, 2147483647)},
    // Decomposition
    Param{"--global-bucket", "global_bucket", "Global tree leaf size: the unit of MPI load "
          "balance (particles); grown to N / 2^20 for N above 2^20 times it, so that the global "
          "tree keeps about 2^20 leaves", "", OnRestart::kept, &Config::global_bucket,
          in_range(1, 1 << 20)},
    Param{"--balance", "balance", "MPI load balance: equal particle counts per rank, or equal "
          "expected work (cost: with block time steps an inactive particle costs 0.15 of an active "
          "one, at most 1.5 x the mean count per rank; global steps: as count)", "", OnRestart::given, &Config::balance},
    Param{"--no-halo-overlap", "no_halo_overlap", "Benchmarks: wait for each halo exchange of "
          "the SPH passes before the next pass, instead of computing the particles that do not "
          "need it meanwhile (to measure what the overlap hides)", "", OnRestart::given,
          &Config::no_halo_overlap},
    Param{"--sync-every", "sync_every", "Most steps between domain syncs (global tree counts, "
          "load balance, migration, halo discovery; one collective each). In between, the halos "
          "found at the last sync (with a skin of the smallest h) are refreshed point to point, "
          "and a sync comes early once some particle has moved, or its h grown, by half the "
          "skin. Global time steps without self-gravity only; 1: every step", "",
          OnRestart::given, &Config::sync_every, in_range(1, 1 << 20)},
    Param{"--leaf-size", "leaf_size", "Local octree leaf size (particles)", "", OnRestart::kept,
          &Config::leaf_size, in_range(1, 4096)},
    Param{"--curve", "curve", "Space-filling curve: hilbert or morton", "", OnRestart::kept, &Config::curve},
    // Run control
    Param{"-s,--steps", "steps", "Stop after step N (counted from the start of the simulation, "
          "across restarts)", "", OnRestart::given, &Config::steps, kNonNegative, false},
    Param{"--t-end", "t_end", "Physical end time; with -s the run stops at whichever comes first "
          "(default: the case's end time when -s is not given)", "code units", OnRestart::given,
          &Config::t_end, kPositive, false},
    Param{"--threads", "threads", "OpenMP threads (default: OMP_NUM_THREADS or all)", "",
          OnRestart::given, &Config::threads, in_range(1, 4096), false},
    Param{"--backend", "backend", "Where the SPH passes run: cpu (OpenMP threads), cuda (one "
          "GPU per rank, rank modulo the visible devices; gravity stays on the CPU) or auto "
          "(cuda where this build has it and a device is visible, else cpu)", "",
          OnRestart::given, &Config::backend},
    Param{"--restart", "restart", "Continue the run saved in this checkpoint, or in the newest "
          "checkpoint of this directory that reads and verifies (any rank count); the physics "
          "parameters come from the checkpoint", "", OnRestart::given,
          &Config::restart_file, {}, false},
    // Output
    Param{"--out", "out", "Output directory (diagnostics.csv, snapshots, checkpoints)", "",
          OnRestart::given, &Config::out_dir},
    Param{"-w,--write-every", "write_every", "Snapshots: every N steps (an integer), or every T "
          "of physical time (a number with a decimal point or exponent, written at the first "
          "step at or after each multiple of T)", "", OnRestart::given, kWriteEvery, {}, false},
    Param{"-f,--fields", "fields", "Snapshot fields, comma-separated (default: every snapshot "
          "field the run carries); x,y,z are always written", "", OnRestart::given,
          &Config::snapshot_fields, {}, false, ','},
    Param{"--diagnostics-every", "diagnostics_every", "Sum the diagnostics (energies, "
          "momenta, the next box; one collective) and write their row every N steps, and at "
          "syncs, outputs and the end; the conservation watchdog checks the steps whose previous "
          "step was summed too (global time steps only)", "", OnRestart::given,
          &Config::diagnostics_every, in_range(1, 1 << 20)},
    Param{"--comm-report", "comm_report", "Write OUT/comm_matrix.csv at the end: per rank, "
          "peer and kind of traffic (halo, migration, gravity), the point-to-point messages and "
          "bytes sent and received (tools/comm_matrix.py draws it)", "", OnRestart::given,
          &Config::comm_report},
    Param{"--checkpoint-every", "checkpoint_every", "Write a checkpoint every N steps (also at "
          "the end of the run), or 'auto': every sqrt(2 C M) s of wall time (Young/Daly) from the "
          "measured checkpoint cost C and the run's MTBF M = --mtbf / nodes", "",
          OnRestart::given, kCheckpointEvery, {}, false},
    Param{"--mtbf", "mtbf", "With --checkpoint-every auto: mean time between failures of one "
          "node", "hours", OnRestart::given, &Config::mtbf_hours, kPositive, false},
    Param{"--checkpoint-minutes", "checkpoint_minutes", "Write a checkpoint every M minutes of "
          "wall-clock time", "minutes", OnRestart::given, &Config::checkpoint_minutes, kPositive,
          false},
    // Silent data corruption
    Param{"--on-sdc", "on_sdc", "Silent data corruption (state changed between steps, broken "
          "invariants, conservation watchdog): rollback to the last verified state (see "
          "--sdc-rollback-store), abort, or off (no checks)", "", OnRestart::given,
          &Config::on_sdc},
    Param{"--sdc-rollback-every", "sdc_rollback_every", "Steps between rollback points", "",
          OnRestart::given, &Config::sdc_rollback_every, in_range(1, 1 << 30)},
    Param{"--sdc-rollback-store", "sdc_rollback_store", "Where --on-sdc rollback keeps the "
          "verified state: disk (one file per rank, ~112 B/particle, in --sdc-rollback-dir, "
          "removed at the end) or memory (a copy of the state: ~112 B/particle more RAM, no I/O)",
          "", OnRestart::given, &Config::sdc_rollback_store},
    Param{"--sdc-rollback-dir", "sdc_rollback_dir", "Directory of the disk rollback point, e.g. "
          "node-local scratch on a cluster (default: the --out directory)", "", OnRestart::given,
          &Config::sdc_rollback_dir, {}, false},
    Param{"--inject-fault", "inject_fault", "Testing: flip bit BIT of field FIELD of particle "
          "ID at the start of step STEP, or at the end of its phase PHASE (sync, neighbours, "
          "density, density_halos, iad, momentum_energy, gravity, timestep, update, h_update, "
          "diagnostics), once (STEP:FIELD:ID:BIT[:PHASE])", "",
          OnRestart::given, &Config::inject_fault, {}, false},
};
// clang-format on

// The parameter with this key (nullptr if none).
inline const Param* find_parameter(std::string_view key) {
    for (const auto& p : kParameters)
        if (key == p.key) return &p;
    return nullptr;
}

} // namespace exasph
