#pragma once
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "exasph/build_info.hpp"
#include "exasph/config/parameter_text.hpp"
#include "exasph/io/h5_file.hpp"
#include "exasph/sph/eos.hpp"
#include "exasph/util/box.hpp"

namespace exasph {

inline const char* eos_name(EosKind k) {
    return k == EosKind::tait ? "tait" : "ideal-gas";
}

// One parameter as the attribute "param:KEY": numbers as double, integers and flags as int64,
// strings and enums by name.
inline void write_parameter(const h5::Group& g, const Param& p, const Config& cfg) {
    const std::string name = std::string("param:") + p.key;
    std::visit(
        [&](const auto& m) {
            using M = std::decay_t<decltype(m)>;
            if constexpr (std::is_same_v<M, CustomValue>) {
                h5::write_attribute(g, name, m.format(cfg));
            } else {
                using V = std::decay_t<decltype(cfg.*m)>;
                if constexpr (std::is_same_v<V, double>)
                    h5::write_attribute(g, name, cfg.*m);
                else if constexpr (std::is_integral_v<V>)
                    h5::write_attribute(g, name, std::int64_t(cfg.*m));
                else
                    h5::write_attribute(g, name, format_value(p, cfg));
            }
        },
        p.member);
}

// Reads "param:KEY" back into cfg; an older file without it leaves the default.
inline void read_parameter(const h5::Group& g, const Param& p, Config& cfg) {
    const std::string name = std::string("param:") + p.key;
    if (!h5::has_attribute(g, name)) return;
    // A number the parameter's range admits (what the command line would accept), and one an
    // integer holds: a damaged or hand-edited file must not set what no option could.
    auto number = [&](double limit) {
        auto v = h5::read_attribute_doubles(g, name);
        if (v.size() != 1 || !admits(p.range, v[0]) || std::abs(v[0]) >= limit)
            throw input_error(
                g.file().path() + ": attribute " + name + " malformed or out of " + "range", true);
        return v[0];
    };
    std::visit(
        [&](const auto& m) {
            using M = std::decay_t<decltype(m)>;
            if constexpr (std::is_same_v<M, CustomValue>) {
                try {
                    m.parse(h5::read_attribute_string(g, name), cfg);
                } catch (const std::invalid_argument& e) {
                    throw input_error(g.file().path() + ": attribute " + name + ": " + e.what(),
                                      true);
                }
            } else {
                auto& v = cfg.*m;
                using V = std::decay_t<decltype(v)>;
                if constexpr (std::is_same_v<V, bool>)
                    v = number(2) != 0;
                else if constexpr (std::is_integral_v<V>)
                    v = V(number(double(std::numeric_limits<V>::max())));
                else if constexpr (std::is_arithmetic_v<V>)
                    v = V(number(std::numeric_limits<double>::max()));
                else if constexpr (std::is_same_v<V, std::string>)
                    v = h5::read_attribute_string(g, name);
                else if constexpr (std::is_enum_v<V>) {
                    const auto text = h5::read_attribute_string(g, name);
                    const auto e = choice_from_name<V>(text);
                    if (!e)
                        throw input_error(g.file().path() + ": attribute " + name + " '" + text +
                                              "' is not one of " + choice_list<V>(),
                                          true);
                    v = *e;
                }
            }
        },
        p.member);
}

// Attributes every output file carries on its root group: code version, units, the box and the
// EOS (so that a snapshot can seed a new run with --init) and the run's physics parameters
// (those the restart rule keeps, OnRestart::kept), as "param:KEY", and the case's --param
// values as "case_params".
template <class T>
void write_run_attributes(const h5::Group& g, const Config& cfg, const Box<T>& box,
                          const EosParams& eos, const std::string& units) {
    h5::write_attribute(g, "code_version", std::string("exasph ") + kVersion);
    h5::write_attribute(g, "units", units);
    h5::write_attribute(g, "box_lo", std::vector<double>{box.lo[0], box.lo[1], box.lo[2]});
    h5::write_attribute(g, "box_hi", std::vector<double>{box.hi[0], box.hi[1], box.hi[2]});
    h5::write_attribute(
        g, "periodic",
        std::vector<std::int64_t>{box.periodic[0], box.periodic[1], box.periodic[2]});
    h5::write_attribute(g, "eos", std::string(eos_name(eos.kind)));
    h5::write_attribute(g, "gamma", eos.gamma);
    h5::write_attribute(g, "sound_speed", eos.c0);
    for (const auto& p : kParameters)
        if (p.restart == OnRestart::kept) write_parameter(g, p, cfg);
    // The case's --param values, so that tools measure against the case that ran (e.g. the
    // wind-cloud's radius sets tau_KH). Absent where none was given.
    if (!cfg.case_params.empty()) {
        std::string joined;
        for (const std::string& kv : cfg.case_params) joined += (joined.empty() ? "" : " ") + kv;
        h5::write_attribute(g, "case_params", joined);
    }
}

// Reads back the physics parameters written by write_run_attributes (restart). A file from
// before self-gravity (no param:G) ran without it.
inline void read_run_parameters(const h5::Group& g, Config& cfg) {
    if (!h5::has_attribute(g, "param:G")) cfg.G = 0.0;
    for (const auto& p : kParameters)
        if (p.restart == OnRestart::kept) read_parameter(g, p, cfg);
}

} // namespace exasph
