#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "exasph/sfc/keys.hpp"

namespace exasph {

// Everything a run is configured with; filled by the command line (apps/exasph.cpp).
struct Config {
    std::string init = "square-patch"; // case name
    int side = 30;                     // particles per axis (-n)
    std::int64_t steps = -1;           // -s; < 0: not given
    double t_end = -1.0;               // --t-end; < 0: not given
    std::string out_dir = "exasph-output";
    double ng0 = 100;             // target neighbour count (SPEC 2)
    int ngmax = 150;              // neighbour cap: exceeding it is reported
    double kernel_exponent = 6;   // sinc exponent n (SPEC 1)
    double courant = 0.2;         // K_cour (SPEC 7)
    double alpha = 1.0;           // artificial viscosity (SPEC 6); the maximum with --av-switch
    bool av_switch = false;       // evolve alpha per particle (Morris & Monaghan)
    double alpha_min = 0.05;      // AV switch: floor of alpha
    double av_decay = 0.2;        // AV switch: decay rate in sound-crossing times of h
    double conductivity = 0.0;    // artificial conductivity alpha_u (0: off)
    bool av_limiter = false;      // viscosity from limited midpoint-reconstructed velocities
    bool volume_elements = false; // generalised volume elements X = (m/rho)^ve_exponent
    double ve_exponent = 0.7;
    double G = -1.0;        // gravitational constant (--G); < 0: the case's (0: no gravity)
    double theta = 0.5;     // Barnes-Hut opening angle (SPEC 8)
    double accel_eps = 0.2; // gravity time-step factor: dt <= sqrt(accel_eps h / |a|) (SPEC 7)
    int gravity_bucket =
        16; // gravity-tree leaf size: one interaction list per leaf (bench_gravity)
    std::string on_sdc = "rollback"; // --on-sdc abort|rollback|off (silent data corruption)
    int sdc_rollback_every = 10;     // steps between rollback points
    // --sdc-rollback-store memory|disk: disk by default, because the copy in memory would add
    // ~112 B to the ~300 B a particle needs (issue 7); the file is written every 10 steps.
    std::string sdc_rollback_store = "disk";
    std::string sdc_rollback_dir; // --sdc-rollback-dir (empty: out_dir)
    std::string inject_fault;     // --inject-fault STEP:FIELD:ID:BIT (tests)
    int threads = 0;              // 0: OpenMP default
    int bucket_size = 64;         // local octree leaf size
    int global_bucket = 128;      // global (top) tree leaf size: the unit of MPI load balance
    CurveKind curve = CurveKind::hilbert;
    bool lattice = false; // sedov/noh: regular lattice instead of the (cached) glass
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
