#pragma once
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

#include "exasph/io/h5_file.hpp"
#include "exasph/util/error.hpp"

// The physical scale of a run's units, when it has one: code units are dimensionless, a run in
// cgs has scale 1, and initial conditions from another code bring theirs (GADGET's
// UnitLength_in_cm, UnitMass_in_g, UnitVelocity_in_cm_per_s). The run's `units` text (root
// attribute `units` of every output, kept by restarts) carries it; snapshots state it in /Header
// as GADGET does, which exasph.yt_load hands to yt.
namespace exasph {

struct UnitScales {
    double length_cm = 1;
    double mass_g = 1;
    double velocity_cm_per_s = 1;
};

inline constexpr const char* kGadgetUnitsPrefix = "GADGET units: ";

// The `units` text of a run in these scales (read back by unit_scales).
inline std::string describe_units(const UnitScales& s) {
    char text[160];
    std::snprintf(text, sizeof text,
                  "%sUnitLength_in_cm=%.17g UnitMass_in_g=%.17g UnitVelocity_in_cm_per_s=%.17g",
                  kGadgetUnitsPrefix, s.length_cm, s.mass_g, s.velocity_cm_per_s);
    return text;
}

// The scales a `units` text states: cgs (1, 1, 1), those of describe_units, else none (code
// units).
inline std::optional<UnitScales> unit_scales(const std::string& units) {
    if (units.rfind("cgs", 0) == 0) return UnitScales{};
    if (units.rfind(kGadgetUnitsPrefix, 0) != 0) return std::nullopt;
    UnitScales s;
    if (std::sscanf(units.c_str() + std::string(kGadgetUnitsPrefix).size(),
                    "UnitLength_in_cm=%lg UnitMass_in_g=%lg UnitVelocity_in_cm_per_s=%lg",
                    &s.length_cm, &s.mass_g, &s.velocity_cm_per_s) != 3)
        return std::nullopt;
    return s;
}

// The unit scales of a GADGET-layout file, where its writer states them: as attributes
// UnitLength_in_cm, UnitMass_in_g, UnitVelocity_in_cm_per_s of /Header, /Parameters (GADGET-4,
// AREPO) or /Units (OWLS, EAGLE); SWIFT's /Units "Unit length in cgs (U_L)", "Unit mass in cgs
// (U_M)", "Unit time in cgs (U_t)". None when the file states none or only some.
inline std::optional<UnitScales> read_unit_scales(const h5::File& file) {
    h5::Group root(file, "/", false);
    auto number = [](const h5::Group& g, const std::string& name) {
        const double v = h5::read_attribute_doubles(g, name).at(0);
        if (!(v > 0 && std::isfinite(v)))
            throw input_error(g.file().path() + ": attribute " + g.name() + "/" + name +
                              " must be a positive unit scale, is " + std::to_string(v));
        return v;
    };
    for (const char* where : {"Header", "Parameters", "Units"}) {
        if (!h5::has_link(root, where)) continue;
        h5::Group g(file, std::string("/") + where, false);
        if (h5::has_attribute(g, "UnitLength_in_cm") && h5::has_attribute(g, "UnitMass_in_g") &&
            h5::has_attribute(g, "UnitVelocity_in_cm_per_s"))
            return UnitScales{number(g, "UnitLength_in_cm"), number(g, "UnitMass_in_g"),
                              number(g, "UnitVelocity_in_cm_per_s")};
        const std::string l = "Unit length in cgs (U_L)", m = "Unit mass in cgs (U_M)",
                          t = "Unit time in cgs (U_t)";
        if (h5::has_attribute(g, l) && h5::has_attribute(g, m) && h5::has_attribute(g, t))
            return UnitScales{number(g, l), number(g, m), number(g, l) / number(g, t)};
    }
    return std::nullopt;
}

} // namespace exasph
