#pragma once
#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

#include "exasph/util/annotate.hpp"

namespace exasph {

// Every particle field, declared once. Sorting, (later) migration, halo exchange, snapshots and
// checkpoints iterate this list; adding a field means adding one enumerator and one row below.
enum class Field : std::uint8_t {
    x,
    y,
    z, // position
    x_m1,
    y_m1,
    z_m1, // position at the previous step (Press scheme, physics.md §7)
    vx,
    vy,
    vz,    // velocity
    h,     // smoothing length
    m,     // mass
    u,     // specific internal energy
    du_m1, // du/dt of the previous step (Adams-Bashforth, physics.md §7)
    rho0,  // reference density of the Tait EOS (physics.md §4), measured at step 0
    p0,    // background pressure of the Tait EOS (physics.md §4, 9.1)
    rho,   // density (physics.md §3)
    pgrad, // P / (Omega k^2): pressure-force coefficient, grad-h term Omega (physics.md §3, 6)
    p,     // pressure
    c,     // sound speed
    c11,
    c12,
    c13,
    c22,
    c23,
    c33, // IAD matrix C = tau^-1 (physics.md §5)
    // The artificial stress's matrix M (row-major), only with the stress (--tensile-stress or
    // --tensile-stress-positive) and --torque-free (tensile_stress.hpp).
    s11,
    s12,
    s13,
    s21,
    s22,
    s23,
    s31,
    s32,
    s33,
    ax,
    ay,
    az,    // acceleration
    du,    // du/dt
    nc,    // neighbour count within 2h (physics.md §2)
    alpha, // artificial-viscosity coefficient (constant, or evolved by the AV switch)
    divv,  // velocity divergence (IAD), drives the AV switch
    xm,    // volume-element weight X (= m for standard SPH; (m/rho)^p with volume elements)
    kx,    // volume-element normalisation k = sum_b X_b W_ab
    phi,   // gravitational potential (physics.md §8; 0 without gravity)
    gsoft, // the softening correction's xi (sph/softening_correction_kern.hpp; with gravity)
    stir,  // power per unit mass of the stirring force, v . a_stir (driven turbulence)
    // Strain rate S = (G + G^T) / 2 of the IAD velocity gradient G_ij = dv_i/dx_j, only with
    // --av-limiter: the reconstruction's slope along a pair axis d is d.G.d = d.S.d, so the
    // symmetric part is all the viscosity needs (6 narrow fields, 24 B/particle, not 9 in T).
    e11,
    e12,
    e13,
    e22,
    e23,
    e33,
    // Block time steps (--timesteps block, sim/block_clock.hpp): the particle's rung k (its step
    // is dt_max / 2^k), its velocity and internal energy kicked to the middle of its step (the
    // leapfrog's v_{1/2}, u_{1/2}; v and u then hold the values predicted to the current time),
    // and its own time-step limit from this step's forces.
    rung,
    vhx,
    vhy,
    vhz,
    uh,
    dtc,
    count_ // number of fields (not a field)
};

inline constexpr std::size_t kNumFields = static_cast<std::size_t>(Field::count_);

// Role bits. `state` fields carry information from one step to the next and therefore must be
// permuted by the SFC sort, migrated, and checkpointed; the others are recomputed every step.
enum FieldRole : std::uint8_t {
    kState = 1u << 0,
    kDerived = 1u << 1,
    kSnapshot = 1u << 2, // written to snapshots by default
    // Halo groups: fields that halo particles need, by the point of the step where they become
    // valid (DESIGN: three halo exchanges per step).
    kHaloSync = 1u << 3,    // after the domain sync, before the neighbour search
    kHaloDensity = 1u << 4, // after density and EOS, before IAD
    kHaloIad = 1u << 5,     // after IAD, before momentum and energy
    kHaloGrad = 1u << 6,    // with kHaloIad, only when the velocity gradient is used
    // Needed only by some cases or options (Tait EOS, volume elements, the AV switch, gravity,
    // the AV limiter): no memory until ParticleSet::enable.
    kOptional = 1u << 7,
};

struct FieldInfo {
    Field field;
    std::string_view name;
    std::string_view unit; // symbolic (code units of the case)
    std::uint8_t roles;
    std::string_view description;
};

// clang-format off
inline constexpr std::array<FieldInfo, kNumFields> kFieldTable{{
    {Field::x,        "x",        "length",      kState | kHaloSync | kSnapshot, "position x"},
    {Field::y,        "y",        "length",      kState | kHaloSync | kSnapshot, "position y"},
    {Field::z,        "z",        "length",      kState | kHaloSync | kSnapshot, "position z"},
    {Field::x_m1,     "x_m1",     "length",      kState, "position x at the previous step"},
    {Field::y_m1,     "y_m1",     "length",      kState, "position y at the previous step"},
    {Field::z_m1,     "z_m1",     "length",      kState, "position z at the previous step"},
    {Field::vx,       "vx",       "length/time", kState | kHaloSync | kSnapshot, "velocity x"},
    {Field::vy,       "vy",       "length/time", kState | kHaloSync | kSnapshot, "velocity y"},
    {Field::vz,       "vz",       "length/time", kState | kHaloSync | kSnapshot, "velocity z"},
    {Field::h,        "h",        "length",      kState | kHaloSync | kSnapshot, "smoothing length"},
    {Field::m,        "m",        "mass",        kState | kHaloSync | kSnapshot, "mass"},
    {Field::u,        "u",        "energy/mass", kState | kHaloSync | kSnapshot, "specific internal energy"},
    {Field::du_m1,    "du_m1",    "energy/mass/time", kState, "du/dt at the previous step"},
    {Field::rho0,     "rho0",     "mass/length^3", kState | kOptional, "Tait EOS reference density"},
    {Field::p0,       "p0",       "pressure",    kState | kOptional, "Tait EOS background pressure"},
    {Field::rho,      "rho",      "mass/length^3", kDerived | kHaloDensity | kSnapshot, "density"},
    {Field::pgrad,    "pgrad",    "length^5/(mass*time^2)", kDerived | kHaloDensity, "pressure-force coefficient P/(Omega k^2)"},
    {Field::p,        "p",        "pressure",    kDerived | kHaloDensity | kSnapshot, "pressure"},
    {Field::c,        "c",        "length/time", kDerived | kHaloDensity | kSnapshot, "sound speed"},
    {Field::c11,      "c11",      "1/length^2",  kDerived | kHaloIad, "IAD matrix C_11"},
    {Field::c12,      "c12",      "1/length^2",  kDerived | kHaloIad, "IAD matrix C_12"},
    {Field::c13,      "c13",      "1/length^2",  kDerived | kHaloIad, "IAD matrix C_13"},
    {Field::c22,      "c22",      "1/length^2",  kDerived | kHaloIad, "IAD matrix C_22"},
    {Field::c23,      "c23",      "1/length^2",  kDerived | kHaloIad, "IAD matrix C_23"},
    {Field::c33,      "c33",      "1/length^2",  kDerived | kHaloIad, "IAD matrix C_33"},
    {Field::s11,      "stress_m11", "1/length^2", kDerived | kHaloIad | kOptional, "artificial stress matrix M_11"},
    {Field::s12,      "stress_m12", "1/length^2", kDerived | kHaloIad | kOptional, "artificial stress matrix M_12"},
    {Field::s13,      "stress_m13", "1/length^2", kDerived | kHaloIad | kOptional, "artificial stress matrix M_13"},
    {Field::s21,      "stress_m21", "1/length^2", kDerived | kHaloIad | kOptional, "artificial stress matrix M_21"},
    {Field::s22,      "stress_m22", "1/length^2", kDerived | kHaloIad | kOptional, "artificial stress matrix M_22"},
    {Field::s23,      "stress_m23", "1/length^2", kDerived | kHaloIad | kOptional, "artificial stress matrix M_23"},
    {Field::s31,      "stress_m31", "1/length^2", kDerived | kHaloIad | kOptional, "artificial stress matrix M_31"},
    {Field::s32,      "stress_m32", "1/length^2", kDerived | kHaloIad | kOptional, "artificial stress matrix M_32"},
    {Field::s33,      "stress_m33", "1/length^2", kDerived | kHaloIad | kOptional, "artificial stress matrix M_33"},
    {Field::ax,       "ax",       "length/time^2", kDerived | kSnapshot, "acceleration x"},
    {Field::ay,       "ay",       "length/time^2", kDerived | kSnapshot, "acceleration y"},
    {Field::az,       "az",       "length/time^2", kDerived | kSnapshot, "acceleration z"},
    {Field::du,       "du",       "energy/mass/time", kDerived | kSnapshot, "du/dt"},
    {Field::nc,       "nc",       "1",           kDerived | kSnapshot, "neighbour count within 2h"},
    {Field::alpha,    "alpha",    "1",           kState | kHaloSync | kSnapshot | kOptional, "artificial viscosity alpha"},
    {Field::divv,     "divv",     "1/time",      kDerived | kOptional, "velocity divergence"},
    {Field::xm,       "xm",       "volume^p",    kState | kHaloSync | kOptional, "volume-element weight X"},
    {Field::kx,       "kx",       "volume^(p-1)", kDerived | kHaloDensity | kOptional, "volume-element normalisation k"},
    {Field::phi,      "phi",      "energy/mass", kDerived | kSnapshot | kOptional, "gravitational potential"},
    {Field::gsoft,    "gsoft",    "length^5/(mass*time^2)", kDerived | kHaloDensity | kOptional, "softening correction xi"},
    {Field::stir,     "stir_power", "energy/mass/time", kDerived | kOptional, "power per unit mass of the stirring force"},
    {Field::e11,      "strain_xx", "1/time",     kDerived | kHaloGrad | kOptional, "strain rate (dvx/dx)"},
    {Field::e12,      "strain_xy", "1/time",     kDerived | kHaloGrad | kOptional, "strain rate (dvx/dy + dvy/dx)/2"},
    {Field::e13,      "strain_xz", "1/time",     kDerived | kHaloGrad | kOptional, "strain rate (dvx/dz + dvz/dx)/2"},
    {Field::e22,      "strain_yy", "1/time",     kDerived | kHaloGrad | kOptional, "strain rate (dvy/dy)"},
    {Field::e23,      "strain_yz", "1/time",     kDerived | kHaloGrad | kOptional, "strain rate (dvy/dz + dvz/dy)/2"},
    {Field::e33,      "strain_zz", "1/time",     kDerived | kHaloGrad | kOptional, "strain rate (dvz/dz)"},
    {Field::rung,     "rung",     "1",           kState | kHaloSync | kSnapshot | kOptional, "time-step rung k: dt = dt_max / 2^k (block time steps)"},
    {Field::vhx,      "vhx",      "length/time", kState | kOptional, "velocity x at the middle of the particle's step (block time steps)"},
    {Field::vhy,      "vhy",      "length/time", kState | kOptional, "velocity y at the middle of the particle's step (block time steps)"},
    {Field::vhz,      "vhz",      "length/time", kState | kOptional, "velocity z at the middle of the particle's step (block time steps)"},
    {Field::uh,       "uh",       "energy/mass", kState | kOptional, "internal energy at the middle of the particle's step (block time steps)"},
    {Field::dtc,      "dt_own",   "time",        kDerived | kOptional, "the particle's own time-step limit (block time steps)"},
}};
// clang-format on

// The strain rate's six components S_11, S_12, S_13, S_22, S_23, S_33 (the layout of StrainRate):
// component c is field e11 + c. A function, not a table, so that device code can call it.
static_assert(int(Field::e33) - int(Field::e11) == 5, "the strain-rate fields are contiguous");
EXASPH_HD constexpr Field strain_rate_field(int c) {
    return static_cast<Field>(int(Field::e11) + c);
}
// Component d (0, 1, 2) of a vector kept as three consecutive fields, named by its first: x,
// x_m1, vx, ax, vhx. A function, not a table, so that device code can call it.
static_assert(int(Field::z) - int(Field::x) == 2 && int(Field::z_m1) - int(Field::x_m1) == 2 &&
                  int(Field::vz) - int(Field::vx) == 2 && int(Field::az) - int(Field::ax) == 2 &&
                  int(Field::vhz) - int(Field::vhx) == 2,
              "vector fields are consecutive");
EXASPH_HD constexpr Field component(Field first, int d) {
    return static_cast<Field>(int(first) + d);
}
// The artificial stress's matrix M_ij, row-major: component c is field s11 + c.
static_assert(int(Field::s33) - int(Field::s11) == 8, "the stress matrix fields are contiguous");
EXASPH_HD constexpr Field stress_matrix_field(int c) {
    return static_cast<Field>(int(Field::s11) + c);
}

// The fields carrying any of the role bits, in table order.
inline std::vector<Field> fields_with_role(std::uint8_t roles) {
    std::vector<Field> out;
    for (const auto& info : kFieldTable)
        if (info.roles & roles) out.push_back(info.field);
    return out;
}

constexpr const FieldInfo& field_info(Field f) {
    return kFieldTable[static_cast<std::size_t>(f)];
}

// Derived fields stored in single precision (issue 7: bytes per particle). Only quantities that
// enter the sums as coefficients of both members of a pair, so that the pairwise symmetry that
// conserves momentum and energy is kept exactly (the density is recomputed every step from the
// positions and enters the pair terms only as rho_a and rho_b); positions, velocities, h, m, u
// and the accelerations stay in the working precision. nc is an integer count (exact in float).
// The sums themselves run in the working precision. (The
// signal velocity max_b v^sig_ab is not stored: the momentum-energy pass reduces it to the
// Courant time step where it computes it.) --double-precision stores them in T instead
// (ParticleSet::set_narrow_single): single-precision rounding of values that differ between
// symmetric particles in the last double bits makes differences of ~1e-7, which an unstable
// flow can grow (the square patch's z-symmetry, docs/validation.md).
constexpr bool is_narrow(Field f) {
    switch (f) {
    case Field::rho:
    case Field::pgrad:
    case Field::p:
    case Field::c:
    case Field::c11:
    case Field::c12:
    case Field::c13:
    case Field::c22:
    case Field::c23:
    case Field::c33:
    case Field::e11:
    case Field::e12:
    case Field::e13:
    case Field::e22:
    case Field::e23:
    case Field::e33:
    case Field::nc:
        return true;
    default:
        return false;
    }
}

// The table is indexed by the enum: a row out of place is a compile error, not a silent bug.
constexpr bool field_table_in_order() {
    for (std::size_t i = 0; i < kNumFields; ++i)
        if (static_cast<std::size_t>(kFieldTable[i].field) != i) return false;
    return true;
}
static_assert(field_table_in_order(), "kFieldTable rows must follow the Field enum order");

} // namespace exasph
