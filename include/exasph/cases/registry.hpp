#pragma once
#include <string>
#include <vector>

#include "exasph/cases/case_info.hpp"
#include "exasph/cases/evrard.hpp"
#include "exasph/cases/gresho_chan.hpp"
#include "exasph/cases/isobaric_cube.hpp"
#include "exasph/cases/jeans.hpp"
#include "exasph/cases/kelvin_helmholtz.hpp"
#include "exasph/cases/noh.hpp"
#include "exasph/cases/sedov.hpp"
#include "exasph/cases/square_patch.hpp"
#include "exasph/cases/turbulence.hpp"
#include "exasph/cases/turbulent_collapse.hpp"
#include "exasph/cases/wind_cloud.hpp"

namespace exasph {

// Every test case --init accepts, in the order --help lists them. A new case is one file in
// cases/ (its parameters, maker and CaseInfo) and one entry here (with its #include).
inline const std::vector<const CaseInfo*>& case_registry() {
    static const std::vector<const CaseInfo*> cases{
        &square_patch_case(),
        &sedov_case(),
        &noh_case(),
        &evrard_case(),
        &gresho_chan_case(),
        &isobaric_cube_case(),
        &kelvin_helmholtz_case(),
        &wind_cloud_case(),
        &turbulence_case(),
        &turbulent_collapse_case(),
        &jeans_case(),
    };
    return cases;
}

// The case called `name`, or nullptr.
inline const CaseInfo* find_case(const std::string& name) {
    for (const CaseInfo* c : case_registry())
        if (c->name == name) return c;
    return nullptr;
}

// The scheme a run of `init` (a case or a file) uses when --scheme is not given: the case's,
// and ve for initial conditions from a file.
inline Scheme default_scheme(const std::string& init) {
    const CaseInfo* c = find_case(init);
    return c ? c->scheme : Scheme::ve;
}

// "square-patch, sedov, ...": the names for messages.
inline std::string case_names() {
    std::string s;
    for (const CaseInfo* c : case_registry()) s += (s.empty() ? "" : ", ") + c->name;
    return s;
}

} // namespace exasph
