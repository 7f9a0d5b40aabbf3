#pragma once
#include <string>
#include <vector>

#include "exasph/cases/case_info.hpp"
#include "exasph/cases/evrard.hpp"
#include "exasph/cases/noh.hpp"
#include "exasph/cases/sedov.hpp"
#include "exasph/cases/square_patch.hpp"

namespace exasph {

// Every test case --init accepts, in the order --help lists them. A new case is one file in
// cases/ (its parameters, maker and CaseInfo) and one entry here (with its #include).
inline const std::vector<const CaseInfo*>& case_registry() {
    static const std::vector<const CaseInfo*> cases{
        &square_patch_case(),
        &sedov_case(),
        &noh_case(),
        &evrard_case(),
    };
    return cases;
}

// The case called `name`, or nullptr.
inline const CaseInfo* find_case(const std::string& name) {
    for (const CaseInfo* c : case_registry())
        if (c->name == name) return c;
    return nullptr;
}

// "square-patch, sedov, ...": the names for messages.
inline std::string case_names() {
    std::string s;
    for (const CaseInfo* c : case_registry()) s += (s.empty() ? "" : ", ") + c->name;
    return s;
}

} // namespace exasph
