#pragma once
#include <algorithm>
#include <string>
#include <vector>

#include "exasph/build_info.hpp"
#include "exasph/io/h5_file.hpp"
#include "exasph/sim/config.hpp"
#include "exasph/sph/eos.hpp"
#include "exasph/util/box.hpp"

namespace exasph {

inline const char* curve_name(CurveKind c) {
    return c == CurveKind::hilbert ? "hilbert" : "morton";
}
inline const char* eos_name(EosKind k) {
    return k == EosKind::tait ? "tait" : "ideal-gas";
}

// Attributes every output file carries on its root group: code version, units, the box and the
// EOS (so that a snapshot can seed a new run with --init) and all run parameters ("param:*").
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
    h5::write_attribute(g, "param:init", cfg.init);
    h5::write_attribute(g, "param:side", std::int64_t(cfg.side));
    h5::write_attribute(g, "param:ng0", cfg.ng0);
    h5::write_attribute(g, "param:ngmax", std::int64_t(cfg.ngmax));
    h5::write_attribute(g, "param:kernel_exponent", cfg.kernel_exponent);
    h5::write_attribute(g, "param:courant", cfg.courant);
    h5::write_attribute(g, "param:alpha", cfg.alpha);
    h5::write_attribute(g, "param:av_switch", std::int64_t(cfg.av_switch));
    h5::write_attribute(g, "param:alpha_min", cfg.alpha_min);
    h5::write_attribute(g, "param:volume_elements", std::int64_t(cfg.volume_elements));
    h5::write_attribute(g, "param:conductivity", cfg.conductivity);
    h5::write_attribute(g, "param:av_limiter", std::int64_t(cfg.av_limiter));
    h5::write_attribute(g, "param:G", std::max(cfg.G, 0.0));
    h5::write_attribute(g, "param:theta", cfg.theta);
    h5::write_attribute(g, "param:accel_eps", cfg.accel_eps);
    h5::write_attribute(g, "param:leaf_size", std::int64_t(cfg.bucket_size));
    h5::write_attribute(g, "param:global_bucket", std::int64_t(cfg.global_bucket));
    h5::write_attribute(g, "param:curve", std::string(curve_name(cfg.curve)));
}

// Reads back the physics parameters written by write_run_attributes (restart).
inline void read_run_parameters(const h5::Group& g, Config& cfg) {
    auto num = [&](const char* name) {
        auto v = h5::read_attribute_doubles(g, name);
        if (v.size() != 1)
            throw input_error(g.file().path() + ": attribute " + name + " malformed");
        return v[0];
    };
    cfg.init = h5::read_attribute_string(g, "param:init");
    cfg.side = int(num("param:side"));
    cfg.ng0 = num("param:ng0");
    cfg.ngmax = int(num("param:ngmax"));
    cfg.kernel_exponent = num("param:kernel_exponent");
    cfg.courant = num("param:courant");
    cfg.alpha = num("param:alpha");
    cfg.av_switch = num("param:av_switch") != 0;
    cfg.alpha_min = num("param:alpha_min");
    cfg.volume_elements = num("param:volume_elements") != 0;
    cfg.conductivity = num("param:conductivity");
    cfg.av_limiter = h5::has_attribute(g, "param:av_limiter") && num("param:av_limiter") != 0;
    // Gravity parameters came with issue 6: older files ran without gravity.
    cfg.G = h5::has_attribute(g, "param:G") ? num("param:G") : 0.0;
    if (h5::has_attribute(g, "param:theta")) cfg.theta = num("param:theta");
    if (h5::has_attribute(g, "param:accel_eps")) cfg.accel_eps = num("param:accel_eps");
    cfg.bucket_size = int(num("param:leaf_size"));
    cfg.global_bucket = int(num("param:global_bucket"));
    cfg.curve = h5::read_attribute_string(g, "param:curve") == "morton" ? CurveKind::morton
                                                                        : CurveKind::hilbert;
}

} // namespace exasph
