#pragma once
#include <cstdint>
#include <string>
#include <variant>
#include <vector>

#include "exasph/config/config.hpp"
#include "exasph/config/custom_values.hpp"

// The shape of one row of the parameter table (config/parameters.hpp): its restart rule, the
// range its value must lie in and the Config member it sets.
namespace exasph {

// What --restart does with a parameter.
enum class OnRestart {
    kept,    // part of the run's physics: stored in every output file ("param:KEY"), restored
             // from the checkpoint, and refused if given with --restart
    initial, // shapes only the initial conditions (the checkpoint holds the particles):
             // refused if given with --restart
    given,   // run control: a restart takes it from its own command line (or the default)
};

// Bounds a numeric parameter's value must lie in (checked by the command line).
struct ValueRange {
    enum Kind { any, closed, positive, nonnegative } kind = any;
    double lo = 0, hi = 0;
};
inline constexpr ValueRange in_range(double lo, double hi) {
    return {ValueRange::closed, lo, hi};
}
// Whether x is a finite value the range allows (what the command line's checks accept).
inline constexpr bool admits(const ValueRange& r, double x) {
    if (!(x - x == 0)) return false; // NaN or infinite
    switch (r.kind) {
    case ValueRange::closed:
        return x >= r.lo && x <= r.hi;
    case ValueRange::positive:
        return x > 0;
    case ValueRange::nonnegative:
        return x >= 0;
    default:
        return true;
    }
}
inline constexpr ValueRange kPositive{ValueRange::positive};
inline constexpr ValueRange kNonNegative{ValueRange::nonnegative};

// The member of Config a parameter sets. Lists (-f, --param) take repeated or comma-separated
// values; enums take one of their names (config/choices.hpp); bools are flags.
using ParamMember =
    std::variant<double Config::*, int Config::*, std::int64_t Config::*, bool Config::*,
                 std::string Config::*, std::vector<std::string> Config::*, CurveKind Config::*,
                 Scheme Config::*, SdcPolicy Config::*, RollbackStore Config::*,
                 BackendChoice Config::*, TimeStepping Config::*, Balance Config::*, CustomValue>;

// One run parameter, declared once: the command line, --help, the restart rule, the checkpoint
// attributes and the run header are all generated from kParameters.
struct Param {
    const char* flags; // CLI11 option names: "-s,--steps"
    const char* key;   // attribute "param:KEY" in output files, and the name in the run header
    const char* help;
    const char* unit; // "" for counts, flags and dimensionless numbers
    OnRestart restart;
    ParamMember member;
    ValueRange range = {};
    bool show_default = true; // false where the default is a sentinel ("not given")
    char delimiter = '\0';    // lists: separator of several values in one argument
};

} // namespace exasph
