#pragma once
#include <cmath>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "exasph/cases/case_context.hpp"
#include "exasph/cases/initial_conditions.hpp"
#include "exasph/config/choices.hpp"
#include "exasph/util/error.hpp"

namespace exasph {

// What the run asks of a case: the common parameters and the --param KEY=VALUE overrides.
struct CaseRequest {
    int side = 30;
    double ng0 = 100;
    double G = -1; // --G; < 0: the case's own
    std::vector<std::string> params;
};

// A case parameter as --help lists it.
struct CaseParamInfo {
    std::string key, help;
    double default_value;
};

// One test case of the registry (cases/registry.hpp): its name for --init, its parameters and
// its maker.
struct CaseInfo {
    std::string name;
    std::string summary;      // one line for --help
    bool from_points = false; // made from a glass or, with --lattice, a lattice
    std::vector<CaseParamInfo> params;
    std::function<InitialConditions<double>(const CaseRequest&, const CaseContext&)> make;
    // The scheme a run of this case uses when --scheme is not given (config/scheme.hpp).
    Scheme scheme = Scheme::ve;
};

// A --param key of the case whose parameters are P.
template <class P>
struct CaseKey {
    const char* key;
    double P::*member;
    const char* help;
};

// Applies --param KEY=VALUE overrides to p; every value must be a positive number.
template <class P>
void apply_case_params(const std::string& name, const std::vector<CaseKey<P>>& keys,
                       const std::vector<std::string>& given, P& p) {
    std::string names;
    for (const auto& k : keys) names += (names.empty() ? "" : ", ") + std::string(k.key);
    for (const auto& kv : given) {
        const auto eq = kv.find('=');
        const std::string key = kv.substr(0, eq);
        const CaseKey<P>* found = nullptr;
        for (const auto& k : keys)
            if (key == k.key) found = &k;
        if (eq == std::string::npos || !found)
            throw input_error("--param " + kv + ": case " + name + " has the parameters " +
                                  (names.empty() ? "(none)" : names) + " (use KEY=VALUE)",
                              true);
        const auto v = parse_number(kv.substr(eq + 1));
        if (!v || !std::isfinite(*v) || !(*v > 0))
            throw input_error("--param " + kv + ": the value must be a positive number", true);
        p.*(found->member) = *v;
    }
}

// Builds the registry entry of a case with parameters P (which has `side` and `ng0`, and `G` if
// the case has self-gravity) from its keys and its maker.
template <class P, class Maker>
CaseInfo case_info(std::string name, std::string summary, bool from_points,
                   std::vector<CaseKey<P>> keys, Maker maker) {
    CaseInfo info{name, std::move(summary), from_points, {}, {}, Scheme::ve};
    const P defaults{};
    for (const auto& k : keys) info.params.push_back({k.key, k.help, defaults.*(k.member)});
    info.make = [name, keys, maker](const CaseRequest& req, const CaseContext& ctx) {
        P p{};
        p.side = req.side;
        p.ng0 = req.ng0;
        if constexpr (requires { p.G; })
            if (req.G >= 0) p.G = req.G;
        apply_case_params(name, keys, req.params, p);
        return maker(p, ctx);
    };
    return info;
}

// `info` with its default scheme set to s.
inline CaseInfo with_scheme(Scheme s, CaseInfo info) {
    info.scheme = s;
    return info;
}

} // namespace exasph
