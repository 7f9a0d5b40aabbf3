#pragma once
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "exasph/config/choices.hpp"
#include "exasph/config/config.hpp"

namespace exasph {

// A parameter whose text sets more than one member of Config (-w N|T, --checkpoint-every N|auto).
struct CustomValue {
    void (*parse)(const std::string& text, Config& cfg); // throws std::invalid_argument
    std::string (*format)(const Config& cfg);            // "" when not set
    const char* type_name;
    std::string (*option_text)(const Config& cfg); // as `parse` takes it back ("" when not set)
};

// -w N (every N steps: an integer) or -w T (every T of physical time: a decimal point or an
// exponent makes it a time).
// A count must be whole and fit an int64 ("inf" or 1e20 steps into an integer is undefined
// behaviour: a fuzz finding of issue 21).
inline void parse_write_every(const std::string& v, Config& cfg) {
    const auto x = parse_number(v);
    if (!x || !(*x > 0) || !std::isfinite(*x))
        throw std::invalid_argument("'" + v + "' is not a positive step count or time");
    if (v.find_first_of(".eE") != std::string::npos) {
        cfg.snapshot_every_time = *x;
        return;
    }
    if (*x != std::floor(*x) || *x >= 9.2e18)
        throw std::invalid_argument("'" + v +
                                    "' is not a step count (a whole number below 9.2e18)");
    cfg.snapshot_every_steps = std::int64_t(*x);
}
inline std::string format_write_every(const Config& cfg) {
    if (cfg.snapshot_every_steps > 0) return std::to_string(cfg.snapshot_every_steps);
    if (cfg.snapshot_every_time > 0) return format_number(cfg.snapshot_every_time) + " (time)";
    return "";
}

// A time keeps a decimal point or an exponent (17 digits: exact), so it reads back as a time.
inline std::string write_every_text(const Config& cfg) {
    if (cfg.snapshot_every_time <= 0) return format_write_every(cfg);
    return exact_number(cfg.snapshot_every_time, true);
}

// --checkpoint-every N (steps) or auto (Young/Daly, needs --mtbf).
inline void parse_checkpoint_every(const std::string& v, Config& cfg) {
    if (v == "auto") {
        cfg.checkpoint_auto = true;
        return;
    }
    std::size_t used = 0;
    long long n = -1;
    try {
        n = std::stoll(v, &used);
    } catch (const std::exception&) {
    }
    if (used != v.size() || n <= 0)
        throw std::invalid_argument("expects a positive step count or auto, got " + v);
    cfg.checkpoint_every = n;
}
inline std::string format_checkpoint_every(const Config& cfg) {
    if (cfg.checkpoint_auto) return "auto";
    return cfg.checkpoint_every > 0 ? std::to_string(cfg.checkpoint_every) : "";
}

inline constexpr CustomValue kWriteEvery{parse_write_every, format_write_every, "N|T",
                                         write_every_text};
inline constexpr CustomValue kCheckpointEvery{parse_checkpoint_every, format_checkpoint_every,
                                              "N|auto", format_checkpoint_every};

} // namespace exasph
