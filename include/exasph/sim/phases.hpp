#pragma once
#include <array>
#include <cstddef>
#include <string_view>

namespace exasph {

// Phases of the step, each timed. `sync` is migration + SFC sort + trees + halo discovery and
// exchange; `density_halos` is the halo exchange of the density pass's results; `iad` includes
// the halo exchange that follows it.
enum Phase : std::size_t {
    kSync,
    kNeighbours,
    kDensity,
    kDensityHalos,
    kIad,
    kMomentumEnergy,
    kGravity,
    kTimeStep,
    kUpdate,
    kSmoothingLength,
    kDiagnostics,
    kNumPhases
};
inline constexpr std::array<std::string_view, kNumPhases> kPhaseNames{
    "sync",    "neighbours", "density", "density_halos", "iad",        "momentum_energy",
    "gravity", "timestep",   "update",  "h_update",      "diagnostics"};

} // namespace exasph
